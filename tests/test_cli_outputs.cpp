// The command line as a CI job and a person see it: --version, progress on
// stderr (piped and on a terminal), --quiet, mfv run --baseline (a planted
// change is caught, an unchanged model is not), the chi-square images of
// mfv samplers, and the plots' labels.
#include "device_fixture.hpp"
#include "kernel_dir.hpp"
#include "run_mfv.hpp"
#include "test_files.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace mfv::test;

namespace {

// Output of a shell command (stdout).
std::string shell(const std::string& cmd) {
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p != nullptr);
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  pclose(p);
  return out;
}

bool is_png(const std::string& bytes) { return bytes.rfind("\x89PNG", 0) == 0; }

// A run long enough to report progress several times (masking and furnace at
// 16x the samples: tens of seconds on 2 cores); tests stop it early.
const std::string kLongRun = "run --check masking furnace --samples 65536";

}  // namespace

TEST_CASE("mfv --version prints the version and the build's git description", "[cli][ux]") {
  auto r = run_mfv("--version");
  CHECK(r.code == 0);
  CHECK(r.out.rfind("mfv " MFV_VERSION " (git ", 0) == 0);
}

TEST_CASE("progress appears in a piped run within seconds, on stderr only, and --quiet silences it",
          "[cli][ux][device]") {
  if (!mfv::test::device_runtime()) return;
  Scratch s("mfv_progress");
  // Start the run with stdout and stderr in files; poll stderr every 0.5 s
  // for the first progress line, print the half-seconds it took, stop the run.
  auto poll = [&](const std::string& args, int max_halves) {
    const std::string cmd = fmt::format(
        // empty both files here first: the background run's own redirections
        // may open them only after the first grep, which would then read the
        // previous run's progress
        ": > {2}; : > {3}; {0} {1} > {2} 2> {3} & pid=$!; t=0; while [ $t -lt {4} ]; do "
        "if grep -q '^mfv: ' {3}; then break; fi; sleep 0.5; t=$((t+1)); done; kill $pid 2>/dev/null; wait $pid; echo "
        "$t",
        MFV_BINARY, args, s / "out.txt", s / "err.txt", max_halves);
    return std::stoi(shell(cmd));
  };
  // the first line comes 2 s after the first check starts; allow 20 s for
  // OpenCL start-up and kernel builds on a loaded machine
  const int halves = poll(kLongRun, 40);
  INFO(slurp(s.dir / "err.txt"));
  CHECK(halves < 40);
  CHECK(slurp(s.dir / "err.txt").find("samples") != std::string::npos);
  CHECK(slurp(s.dir / "out.txt").find("mfv: ") == std::string::npos);  // stdout keeps the results
  // --quiet, a global option given after the command: nothing in 6 s
  CHECK(poll(kLongRun + " --quiet", 12) == 12);
  CHECK(slurp(s.dir / "err.txt").empty());
}

TEST_CASE("on a terminal, progress is a bar with the time left, redrawn in place", "[cli][ux][device]") {
  if (!mfv::test::device_runtime()) return;
  if (shell("command -v script").empty()) return;  // util-linux script gives the run a terminal
  Scratch s("mfv_tty");
  // stop the run once the bar has been drawn twice (or after 30 s on a
  // loaded machine); timeout passes the kill on to script and its child
  shell(
      fmt::format("timeout 30 script -qec '{0} {1}' /dev/null > {2} 2>&1 & pid=$!; t=0; while [ $t -lt 60 ]; do "
                  "if [ $(grep -o '% \\[' {2} | wc -l) -ge 2 ]; then break; fi; sleep 0.5; t=$((t+1)); done; "
                  "kill $pid 2>/dev/null; wait $pid",
                  MFV_BINARY, kLongRun, s / "tty.txt"));
  const std::string tty = slurp(s.dir / "tty.txt");
  INFO(tty.substr(0, 2000));
  CHECK(tty.find("\r\033[K") != std::string::npos);
  CHECK(tty.find("% [") != std::string::npos);
}

TEST_CASE("mfv run --baseline passes an unchanged model under another seed and catches a planted change",
          "[cli][ux][device][planted]") {
  if (!mfv::test::device_runtime()) return;
  Scratch s("mfv_baseline");
  const std::string args = "run --check furnace --model ggx/smith_ggx_correlated --samples 16384 ";
  auto before = run_mfv(args + "--out " + s / "before");
  REQUIRE(before.code == 0);
  const std::string base = " --baseline " + s / "before/results.json";
  auto same = run_mfv(args + "--seed 2" + base);
  INFO(same.out);
  CHECK(same.code == 0);
  CHECK(same.out.find("384 values compared") != std::string::npos);
  CHECK(same.out.find(": 0 moved") != std::string::npos);

  // G scaled by 0.9: every albedo drops by 10 %, still <= 1; the baseline sees
  // each integral move by ~7 combined standard errors (and the furnace's
  // two-sided pool against the quadrature truth fails the gate as well)
  const mfv::test::PlantedKernelDir dir("terms_g.cl",
                                        "real g = R(1.0) / (R(1.0) + Lambda_ggx(NoL, alpha) + Lambda_ggx(NoV, alpha));",
                                        "real g = R(0.9) / (R(1.0) + Lambda_ggx(NoL, alpha) + Lambda_ggx(NoV, alpha));");
  // the plant is in the kernel only: leave out the same-sample reference
  // comparison, which would catch it, to test the baseline alone
  auto moved = run_mfv("--kernel-dir " + dir.path() + " " + args + "--reference-samples 0" + base);
  INFO(moved.out);
  CHECK(moved.code == 1);
  CHECK(moved.out.find("gate: FAILED") != std::string::npos);
  CHECK(moved.out.find("MOVED furnace ggx/smith_ggx_correlated/none") != std::string::npos);
}

