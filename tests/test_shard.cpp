// mfv run --shard K/N and mfv merge (docs/scale.md): shards merged equal the
// single run record for record and verdict for verdict, with the shard's
// index from --shard or from Bazel's, Slurm's and Kubernetes' variables; each
// bad merge input exits 2 naming the shard.
#include "checks/shard.hpp"
#include "device_fixture.hpp"
#include "run_mfv.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <set>
#include <cmath>

using namespace mfv;
using namespace mfv::test;
using nlohmann::json;

namespace {

// A small run over every kind of plan: D x G x F checks (charlie with every
// G), whole models (energy, closed_form), anisotropic and sheen cases (the
// sheen's d_norm), reciprocity.
// The integral kinds only: the pointwise kinds (agree, stability) do not shard.
const std::string kBase =
    "--quiet run --scale 0.05 --model charlie --model lambert --model aniso_ggx/smith_aniso_ggx --check d_norm "
    "--check masking --check furnace --check energy --check energy_diffuse --check reciprocity --check closed_form";
const std::string kRun = kBase + " --seed 7";

json results(const std::string& dir) { return json::parse(slurp(dir + "/results.json")); }

// The records and verdicts of a results.json, less what differs between
// runs (time, date, provenance): records, groups, test counts, reference.
json verdicts(const json& r) {
  json out;
  out["results"] = r.at("results");
  out["groups"] = r.at("groups");
  out["tests"] = r.at("run").at("tests");
  out["pooled_tests"] = r.at("run").at("pooled_tests");
  out["z_threshold"] = r.at("run").at("z_threshold");
  json ref = r.at("reference");
  out["reference"] = ref;
  json integrals = json::object();
  for (auto& t : r.at("timings")) {
    integrals[t.at("check").get<std::string>()] =
        integrals.value(t.at("check").get<std::string>(), 0) + t.at("integrals").get<int>();
  }
  out["integrals"] = integrals;
  return out;
}

// junit.xml without its times and timestamps.
std::string junit_shape(const std::string& path) {
  std::string x = slurp(path), out;
  for (size_t i = 0; i < x.size();) {
    size_t t = std::min(x.find("time=\"", i), x.find("timestamp=\"", i));
    if (t == std::string::npos) {
      out += x.substr(i);
      break;
    }
    out += x.substr(i, t - i);
    i = x.find('"', x.find('"', t) + 1) + 1;
  }
  return out;
}

void require_equal_runs(const std::string& single, const std::string& merged) {
  const json a = verdicts(results(single)), b = verdicts(results(merged));
  REQUIRE(a.at("results").size() == b.at("results").size());
  for (size_t i = 0; i < a.at("results").size(); ++i) {
    INFO("record " << i);
    REQUIRE(a.at("results")[i] == b.at("results")[i]);
  }
  CHECK(a == b);
  CHECK(junit_shape(single + "/junit.xml") == junit_shape(merged + "/junit.xml"));
}

}  // namespace

TEST_CASE("mfv run --shard reads K/N from 1 to N and refuses anything else", "[shard]") {
  ShardSpec s = parse_shard_option("2/5");
  CHECK(s.index == 1);
  CHECK(s.count == 5);
  for (const char* bad : {"0/3", "4/3", "3", "1/0", "a/b", "-1/3", "1/3x", ""}) {
    INFO(bad);
    CHECK_THROWS_AS(parse_shard_option(bad), Error);
  }
}

