// The mfv command line as an object: main parses argv with it, and the
// option-parser fuzz test (tests/host/test_fuzz.cpp) parses random argv with
// the subcommands' callbacks removed.
#pragma once

#include "cli/commands.hpp"

namespace mfv::cli {

// Every subcommand and option, each number read strictly (strict_numbers.hpp).
void build_app(CLI::App& app, Globals& g, int& rc);

// Names an unknown command (instead of CLI11's "a subcommand is required"),
// then app.parse, which runs the chosen subcommand's callback.
void parse_command_line(CLI::App& app, int argc, const char* const* argv);

}  // namespace mfv::cli