TEST_CASE("mfv run --baseline rejects what is not a usable results.json with one line and exit 2", "[cli][ux]") {
  struct Case {
    std::string baseline, more, says;  // the file given to --baseline, further options
  };
  auto c = GENERATE(Case{"missing.json", "", "cannot read the file"}, Case{"text.json", "", "--baseline is not JSON"},
                    Case{"energy.json", "", "is not an mfv run results.json"},
                    Case{"energy.json", " --baseline-alpha-fw 0", "--baseline-alpha-fw"},
                    Case{"empty.json", " --check d_norm --model ggx", "--baseline shares no integral with this run"});
  Scratch s("mfv_baseline_bad");  // after GENERATE: Catch2 runs the body once per case
  std::ofstream(s / "energy.json") << R"({"schema": "mfv-energy/1", "results": []})";
  std::ofstream(s / "text.json") << "not json";
  std::ofstream(s / "empty.json") << R"({"schema": "mfv-run/1", "results": []})";
  auto r = run_mfv("run --baseline " + s / c.baseline + c.more);
  INFO(r.out);
  CHECK(r.code == 2);
  CHECK(r.out.find("mfv: error:") != std::string::npos);
  CHECK(r.out.find(c.says) != std::string::npos);
}

TEST_CASE(
    "mfv samplers draws an observed/expected/difference image of a failed chi-square test, and of every "
    "test with --plots",
    "[cli][ux][samplers][planted]") {
  if (shell("command -v gnuplot").empty()) return;
  Scratch s("mfv_sampler_plots");
  const std::string small = " samplers --samples 65536 --bins 16x32 --device-only --out ";
  // the Cauchy slopes' inverse CDF turned into GGX's (as tests/test_samplers.cpp)
  const mfv::test::PlantedKernelDir dir("estimators.cl", "sqrt(u_r * (R(2.0) - u_r))", "sqrt(u_r * (R(1.0) - u_r))");
  // the sizes of tests/test_samplers.cpp, where this plant is known to fail
  auto bad = run_mfv("--kernel-dir " + dir.path() + " samplers --samples 262144 --device-only --out " + s / "bad");
  INFO(bad.out);
  CHECK(bad.code == 1);
  const fs::path png = s.dir / "bad/plots/chi2_cauchy_slopes_w0.3_cos1_device.png";
  CHECK(is_png(slurp(png)));
  CHECK(slurp(fs::path(png).replace_extension(".svg")).find("observed") != std::string::npos);
  CHECK(slurp(s.dir / "bad/samplers.json").find("plots/chi2_cauchy_slopes") != std::string::npos);
  CHECK(!fs::exists(s.dir / "bad/plots/chi2_cosine_w1_cos1_device.png"));  // passed: no image by default

  auto all = run_mfv(small + s / "all --plots");
  INFO(all.out);
  CHECK(all.code == 0);
  CHECK(is_png(slurp(s.dir / "all/plots/chi2_cosine_w1_cos1_device.png")));

  auto no_out = run_mfv("samplers --plots");
  CHECK(no_out.code == 2);
  CHECK(no_out.out.find("--plots needs --out") != std::string::npos);
}

TEST_CASE("energy plots come as PNG and SVG with their labels set as text, not as accidental subscripts",
          "[cli][ux][energy]") {
  if (shell("command -v gnuplot").empty()) return;
  Scratch s("mfv_energy_plots");
  auto r = run_mfv("--quiet energy --models ggx/smith_ggx_correlated --grid 4x4 --max-points 1024 --out " + s / "e");
  INFO(r.out);
  REQUIRE(r.code == 0);
  for (const char* f : {"heat_ggx", "curves_ggx", "eavg"}) {
    CHECK(is_png(slurp(s.dir / "e/plots" / (std::string(f) + ".png"))));
    CHECK(fs::exists(s.dir / "e/plots" / (std::string(f) + ".svg")));
  }
  // enhanced text: "E_avg" drew "E" + subscript "a" + "vg"; E_{avg} draws "avg" as one subscript
  const std::string eavg = slurp(s.dir / "e/plots/eavg.svg");
  CHECK(eavg.find(">avg<") != std::string::npos);
  CHECK(eavg.find(">vg<") == std::string::npos);
  const std::string heat = slurp(s.dir / "e/plots/heat_ggx.svg");
  CHECK(heat.find(">view<") != std::string::npos);
  CHECK(heat.find(">iew") == std::string::npos);
}
