#include "checks/energy_layouts.hpp"

#include "util/error.hpp"
#include "util/parse.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace mfv {

const std::vector<EnergyLayout>& energy_layouts() {
  static const std::vector<EnergyLayout> layouts = {
      // Kulla & Conty 2017 ("Revisiting physically based shading at Imageworks", §2.2):
      // E(mu, r) and E_avg(r) on cell edges, mu = y/(N-1), r = x/(N-1), alpha = r².
      {"kulla-conty", "edges", "edges", RoughnessAxis::R2, {"E", "E_avg"}, "ggx/smith_ggx_correlated",
       "Kulla & Conty 2017 §2.2 energy compensation: E(mu, r) and E_avg(r), mu = y/(N-1), r = x/(N-1), alpha = r^2",
       "E: gray (one channel), E_avg: a separate one-row image", "", 0},
      // Karis 2013 ("Real Shading in Unreal Engine 4", split sum) as engines bake
      // it: texel centres, x = NoV, y = perceptual roughness, alpha = r².
      {"split-sum", "centers", "centers", RoughnessAxis::R2, {"A", "B"}, "ggx/smith_ggx_correlated",
       "Karis 2013 split-sum DFG: E_F = F0 A + F90 B, mu = (x+1/2)/N, r = (y+1/2)/N, alpha = r^2",
       "R = A, G = B", "", 0},
      // Estevez & Kulla 2017 Charlie sheen with its visibility (KHR_materials_sheen
      // "Albedo-scaling"): E_sheen(mu, r), texel centres, alpha = r².
      {"sheen", "centers", "centers", RoughnessAxis::R2, {"E"}, "charlie/charlie_sheen",
       "Estevez & Kulla 2017 Charlie sheen E (KHR_materials_sheen albedo scaling): mu = (x+1/2)/N, r = (y+1/2)/N, "
       "alpha = r^2",
       "E: gray (one channel)", "", 0},
      // Walter et al. 2007 rough dielectric (eq. 20 reflection, eq. 21 transmission), flux form, as a
      // renderer's glass energy tables per (mu, roughness, eta) hold it: texel centres, alpha = r², eta
      // log-spaced over the BSDFs' declared range, entering (eta) and leaving (1/eta).
      {"glass", "centers", "centers", RoughnessAxis::R2, {"E", "E_R", "E_T", "E_avg"}, "walter_ggx_correlated",
       "Walter et al. 2007 rough dielectric flux: E = E_R + E_T of the light from mu; mu = (x+1/2)/N, "
       "r = (y+1/2)/N, alpha = r^2, eta: N indices log-spaced 1.01..100 and their inverses (leaving)",
       "E, E_R, E_T: R = E, G = E_R, B = E_T; an atlas of the 2N eta slices, N rows each, eta slowest", "log:1.01:100", 0},
      // The same, one side only: a renderer's entering table and its leaving (inverse-eta) table apart.
      {"glass-enter", "centers", "centers", RoughnessAxis::R2, {"E", "E_R", "E_T", "E_avg"}, "walter_ggx_correlated",
       "Walter et al. 2007 rough dielectric flux, entering: as glass, eta: N indices log-spaced 1.01..100",
       "E, E_R, E_T: R = E, G = E_R, B = E_T; an atlas of the N eta slices, N rows each, eta slowest", "log:1.01:100",
       +1},
      {"glass-leave", "centers", "centers", RoughnessAxis::R2, {"E", "E_R", "E_T", "E_avg"}, "walter_ggx_correlated",
       "Walter et al. 2007 rough dielectric flux, leaving: as glass, relative index 1/eta, eta: N indices log-spaced "
       "1.01..100 (1/eta ascending)",
       "E, E_R, E_T: R = E, G = E_R, B = E_T; an atlas of the N 1/eta slices, N rows each, 1/eta slowest",
       "log:1.01:100", -1},
  };
  return layouts;
}

std::string LayoutChoice::text() const { return fmt::format("{}:{}", layout->name, n); }

LayoutChoice parse_energy_layout(const std::string& text) {
  const std::vector<std::string> f = split(text, ':');
  std::string names;
  for (auto& l : energy_layouts()) names += (names.empty() ? "" : ", ") + l.name;
  LayoutChoice c;
  for (auto& l : energy_layouts())
    if (!f.empty() && l.name == f[0]) c.layout = &l;
  if (c.layout == nullptr || f.size() > 2 || text.back() == ':')
    throw Error(fmt::format("--layout '{}': want NAME or NAME:N, NAME one of {}", text, names));
  if (f.size() == 2) c.n = int(parse_unsigned("--layout N", f[1], 1024));
  if (c.n < 2) throw Error(fmt::format("--layout {}: N must be 2..1024", text));
  // a glass table's E_avg is the midpoint rule over its mu cells, whose error
  // bound compares it with the rule of 3 cells' width (checks/energy_judge.cpp)
  if (!c.layout->eta_form.empty() && c.n < 3)
    throw Error(fmt::format("--layout {}: N must be at least 3 (E_avg's midpoint rule needs 3 mu cells)", text));
  return c;
}

std::vector<double> layout_eta_axis(const EnergyLayout& l, int n) {
  if (l.eta_form.empty()) return {};
  const std::vector<double> in = parse_energy_axis("--layout eta", l.eta_form + ":" + std::to_string(n));
  std::vector<double> eta;
  if (l.eta_sides <= 0)
    for (size_t k = in.size(); k-- > 0;) eta.push_back(1.0 / in[k]);  // leaving: 1/eta, ascending
  if (l.eta_sides >= 0) eta.insert(eta.end(), in.begin(), in.end());
  return eta;
}

void apply_energy_layout(EnergyOptions& opt, const LayoutChoice& c) {
  const EnergyLayout& l = *c.layout;
  const std::string n = std::to_string(c.n);
  const std::vector<double> r = parse_energy_axis("--layout roughness", l.width_form + ":" + n);
  const std::vector<double> eta = layout_eta_axis(l, c.n);
  // a glass layout's widths are its (eta, roughness) pairs, eta slowest
  std::vector<double> widths, eta_of_width;
  for (size_t k = 0; k < std::max<size_t>(1, eta.size()); ++k)
    for (double x : r) {
      widths.push_back(x);
      if (!eta.empty()) eta_of_width.push_back(eta[k]);
    }
  set_energy_axes(opt, parse_energy_axis("--layout mu", l.mu_form + ":" + n), widths, l.param, false);
  opt.eta = eta_of_width;
  // the glass integrand's float32 rounding where |eta i + o| cancels (eta -> 1) has no derived
  // bound (docs/transmission.md); in double it is far below any target (docs/energy-layouts.md)
  if (!eta.empty()) opt.fp64 = true;
  opt.layout = c.text();
  if (opt.models.empty()) opt.models = {l.models};
  opt.catalog_models = false;  // a layout is a D x G table
}

const std::vector<Cell>& table_quantity(const EnergyTable& t, const std::string& q) {
  return q == "E" ? t.E : (q == "A" || q == "E_R") ? t.A : (q == "B" || q == "E_T") ? t.B : t.eavg;
}

bool layout_quantity_per_cell(const std::string& q) { return q != "E_avg"; }

}  // namespace mfv
