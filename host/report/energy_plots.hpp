// mfv energy's plots, shown by its report.md (report/energy_report.cpp).
#pragma once

#include "checks/energy.hpp"
#include "report/gnuplot.hpp"

#include <string>
#include <vector>

namespace mfv {

// A D x G table's file name stem: "ggx__smith_ggx_correlated".
std::string energy_file_stem(const EnergyTable& t);

// The plots (PNG and SVG, report/gnuplot.hpp); `names` gets the PNGs the
// report shows. Nothing (with one printed line) where gnuplot is missing or fails.
NamedBytes energy_plots(const EnergyReport& rep, std::vector<std::string>& names);

}  // namespace mfv
