#include "report/gnuplot.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace mfv {

NamedBytes render_gnuplot(const NamedBytes& inputs, const std::string& script, const std::vector<std::string>& outputs) {
  namespace fs = std::filesystem;
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    fmt::print("gnuplot not found: plots skipped (install gnuplot-nox); tables and report still written\n");
    return {};
  }
  static std::atomic<int> counter{0};
  const fs::path scratch = fs::temp_directory_path() / fmt::format("mfv_gnuplot_{}_{}", ::getpid(), counter++);
  fs::remove_all(scratch);
  fs::create_directories(scratch);
  for (const auto& [name, text] : inputs) std::ofstream(scratch / name) << text;
  std::ofstream(scratch / "plots.gp") << script;
  NamedBytes made;
  const std::string run = fmt::format("cd '{}' && gnuplot plots.gp > gnuplot.log 2>&1", scratch.string());
  if (std::system(run.c_str()) == 0) {
    for (const auto& name : outputs) {
      std::ifstream img(scratch / name, std::ios::binary);
      std::ostringstream bytes;
      bytes << img.rdbuf();
      made.push_back({name, bytes.str()});
    }
  } else {
    std::ifstream log(scratch / "gnuplot.log");
    std::string why;
    std::getline(log, why);
    fmt::print("gnuplot failed ({}): plots skipped; tables and report still written\n", why);
  }
  fs::remove_all(scratch);
  return made;
}

}  // namespace mfv
