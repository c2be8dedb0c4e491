// mfv energy's plots: heat maps of 1 - E over (θ_view, α) and E(θ_view)
// curves per D, E_avg(α) across combinations (gnuplot, report/gnuplot.hpp).
#include "report/energy_plots.hpp"

#include "catalog/roughness.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mfv {

std::string energy_file_stem(const EnergyTable& t) { return t.bsdf ? t.bsdf->id : t.d->id + "__" + t.g->id; }

namespace {

// Per table: E over (θ, α) blocks (.dat) and E_avg over α (.avg).
// The plots' width coordinate: the caller's roughness r where it gave r (alpha = r²), else alpha.
double width_coord(const EnergyReport& rep, size_t a) {
  return rep.opt.roughness.empty() ? rep.alpha[a] : rep.opt.roughness[a];
}

NamedBytes plot_data(const EnergyReport& rep) {
  NamedBytes data;
  const size_t nm = rep.mu.size(), na = rep.alpha.size();
  for (auto& t : rep.tables) {
    std::string f, e;
    for (const CellAt& c : rep.cells()) {
      f += fmt::format("{:.6f} {:.9g} {:.9g} {:.9g}\n", std::acos(rep.mu[c.m]) * 180 / M_PI, width_coord(rep, c.a),
                       t.E[c.c].mean, 1 - t.E[c.c].mean);
      if (!rep.paired && c.m + 1 == nm) f += "\n";  // one block per alpha
    }
    for (size_t a = 0; a < na; ++a)
      e += fmt::format("{:.9g} {:.9g} {:.3e}\n", width_coord(rep, a), t.eavg[a].mean, t.eavg[a].se);
    data.push_back({energy_file_stem(t) + ".dat", f});
    data.push_back({energy_file_stem(t) + ".avg", e});
  }
  return data;
}

// Which alpha blocks the E(theta) curves show: those nearest 0.01, 0.1, 0.3, 1.
std::vector<size_t> curve_alphas(const std::vector<double>& alpha) {
  const size_t na = alpha.size();
  std::vector<size_t> cols;
  for (double s : {0.01, 0.1, 0.3, 1.0}) {
    size_t best = 0;
    for (size_t a = 0; a < na; ++a)
      if (std::fabs(std::log(alpha[a] / s)) < std::fabs(std::log(alpha[best] / s))) best = a;
    if (std::find(cols.begin(), cols.end(), best) == cols.end()) cols.push_back(best);
  }
  return cols;
}

// The heat maps of 1 - E (one panel per G) and the E(θ) curves for D `d`.
std::string d_plots(const EnergyReport& rep, const Term* d, const std::vector<size_t>& cols,
                    std::vector<std::string>& names) {
  std::string gp;
  std::vector<const EnergyTable*> ts;
  for (auto& t : rep.tables)
    if (t.d == d) ts.push_back(&t);
  const int n = int(ts.size());
  const int cols_n = int(std::ceil(std::sqrt(double(n)))), rows_n = (n + cols_n - 1) / cols_n;
  // heat maps of 1 - E over (theta, alpha), one panel per G
  std::string png = "heat_" + d->id + ".png";
  names.push_back(png);
  gp += fmt::format("set terminal pngcairo size {},{} font ',9'\nset output '{}'\n", 420 * cols_n, 340 * rows_n, png);
  gp += fmt::format("set multiplot layout {},{} title '1 − E(θ_{{view}}, α), D = {}, F = none (α = r^2)'\n", rows_n,
                    cols_n, gnuplot_literal(d->id));
  // x spans the data: the view cosines are cell midpoints (m + 1/2)/MU, so
  // the first lies at θ = acos(1 - 1/(2 MU)) (10° for 32 cells), not at 0
  // the default grid: log alpha 1e-3..1; the caller's axes or points: as given (linear)
  const bool given = !rep.opt.mu_axis.empty();
  gp += fmt::format("set view map\n{}set xlabel 'θ_{{view}} (deg)'\nset ylabel '{}'\nset cbrange [0:*]\n"
                    "set palette rgb 33,13,10\nset autoscale xfix\n{}",
                    given ? "" : "set logscale y\n", rep.opt.roughness.empty() ? "α" : "r (α = r^2)",
                    given ? "set autoscale yfix\n" : "set yrange [0.001:1]\n");
  for (auto* t : ts)
    gp += fmt::format("set title 'G = {}' noenhanced\nsplot '{}.dat' using 1:2:4 with {} notitle\n", t->g->id,
                      energy_file_stem(*t), rep.paired ? "points pt 7 ps 1.5 palette" : "pm3d");
  gp += "unset multiplot\nunset view\nunset logscale y\nunset cbrange\nunset yrange\nunset xrange\n";
  if (rep.paired) return gp;  // points: the scatter above is the plot
  // E(theta) curves for a few alpha, comparing the G terms
  png = "curves_" + d->id + ".png";
  names.push_back(png);
  const int pc = int(cols.size()) > 1 ? 2 : 1, pr = (int(cols.size()) + pc - 1) / pc;
  gp += fmt::format("set terminal pngcairo size {},{} font ',9'\nset output '{}'\n", 560 * pc, 400 * pr, png);
  gp += fmt::format("set multiplot layout {},{} title 'E(θ_{{view}}) with F = 1, D = {}: G terms compared'\n", pr, pc,
                    gnuplot_literal(d->id));
  gp += "set key left bottom noenhanced font ',7'\nset xlabel 'θ_{view} (deg)'\nset ylabel 'E'\nset xrange [0:90]\n";
  for (size_t c : cols) {
    gp += fmt::format("set title 'α = {:.3g} (r = {:.3g})'\nplot ", rep.alpha[c], perceptual_from_alpha(rep.alpha[c]));
    for (size_t i = 0; i < ts.size(); ++i)
      gp += fmt::format("{}'{}.dat' every :::{}::{} using 1:3 with linespoints pt 7 ps 0.4 {} title '{}'",
                        i ? ", " : "", energy_file_stem(*ts[i]), c, c, series_colour(i), ts[i]->g->id);
    gp += "\n";
  }
  gp += "unset multiplot\nunset xrange\n";
  return gp;
}

// E_avg(alpha) across combinations: one panel per D.
std::string eavg_plot(const EnergyReport& rep, const std::vector<const Term*>& ds, std::vector<std::string>& names) {
  std::string gp;
  names.push_back("eavg.png");
  const int n = int(ds.size()), pc = n > 1 ? 2 : 1, pr = (n + pc - 1) / pc;
  gp += fmt::format("set terminal pngcairo size {},{} font ',9'\nset output 'eavg.png'\n", 560 * pc, 400 * pr);
  gp += fmt::format("set multiplot layout {},{} title 'E_{{avg}}(α) = 2 ∫ E(μ) μ dμ, F = 1'\n", pr, pc);
  gp += fmt::format("{}set key left bottom noenhanced font ',7'\nset xlabel '{}'\nset ylabel 'E_{{avg}}'\n",
                    rep.opt.mu_axis.empty() ? "set logscale x\n" : "unset logscale x\n",
                    rep.opt.roughness.empty() ? "α (= r^2)" : "r (α = r^2)");
  for (auto* d : ds) {
    gp += fmt::format("set title 'D = {}' noenhanced\nplot ", d->id);
    size_t i = 0;
    for (auto& t : rep.tables)
      if (t.d == d) {
        gp += fmt::format("{}'{}.avg' using 1:2 with linespoints pt 7 ps 0.4 {} title '{}'", i ? ", " : "",
                          energy_file_stem(t), series_colour(i), t.g->id);
        ++i;
      }
    gp += "\n";
  }
  gp += "unset multiplot\n";
  return gp;
}

}  // namespace

NamedBytes energy_plots(const EnergyReport& rep, std::vector<std::string>& names) {
  std::vector<const Term*> ds;
  for (auto& t : rep.tables)
    if (std::find(ds.begin(), ds.end(), t.d) == ds.end()) ds.push_back(t.d);
  const std::vector<size_t> cols = curve_alphas(rep.alpha);
  std::string gp = "set encoding utf8\nset datafile missing 'nan'\n";
  for (auto* d : ds) gp += d_plots(rep, d, cols, names);
  gp += eavg_plot(rep, ds, names);
  NamedBytes made = render_gnuplot(plot_data(rep), gp, names);
  if (made.empty()) names.clear();
  return made;
}

}  // namespace mfv
