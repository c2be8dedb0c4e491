// The rough dielectric BTDF of Walter et al. 2007 (needs the generated
// eval_D and eval_G1_aniso).
// Reference twin: host/reference/btdf.cpp. Convention (docs/transmission.md):
// this is the radiance form, which carries η_o² (radiance across an interface
// scales as (η_o/η_i)²); the flux a direction i sends through the surface is
// E_T(i) = ∫ f_t(i, o) |o·n| do, with no extra factor.
//
// Local frame n = +z; wi (l) = the incident direction, wo (v) = the outgoing
// one, both pointing away from the surface, on opposite sides of it. eta =
// η_below / η_above, the index of the medium under the surface relative to
// the one above: light from above enters (η_i = 1, η_o = eta), light from
// below leaves (η_i = eta, η_o = 1; the same as 1, 1/eta after the flip).
#include "abi/bsdf.h"

// The G2 of a transmitted pair from the two G1 (orientation already tested).
// Separable: G1(i) G1(o) (Walter et al. 2007 eq. 23); height-correlated:
// 1/(1 + Λ(i) + Λ(o)) with Λ = 1/G1 - 1, written as a b / (a + b - a b)
// (no 1/G1 overflow; a or b = 0: fully masked, G2 = 0).
static inline real btdf_g2(int form, real a, real b) {
  if (form == MFV_BTDF_SEPARABLE) return a * b;
  if (a <= R(0.0) || b <= R(0.0)) return R(0.0);
  return a * b / (a + b - a * b);
}

// 1 - F of the exact dielectric Fresnel, formed without the cancellation of
// 1 - F where F -> 1 (grazing, near the critical angle): with g = η cosθt,
// g² = η² - 1 + c² (seed 000's g), 1 - r_s² = 4 c g / (c + g)² and
// 1 - r_p² = 4 η² c g / (η² c + g)² (Born and Wolf §1.5.3, r_p = (η² c - g)/(η² c + g)),
// so T = 2 c g (1/(c + g)² + η²/(η² c + g)²); total internal reflection: 0.
static inline real T_dielectric(real c, real eta) {
  // Walter et al. 2007 eq. 22 (exact dielectric Fresnel), its complement
  c = min(fabs(c), R(1.0));
  real g2 = (eta - R(1.0)) * (eta + R(1.0)) + c * c;
  if (g2 <= R(0.0) || c <= R(0.0)) return R(0.0);  // TIR (or grazing: F = 1)
  real g = sqrt(g2), e2c = eta * eta * c;
  return R(2.0) * c * g * (R(1.0) / sqr(c + g) + eta * eta / sqr(e2c + g));
}

// By components, as brdf_eval_c. code = MFV_BTDF_CODE(form, variant).
static inline real btdf_eval_c(int d, int g, int code, real lx, real ly, real lz, real vx, real vy, real vz,
                               real pd, real pg, real eta) {
  // Walter et al. 2007 eq. 21: f_t = |i·h||o·h| / (|i·n||o·n|) η_o² (1 - F(i·h)) G2 D(h) / (η_i i·h + η_o o·h)²,
  // h ∝ -(η_i i + η_o o) (eq. 16). One flip at the top (pbrt-v4 DielectricBxDF):
  // light from below is light from above with both directions mirrored through
  // the surface and eta -> 1/eta, so below η_i = 1 and η_o = eta.
  int form = code & 1, variant = code >> 1;
  if (lz < R(0.0)) {
    lx = -lx, ly = -ly, lz = -lz;
    vx = -vx, vy = -vy, vz = -vz;
    eta = R(1.0) / eta;
  }
  if (lz <= R(0.0) || vz >= R(0.0)) return R(0.0);  // not a transmitted pair (a grazing i transmits nothing)
  // s = η_i i + η_o o; h = ±s/|s| on the normal's side. Then η_i i·h + η_o o·h
  // = s·h = ±|s|: the denominator of eq. 21 is |s|², formed without cancellation.
  real hx, hy, hz;
  real len = normalize_sum(lx + eta * vx, ly + eta * vy, lz + eta * vz, &hx, &hy, &hz);
  // |s| = 0 only at eta = 1 and o = -i: index matched, the light passes
  // straight through (a Dirac in o that no BTDF value represents): 0.
  if (!(len > R(0.0))) return R(0.0);
  if (hz < R(0.0)) hx = -hx, hy = -hy, hz = -hz;
  real IoH = lx * hx + ly * hy + lz * hz;
  real OoH = vx * hx + vy * hy + vz * hz;
  if (variant == MFV_BTDF_BAD_SAME_SIDE) {
    // planted: no orientation test, so o on i's side of m is counted too
    IoH = fabs(IoH);
    OoH = -fabs(OoH);
  }
  // χ+(i·h / i·n) and χ+(o·h / o·n) (Walter et al. 2007 eq. 23), i·n > 0 > o·n:
  // refraction leaves i and o on opposite sides of m; anything else is not
  // transmission through this microfacet.
  if (IoH <= R(0.0) || OoH >= R(0.0)) return R(0.0);
  real D = eval_D(d, hz, hx * hx + hy * hy, pd);
  if (D == R(0.0)) return R(0.0);  // h at the horizon or beyond D's support: no 0 x inf below
  real a = eval_G1_aniso(g, lz, R(0.0), R(0.0), pg, pg);
  real b = eval_G1_aniso(g, -vz, R(0.0), R(0.0), pg, pg);
  real T = T_dielectric(variant == MFV_BTDF_BAD_F_AT_N ? lz : IoH, eta);
  real den = variant == MFV_BTDF_BAD_JACOBIAN ? sqr(IoH + OoH) : len * len;
  real eta2 = variant == MFV_BTDF_BAD_NO_ETA2 ? R(1.0) : eta * eta;
  // (i·h / i·n)(|o·h| / |o·n|) one quotient at a time: i·n and o·n may be tiny
  real t = (IoH / lz) * (-OoH / -vz);
  return t * (eta2 * T * btdf_g2(form, a, b) * D / den);
}

static inline real btdf_eval(int d, int g, int code, real3 wi, real3 wo, real pd, real pg, real eta) {
  return btdf_eval_c(d, g, code, wi.x, wi.y, wi.z, wo.x, wo.y, wo.z, pd, pg, eta);
}
