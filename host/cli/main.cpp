// mfv: the microfacet-verify command line.
#include "cli/commands.hpp"
#include "runtime/error.hpp"
#include "util/progress.hpp"
#include "util/version.hpp"

#include <CL/opencl.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  // Line-buffered stdout: a CI log shows each result line as it is printed.
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  CLI::App app{"mfv: verify microfacet BRDFs on OpenCL against a double-precision reference"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "mfv " + mfv::version_text());
  bool quiet = false;
  app.add_flag("--quiet,-q", quiet, "no progress on stderr (by default: a bar on a terminal, a line every few "
                                    "seconds otherwise)");
  // Global options are also accepted after the command (mfv run --quiet).
  app.fallthrough();
  mfv::cli::Globals g;
  app.add_option("--device", g.device, "OpenCL device: index or name substring (default: first GPU, else CPU)");
  app.add_option("--kernel-dir", g.kernel_dir, "read kernels from this folder instead of the embedded copies")
      ->check(CLI::ExistingDirectory);
  int rc = 0;
  mfv::cli::add_devices(app, g, rc);
  mfv::cli::add_list(app, g, rc);
  mfv::cli::add_agree(app, g, rc);
  mfv::cli::add_eval(app, g, rc);
  mfv::cli::add_run(app, g, rc);
  mfv::cli::add_stability(app, g, rc);
  mfv::cli::add_energy(app, g, rc);
  mfv::cli::add_check(app, g, rc);
  mfv::cli::add_samplers(app, g, rc);
  mfv::cli::add_bench(app, g, rc);
  mfv::cli::add_convergence(app, g, rc);
  mfv::cli::add_help_footers(app);
  // Subcommands run inside app.parse(): --quiet must take effect before it.
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--quiet" || std::string(argv[i]) == "-q") mfv::progress::set_quiet(true);
  try {
    // Name an unknown command instead of CLI11's "a subcommand is required".
    for (int i = 1; i < argc; ++i) {
      std::string a = argv[i];
      if (a == "--device" || a == "--kernel-dir") {
        ++i;
        continue;
      }
      if (a.rfind("-", 0) == 0) continue;
      bool known = false;
      std::string names;
      for (auto* sub : app.get_subcommands({})) {
        known = known || sub->get_name() == a;
        names += (names.empty() ? "" : ", ") + sub->get_name();
      }
      if (!known) throw mfv::Error("unknown command '" + a + "' (commands: " + names + "; see 'mfv --help')");
      break;
    }
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "mfv: error: %s (see 'mfv --help')\n", e.what());
    return 2;
  } catch (const mfv::Error& e) {
    std::fprintf(stderr, "mfv: error: %s\n", e.what());
    return 2;
  } catch (const cl::Error& e) {
    std::fprintf(stderr, "mfv: error: OpenCL call %s failed with code %d\n", e.what(), e.err());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "mfv: error: out of host memory; lower --samples\n");
    return 2;
  }
  return rc;
}
