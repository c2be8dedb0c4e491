// mfv energy --layout's own table in the engine's layout (docs/energy-layouts.md):
// CSV, a C/C++ array file and a 16-bit PNG per quantity group, which
// `mfv energy --compare` reads back; and --compare's report: console (worst
// cells first), compare.csv and a heat map of the deviations in units of total uncertainty.
#pragma once

#include "checks/energy_compare.hpp"
#include "report/gnuplot.hpp"

#include <string>
#include <utility>
#include <vector>

namespace mfv {

// Files (path, bytes) under dir/layout/ for rep, run on a layout's axes.
std::vector<std::pair<std::string, std::string>> energy_layout_files(const EnergyReport& rep, const EnergyLayout& l,
                                                                     const std::string& dir);

// A 16-bit PNG of w x h pixels, `channels` (1 = gray, 3 = RGB) interleaved values in [0, 1], row 0 first.
std::string png16(const std::vector<double>& v, size_t w, size_t h, size_t channels);

void print_compare_console(const CompareResult& r);
// compare.csv, compare.json and plots/compare_heat_<quantity>.png (gnuplot: where installed).
std::vector<std::pair<std::string, std::string>> compare_files(const CompareResult& r, const EnergyReport& rep,
                                                               const std::string& dir);

}  // namespace mfv
