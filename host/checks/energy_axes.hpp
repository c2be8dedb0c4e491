// mfv energy's axes and points (issue 33): the values of an axis as a list or
// a range form, the roughness parametrization, and single (mu, alpha)
// points; docs/cli/energy.md "Axes and points". Errors are mfv::Error naming
// the option and the offending field.
#pragma once

#include "checks/energy.hpp"

#include <string>
#include <utility>
#include <vector>

namespace mfv {

// An axis: "0.1,0.5,1" (values in the given order), "lin:A:B:N" (N values
// from A to B, both included), "log:A:B:N" (N values log-spaced from A to B,
// both included, A, B > 0), "centers:N" ((i + 1/2)/N) or "edges:N"
// (i/(N-1), N >= 2). `what` names the option in messages.
std::vector<double> parse_energy_axis(const std::string& what, const std::string& text);

// "MU,ALPHA" (mfv energy --at).
std::pair<double, double> parse_energy_point(const std::string& text);

// How the caller's width values read: the width alpha itself, or the
// perceptual roughness r with alpha = r² (Burley 2012).
enum class RoughnessAxis { Alpha, R2 };
RoughnessAxis parse_roughness_axis(const std::string& text);

// Sets opt's axes from the caller's mu and width values (a grid), or from
// points (paired); widths read as `param` says. Validates the values: mu in
// [0, 1], alpha in [0, 10] (0: a mirror, see energy_eval_alpha), finite.
void set_energy_axes(EnergyOptions& opt, const std::vector<double>& mu, const std::vector<double>& width,
                     RoughnessAxis param, bool paired);

}  // namespace mfv
