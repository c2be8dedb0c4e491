#include "numeric/quadrature.hpp"

#include <cmath>

namespace mfv {

GaussRule gauss_legendre(int n) {
  GaussRule r;
  r.x.resize(n);
  r.w.resize(n);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p1 = 1, p2 = 0;
      for (int j = 1; j <= n; ++j) {  // P_j by the three-term recurrence
        const double p3 = p2;
        p2 = p1;
        p1 = ((2.0 * j - 1.0) * z * p2 - (j - 1.0) * p3) / j;
      }
      dp = n * (z * p1 - p2) / (z * z - 1.0);
      const double z1 = z;
      z = z1 - p1 / dp;
      if (std::fabs(z - z1) < 1e-15) break;
    }
    r.x[i] = -z;
    r.x[n - 1 - i] = z;
    r.w[i] = r.w[n - 1 - i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
  return r;
}

std::vector<double> geometric_panels(double t_min, int per_decade) {
  std::vector<double> e{0.0};
  const int decades = int(std::ceil(-std::log10(t_min)));
  for (int k = decades * per_decade; k >= 0; --k) e.push_back(std::pow(10.0, -double(k) / per_decade));
  return e;
}

}  // namespace mfv
