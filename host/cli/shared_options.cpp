#include "cli/shared_options.hpp"

#include "checks/check_table.hpp"
#include "cli/run_shard.hpp"
#include "util/error.hpp"
#include "util/files.hpp"

#include <fmt/format.h>

#include <cstdio>

namespace mfv::cli {

void SharedValues::prepare_out() const {
  if (!out_dir.empty()) prepare_output_dir(out_dir);
}

void SharedValues::apply_samples(double& scale) const {
  if (samples_option == nullptr || samples_option->count() == 0) return;
  if (samples <= 0) throw Error(fmt::format("--samples must be a positive count, not {}", samples));
  scale = double(samples) / double(kSuiteBaseSamples);
}

Scene SharedValues::load_scene_instead_of(bool other_given, const std::string& other, const std::string& chosen) const {
  if (scene_path.empty()) return Scene{};
  if (other_given)
    throw Error(fmt::format("{} and --scene cannot be combined: the scene chooses the {}", other, chosen));
  return load_scene(scene_path);
}

std::optional<ShardSpec> SharedValues::shard_to_run(const std::string& file, const std::string& merger) const {
  if (!merge.empty() && !shard.empty() && shard != "off") throw Error("--merge and --shard: give one");
  if (!merge.empty()) return std::nullopt;
  std::optional<ShardSpec> s = shard_of(shard, shard_count);
  if (s && out_dir.empty())
    throw Error(fmt::format("a shard's values go to DIR/{}: give --out DIR (then {} the DIRs)", file, merger));
  return s;
}

SharedOptions& SharedOptions::seed(uint64_t& seed) {
  cmd_->add_option("--seed", seed, "Philox key");
  return *this;
}

SharedOptions& SharedOptions::out(const std::string& files, const std::string& more) {
  cmd_->add_option("--out", values_.out_dir, "write " + files + " here" + more);
  return *this;
}

SharedOptions& SharedOptions::fp64(bool& fp64) {
  cmd_->add_flag("--fp64", fp64, "run the kernels in double (device needs cl_khr_fp64)");
  return *this;
}

SharedOptions& SharedOptions::only(std::vector<std::string>& only, const std::string& examples) {
  cmd_->add_option("--only", only, "only cases whose name contains one of these (e.g. " + examples + ")");
  return *this;
}

SharedOptions& SharedOptions::scene(const std::string& help) {
  cmd_->add_option("--scene", values_.scene_path, help);
  return *this;
}

SharedOptions& SharedOptions::terms_only(const std::string& skipped) {
  cmd_->add_flag("--terms-only", values_.terms_only, "skip " + skipped);
  return *this;
}

SharedOptions& SharedOptions::budget(double& scale, double& family_alpha) {
  cmd_->add_option("--scale", scale, "multiply every check's samples (budget); 1 = about a minute on 2 cores");
  values_.samples_option =
      cmd_->add_option("--samples", values_.samples,
                       "samples per masking/furnace integral (default 4096); the other checks scale in proportion");
  cmd_->add_option("--alpha-fw", family_alpha, "family-wise false-alarm rate for the whole run")
      ->check(CLI::Range(1e-300, 0.5));
  return *this;
}

SharedOptions& SharedOptions::baseline(const std::string& help, const std::string& alpha_name, double& alpha_fw) {
  cmd_->add_option("--baseline", values_.baseline, help);
  cmd_->add_option(alpha_name, alpha_fw, "family-wise false-alarm rate of the baseline comparison (default 1e-3)")
      ->check(CLI::Range(1e-300, 0.5));
  return *this;
}

SharedOptions& SharedOptions::shard(const std::string& part, const std::string& file, const std::string& merger,
                                    const std::string& merged) {
  cmd_->add_option("--shard", values_.shard,
                   "run part K of N (1 <= K <= N) of " + part + " into --out DIR/" + file + ", for " + merger +
                       "; absent: Bazel's, GoogleTest's, Slurm's or a Kubernetes Indexed Job's variables if set; off: "
                       "the whole run (docs/scale.md)");
  cmd_->add_option("--shard-count", values_.shard_count,
                   "with JOB_COMPLETION_INDEX (Kubernetes): the number of shards (else MFV_SHARD_COUNT)")
      ->check(CLI::PositiveNumber);
  if (!merged.empty())
    cmd_->add_option("--merge", values_.merge,
                     "the --out folders of every shard (" + merger.substr(0, merger.find(" --merge")) +
                         " --shard K/N, with the same options as here): the whole run's outputs from their " + merged)
        ->expected(1, -1);
  return *this;
}

std::pair<int, int> parse_cells(const std::string& option, const std::string& text, const std::string& form,
                                const std::string& example) {
  int cols = 0, rows = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &cols, &x, &rows, &extra) != 3 || (x != 'x' && x != 'X'))
    throw Error(fmt::format("{} '{}': expected {}, e.g. {}", option, text, form, example));
  return {cols, rows};
}

}  // namespace mfv::cli
