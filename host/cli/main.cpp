// mfv: the microfacet-verify command line.
#include "cli/app.hpp"
#include "cli/report_errors.hpp"
#include "runtime/provenance.hpp"

int main(int argc, char** argv) {
  CLI::App app{"mfv: verify microfacet BRDFs on OpenCL against a double-precision reference"};
  mfv::cli::Globals g;
  int rc = 0;
  mfv::cli::build_app(app, g, rc);
  mfv::record_command_line(argc, argv);
  try {
    return mfv::cli::run_reporting_errors([&] {
      mfv::cli::parse_command_line(app, argc, argv);
      return rc;
    });
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  }
}
