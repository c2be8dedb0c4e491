// Outputs of mfv energy: console summary, energy.json (schema mfv-energy/1),
// CSV per D x G, kulla_conty.h, report.md with gnuplot plots.
#pragma once

#include "checks/energy.hpp"
#include "runtime/opencl.hpp"

#include <string>
#include <utility>
#include <vector>

namespace mfv {

void print_energy_console(const EnergyReport& rep);
void print_baseline_console(const BaselineDiff& diff);

std::string energy_json(const EnergyReport& rep, const Runtime& rt);

// Every output file as (path, contents) under `dir`; plots are made with
// gnuplot when it is installed (otherwise one line is printed and the rest is
// still written). `baseline` may be null.
std::vector<std::pair<std::string, std::string>> energy_outputs(const EnergyReport& rep, const Runtime& rt,
                                                                const std::string& dir, const BaselineDiff* baseline);

}  // namespace mfv
