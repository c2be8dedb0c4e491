// mfv energy --compare's verdict (checks/energy_compare.hpp).
#include "checks/energy_compare.hpp"

#include "stats/normal.hpp"
#include "stats/verdict.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mfv {

double energy_rounding_bound(const EnergyTable& t, double v, bool fp64) {
  // As float_rounding_of_mean (checks/energy_judge.cpp): each point's value
  // is one evaluation of D and G within their ulp budgets (mfv agree), times
  // the estimator's weight (<= 16 ulps), and the sums are in double, so the
  // mean's relative error is at most the per-point one.
  constexpr double kWeightUlps = 16;
  return std::fabs(v) * (t.d->ulp_budget + t.g->ulp_budget + kWeightUlps) * (fp64 ? 0x1p-53 : 0x1p-24);
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
    const std::vector<Cell>& ours = q.quantity == "E" ? t.E : q.quantity == "A" ? t.A : q.quantity == "B" ? t.B : t.eavg;
    for (size_t c = 0; c < q.value.size(); ++c) {
      CompareCell cell;
      cell.quantity = q.quantity;
      cell.where = q.where[c];
      cell.a = per_cell ? c / nm : c;
      cell.m = per_cell ? c % nm : 0;
      cell.theirs = q.value[c];
      cell.ours = ours[c].mean;
      cell.se = std::hypot(ours[c].se, q.se[c]);  // independent estimates: variances add
      cell.rounding = energy_rounding_bound(t, cell.ours, rep.opt.fp64);
      cell.precision = q.precision[c];
      // the two bias bounds add linearly to the standard error (stats/verdict.hpp)
      cell.total = stats::total_uncertainty(cell.se, cell.rounding + cell.precision);
      const double dev = cell.theirs - cell.ours;
      cell.z = cell.total > 0 ? dev / cell.total : (dev == 0 ? 0.0 : INFINITY);
      cell.p = std::isfinite(cell.z) ? stats::student_t_two_sided_p(cell.z, dof) : 0.0;
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
