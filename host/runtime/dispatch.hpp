// Generates the OpenCL C that routes a term id to its kernel function, for
// exactly the terms a program needs (docs/design.md §5: compile only what is
// needed). Ids are positions in catalog(); a program with one term of a kind
// calls it directly, so the switch disappears.
#pragma once

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"

#include <string>
#include <vector>

namespace mfv {

// A D and a G term by id (term_index), and whether the program specializes
// the RQMC albedo kernel to the pair too (mfv energy's tables; a run whose
// integrals of the pair are all AlbedoMis or masking leaves it out: one
// front-end compile fewer per pair, runtime/specialize.hpp fast_path_pairs).
struct TermPair {
  int d = 0, g = 0;
  bool rqmc = true;
  bool operator<(const TermPair& o) const { return d != o.d ? d < o.d : g < o.g; }
};

struct TermSelection {
  std::vector<const Term*> d, g, f;
  bool g1 = false;                   // also emit eval_G1 for the Smith G terms in g
  std::vector<const Model*> models;  // whole models: eval_model(id, ...), id = Model::number()
  // (D, G) pairs whose fast-path kernels the integration program specializes
  // (runtime/specialize.hpp; PoCL only): the pairs a run integrates.
  std::vector<TermPair> specialized;
  // Whole models' reciprocity kernels per model (model_reciprocity_values__mN, runtime/specialize.hpp;
  // PoCL only): where the run's pairs pay their compile (model_reciprocity_per_model_pays);
  // otherwise the generic reciprocity_values takes the whole models, the same floats.
  bool reciprocity_per_model = false;
  static TermSelection all();        // every term and every model
  void add(const TermSelection& o);  // o's terms, models and pairs not yet here, appended
};

int term_index(const Term& t);  // the id the kernels receive
std::string generate_dispatch(const TermSelection& s);

}  // namespace mfv
