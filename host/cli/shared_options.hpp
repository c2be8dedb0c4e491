// The options several commands share (--seed, --out, --fp64, --only, --scene,
// --scale/--samples/--alpha-fw, --baseline), each registered here once with
// one name, help text and check, and the few steps their values take in a
// command's callback. A command adds only the options that are its own.
#pragma once

#include "checks/shard.hpp"
#include "cli/commands.hpp"
#include "scene/scene.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mfv::cli {

// The values of the shared options that no command's own options struct
// (AgreeOptions, SuiteOptions, ...) holds. Each command's values derive from it.
struct SharedValues {
  std::string out_dir;      // --out: the results folder ("" = none)
  std::string scene_path;   // --scene: a glTF or material file ("" = none)
  std::string baseline;     // --baseline: an earlier results file ("" = none)
  bool terms_only = false;  // --terms-only: the single terms alone
  int64_t samples = 0;      // --samples of run and check: sets the scale
  CLI::Option* samples_option = nullptr;
  std::string shard;               // --shard K/N ("" = the engines' variables, "off" = the whole run)
  uint32_t shard_count = 0;        // --shard-count: JOB_COMPLETION_INDEX's count (Kubernetes)
  std::vector<std::string> merge;  // --merge DIR...: the shards' --out folders (energy, agree, stability)

  // Creates the --out folder, if one was given: checked before the work, not after it.
  void prepare_out() const;
  // --samples N, when given, as a scale of kSuiteBaseSamples (positive N only).
  void apply_samples(double& scale) const;
  // The --scene file, when given. The scene chooses what runs, so the option
  // `other` (--only, --model, --models) that would too must not be given.
  Scene load_scene_instead_of(bool other_given, const std::string& other, const std::string& chosen) const;
  // The shard a command with --merge runs (--shard, else the engines'
  // variables: cli/run_shard.hpp shard_of), nullopt for the whole run or a
  // merge. A shard writes DIR/`file` and needs --out DIR; --merge and
  // --shard go apart; `merger` (e.g. "mfv agree --merge") names the merge.
  std::optional<ShardSpec> shard_to_run(const std::string& file, const std::string& merger) const;
};

// Adds the subcommand `name`. A Command is one command's values, options and
// work: a SharedValues with `void add_options(CLI::App* cmd)`, which sets the
// command's description and binds its options to its members, and
// `int run(const Globals& g)`, which returns the exit code (0 all good, 1 a
// check did not match expectation). It lives in Globals::command_values, as
// long as the app that parses into it.
template <class Command>
void add_command(CLI::App& app, Globals& g, int& rc, const std::string& name) {
  auto command = std::make_shared<Command>();
  g.command_values.push_back(command);
  CLI::App* cmd = app.add_subcommand(name);
  command->add_options(cmd);
  cmd->callback([&g, &rc, command] { rc = command->run(g); });
}

// Registers the shared options on one command, into its SharedValues.
class SharedOptions {
 public:
  SharedOptions(CLI::App* cmd, SharedValues& values) : cmd_(cmd), values_(values) {}
  SharedOptions& seed(uint64_t& seed);
  // --out DIR: "write FILES here" and `more` (e.g. ", and ... into plots/").
  SharedOptions& out(const std::string& files, const std::string& more = "");
  SharedOptions& fp64(bool& fp64);
  // --only NAME...: "only cases whose name contains one of these (EXAMPLES)".
  SharedOptions& only(std::vector<std::string>& only, const std::string& examples);
  SharedOptions& scene(const std::string& help);
  // --terms-only: "skip SKIPPED".
  SharedOptions& terms_only(const std::string& skipped);
  // The suite's budget: --scale, --samples (a scale) and --alpha-fw.
  SharedOptions& budget(double& scale, double& family_alpha);
  // --baseline FILE and its family-wise false-alarm rate, the option `alpha_name`.
  SharedOptions& baseline(const std::string& help, const std::string& alpha_name, double& alpha_fw);
  // --shard K/N and --shard-count (docs/scale.md): "run part K of N of PART
  // into --out DIR/FILE, for MERGER"; and, where `merged` is given, --merge
  // DIR...: the whole run's outputs from the shards' MERGED.
  SharedOptions& shard(const std::string& part, const std::string& file, const std::string& merger,
                       const std::string& merged = "");

 private:
  CLI::App* cmd_;
  SharedValues& values_;
};

// "COLSxROWS" (e.g. 32x32, for --grid and --bins): the two counts, or an
// Error naming the option and the form it expects.
std::pair<int, int> parse_cells(const std::string& option, const std::string& text, const std::string& form,
                                const std::string& example);

}  // namespace mfv::cli
