// The reference twins of one catalog entry: the function pointers through
// which the assembled BRDF (brdf.hpp) and the estimators call a term or a
// whole model. The catalog's Term and Model derive from these structs, so the
// reference needs nothing from the catalog, the layer above it
// (docs/design.md, "Layers").
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>

namespace mfv::ref {

using RefD = double (*)(double NoH, double p);
using RefDcs = double (*)(double cos2, double sin2, double p);  // D from cos²θ and sin²θ given apart
using RefG = double (*)(double NoL, double NoV, double NoH, double VoH, double p);
using RefG1 = double (*)(double NoV, double p);
using RefF = double (*)(double VoH, double p0, double p1);
// Anisotropic terms (aniso below): directions in the tangent frame t = +x,
// b = +y, n = +z, widths ax along t and ay along b.
using RefDAniso = double (*)(const glm::dvec3& m, double ax, double ay);
using RefG1Aniso = double (*)(const glm::dvec3& v, double ax, double ay);
using RefGAniso = double (*)(const glm::dvec3& l, const glm::dvec3& v, double VoH, double ax, double ay);

struct TermTwins {
  RefD ref_d = nullptr;  // exactly one of ref_d, ref_g, ref_f is set, by kind
  // D: the same from cos²θ and sin²θ (where the form has tan²θ or (n·h)^e), which the
  // reference estimators take: a cosine alone leaves 1 − cosθ to u/θ² near a
  // narrow peak, less precise than the float kernels, which keep sin²θ.
  RefDcs ref_d_cs = nullptr;
  RefG ref_g = nullptr;
  RefF ref_f = nullptr;
  // Smith G terms: the G1 they are built from, used by the masking check.
  RefG1 ref_g1 = nullptr;
  // A separable Smith G: ref_g(NoL, NoV, NoH, VoH, p) is ref_g1(NoL, p) *
  // ref_g1(NoV, p) where NoL, NoV and VoH > 0, else 0, bit for bit
  // (tests/test_g_separable.cpp), so a caller at one view takes G1(NoV)
  // once (the furnace truth, checks/furnace_views.cpp).
  bool g_separable = false;
  // A height-correlated Smith G: ref_g(NoL, NoV, NoH, VoH, p) is 1 / (1 +
  // Λ(NoL, p) + Λ(NoV, p)) with Λ this, where NoL, NoV and VoH > 0, else 0,
  // bit for bit (the same test, the same use).
  RefG1 g_correlated_lambda = nullptr;

  // Anisotropic D and Smith G: params are (alpha_x, alpha_y) in the tangent
  // frame t = +x, b = +y, n = +z. ref_d/ref_g/ref_g1 above are their
  // isotropic slice (direction in the xz-plane, alpha_y = alpha_x), the
  // one-width view of the generic checks; the *_aniso twins take directions.
  bool aniso = false;
  RefDAniso ref_d_aniso = nullptr;
  RefG1Aniso ref_g1_aniso = nullptr;
  RefGAniso ref_g_aniso = nullptr;
};

constexpr size_t kModelParams = 7;  // p[0..6] travel in IntegralSpec pd, pg, f0, f1, kd, p5, pd2 (0 for most models)

// f(l, v): l = light, v = view, both unit and pointing away from the surface, n = +z.
using RefModel = double (*)(const glm::dvec3& wi, const glm::dvec3& wo, const double* p);
// Exact directional albedo E(l) = ∫ f(l, v) (n·v) dv at n·l = cos_l; NaN where unknown.
using RefAlbedo = double (*)(double cos_l, const double* p);

struct ModelTwins {
  RefModel ref = nullptr;
  RefAlbedo ref_albedo = nullptr;  // exact albedo where known (the energy check then tests equality)
};

}  // namespace mfv::ref
