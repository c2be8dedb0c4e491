#include "checks/energy_layouts.hpp"

#include "util/error.hpp"
#include "util/parse.hpp"

#include <fmt/format.h>

namespace mfv {

const std::vector<EnergyLayout>& energy_layouts() {
  static const std::vector<EnergyLayout> layouts = {
      // Kulla & Conty 2017 ("Revisiting physically based shading at Imageworks", §2.2):
      // E(mu, r) and E_avg(r) on cell edges, mu = y/(N-1), r = x/(N-1), alpha = r².
      {"kulla-conty", "edges", "edges", RoughnessAxis::R2, {"E", "E_avg"}, "ggx/smith_ggx_correlated",
       "Kulla & Conty 2017 §2.2 energy compensation: E(mu, r) and E_avg(r), mu = y/(N-1), r = x/(N-1), alpha = r^2",
       "E: gray (one channel), E_avg: a separate one-row image"},
      // Karis 2013 ("Real Shading in Unreal Engine 4", split sum) as engines bake
      // it: texel centres, x = NoV, y = perceptual roughness, alpha = r².
      {"split-sum", "centers", "centers", RoughnessAxis::R2, {"A", "B"}, "ggx/smith_ggx_correlated",
       "Karis 2013 split-sum DFG: E_F = F0 A + F90 B, mu = (x+1/2)/N, r = (y+1/2)/N, alpha = r^2",
       "R = A, G = B"},
      // Estevez & Kulla 2017 Charlie sheen with its visibility (KHR_materials_sheen
      // "Albedo-scaling"): E_sheen(mu, r), texel centres, alpha = r².
      {"sheen", "centers", "centers", RoughnessAxis::R2, {"E"}, "charlie/charlie_sheen",
       "Estevez & Kulla 2017 Charlie sheen E (KHR_materials_sheen albedo scaling): mu = (x+1/2)/N, r = (y+1/2)/N, "
       "alpha = r^2",
       "E: gray (one channel)"},
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
  return c;
}

void apply_energy_layout(EnergyOptions& opt, const LayoutChoice& c) {
  const EnergyLayout& l = *c.layout;
  const std::string n = std::to_string(c.n);
  set_energy_axes(opt, parse_energy_axis("--layout mu", l.mu_form + ":" + n),
                  parse_energy_axis("--layout roughness", l.width_form + ":" + n), l.param, false);
  opt.layout = c.text();
  if (opt.models.empty()) opt.models = {l.models};
  opt.catalog_models = false;  // a layout is a D x G table
}

bool layout_quantity_per_cell(const std::string& q) { return q != "E_avg"; }

}  // namespace mfv
