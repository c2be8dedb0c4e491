#include "report/sampler_plots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace mfv {
namespace {

// The relative index of a transmission sampler (Flux), "" for the others.
std::string eta_of(const SamplerResult& r, const char* sep) {
  return r.c.sampler == Sampler::Flux ? fmt::format("{}{:.4g}", sep, r.c.eta) : "";
}

std::string stem_of(const SamplerResult& r) {
  return fmt::format("chi2_{}_w{:g}_cos{:g}{}_{}", sampler_name(r.c.sampler), r.c.width, r.c.cos_o, eta_of(r, "_eta"),
                     r.impl);
}

// (observed - expected) / sqrt(expected) of cell k; a cell with nothing
// expected holds impossible draws, shown as their count.
double standardized(const SamplerResult& r, size_t k) {
  const double obs = r.observed[k], exp = r.expected[k];
  return exp > 0 ? (obs - exp) / std::sqrt(exp) : obs;
}

// One row per cell: phi at the cell centre (deg), cos theta at the cell
// centre, observed, expected, standardized difference; a blank line per cos
// theta row (gnuplot's grid format for `with image`).
std::string cells_text(const SamplerResult& r) {
  std::string o;
  const double dz = (1.0 - r.cos_low) / r.cos_bins, dp = 360.0 / r.phi_bins;
  for (int iz = 0; iz < r.cos_bins; ++iz) {
    for (int ip = 0; ip < r.phi_bins; ++ip) {
      const size_t k = size_t(iz) * r.phi_bins + ip;
      o += fmt::format("{:.6g} {:.6g} {:.6g} {:.6g} {:.6g}\n", (ip + 0.5) * dp, r.cos_low + (iz + 0.5) * dz,
                       r.observed[k], r.expected[k], standardized(r, k));
    }
    o += "\n";
  }
  return o;
}

// Colour ranges: observed and expected on one scale; the differences on a
// symmetric one, so white is 0.
std::pair<double, double> ranges_of(const SamplerResult& r) {
  double counts = 1, diff = 1;
  for (size_t k = 0; k < r.observed.size(); ++k) {
    counts = std::max({counts, r.observed[k], r.expected[k]});
    diff = std::max(diff, std::fabs(standardized(r, k)));
  }
  return {counts, diff};
}

std::string script_of(const SamplerResult& r, const std::string& stem) {
  const auto [counts, diff] = ranges_of(r);
  std::string gp = fmt::format("set terminal pngcairo size 1500,460 font ',9'\nset output '{}.png'\n", stem);
  gp += fmt::format("set multiplot layout 1,3 title '{}: χ^2 = {:.1f}, {} dof, p = {:.3g} (level {:.3g}): {}'\n",
                    gnuplot_literal(fmt::format("{} w = {:g}, cos_o = {:g}{}, {} draws", sampler_name(r.c.sampler),
                                                r.c.width, r.c.cos_o, eta_of(r, ", eta = "), r.impl)),
                    r.chi2, r.dof, r.p_value, r.level, r.pass() ? "pass" : "FAIL");
  gp += "set xlabel 'φ (deg)'\nset ylabel 'cos θ'\nset xrange [0:360]\n";
  gp += fmt::format("set yrange [{:g}:1]\nset palette rgb 33,13,10\nset cbrange [0:{:g}]\n", r.cos_low, counts);
  gp += fmt::format("set title 'observed'\nplot '{}.dat' using 1:2:3 with image notitle\n", stem);
  gp += fmt::format("set title 'expected (reference pdf)'\nplot '{}.dat' using 1:2:4 with image notitle\n", stem);
  // a diverging palette centred on 0 for the residuals
  gp += fmt::format("set palette defined (-1 '#2166ac', 0 '#f7f7f7', 1 '#b2182b')\nset cbrange [{:g}:{:g}]\n", -diff,
                    diff);
  gp += fmt::format("set title '(observed − expected) / √expected'\nplot '{}.dat' using 1:2:5 with image notitle\n",
                    stem);
  gp += "unset multiplot\nunset cbrange\n";
  return gp;
}

}  // namespace

NamedBytes sampler_plots(std::vector<SamplerResult>& results, bool all) {
  NamedBytes made;
  for (auto& r : results) {
    if (!all && r.pass()) continue;
    if (r.observed.empty()) continue;  // no histogram (no draws)
    const std::string stem = stem_of(r);
    NamedBytes images = render_gnuplot({{stem + ".dat", cells_text(r)}}, script_of(r, stem), {stem + ".png"});
    if (images.empty()) return made;  // gnuplot missing or failing: said once
    r.plot = stem + ".png";
    made.insert(made.end(), images.begin(), images.end());
  }
  return made;
}

}  // namespace mfv
