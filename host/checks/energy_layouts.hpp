// The tables engines ship, as mfv energy layouts (issue 33; docs/energy-layouts.md):
// each names its axes (mu and a width, as range forms of energy_axes.hpp),
// the width's parametrization, the quantities a cell holds, the D/G it is
// made of by default, and the order of a flat array. A layout with an index
// of refraction axis (glass tables) adds an `eta` axis here.
#pragma once

#include "checks/energy_axes.hpp"

#include <string>
#include <vector>

namespace mfv {

struct EnergyLayout {
  std::string name;
  std::string mu_form, width_form;      // range forms with N left out: "edges", "centers"
  RoughnessAxis param;                  // the width axis: alpha, or r with alpha = r²
  std::vector<std::string> quantities;  // per cell (E, A, B) or per width (E_avg)
  std::string models;                   // the D/G it is made of unless --models says
  std::string source;                   // who ships it, and where it is defined
  std::string image_channels;           // what a PNG/EXR of it holds, channel by channel
  // A glass layout's index axis: a range form with N left out ("log:1.01:100"),
  // the relative indices entered; the layout holds them and their inverses
  // (leaving), ascending. Empty: no eta axis.
  std::string eta_form;
  int eta_sides = 0;  // with eta_form: 0 both (1/eta then eta), +1 entering only, -1 leaving only
};

const std::vector<EnergyLayout>& energy_layouts();

// A layout and its size: "NAME" (N = 32) or "NAME:N".
struct LayoutChoice {
  const EnergyLayout* layout = nullptr;
  int n = 32;
  std::string text() const;  // "kulla-conty:32"
};
LayoutChoice parse_energy_layout(const std::string& text);

// Sets opt's axes, layout name and (when opt.models is empty) its models.
void apply_energy_layout(EnergyOptions& opt, const LayoutChoice& choice);

// A layout's eta axis at size n: the inverses of the entered indices, then
// the indices, ascending (empty without an eta axis).
std::vector<double> layout_eta_axis(const EnergyLayout& l, int n);

// A table's cells of quantity q: E; A or E_R (a glass table keeps E_R in A);
// B or E_T (in B); E_avg.
const std::vector<Cell>& table_quantity(const EnergyTable& t, const std::string& q);

// A cell quantity (E, A, B, E_R, E_T) or a per-width one (E_avg).
bool layout_quantity_per_cell(const std::string& q);

}  // namespace mfv
