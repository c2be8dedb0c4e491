#include "checks/bench_case.hpp"
#include "checks/bench.hpp"
#include "mfv_git_commit.h"

#include "catalog/catalog.hpp"
#include "catalog/roughness.hpp"
#include "checks/integrate.hpp"
#include "util/error.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <iterator>
#include <cmath>
#include <sstream>

namespace mfv {
namespace {

const Term& term_of(const std::string& id, Kind kind, const char* what) {
  const Term* t = try_find_term(id, kind);
  if (!t) throw Error(fmt::format("--case: '{}' is not a {} term of the catalog (see 'mfv list')", id, what));
  return *t;
}

double number(const std::string& s, const char* what) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || s.empty() || !std::isfinite(v))
    throw Error(fmt::format("--case: {} '{}' is not a number", what, s));
  return v;
}

IntegralSpec case_spec(const BenchCase& c) {
  const Term &d = find_term(c.d), &g = find_term(c.g), &f = find_term(c.f);
  const double pg = g.params.empty() ? 0.0 : std::min(native_from_alpha(g.roughness, c.alpha), g.params[0].hi);
  MicrofacetIntegral m;
  m.kind = IntegralKind::AlbedoMis;
  m.d = &d, m.g = &g, m.f = &f;
  m.pd = native_from_alpha(d.roughness, c.alpha), m.pg = pg;
  m.f0 = c.f0, m.f1 = c.f1;
  m.width = c.alpha, m.cos_o = c.mu;
  IntegralSpec s = spec_of(m);
  s.stream = 0;
  return s;
}

}  // namespace

BenchCase parse_bench_case(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream ss(text);
  for (std::string p; std::getline(ss, p, ':');) parts.push_back(p);
  const size_t s1 = parts.empty() ? std::string::npos : parts[0].find('/');
  const size_t s2 = s1 == std::string::npos ? s1 : parts[0].find('/', s1 + 1);
  if (parts.size() != 3 || s2 == std::string::npos || parts[0].find('/', s2 + 1) != std::string::npos)
    throw Error(fmt::format("--case '{}': expected D/G/F:ALPHA:MU, e.g. ggx/smith_ggx_correlated/none:0.5:0.5", text));
  BenchCase c;
  c.d = parts[0].substr(0, s1);
  c.g = parts[0].substr(s1 + 1, s2 - s1 - 1);
  c.f = parts[0].substr(s2 + 1);
  term_of(c.d, Kind::D, "D");
  term_of(c.g, Kind::G, "G");
  const Term& f = term_of(c.f, Kind::F, "F");
  if (!f.params.empty()) c.f0 = f.params[0].fallback;
  if (f.params.size() > 1) c.f1 = f.params[1].fallback;
  c.alpha = number(parts[1], "ALPHA");
  c.mu = number(parts[2], "MU");
  const Term& d = find_term(c.d);
  const double native = native_from_alpha(d.roughness, c.alpha);
  if (!(c.alpha > 0) || !(native >= d.params[0].lo && native <= d.params[0].hi))
    throw Error(fmt::format("--case: ALPHA {} is out of {}'s range", parts[1], c.d));
  if (!(c.mu > 0 && c.mu <= 1)) throw Error(fmt::format("--case: MU {} must be in (0, 1]", parts[2]));
  return c;
}

BenchCaseResult run_bench_case(const std::string& device_selector, const std::string& kernel_dir, const BenchCase& c,
                               int repeats, uint64_t seed) {
  const DeviceInfo dev = select_device(device_selector);
  Runtime rt(std::to_string(dev.index), kernel_dir);
  TermSelection sel;  // the one term triple: a program PoCL vectorizes
  sel.d = {&find_term(c.d)};
  sel.g = {&find_term(c.g)};
  sel.f = {&find_term(c.f)};
  // its kernels specialized to the pair: AlbedoMis in one kernel, not three (runtime/specialize.hpp)
  sel.specialized = {{term_index(find_term(c.d)), term_index(find_term(c.g))}};
  Integrator in(rt, sel);
  const IntegralSpec spec = case_spec(c);
  BenchCaseResult r;
  r.c = c;
  r.device = dev.name;
  r.replicates = kMisReplicates;
  r.repeats = repeats;
  // Every whole-net count 20, 40, 80, ... (Integrator::mis_points: 5·2^(m-2),
  // each share a whole Owen-scrambled Sobol net; counts between them, the
  // shares' first points, gave no smaller SE: docs/performance.md) is timed
  // with `repeats` calls, from the smallest up to the first count that
  // reaches the last target and one count beyond it (so a script taking
  // medians over rounds sees both sides of each target, as for Mitsuba's
  // sizes). A target's call is the fewest points whose timed calls' rms SE
  // is at most the target: the rule scripts/bench-peers.sh applies to
  // Mitsuba 3's sizes.
  constexpr uint32_t kMaxPoints = uint32_t(5) << 20;
  in.run({spec}, 20 * kMisReplicates, seed);  // warm-up: first launch, allocations
  const double last_target = kBenchCaseTargets[std::size(kBenchCaseTargets) - 1];
  bool beyond = false;
  for (uint32_t points = 20; points <= kMaxPoints; points *= 2) {
    const uint64_t n = uint64_t(points) * kMisReplicates;
    BenchCaseCount t;
    t.points = in.mis_points(n);
    t.samples = uint64_t(t.points) * kMisReplicates;
    std::vector<double> wall, cpu;
    double ss = 0;
    in.run({spec}, n, seed);  // warm-up at this count (buffers)
    for (int k = 0; k < repeats; ++k) {
      const double c0 = bench_cpu_now(), t0 = bench_now();
      const Estimate e = in.run({spec}, n, seed + uint64_t(k))[0];
      wall.push_back(bench_now() - t0);
      cpu.push_back(bench_cpu_now() - c0);
      if (k == 0) t.estimate = e.mean, t.stderr_ = e.stderr_;
      ss += e.stderr_ * e.stderr_;
    }
    t.rms_stderr = std::sqrt(ss / repeats);
    t.median_seconds = bench_median(wall);
    t.median_cpu_seconds = bench_median(cpu);
    t.samples_per_s = double(t.samples) / t.median_seconds;
    t.variance_per_sample = double(t.samples) * t.rms_stderr * t.rms_stderr;
    r.grid.push_back(t);
    if (beyond) break;
    beyond = t.rms_stderr <= last_target;
  }
  for (const double target : kBenchCaseTargets) {
    // the fewest points reaching the target; else the largest count, its
    // time scaled by (SE / target)² (an RQMC error falls faster than that:
    // an upper bound, flagged by seconds_to_se > median_seconds)
    auto it =
        std::find_if(r.grid.begin(), r.grid.end(), [&](const BenchCaseCount& t) { return t.rms_stderr <= target; });
    BenchCaseTarget t;
    static_cast<BenchCaseCount&>(t) = it != r.grid.end() ? *it : r.grid.back();
    t.target_se = target;
    const double over = t.rms_stderr / target;
    t.seconds_to_se = t.median_seconds * (over > 1 ? over * over : 1.0);
    r.targets.push_back(t);
  }
  return r;
}

