// The bad merge inputs every sharded command refuses (docs/scale.md): each
// exits 2 with one line naming the shard and writes nothing. For commands
// whose merge is `--merge DIR...` on the command itself (energy, agree,
// stability); the shards' folders hold DIR/`file`.
#pragma once

#include "run_mfv.hpp"
#include "test_files.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

namespace mfv::test {

struct BadMerges {
  const Scratch& s;
  std::string options;  // the command and the shards' options, e.g. "--quiet agree --samples 100 --seed 5"
  std::string file;     // the shard's file in its folder, e.g. "agree_shard.json"
  std::string output;   // a file the merge writes to --out, e.g. "agree.json"

  // mfv OPTIONS --merge DIRS --out BAD: exit 2, one line that holds `named`, no output.
  void expect(const std::string& dirs, const std::string& named, const std::string& merge_options = "") const {
    std::filesystem::remove_all(s / "bad");
    auto r = run_mfv((merge_options.empty() ? options : merge_options) + " --merge " + dirs + " --out " + s / "bad");
    INFO(dirs << "\n" << r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
    CHECK(r.out.find(named) != std::string::npos);
    CHECK(!std::filesystem::exists(s / ("bad/" + output)));
  }

  // A folder NAME holding `doc` as its shard file.
  std::string edited(const std::string& name, const nlohmann::json& doc) const {
    std::filesystem::create_directories(s / name);
    std::ofstream(s / (name + "/" + file)) << doc.dump();
    return s / name;
  }

  // Shard 2 missing, given twice, cut short, of another mfv, a unit short,
  // not complete, one of 4 shards; a folder with no shard file. s1, s2, s3:
  // the three shards' folders.
  void common(const std::string& s1, const std::string& s2, const std::string& s3) const {
    expect(s1 + " " + s3, "shard 2/3 missing");
    expect(s1 + " " + s2 + " " + s2 + " " + s3, "shard 2/3 (" + s2 + "/" + file + ") is given twice");
    const std::string text = slurp(s2 + "/" + file);
    std::filesystem::create_directories(s / "cut");
    std::ofstream(s / ("cut/" + file)) << text.substr(0, text.size() / 2);
    expect(s1 + " " + s / "cut" + " " + s3, s / ("cut/" + file) + ": truncated or not JSON");
    const nlohmann::json doc = nlohmann::json::parse(text);
    nlohmann::json version = doc;
    version["tool"]["commit"] = "0000000";
    expect(s1 + " " + edited("version", version) + " " + s3,
           "shard 2/3 (" + s / ("version/" + file) + ") was written by");
    nlohmann::json dropped = doc;
    REQUIRE(!dropped["units"].empty());
    dropped["units"].erase(dropped["units"].begin());
    expect(s1 + " " + edited("dropped", dropped) + " " + s3, "shard 2/3 (" + s / ("dropped/" + file) + ")");
    nlohmann::json incomplete = doc;
    incomplete.erase("complete");
    expect(s1 + " " + edited("incomplete", incomplete) + " " + s3, s / ("incomplete/" + file));
    expect(s / "nothing", "no shard file");
    REQUIRE(run_mfv(options + " --shard 2/4 --out " + s / "four").code == 0);
    expect(s1 + " " + s / "four" + " " + s3, "is one of 4 shards");
  }

  // A shard 2/3 run with the options `other` (another seed or plan) in
  // place of s2: refused, naming it with `shard_says` ("ran seed 6"); and the
  // three shards merged with `other`'s options: refused, naming the first
  // with `merge_says` ("ran seed 5").
  void foreign(const std::string& s1, const std::string& s2, const std::string& s3, const std::string& other,
               const std::string& shard_says, const std::string& merge_says) const {
    const std::string dir = s / "foreign";
    std::filesystem::remove_all(dir);
    REQUIRE(run_mfv(other + " --shard 2/3 --out " + dir).code == 0);
    expect(s1 + " " + dir + " " + s3, "shard 2/3 (" + dir + "/" + file + ") " + shard_says);
    expect(s1 + " " + s2 + " " + s3, "shard 1/3 (" + s1 + "/" + file + ") " + merge_says, other);
  }
};

}  // namespace mfv::test
