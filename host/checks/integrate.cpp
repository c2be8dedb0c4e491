#include "checks/integrate.hpp"

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "runtime/dispatch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mfv {

IntegralSpec spec_of(const MicrofacetIntegral& m) {
  IntegralSpec s;
  s.check = static_cast<int32_t>(m.kind);
  s.d = term_index(*m.d);
  s.g = m.g ? term_index(*m.g) : 0;
  s.f = m.f ? term_index(*m.f) : 0;
  s.pd = float(m.pd);
  s.pg = float(m.pg);
  s.pd2 = float(m.pd2);
  s.pg2 = float(m.pg2);
  s.width_y = m.pd2 > 0 ? float(m.pd2) : 0.f;  // anisotropic terms: the proposal stretched as D
  s.f0 = float(m.f0);
  s.f1 = float(m.f1);
  s.kd = float(m.kd);
  s.width = float(m.width);
  s.cos_o = float(m.cos_o);
  s.phi_o = float(m.phi_o);
  return s;
}

IntegralSpec model_spec(IntegralKind kind, const Model& m, const ModelParams& p, double cos_o) {
  IntegralSpec s;
  s.check = static_cast<int32_t>(kind);
  s.model = m.number();
  for (size_t k = 0; k < 7; ++k) s.p[k] = float(p[k]);
  s.width = float(m.proposal_width(p.data()));
  s.width_y = p[6] > 0 ? float(p[6]) : 0.f;  // a second width (gltf: alpha_b) stretches the proposal
  s.cos_o = float(cos_o);
  return s;
}

namespace {
std::map<const Term*, const Term*>& planted_terms() {
  static std::map<const Term*, const Term*> m;
  return m;
}
const Term* reference_term(int32_t index) {
  const Term* t = &catalog()[size_t(index)];
  auto it = planted_terms().find(t);
  return it == planted_terms().end() ? t : it->second;
}
}  // namespace

bool reference_planted() { return !planted_terms().empty(); }

void plant_reference_term(const Term* original, const Term* planted) {
  if (planted)
    planted_terms()[original] = planted;
  else
    planted_terms().erase(original);
}

ref::IntegralRef reference_of(const IntegralSpec& s) {
  ref::IntegralRef r;
  r.kind = static_cast<ref::Integral>(s.check);
  r.brdf.d = reference_term(s.d);
  r.brdf.g = reference_term(s.g);
  r.brdf.f = reference_term(s.f);
  const bool whole = s.model != MFV_MODEL_MICROFACET;  // a whole model's p[0..6] (BrdfSpec keeps them in its slots)
  r.brdf.pd = whole ? s.p[0] : s.pd;
  r.brdf.pg = whole ? s.p[1] : s.pg;
  r.brdf.f0 = whole ? s.p[2] : s.f0;
  r.brdf.f1 = whole ? s.p[3] : s.f1;
  r.brdf.kd = whole ? s.p[4] : s.kd;
  r.brdf.p5 = whole ? s.p[5] : 0.0;
  r.brdf.pd2 = whole ? s.p[6] : s.pd2;  // the second widths of an anisotropic D and G (kernels/abi/integral.h)
  r.brdf.pg2 = whole ? 0.0 : s.pg2;
  r.phi_o = s.phi_o;
  r.brdf.model = model_by_number(s.model);  // whole models 1..999; nullptr for 0
  r.width = s.width;
  r.cos_o = s.cos_o;
  r.width_y = s.width_y;
  r.stream = s.stream;
  r.stream_hi = s.stream_hi;
  r.strata = s.strata;
  r.points = s.points;
  r.estimator = s.estimator;
  r.eta = s.eta;
  r.side = s.side;
  r.bsdf = s.bsdf;
  r.lobe = s.lobe;
  if (s.check == static_cast<int32_t>(IntegralKind::AlbedoRqmcB)) {
    // B by its definition: the albedo with Schlick's F at F0 = 0 (the
    // reference's own Schlick), where the kernel multiplies by (1 - o·h)^5
    r.kind = ref::Integral::AlbedoRqmc;
    r.brdf.f = &find_term("schlick");
    r.brdf.f0 = 0.0;
  }
  return r;
}

std::vector<Agreement> compare_with_reference(Integrator& in, const std::vector<IntegralSpec>& specs, uint32_t n,
                                              uint64_t seed) {
  if (n == 0 || specs.empty()) return {};
  const std::vector<float> kv = in.sample_values(specs, n, seed);
  return agreement_with_reference(specs, std::vector<double>(kv.begin(), kv.end()), n, seed);
}

std::vector<Agreement> agreement_with_reference(const std::vector<IntegralSpec>& specs,
                                                const std::vector<double>& kv, uint32_t n, uint64_t seed) {
  std::vector<Agreement> out;
  if (n == 0 || specs.empty()) return out;
  for (size_t j = 0; j < specs.size(); ++j) {
    const ref::IntegralRef r = reference_of(specs[j]);
    const uint64_t stride = r.strata >= n ? r.strata / n : 1;  // as kernels/integrate.cl sample_values
    double ks = 0, rs = 0, scale = 0;
    for (uint32_t k = 0; k < n; ++k) {
      const double rv = ref::sample_value(r, seed, k * stride);
      ks += kv[j * n + k];
      rs += rv;
      scale += std::fabs(rv);
    }
    // Relative where the integrand is O(1) or larger, absolute below: the
    // integrals are tested against 1, so a disagreement in a mean of 1e-20
    // (F0 = 0 at normal view) is rounding noise, not a verdict changer.
    double d = std::fabs(ks - rs) / std::max(scale, double(n));
    if (!std::isfinite(ks) || !std::isfinite(rs))
      d = std::isnan(ks) == std::isnan(rs) && ks == rs ? 0 : std::numeric_limits<double>::infinity();
    out.push_back({d, ks / n, rs / n});
  }
  return out;
}

}  // namespace mfv
