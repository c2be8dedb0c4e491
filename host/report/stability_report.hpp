// mfv stability's outputs: the console summary, stability.json,
// stability.md and the error plots (gnuplot).
#pragma once

#include "checks/stability.hpp"

#include <string>
#include <vector>

namespace mfv {

std::string stability_console(const StabilityReport& rep);
std::string stability_json(const StabilityReport& rep);
std::string stability_markdown(const StabilityReport& rep);
// Writes stability.json, stability.md and the plot data under dir (whole or
// not at all), then the plots when gnuplot is found; returns one line per
// note to print (e.g. that gnuplot is missing).
std::vector<std::string> write_stability_outputs(const StabilityReport& rep, const std::string& dir);

}  // namespace mfv