std::string bench_case_text(const BenchCaseResult& r) {
  std::string s = fmt::format(
      "case {}/{}/{} alpha={:g} mu={:g} on {}: the suite's albedo estimator (MIS of visible normals, Cauchy slopes "
      "and the cosine lobe on {} Owen-scrambled Sobol replicates)\n",
      r.c.d, r.c.g, r.c.f, r.c.alpha, r.c.mu, r.device, r.replicates);
  for (const BenchCaseTarget& t : r.targets)
    s += fmt::format(
        "  SE {:g}: one call {:.4g} s (median of {}; CPU {:.4g} s), SE {:.2e} (rms of {} calls {:.2e}); estimate "
        "{:.7f}\n    {} points x {} replicates = {} samples, samples/s {:.3e}, variance/sample {:.3g} (n SE^2), "
        "seconds to SE {:g}: {:.4g}\n",
        t.target_se, t.median_seconds, r.repeats, t.median_cpu_seconds, t.stderr_, r.repeats, t.rms_stderr, t.estimate,
        t.points, r.replicates, t.samples, t.samples_per_s, t.variance_per_sample, t.target_se, t.seconds_to_se);
  s += "  every count timed (points x replicates: median wall, rms SE):";
  for (const BenchCaseCount& t : r.grid)
    s += fmt::format(" {}: {:.3g} s, {:.2e};", t.points, t.median_seconds, t.rms_stderr);
  s.back() = '\n';
  return s;
}

std::string bench_case_json(const BenchCaseResult& r, const std::string& load_average, const std::string& date) {
  using nlohmann::json;
  const auto count_json = [](const BenchCaseCount& t) {
    return json{{"points_per_replicate", t.points},
                {"samples", t.samples},
                {"estimate", t.estimate},
                {"stderr", t.stderr_},
                {"rms_stderr", t.rms_stderr},
                {"median_seconds", t.median_seconds},
                {"median_cpu_seconds", t.median_cpu_seconds},
                {"samples_per_s", t.samples_per_s},
                {"variance_per_sample", t.variance_per_sample}};
  };
  json targets = json::array(), grid = json::array();
  for (const BenchCaseTarget& t : r.targets) {
    json j = count_json(t);
    j["target_se"] = t.target_se;
    j["seconds_to_se"] = t.seconds_to_se;
    targets.push_back(j);
  }
  for (const BenchCaseCount& t : r.grid) grid.push_back(count_json(t));
  const BenchCaseTarget& t = r.targets.front();  // SE 1e-4: the top-level fields of mfv-bench-case/1
  json j{{"schema", "mfv-bench-case/1"},
         {"tool", {{"name", "mfv"}, {"version", MFV_VERSION}, {"commit", MFV_GIT_COMMIT}}},
         {"date", date},
         {"load_average", load_average},
         {"case", fmt::format("{}/{}/{}:{:g}:{:g}", r.c.d, r.c.g, r.c.f, r.c.alpha, r.c.mu)},
         {"device", r.device},
         {"estimator",
          "albedo_mis: visible normals (GGX shape) 61/64 + Cauchy slopes 1/64 + cosine 1/32, balance heuristic, "
          "Owen-scrambled Sobol replicates"},
         {"replicates", r.replicates},
         {"samples", t.samples},
         {"estimate", t.estimate},
         {"stderr", t.stderr_},
         {"rms_stderr", t.rms_stderr},
         {"repeats", r.repeats},
         {"median_seconds", t.median_seconds},
         {"median_cpu_seconds", t.median_cpu_seconds},
         {"samples_per_s", t.samples_per_s},
         {"variance_per_sample", t.variance_per_sample},
         {"seconds_to_se_1e-4", t.seconds_to_se},
         {"seconds_to_se_1e-5", r.targets.back().seconds_to_se},
         {"targets", targets},
         {"grid", grid}};
  return j.dump(2) + "\n";
}

}  // namespace mfv
