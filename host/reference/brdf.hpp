// The assembled reference BRDF, in double with GLM (twin of kernels/brdf.cl).
#pragma once

#include "reference/twins.hpp"

#include <glm/vec3.hpp>

namespace mfv::ref {

// One BRDF: a D, G and F term with their native parameters, plus a Lambert
// diffuse albedo kd (0 for a pure microfacet BRDF).
struct BrdfSpec {
  // The catalog's Term and Model (catalog/) derive from these twins.
  const TermTwins* d = nullptr;
  const TermTwins* g = nullptr;
  const TermTwins* f = nullptr;
  double pd = 0, pg = 0, f0 = 0, f1 = 0, kd = 0;
  // A whole model instead of D x G x F: its p[0..5] are pd, pg, f0, f1, kd, p5.
  const ModelTwins* model = nullptr;
  double p5 = 0;
  // Anisotropic terms (Term::aniso): the second widths along b = +y; 0 for
  // isotropic specs (twin of IntegralSpec::pd2, which D and G share).
  double pd2 = 0, pg2 = 0;
  bool aniso() const { return pd2 > 0; }
};

// The cosines a microfacet BRDF depends on, formed from the directions.
struct Shading {
  double NoL, NoV, NoH, VoH;
  double sin2H = -1;  // |n × h|² from h's components; < 0: not given (derived from NoH)
};

Shading shading_from(const glm::dvec3& wi, const glm::dvec3& wo);  // n = +z
double brdf(const BrdfSpec& s, const Shading& c);
double brdf(const BrdfSpec& s, const glm::dvec3& wi, const glm::dvec3& wo);  // anisotropic too when s.aniso()
// brdf(s, c) from its isotropic terms' values at c: D = eval_d_iso(s, c),
// F = s.f->ref_f(c.VoH, s.f0, s.f1), G = eval_g_iso(s, c) (the same bits as brdf(s, c)).
double brdf_of_terms(const BrdfSpec& s, const Shading& c, double D, double F, double G);
double eval_d_iso(const BrdfSpec& s, const Shading& c);
double eval_g_iso(const BrdfSpec& s, const Shading& c);

// The directions' D and G, anisotropic terms with two widths, isotropic ones
// as brdf() evaluates them (twins of eval_D_aniso, eval_G_aniso, eval_G1_aniso).
double eval_d(const BrdfSpec& s, const glm::dvec3& m);
// An isotropic D at cos θ = c with sin²θ = s2 given apart (Term::ref_d_cs where the D has one).
double eval_d_cs(const BrdfSpec& s, double c, double s2);
double eval_g(const BrdfSpec& s, const glm::dvec3& wi, const glm::dvec3& wo, const Shading& c);
double eval_g1(const BrdfSpec& s, const glm::dvec3& v);

}  // namespace mfv::ref
