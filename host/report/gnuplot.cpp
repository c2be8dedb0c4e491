#include "report/gnuplot.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace mfv {
namespace {

// The same script for the svg terminal: "set terminal pngcairo size W,H ..."
// becomes "set terminal svg size W,H dynamic ...", and every output '.png'
// becomes '.svg'.
std::string svg_twin(const std::string& png_script) {
  std::string s = std::regex_replace(png_script, std::regex("set terminal pngcairo size ([0-9]+),([0-9]+)"),
                                     "set terminal svg size $1,$2 dynamic");
  return std::regex_replace(s, std::regex("\\.png'"), ".svg'");
}

std::string svg_name(const std::string& png) { return png.substr(0, png.size() - 4) + ".svg"; }

}  // namespace

std::string gnuplot_literal(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (std::string("_^{}@&~").find(c) != std::string::npos) o += '\\';
    o += c;
  }
  return o;
}

std::string series_colour(size_t i) {
  // Okabe-Ito's eight colour-blind-safe colours, then four darker ones
  static const char* colours[] = {"#000000", "#e69f00", "#56b4e9", "#009e73", "#f0e442", "#0072b2",
                                  "#d55e00", "#cc79a7", "#7f7f7f", "#8c564b", "#17becf", "#9467bd"};
  return fmt::format("lc rgb '{}'", colours[i % (sizeof colours / sizeof colours[0])]);
}

NamedBytes render_gnuplot(const NamedBytes& inputs, const std::string& script,
                          const std::vector<std::string>& outputs) {
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
  std::ofstream(scratch / "plots.gp") << script << "\n" << svg_twin(script);
  NamedBytes made;
  const std::string run = fmt::format("cd '{}' && gnuplot plots.gp > gnuplot.log 2>&1", scratch.string());
  if (std::system(run.c_str()) == 0) {
    for (const auto& png : outputs)
      for (const auto& name : {png, svg_name(png)}) {
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
