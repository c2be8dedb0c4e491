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

// Reads `path` as the layout's table on axes mu x alpha (rep's): a CSV with a
// header (mu and roughness, r or alpha columns, and E, A, B or E_avg ones, any
// row order), a C/C++ array literal file (.h, .hpp, .c, .cpp, .inl: flat lists
// in the layout's order) or an image (.png). Throws mfv::Error naming the
// file, row and field on bad input; never returns a partial table.
std::vector<TheirTable> read_their_table(const std::string& path, const EnergyLayout& layout,
                                         const std::vector<double>& mu, const std::vector<double>& alpha,
                                         const std::vector<double>& roughness);

struct CompareCell {
  std::string quantity, where;  // where: the file's place for it
  size_t a = 0, m = 0;          // width and view index (m unused for E_avg)
  double theirs = 0, ours = 0, se = 0, rounding = 0, precision = 0;  // se: mfv's ⊕ the table's stated one
  double total = 0, z = 0, p = 1;  // total uncertainty, deviation in units of it, two-sided p (Student t, R - 1 dof)
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

// mfv's rounding bound of a table value v: float32 kernels, |v| (ulps of D
// and G + the estimator's 16) 2^-24; double ones 2^-53 in place of 2^-24.
double energy_rounding_bound(const EnergyTable& t, double v, bool fp64);

// The comparison of `theirs` with rep's one table (rep.tables.size() == 1).
CompareResult compare_their_table(const EnergyReport& rep, const std::vector<TheirTable>& theirs, double alpha_fw);

}  // namespace mfv