TEST_CASE("the engines' shard variables give the shard, the variable named, and bad values are errors", "[shard]") {
  auto env_of = [](std::map<std::string, std::string> m) {
    return [m = std::move(m)](const char* n) -> const char* {
      auto it = m.find(n);
      return it == m.end() ? nullptr : it->second.c_str();
    };
  };
  CHECK(!shard_from_environment(0, env_of({})));
  auto bazel = shard_from_environment(0, env_of({{"TEST_TOTAL_SHARDS", "4"}, {"TEST_SHARD_INDEX", "3"}}));
  REQUIRE(bazel);
  CHECK((bazel->index == 3 && bazel->count == 4));
  CHECK(bazel->source.find("TEST_SHARD_INDEX") != std::string::npos);
  auto gtest = shard_from_environment(0, env_of({{"GTEST_TOTAL_SHARDS", "2"}, {"GTEST_SHARD_INDEX", "0"}}));
  REQUIRE(gtest);
  CHECK((gtest->index == 0 && gtest->count == 2));
  auto slurm = shard_from_environment(
      0, env_of({{"SLURM_ARRAY_TASK_ID", "3"}, {"SLURM_ARRAY_TASK_MIN", "1"}, {"SLURM_ARRAY_TASK_COUNT", "3"}}));
  REQUIRE(slurm);
  CHECK((slurm->index == 2 && slurm->count == 3));
  CHECK(slurm->source.find("SLURM_ARRAY_TASK_ID") != std::string::npos);
  auto k8s = shard_from_environment(3, env_of({{"JOB_COMPLETION_INDEX", "1"}}));
  REQUIRE(k8s);
  CHECK((k8s->index == 1 && k8s->count == 3));
  auto k8s_env = shard_from_environment(0, env_of({{"JOB_COMPLETION_INDEX", "0"}, {"MFV_SHARD_COUNT", "2"}}));
  REQUIRE(k8s_env);
  CHECK(k8s_env->count == 2);
  CHECK_THROWS_AS(shard_from_environment(0, env_of({{"JOB_COMPLETION_INDEX", "0"}})), Error);  // no count
  CHECK_THROWS_AS(shard_from_environment(0, env_of({{"TEST_TOTAL_SHARDS", "2"}, {"TEST_SHARD_INDEX", "2"}})), Error);
  CHECK_THROWS_AS(shard_from_environment(0, env_of({{"TEST_TOTAL_SHARDS", "x"}, {"TEST_SHARD_INDEX", "0"}})), Error);
  CHECK_THROWS_AS(shard_from_environment(0, env_of({{"SLURM_ARRAY_TASK_ID", "1"}})), Error);  // no count
}

TEST_CASE("shards cover every integral of the run exactly once, each a like share of every plan's cost",
          "[shard]") {
  SuiteOptions opt;
  opt.scale = 0.05;
  const SuitePlans sp = make_suite_plans(opt);
  const size_t total = plan_integrals(sp);
  // The same-sample reference comparison's points, by position in the whole
  // run: a plan's own pick where it has one (bsdf_furnace leaves out its
  // known-bad entries and index-matched points, whose comparison would fail
  // on the planted formula or on F's absolute rounding at F = 0), else every
  // reference_every-th point. The shards together must pick the same points.
  std::set<size_t> whole_picks;
  size_t offset = 0;
  bool own_pick = false;
  for (auto& p : sp.plans) {
    own_pick = own_pick || p.reference_pick.has_value();
    for (size_t i : p.reference_pick ? *p.reference_pick : reference_subset(p, opt.reference_every))
      whole_picks.insert(offset + i);
    offset += p.specs.size();
  }
  CHECK(own_pick);  // the run holds a plan with its own pick, so the comparison below can fail
  for (uint32_t n : {1u, 3u, 7u}) {
    std::set<size_t> seen, shard_picks;
    std::vector<double> cost(n, 0.0);
    for (uint32_t k = 0; k < n; ++k) {
      SuitePlans cut = sp;
      const std::vector<size_t> pos = cut_to_shard(cut, opt, {k, n, ""});
      CHECK(pos == shard_positions(sp, {k, n, ""}));
      for (size_t p : pos) CHECK(seen.insert(p).second);
      size_t at = 0;  // the shard's integrals, plan by plan, in pos's order
      for (auto& p : cut.plans) {
        for (size_t i : *p.reference_pick) shard_picks.insert(pos.at(at + i));
        at += p.specs.size();
      }
      for (auto& p : cut.plans) cost[k] += double(p.specs.size()) * double(integral_cost(p, opt.scale));
      cost[k] += double(cut.reciprocity.specs.size()) * double(integral_cost(cut.reciprocity, opt.scale));
      // streams are those of the whole run (keyed by identity before the cut), not renumbered
      if (!cut.plans.front().specs.empty()) {
        const IntegralSpec& whole = sp.plans.front().specs.at(pos.front());
        CHECK(cut.plans.front().specs.front().stream == whole.stream);
        CHECK(cut.plans.front().specs.front().stream_hi == whole.stream_hi);
      }
    }
    CHECK(seen.size() == total);
    CHECK(shard_picks == whole_picks);
    const double mean = std::accumulate(cost.begin(), cost.end(), 0.0) / n;
    for (double c : cost) CHECK(std::fabs(c - mean) <= 0.02 * mean);  // within a few integrals per plan
  }
}

