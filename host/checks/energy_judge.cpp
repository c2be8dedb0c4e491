// mfv energy's conclusions from its cells: the midpoint-rule cross-check of
// E_avg, the largest standard error and where, and whether a whole model gains energy.
#include "checks/energy_judge.hpp"

#include "stats/normal.hpp"
#include "stats/verdict.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mfv {

namespace {

// E_avg = 2 ∫ E(mu) mu dmu by the midpoint rule over the mu grid (cells
// E[0..n-1]), with its total uncertainty: the propagated standard error of
// the cells plus the rule's own error. Every third node is the midpoint of a
// cell three times wider, so the same values give the midpoint rule of width
// 3h over the first 3 floor(n/3) cells (the rest keep width h). The midpoint
// rule's error falls as width² (Davis & Rabinowitz 1984, §2.1.4), so
// |Q_3h - I| ~ 9 |Q_h - I| and |Q_3h - Q_h| bounds |Q_h - I| wherever the
// coarse rule is at least twice as wrong as the fine one. The noise-only SE
// left this out and read 9 SE off on the 32-point grid.
Cell eavg_by_midpoints(const std::vector<double>& mu, const Cell* E) {
  const size_t nm = mu.size();
  double s = 0, v = 0;
  for (size_t m = 0; m < nm; ++m) {
    const double w = 2.0 * mu[m] / double(nm);
    s += w * E[m].mean;
    v += w * w * E[m].se * E[m].se;
  }
  double coarse = 0;
  const size_t n3 = nm / 3 * 3;
  for (size_t m = 1; m < n3; m += 3) coarse += 3.0 * 2.0 * mu[m] / double(nm) * E[m].mean;
  for (size_t m = n3; m < nm; ++m) coarse += 2.0 * mu[m] / double(nm) * E[m].mean;
  const double rule_error = n3 > 0 ? std::fabs(coarse - s) : 0.0;
  return {s, stats::total_uncertainty(std::sqrt(v), rule_error)};
}

// Float32 rounding of E (issue 21: E = 1.0000 ± 1.9e-9 read as a gain). Each
// point's value f·cos/pdf is one float32 evaluation of the model, within
// Model::ulp_budget ulps of the double reference (measured by mfv agree),
// times the estimator's weight (cosine, two proposal densities, their MIS
// sum: under 16 operations of <= 1/2 ulp each, so <= 8 ulps; 16 allowed).
// Every value is >= 0 and the sums are in double (kernels/integrate.cl), so
// the mean's relative error is at most the per-point one: |ΔE| <= E (budget + 16) 2^-24.
double float_rounding_of_mean(const Model& m, double e) {
  constexpr double kWeightUlps = 16;
  return std::fabs(e) * (m.ulp_budget + kWeightUlps) * std::ldexp(1.0, -24);
}

}  // namespace

// A whole model gains energy where some E(mu) exceeds 1 + its rounding bound
// beyond its noise: one-sided Student t (R - 1 degrees of freedom) per cell,
// Bonferroni over every model cell of the run at family-wise rate
// opt.gain_alpha. A cell whose standard error stayed above target and whose
// upper bound (mean + 3 se, one-sided 99.87 % normal) exceeds 1 + rounding
// is unresolved: neither a gain nor ruled out (issue 21: max E 1.338 ± 0.21).
void judge_model_gains(EnergyReport& rep) {
  size_t cells = 0;
  for (auto& me : rep.models) cells += me.E.size();
  const double threshold = rep.opt.gain_alpha / double(std::max<size_t>(1, cells));
  const double df = rep.opt.replicates - 1;
  for (auto& me : rep.models) {
    me.max_at = 0;
    me.excess_p = 1;
    me.unresolved = false;
    for (size_t m = 0; m < me.E.size(); ++m) {
      const Cell& c = me.E[m];
      if (c.mean > me.E[me.max_at].mean || !std::isfinite(c.mean)) me.max_at = m;
      double p;
      const double one = 1.0 + float_rounding_of_mean(*me.point.model, c.mean);
      if (!std::isfinite(c.mean))
        p = c.mean > 0 || std::isnan(c.mean) ? 0 : 1;
      else if (c.se > 0)
        p = c.mean > one ? 0.5 * stats::student_t_two_sided_p((c.mean - one) / c.se, df) : 1;
      else
        p = c.mean > one ? 0 : 1;
      me.excess_p = std::min(me.excess_p, p);
      if (c.se > rep.opt.target && c.mean + 3.0 * c.se > one) me.unresolved = true;
    }
    me.gains = me.excess_p < threshold;
    me.unresolved = me.unresolved && !me.gains;
  }
}

// E_avg by the midpoint rule over the mu grid, as a cross-check of the
// dedicated integral (its error is the quadrature's O(1/n^2) plus noise).
void add_quadrature_cross_check(EnergyReport& rep) {
  const size_t nm = rep.mu.size();
  for (auto& t : rep.tables)
    for (size_t a = 0; a < rep.alpha.size(); ++a) t.eavg_quad[a] = eavg_by_midpoints(rep.mu, &t.E[a * nm]);
  for (auto& me : rep.models) me.eavg_quad = eavg_by_midpoints(rep.mu, me.E.data());
}

// The cells above the target standard error, and the largest error and where.
void track_largest_error(EnergyReport& rep) {
  auto consider = [&](const Cell& c, const std::string& where) {
    if (!(c.se <= rep.opt.target)) rep.above_target++;
    if (!(c.se <= rep.max_se)) {
      if (!std::isfinite(c.se) || c.se > rep.max_se) rep.max_se_at = where;
      rep.max_se = std::isfinite(c.se) ? c.se : std::numeric_limits<double>::infinity();
    }
  };
  const size_t nm = rep.mu.size();
  const std::vector<CellAt> cells = rep.cells();
  for (auto& t : rep.tables) {
    for (const CellAt& c : cells) {
      const std::string w = fmt::format("{} alpha={:.4g} mu={:.4g}", t.name(), rep.alpha[c.a], rep.mu[c.m]);
      consider(t.E[c.c], "E " + w);
      consider(t.A[c.c], "A " + w);
      consider(t.B[c.c], "B " + w);
    }
    for (size_t a = 0; a < rep.alpha.size(); ++a)
      consider(t.eavg[a], fmt::format("E_avg {} alpha={:.4g}", t.name(), rep.alpha[a]));
  }
  for (auto& me : rep.models) {
    for (size_t m = 0; m < nm; ++m) consider(me.E[m], fmt::format("E {} mu_l={:.4g}", me.point.name, rep.mu[m]));
    consider(me.eavg, "E_avg " + me.point.name);
  }
}

}  // namespace mfv
