// Every numeric option of the command line read strictly (util/parse.hpp):
// CLI11 alone wraps "-1" and 2^64 to 2^64-1 in an unsigned option, saturates
// overflow, reads "" as 0, and falls back to a double for "2e19" whose cast
// to an integer is undefined. One pass over the finished app gives each
// integer and floating-point option a transform that rejects all of that.
#pragma once

#include <CLI/CLI.hpp>

namespace mfv::cli {

// Call once after every subcommand and option was added.
void make_options_strict(CLI::App& app);

}  // namespace mfv::cli
