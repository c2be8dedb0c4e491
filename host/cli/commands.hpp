// mfv subcommands. Each returns the process exit code: 0 all good, 1 a check
// did not match expectation; errors throw mfv::Error (exit 2, one line).
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace mfv::cli {

struct Globals {
  std::string device;      // --device: index or name substring
  std::string kernel_dir;  // --kernel-dir: read kernels from here instead of the binary
  // Each command's option values (a struct per cmd_*.cpp, bound to its
  // options): kept here so that they live as long as the app that parses into
  // them, whatever becomes of the command's callback.
  std::vector<std::shared_ptr<void>> command_values;
};

void add_devices(CLI::App& app, Globals& g, int& rc);
void add_list(CLI::App& app, Globals& g, int& rc);
void add_agree(CLI::App& app, Globals& g, int& rc);
void add_eval(CLI::App& app, Globals& g, int& rc);
void add_run(CLI::App& app, Globals& g, int& rc);
void add_stability(CLI::App& app, Globals& g, int& rc);
void add_energy(CLI::App& app, Globals& g, int& rc);
void add_check(CLI::App& app, Globals& g, int& rc);
void add_samplers(CLI::App& app, Globals& g, int& rc);
void add_bench(CLI::App& app, Globals& g, int& rc);
void add_convergence(CLI::App& app, Globals& g, int& rc);
void add_merge(CLI::App& app, Globals& g, int& rc);

// Each command's --help ends with the global options and a few examples.
void add_help_footers(CLI::App& app);

}  // namespace mfv::cli
