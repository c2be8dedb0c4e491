// mfv energy's plan: the D x G tables and whole-model points a run
// integrates (their cells not yet run), and their integrals: one unit per
// row of energy_check_rows() (checks/check_table.hpp) and cell, described by
// spec_of / model_spec (checks/integrate.hpp), each on Philox streams of its own.
#pragma once

#include "checks/energy.hpp"
#include "runtime/integrator.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace mfv {

// The tables' D x G pairs: every D x G of the shared-width grid, and each own
// lobe (the sheen) with its G, whose table is E_sheen (KHR_materials_sheen's albedo scaling).
std::vector<std::pair<const Term*, const Term*>> energy_table_pairs();

// One quantity the runs refine: an E/B cell (row energy_mu: one integral per
// replicate yields E and, on the same points, B) or an E_avg (row
// energy_avg), of a table or of a whole model (E only).
struct EnergyUnit {
  size_t table, index;  // table (or rep.models) index; cell index a * n_mu + m, alpha index or mu index
  bool eavg;
  IntegralSpec base;  // its stream is first_stream + the replicate
  uint32_t first_stream;
  bool model = false;  // `table` indexes rep.models
  // A glass cell: `base` integrates E (both lobes) and `second` E_T on the
  // same streams, hence the same points (E_R = E - E_T, as A = E - B).
  bool has_second = false;
  IntegralSpec second{};
};

// rep.tables and rep.models as rep.opt selects them (cells not yet run), and
// the terms and models their integrals need. Throws mfv::Error when nothing is selected.
TermSelection add_energy_subjects(EnergyReport& rep);

// Every unit of rep's tables, then of its models, in record order, with
// opt.replicates streams each from stream 0 on; `next_stream` gets the first free one.
std::vector<EnergyUnit> energy_units(const EnergyReport& rep, uint32_t& next_stream);

// A unit's R replicate integrals, on streams first_stream + r (then, for a
// glass cell, its second integral's R on the same streams).
std::vector<IntegralSpec> specs_of(const EnergyUnit& u, size_t R);

}  // namespace mfv
