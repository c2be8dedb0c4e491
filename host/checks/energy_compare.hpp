// mfv energy --compare (issue 33): a team's shipped table, read in an engine
// layout (checks/energy_layouts.hpp), against mfv's values on the same cells;
// docs/energy-layouts.md. Each cell's deviation is in units of its total
// uncertainty: mfv's standard error plus, as bias bounds (stats/verdict.hpp
// total_uncertainty), mfv's float rounding and the table's own precision
// (half a unit of its last printed digit, of an image's quantization, of a
// float literal's storage); a table that states its own standard errors (a
// CSV's <q>_se column) adds them to mfv's in quadrature. Holm's step-down over every cell keeps the
// family-wise false-alarm rate at alpha_fw.
#pragma once

#include "checks/energy.hpp"
#include "checks/energy_layouts.hpp"

#include <string>
#include <vector>

namespace mfv {

// One quantity of a team's table on the layout's cells: E, A or B per cell
// (index a * n_mu + m) or E_avg per width (index a).
struct TheirTable {
  std::string file, quantity;
  std::vector<double> value, precision;  // per cell: the value and half a unit of its last digit
  std::vector<double> se;                // per cell: the standard error the table states (a CSV's <q>_se), or 0
  std::vector<std::string> where;        // per cell: "row 12", "element 37", "pixel (3, 5) channel G"
};

// Reads `path` as the layout's table on axes mu x alpha (rep's; a glass
// layout's widths are its (eta, roughness) pairs, `eta` per width): a CSV with a
// header (mu and roughness, r or alpha columns, an eta column for a glass
// layout, and the layout's quantities, any row order), a C/C++ array literal file (.h, .hpp, .c, .cpp, .inl: flat lists
// in the layout's order) or an image (.png). Throws mfv::Error naming the
// file, row and field on bad input; never returns a partial table.
std::vector<TheirTable> read_their_table(const std::string& path, const EnergyLayout& layout,
                                         const std::vector<double>& mu, const std::vector<double>& alpha,
                                         const std::vector<double>& roughness, const std::vector<double>& eta = {});

struct CompareCell {
  std::string quantity, where;  // where: the file's place for it
  size_t a = 0, m = 0;          // width and view index (m unused for E_avg)
  double theirs = 0, ours = 0, se = 0, rounding = 0, precision = 0;  // se: mfv's ⊕ the table's stated one
  double total = 0, z = 0, p = 1;  // total uncertainty, deviation in units of it, two-sided p (Student t, R - 1 dof)
  // One-sided (p of z < 0 only): a glass cell whose E_T mfv's estimate can
  // only underestimate (light leaving beyond the critical angle, below).
  bool one_sided = false;
  bool fails = false;              // rejected by Holm's step-down at alpha_fw
};

struct CompareResult {
  std::string file, layout, table;  // table: d/g
  std::vector<CompareCell> cells;   // in the table's order
  double alpha_fw = 1e-3;
  size_t failed = 0;
  bool pass() const { return failed == 0; }
  std::vector<size_t> worst_first() const;  // cell indices by |z|, largest first
};

// mfv's rounding bound of a table value v at width index a: float32
// kernels, |v| (ulps of D and G + the estimator's 16) 2^-24; double ones
// 2^-53 in place of 2^-24. A glass table: |v| (the BSDF's ulps + 16) u
// (1 + eta)/|eta - 1| max(1, 2/alpha): the half vector of a refraction is
// the normalized eta_i i + eta_o o, whose length cancels to |eta - 1| where o
// nears -i (a tilt of (1 + eta)/|eta - 1| units, docs/transmission.md), and
// D's relative change per radian of tilt is at most 2/alpha (GGX, Beckmann).
double energy_rounding_bound(const EnergyReport& rep, const EnergyTable& t, size_t a, double v);

// Where a glass table's mfv value of quantity q at (width a, mu m) is only a
// lower bound: light leaving (eta < 1) beyond the critical angle (mu <
// sqrt(1 - eta²)) is transmitted through facets tilted past it, a rare event
// for bsdf_furnace's proposal at small widths and grazing mu, whose misses
// its standard error does not show (docs/transmission.md); E and E_T there,
// and E_avg of every leaving width. E_R (= E - E_T on the same points) is not.
bool glass_lower_bound_only(const EnergyReport& rep, const std::string& q, size_t a, size_t m);

// The comparison of `theirs` with rep's one table (rep.tables.size() == 1).
CompareResult compare_their_table(const EnergyReport& rep, const std::vector<TheirTable>& theirs, double alpha_fw);

}  // namespace mfv
