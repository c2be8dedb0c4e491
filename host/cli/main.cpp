// mfv: the microfacet-verify command line.
#include "cli/app.hpp"
#include "cli/report_errors.hpp"
#include "runtime/provenance.hpp"
#include "util/progress.hpp"
#include "util/version.hpp"

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  // Line-buffered stdout: a CI log shows each result line as it is printed.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  CLI::App app{"mfv: verify microfacet BRDFs on OpenCL against a double-precision reference"};
  app.set_version_flag("--version", "mfv " + mfv::version_text());
  bool quiet = false;
  app.add_flag("--quiet,-q", quiet,
               "no progress on stderr (by default: a bar on a terminal, a line every few "
               "seconds otherwise)");
  // Global options are also accepted after the command (mfv run --quiet).
  app.fallthrough();
  mfv::cli::Globals g;
  int rc = 0;
  mfv::cli::build_app(app, g, rc);
  mfv::cli::add_help_footers(app);
  mfv::record_command_line(argc, argv);
  // Subcommands run inside app.parse(): --quiet must take effect before it.
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--quiet" || std::string(argv[i]) == "-q") mfv::progress::set_quiet(true);
  try {
    return mfv::cli::run_reporting_errors([&] {
      mfv::cli::parse_command_line(app, argc, argv);
      return rc;
    });
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  }
}
