// The Ds of the form c(p) exp(e(p) log cos θ) (Phong, seed 004's rho form)
// from log cos θ, which a caller evaluating several widths at one half
// vector takes once (the furnace truth, checks/furnace_views.cpp, issue 30).
#pragma once

#include "reference/twins.hpp"

namespace mfv::ref {

using RefDlc = double (*)(double log_cos, double p);

// log cos θ from cos²θ and sin²θ as the _cs forms take it (cos² <= 1).
double log_cos_cs(double cos2, double sin2);
double D_phong_lc(double log_cos, double alpha_p);
double D_blinn_rho_lc(double log_cos, double rho);
// The form from log cos θ of the D whose ref_d_cs is `cs` (nullptr for the
// others): for cos2 > 0, cs(cos2, sin2, p) is lc(log_cos_cs(min(cos2, 1),
// sin2), p) bit for bit (tests/test_d_log_cos.cpp).
RefDlc d_of_log_cos(RefDcs cs);

}  // namespace mfv::ref
