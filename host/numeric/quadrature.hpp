// Gauss-Legendre rules, for the deterministic quadratures that give the
// high-accuracy values checks compare against.
#pragma once

#include <vector>

namespace mfv {

struct GaussRule {
  std::vector<double> x, w;  // nodes and weights on [-1, 1]
};

// The n-point Gauss-Legendre rule, nodes by Newton's method on P_n
// (Golub & Welsch give the same nodes; this is Numerical Recipes §4.6 gauleg).
GaussRule gauss_legendre(int n);

// Panel edges on [0, 1] in t, geometric towards t = 0 from `t_min` (so a
// peak of width ~t_min at t = 0 is resolved), `per_decade` panels a decade,
// with [0, t_min] as the first panel.
std::vector<double> geometric_panels(double t_min, int per_decade);

}  // namespace mfv
