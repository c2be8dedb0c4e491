// Isotropic microfacet integrals for the integrator tests: an albedo integral
// (D, G and F by catalog id at one shared width alpha, F's f0 (f1 = 1), diffuse
// kd, view cosine cos_o, Philox stream) and a d_norm integral of one D.
#pragma once

#include "catalog/catalog.hpp"
#include "catalog/roughness.hpp"
#include "checks/integrate.hpp"

#include <cstdint>
#include <string>

namespace mfv::test {

inline IntegralSpec albedo_spec(const std::string& d, const std::string& g, const std::string& f, double alpha,
                                double cos_o, double f0, double kd, uint32_t stream,
                                IntegralKind kind = IntegralKind::Albedo) {
  const Term &td = find_term(d), &tg = find_term(g), &tf = find_term(f);
  MicrofacetIntegral m;
  m.kind = kind;
  m.d = &td, m.g = &tg, m.f = &tf;
  m.pd = native_from_alpha(td.roughness, alpha), m.pg = native_from_alpha(tg.roughness, alpha);
  m.f0 = f0, m.f1 = 1.0, m.kd = kd;
  m.width = alpha, m.cos_o = cos_o;
  IntegralSpec s = spec_of(m);
  s.stream = stream;
  return s;
}

// A d_norm integral of D term `d` at width `alpha` (proposal width alpha).
inline IntegralSpec d_norm_spec(const std::string& d, double alpha, uint32_t stream) {
  const Term& t = find_term(d);
  MicrofacetIntegral m;
  m.kind = IntegralKind::DNorm;
  m.d = &t;
  m.pd = native_from_alpha(t.roughness, alpha);
  m.width = alpha;
  IntegralSpec s = spec_of(m);
  s.stream = stream;
  return s;
}

}  // namespace mfv::test
