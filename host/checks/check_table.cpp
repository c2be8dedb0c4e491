#include "checks/check_table.hpp"

#include "catalog/roughness.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace mfv {

const std::vector<CheckRow>& dgf_check_rows() {
  // furnace and energy: the albedo by mfv run's MIS estimator on RQMC
  // replicates (IntegralKind::AlbedoMis, kernels/albedo.cl albedo_mis_microfacet)
  static const std::vector<CheckRow> rows = {
      {"d_norm",
       IntegralKind::DNorm,
       256 * kSuiteBaseSamples,
       0,
       0,
       FSet::None,
       {0.0},
       false,
       "holds for every D but those the catalog marks known_bad"},
      {"masking",
       IntegralKind::Masking,
       kSuiteBaseSamples,
       12,
       32,
       FSet::None,
       {0.0},
       false,
       "holds where G's Smith G1 belongs to D (Term::smith_for, within its tolerance and alpha_max) or G is "
       "normalised against every D (masking_exact); fails otherwise"},
      {"furnace",
       IntegralKind::AlbedoMis,
       kSuiteBaseSamples,
       12,
       32,
       FSet::None,
       {0.0},
       true,
       "holds for Smith Gs (and non-Smith Gs); fails where G's G1 under-masks D's tails (under_masks) or beyond "
       "the fit's alpha_max"},
      {"energy",
       IntegralKind::AlbedoMis,
       kSuiteBaseSamples / 2,
       6,
       24,
       FSet::Real,
       {0.0},
       true,
       "as furnace, but F <= 1 may hide a gain: may fail where furnace must"},
      {"energy_diffuse",
       IntegralKind::AlbedoMis,
       kSuiteBaseSamples / 2,
       3,
       8,
       FSet::Schlick,
       {0.5, 1.0},
       true,
       "seed 000's kd/pi + specular: fails at kd = 1 and F0 = 1, may fail below"},
  };
  return rows;
}

const std::vector<CheckRow>& energy_check_rows() {
  // RQMC replicates (IntegralKind::AlbedoRqmc / EavgRqmc, kernels/albedo.cl);
  // base_samples: points per replicate of the first pass (--min-points).
  static const std::vector<CheckRow> rows = {
      {"energy_mu",
       IntegralKind::AlbedoRqmc,
       1024,
       32,
       32,
       FSet::None,
       {0.0},
       true,
       "tables: measured, no verdict; whole models: E(mu) <= 1 beyond noise and float rounding (ModelCase::energy)"},
      {"energy_avg",
       IntegralKind::EavgRqmc,
       1024,
       32,
       0,
       FSet::None,
       {0.0},
       true,
       "measured, no verdict (cross-checked by the midpoint rule over energy_mu)"},
  };
  return rows;
}

const CheckRow& check_row(const std::string& check) {
  for (auto* rows : {&dgf_check_rows(), &energy_check_rows()})
    for (auto& r : *rows)
      if (check == r.check) return r;
  throw Error(fmt::format("internal: no check row named '{}'", check));
}

NativeWidths native_widths(const Term& d, const Term& g, double alpha) {
  NativeWidths w;
  w.pd = native_from_alpha(d.roughness, alpha);
  w.pg = g.params.empty() ? 0.0 : std::min(native_from_alpha(g.roughness, alpha), g.params[0].hi);
  return w;
}

}  // namespace mfv
