// Fuzz target: scene and material files through their public loader,
// load_scene (issue 17). Every input must load or throw mfv::Error (one line,
// exit 2 at the command line); any other exception, a crash or (under
// cmake/Sanitize.cmake) a memory or UB error fails. A failing input is saved
// beside the build for replay: MFV_FUZZ_SEED=<seed> reproduces it.
#include "fuzz_util.hpp"

#include "scene/scene.hpp"
#include "util/error.hpp"

#include <nlohmann/json.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <typeinfo>

namespace fs = std::filesystem;

TEST_CASE("Scene and material files load or fail with mfv::Error, never otherwise", "[fuzz][scene]") {
  const fs::path dir = fs::temp_directory_path() / ("mfv_fuzz_scene_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  uint64_t loaded = 0, rejected = 0;
  uint64_t n =
      mfv::fuzz::run(mfv::fuzz::corpus("scene"), [&](const fs::path& from, const std::string& input, uint64_t seed) {
        const fs::path path = dir / ("input" + from.extension().string());
        std::ofstream(path, std::ios::binary | std::ios::trunc) << input;
        try {
          mfv::load_scene(path.string());
          ++loaded;
        } catch (const mfv::Error&) {
          ++rejected;
        } catch (const std::exception& e) {
          const fs::path keep =
              fs::current_path() / ("fuzz-scene-failure-" + std::to_string(seed) + from.extension().string());
          fs::copy_file(path, keep, fs::copy_options::overwrite_existing);
          FAIL("seed " << seed << " (" << from.filename() << "): " << typeid(e).name() << ": " << e.what()
                       << "; input saved as " << keep);
        }
      });
  fs::remove_all(dir);
  INFO(n << " inputs: " << loaded << " loaded, " << rejected << " rejected");
  CHECK(n > 0);
  CHECK(rejected > 0);  // the mutations reach the error paths
}
