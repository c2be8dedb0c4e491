// mfv energy's conclusions from the cells of its tables and models (checks/energy_judge.cpp).
#pragma once

#include "checks/energy.hpp"

namespace mfv {

// A whole model gains energy where some E(mu) exceeds 1 plus its float
// rounding beyond its noise (ModelEnergy::gains, excess_p, unresolved).
void judge_model_gains(EnergyReport& rep);
// E_avg by the midpoint rule over the mu grid (eavg_quad), with noise and rule error.
void add_quadrature_cross_check(EnergyReport& rep);
// EnergyReport::above_target, max_se and max_se_at over every cell.
void track_largest_error(EnergyReport& rep);

}  // namespace mfv
