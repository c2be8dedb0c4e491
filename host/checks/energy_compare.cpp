// mfv energy --compare's verdict (checks/energy_compare.hpp).
#include "checks/energy_compare.hpp"

#include "stats/normal.hpp"
#include "stats/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mfv {

double energy_rounding_bound(const EnergyReport& rep, const EnergyTable& t, size_t a, double v) {
  // As float_rounding_of_mean (checks/energy_judge.cpp): each point's value
  // is one evaluation of D and G within their ulp budgets (mfv agree), times
  // the estimator's weight (<= 16 ulps), and the sums are in double, so the
  // mean's relative error is at most the per-point one.
  constexpr double kWeightUlps = 16;
  const double u = rep.opt.fp64 ? 0x1p-53 : 0x1p-24;
  if (!t.bsdf) return std::fabs(v) * (t.d->ulp_budget + t.g->ulp_budget + kWeightUlps) * u;
  const double eta = rep.opt.eta.at(a), alpha = energy_eval_alpha(*t.d, rep.alpha[a]);
  const double tilt = (1 + eta) / std::fabs(eta - 1) * std::max(1.0, 2.0 / alpha);
  return std::fabs(v) * (t.bsdf->ulp_budget + kWeightUlps) * u * tilt;
}

bool glass_lower_bound_only(const EnergyReport& rep, const std::string& q, size_t a, size_t m) {
  if (rep.opt.eta.empty() || q == "E_R" || rep.opt.eta.at(a) >= 1) return false;
  const double eta = rep.opt.eta[a];
  return q == "E_avg" || rep.mu[m] < std::sqrt(1 - eta * eta);
}

std::vector<size_t> CompareResult::worst_first() const {
  std::vector<size_t> at(cells.size());
  std::iota(at.begin(), at.end(), 0);
  std::stable_sort(at.begin(), at.end(), [&](size_t i, size_t j) {
    const double zi = std::isnan(cells[i].z) ? INFINITY : std::fabs(cells[i].z);
    const double zj = std::isnan(cells[j].z) ? INFINITY : std::fabs(cells[j].z);
    return zi > zj;
  });
  return at;
}

CompareResult compare_their_table(const EnergyReport& rep, const std::vector<TheirTable>& theirs, double alpha_fw) {
  const EnergyTable& t = rep.tables.at(0);
  const size_t nm = rep.mu.size();
  const double dof = rep.opt.replicates - 1;
  CompareResult r;
  r.layout = rep.opt.layout;
  r.table = t.name();
  r.alpha_fw = alpha_fw;
  for (const TheirTable& q : theirs) {
    r.file = q.file;
    const bool per_cell = layout_quantity_per_cell(q.quantity);
    const std::vector<Cell>& ours = table_quantity(t, q.quantity);
    for (size_t c = 0; c < q.value.size(); ++c) {
      CompareCell cell;
      cell.quantity = q.quantity;
      cell.where = q.where[c];
      cell.a = per_cell ? c / nm : c;
      cell.m = per_cell ? c % nm : 0;
      cell.theirs = q.value[c];
      cell.ours = ours[c].mean;
      cell.se = std::hypot(ours[c].se, q.se[c]);  // independent estimates: variances add
      cell.rounding = energy_rounding_bound(rep, t, cell.a, cell.ours);
      cell.precision = q.precision[c];
      // the two bias bounds add linearly to the standard error (stats/verdict.hpp)
      cell.total = stats::total_uncertainty(cell.se, cell.rounding + cell.precision);
      const double dev = cell.theirs - cell.ours;
      cell.z = cell.total > 0 ? dev / cell.total : (dev == 0 ? 0.0 : INFINITY);
      cell.p = std::isfinite(cell.z) ? stats::student_t_two_sided_p(cell.z, dof) : 0.0;
      cell.one_sided = glass_lower_bound_only(rep, q.quantity, cell.a, cell.m);
      if (cell.one_sided) cell.p = cell.z < 0 ? 0.5 * cell.p : 1.0;  // theirs above mfv's lower bound is no evidence
      r.cells.push_back(cell);
    }
  }
  // Holm 1979: the k-th smallest p (k = 0, 1, ...) is rejected while p <= alpha / (n - k).
  std::vector<size_t> by_p(r.cells.size());
  std::iota(by_p.begin(), by_p.end(), 0);
  std::stable_sort(by_p.begin(), by_p.end(), [&](size_t i, size_t j) { return r.cells[i].p < r.cells[j].p; });
  const size_t n = r.cells.size();
  for (size_t k = 0; k < n; ++k) {
    CompareCell& c = r.cells[by_p[k]];
    if (!(c.p <= alpha_fw / double(n - k))) break;
    c.fails = true;
    ++r.failed;
  }
  return r;
}

}  // namespace mfv
