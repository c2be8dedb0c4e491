// The options several commands share (host/cli/shared_options.hpp) are
// registered once: each bad value gets the same one-line error and exit 2 on
// every command that takes the option, before any work.
#include "run_mfv.hpp"

#include <catch2/catch.hpp>

#include <string>

using mfv::test::run_mfv;

namespace {

const std::string kScene = std::string(MFV_TEST_DATA_DIR) + "/scene.gltf";
const std::string kBrdf = std::string(MFV_TEST_DATA_DIR) + "/../../examples/brdf/ggx.cl";

}  // namespace

TEST_CASE("A shared option's bad value gets the same one-line error on every command that takes it", "[cli][errors]") {
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"run --samples 0", "--samples must be a positive count, not 0"},
      {"check --brdf " + kBrdf + " --samples -3", "--samples must be a positive count, not -3"},
      {"run --alpha-fw 0.9", "--alpha-fw: Value 0.9 not in range"},
      {"check --brdf " + kBrdf + " --alpha-fw 0", "--alpha-fw: Value 0 not in range"},
      {"run --baseline-alpha-fw 0.6", "--baseline-alpha-fw: Value 0.6 not in range"},
      {"energy --alpha-fw 0.6", "--alpha-fw: Value 0.6 not in range"},
      {"energy --grid 3y3", "--grid '3y3': expected MUxALPHA, e.g. 32x32"},
      {"samplers --bins 64x", "--bins '64x': expected COSxPHI, e.g. 64x128"},
      {"stability --only ggx --scene " + kScene, "--only and --scene cannot be combined: the scene chooses the cases"},
      {"run --model ggx --scene " + kScene, "--model and --scene cannot be combined: the scene chooses the models"},
      {"energy --models ggx --scene " + kScene,
       "--models and --scene cannot be combined: the scene chooses the models"},
      {"agree --seed -1", "--seed"},
      {"bench --seed 1.5", "--seed"},
  };
  for (const auto& c : cases) {
    CAPTURE(c.args);
    const auto r = run_mfv("--quiet " + c.args);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
    CHECK(r.out.find('\n') == r.out.size() - 1);
    CHECK(r.out.find(c.says) != std::string::npos);
  }
  for (const char* command : {"stability", "run", "samplers", "bench", "energy", "agree"}) {
    CAPTURE(command);
    const auto r = run_mfv(std::string("--quiet ") + command + " --out ''");
    CHECK(r.code == 2);
    CHECK(r.out == "mfv: error: --out: the value is empty (see 'mfv --help')\n");
  }
}

TEST_CASE("Every command describes a shared option in the same words", "[cli]") {
  for (const char* command : {"agree", "run", "check", "samplers", "bench", "convergence", "energy"}) {
    CAPTURE(command);
    CHECK(run_mfv(std::string(command) + " --help").out.find("--seed UINT                 Philox key") !=
          std::string::npos);
  }
  for (const char* command : {"agree", "stability", "eval"}) {
    CAPTURE(command);
    CHECK(run_mfv(std::string(command) + " --help").out.find("run the kernels in double (device needs cl_khr_fp64)") !=
          std::string::npos);
  }
}