TEST_CASE("three shards merged equal the single run record for record, with their index from --shard, Bazel's, "
          "Slurm's and Kubernetes' variables, and each bad merge input exits 2 naming the shard",
          "[shard][device]") {
  if (!device_runtime()) return;
  Scratch s("mfv_shard");
  const Run single = run_mfv(kRun + " --out " + s / "single");
  REQUIRE(single.code <= 1);
  const std::string s1 = s / "s1", s2 = s / "s2", s3 = s / "s3", k2 = s / "k2";
  auto shard = [&](const std::string& dir, const std::string& args, const std::string& env, const std::string& from) {
    auto r = run_mfv(kRun + args + " --out " + dir, env);
    INFO(r.out);
    REQUIRE(r.code == 0);
    CHECK(r.out.find(from) != std::string::npos);
  };
  const std::string status = s / "bazel_status";
  shard(s1, " --shard 1/3", "", "shard 1/3 (from --shard)");
  shard(s2, "", "TEST_TOTAL_SHARDS=3 TEST_SHARD_INDEX=1 TEST_SHARD_STATUS_FILE=" + status,
        "shard 2/3 from TEST_SHARD_INDEX/TEST_TOTAL_SHARDS (Bazel)");
  CHECK(std::filesystem::exists(status));  // Bazel's sign that the test shards
  shard(s3, "", "SLURM_ARRAY_TASK_ID=3 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_COUNT=3",
        "shard 3/3 from SLURM_ARRAY_TASK_ID");
  shard(k2, " --shard-count 3", "JOB_COMPLETION_INDEX=1", "shard 2/3 from JOB_COMPLETION_INDEX");
  for (auto [name, dirs] : {std::pair<std::string, std::string>{"merged", s1 + " " + s2 + " " + s3},
                            std::pair<std::string, std::string>{"merged_k8s", s3 + " " + k2 + " " + s1}}) {
    auto m = run_mfv("--quiet merge " + dirs + " --out " + s / name);
    INFO(m.out);
    REQUIRE(m.code == single.code);
    require_equal_runs(s / "single", s / name);
  }
  const json prov = results(s / "merged").at("provenance");
  CHECK(prov.at("shards").at("count") == 3);
  CHECK(prov.at("shards").at("shards")[1].at("source").get<std::string>().find("TEST_SHARD_INDEX") !=
        std::string::npos);

  // bad inputs: exit 2, one line naming the shard, no output written
  auto bad = [&](const std::string& args, const std::string& named) {
    std::filesystem::remove_all(s / "bad");
    auto r = run_mfv("merge " + args + " --out " + s / "bad");
    INFO(args << "\n" << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
    CHECK(r.out.find(named) != std::string::npos);
    CHECK(!std::filesystem::exists(s / "bad/results.json"));
  };
  bad(s1 + " " + s3, "shard 2/3 missing");
  bad(s1 + " " + s2 + " " + k2 + " " + s3, "shard 2/3 (" + k2 + "/shard.json) is given twice");
  const std::string text = slurp(s2 + "/shard.json");
  std::filesystem::create_directories(s / "cut");
  std::ofstream(s / "cut/shard.json") << text.substr(0, text.size() / 2);
  bad(s1 + " " + s / "cut" + " " + s3, s / "cut/shard.json");
  json doc = json::parse(text);
  auto edited = [&](const std::string& name, const json& d) {
    std::filesystem::create_directories(s / name);
    std::ofstream(s / (name + "/shard.json")) << d.dump();
    return s / name;
  };
  json dropped = doc;
  dropped["results"].erase(dropped["results"].begin() + 5);
  bad(s1 + " " + edited("dropped", dropped) + " " + s3, "shard 2/3 (" + s / "dropped/shard.json");
  json version = doc;
  version["tool"]["commit"] = "0000000";
  bad(s1 + " " + edited("version", version) + " " + s3, "shard 2/3 (" + s / "version/shard.json) was written by");
  // foreign shards, run small (d_norm alone): another seed, another plan, another count
  REQUIRE(run_mfv(kBase + " --check d_norm --seed 8 --shard 2/3 --out " + s / "seed8").code == 0);
  bad(s1 + " " + s / "seed8" + " " + s3, "shard 2/3 (" + s / "seed8/shard.json) ran seed 8");
  REQUIRE(run_mfv(kRun + " --check d_norm --shard 2/3 --out " + s / "plan").code == 0);
  bad(s1 + " " + s / "plan" + " " + s3, "shard 2/3 (" + s / "plan/shard.json) ran another plan");
  REQUIRE(run_mfv(kRun + " --check d_norm --shard 2/4 --out " + s / "four").code == 0);
  bad(s1 + " " + s / "four" + " " + s3, "is one of 4 shards");
  bad(s / "nothing", "no shard file");
}

TEST_CASE("a bad --shard, or --shard without --out, is a one-line error", "[shard][cli]") {
  for (const char* args : {"run --shard 0/2 --out /tmp", "run --shard 3/2 --out /tmp", "run --shard 1/2"}) {
    auto r = run_mfv(args);
    INFO(args << "\n" << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
  }
  auto r = run_mfv("run --out /tmp", "TEST_TOTAL_SHARDS=2 TEST_SHARD_INDEX=5");
  CHECK(r.code == 2);
  CHECK(r.out.find("TEST_SHARD_INDEX") != std::string::npos);
}
