// mfv run --profile: the grids' density. "default" is the CI-sized run;
// "deep" (density 3, over 10^6 integrals) puts two more points between
// neighbours of every width and F-parameter grid and three times the view
// cosines and light directions, over every D x G x F and whole-model case
// (docs/scale.md). mfv run --dry-run: the plan's size and its time on this
// device from a short calibration launch.
#pragma once

#include "catalog/catalog.hpp"
#include "checks/suite.hpp"

#include <string>
#include <vector>

namespace mfv {

// The density of --profile NAME (default 1, deep 3); throws mfv::Error naming the profiles.
int profile_density(const std::string& name);

// `v` (sorted, positive or with a leading 0) with density - 1 points between
// neighbours: geometric where both are positive, else arithmetic.
std::vector<double> densify(const std::vector<double>& v, int density);
// The same for F's check points (both parameters), labelled "name=value".
std::vector<ParamPoint> densify_points(const Term& f, int density);

// Every plan cut to at most `per_plan` integrals spread over it (the
// calibration of --dry-run), without the reference.
SuitePlans sample_plans(const SuitePlans& sp, size_t per_plan);

}  // namespace mfv
