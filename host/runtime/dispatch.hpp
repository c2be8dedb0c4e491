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

struct TermSelection {
  std::vector<const Term*> d, g, f;
  bool g1 = false;                   // also emit eval_G1 for the Smith G terms in g
  std::vector<const Model*> models;  // whole models: eval_model(id, ...), id = Model::number()
  static TermSelection all();        // every term and every model
};

int term_index(const Term& t);  // the id the kernels receive
std::string generate_dispatch(const TermSelection& s);

}  // namespace mfv
