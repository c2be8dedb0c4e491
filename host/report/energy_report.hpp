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
// Every cell of the caller's axes or points (up to a screenful), each value with its standard error.
void print_energy_cells(const EnergyReport& rep);

// What alpha means, and how the grid was made (the default grid, or the caller's axes, points or layout).
extern const char* const kEnergyParam;
std::string energy_grid_text(const EnergyReport& rep);

// kulla_conty.h: E, A, B and E_avg as C/C++ arrays (report/energy_header.cpp).
std::string energy_c_header(const EnergyReport& rep);
void print_baseline_console(const BaselineDiff& diff);

std::string energy_json(const EnergyReport& rep, const Runtime& rt);

// Every output file as (path, contents) under `dir`; plots are made with
// gnuplot when it is installed (otherwise one line is printed and the rest is
// still written). `baseline` may be null.
std::vector<std::pair<std::string, std::string>> energy_outputs(const EnergyReport& rep, const Runtime& rt,
                                                                const std::string& dir, const BaselineDiff* baseline);

}  // namespace mfv
