// The transmission checks' integrands (docs/transmission.md; their registry
// entries: host/checks/registry.cpp). Needs estimators.cl (the mixture of
// microfacet normals) and btdf.cl (the BTDF). Reference twin:
// host/reference/transmission.cpp.
#include "abi/integral.h"

// The reflection lobe of the rough dielectric BSDF, by components: Walter et
// al. 2007 eq. 20, f_r = F(i·h) G2(i, o, h) D(h) / (4 |i·n||o·n|), h the
// normalized i + o, F the exact dielectric Fresnel (1 - T_dielectric) and G2
// of the BTDF's form (btdf_g2), so that E_R + E_T is one BSDF's flux. Light
// from below: both directions mirrored and eta -> 1/eta, as btdf_eval_c.
static inline real bsdf_reflect_c(int d, int g, int form, real lx, real ly, real lz, real vx, real vy, real vz,
                                  real pd, real pg, real eta) {
  if (lz < R(0.0)) {
    lx = -lx, ly = -ly, lz = -lz;
    vx = -vx, vy = -vy, vz = -vz;
    eta = R(1.0) / eta;
  }
  if (lz <= R(0.0) || vz <= R(0.0)) return R(0.0);  // not a reflected pair
  real hx, hy, hz;
  real len = normalize_sum(lx + vx, ly + vy, lz + vz, &hx, &hy, &hz);
  if (!(len > R(0.0))) return R(0.0);
  real IoH = lx * hx + ly * hy + lz * hz;
  real D = eval_D(d, hz, hx * hx + hy * hy, pd);
  if (D == R(0.0)) return R(0.0);
  real a = eval_G1_aniso(g, lz, R(0.0), R(0.0), pg, pg);
  real b = eval_G1_aniso(g, vz, R(0.0), R(0.0), pg, pg);
  real F = R(1.0) - T_dielectric(IoH, eta);
  return F * btdf_g2(form, a, b) * (D / (R(4.0) * lz)) / vz;
}

// The BSDF's value at i (the fixed direction) and o in the surface's frame:
// the reflection lobe where o is on i's side, the BTDF on the other. Under
// mfv check (MFV_USER_BRDF) the user's bsdf, or brdf and btdf
// (kernels/user_brdf.cl, built after the user's file).
#ifdef MFV_USER_BRDF
static inline real user_bsdf_adapter(__global const IntegralSpec* s, real3 i, real3 o);
#endif
static inline real spec_bsdf_value(__global const IntegralSpec* s, bool reflected, real ix, real iy, real iz, real ox,
                                   real oy, real oz) {
#ifdef MFV_USER_BRDF
  return user_bsdf_adapter(s, (real3)(ix, iy, iz), (real3)(ox, oy, oz));
#else
  return reflected ? bsdf_reflect_c(s->d, s->g, s->bsdf & 1, ix, iy, iz, ox, oy, oz, s->pd, s->pg, s->eta)
                   : btdf_eval_c(s->d, s->g, s->bsdf, ix, iy, iz, ox, oy, oz, s->pd, s->pg, s->eta);
#endif
}

// Shares of mfv run's sphere proposal for a BSDF's flux (twin: kBsdfCos,
// kBsdfReflect in host/reference/transmission.cpp): a cosine lobe on each
// side (defensive), o reflected about and refracted through a normal m of the
// conformance mixture (sample_m, the width of the model, never its formula).
#define BSDF_COS R(0.1)      // each side's cosine lobe
#define BSDF_REFLECT R(0.4)  // o = reflect(i, m); the rest (0.4): o = refract(i, m)

// The proposal's density of o, in the frame where i is above (iz > 0) and
// eta is the relative index seen from i: the cosine lobe of o's side plus
// the reflection (Jacobian 1/(4 o·h), Walter et al. 2007 eq. 14) or the
// refraction (η² |o·h| / (i·h + η o·h)², eq. 17) of the mixture's normals.
static inline real bsdf_proposal_pdf(real ix, real iy, real iz, real ox, real oy, real oz, real w, real eta) {
  real p = BSDF_COS * fabs(oz) * MFV_INV_PI;
  real hx, hy, hz;
  if (oz > R(0.0)) {
    real len = normalize_sum(ix + ox, iy + oy, iz + oz, &hx, &hy, &hz);
    real oh = ox * hx + oy * hy + oz * hz;
    if (len > R(0.0) && hz > R(0.0) && oh > R(0.0))
      p += BSDF_REFLECT * pdf_m(hz, hx * hx + hy * hy, w) / (R(4.0) * oh);
    return p;
  }
  real len = normalize_sum(ix + eta * ox, iy + eta * oy, iz + eta * oz, &hx, &hy, &hz);
  if (!(len > R(0.0))) return p;
  if (hz < R(0.0)) hx = -hx, hy = -hy, hz = -hz;
  real ih = ix * hx + iy * hy + iz * hz, oh = ox * hx + oy * hy + oz * hz;
  if (ih > R(0.0) && oh < R(0.0))
    p += (R(1.0) - BSDF_COS * R(2.0) - BSDF_REFLECT) * pdf_m(hz, hx * hx + hy * hy, w) * eta * eta * (-oh) / (len * len);
  return p;
}

// One iid sample of a BSDF's flux (bsdf_avg_reciprocity's; bsdf_furnace
// takes bsdf_flux_mis below), the flux form of docs/transmission.md:
// E(i) = ∫ f(i, o) |o·n| do over the sphere of o, i the fixed direction at cos_o on `side`; f is the reflection lobe
// (bsdf_reflect_c) where o lies on i's side and the BTDF (btdf_eval_c) on
// the other, and `lobe` keeps one of the two. The proposal (above) is drawn
// in the frame where i is above (eta -> 1/eta from below) and mirrored back,
// so that the BSDF itself sees i on its side.
static inline real bsdf_flux_at(__global const IntegralSpec* s, uint4 r, real cos_i, int side, uint lobe) {
  real u_branch = u01_open(r.x), u_pick = u01_open(r.y), u_phi = u01_open(r.z), u_r = u01_open(r.w);
  const real below = side == MFV_SIDE_BELOW ? R(-1.0) : R(1.0);
  const real eta = side == MFV_SIDE_BELOW ? R(1.0) / s->eta : s->eta;  // seen from i
  real ix = sqrt(sin2_from_cos(cos_i)), iy = R(0.0), iz = cos_i;
  real ox, oy, oz;
  if (u_branch < R(2.0) * BSDF_COS) {
    cosine_direction(u_phi, u_r, &ox, &oy, &oz);
    if (u_branch < BSDF_COS) oz = -oz;  // the other side's lobe
  } else {
    real c, s2;
    real3 m = sample_m(u_pick, u_phi, u_r, s->width, &c, &s2);
    real im = ix * m.x + iy * m.y + iz * m.z;
    if (im <= R(0.0)) return R(0.0);  // a facet facing away: no output
    if (u_branch < R(2.0) * BSDF_COS + BSDF_REFLECT) {
      ox = R(2.0) * im * m.x - ix, oy = R(2.0) * im * m.y - iy, oz = R(2.0) * im * m.z - iz;
      if (oz <= R(0.0)) return R(0.0);
    } else {
      // Walter et al. 2007 eq. 40 with η_i/η_o = 1/eta: none under total internal reflection
      real k = R(1.0) / eta, t2 = R(1.0) - k * k * (R(1.0) - im * im);
      if (t2 <= R(0.0)) return R(0.0);
      real a = k * im - sqrt(t2);
      ox = a * m.x - k * ix, oy = a * m.y - k * iy, oz = a * m.z - k * iz;
      if (oz >= R(0.0)) return R(0.0);
    }
  }
  const bool reflected = oz > R(0.0);
  if (reflected != (lobe == MFV_LOBE_REFLECT) && lobe != MFV_LOBE_ALL) return R(0.0);
  real p = bsdf_proposal_pdf(ix, iy, iz, ox, oy, oz, s->width, eta);
  if (!(p > R(0.0))) return R(0.0);
  // back to the surface's frame: i (and o) mirrored when i is below
  real f = spec_bsdf_value(s, reflected, ix, iy, below * iz, ox, oy, below * oz);
  return f * fabs(oz) / p;
}

// One sample of the hemispherical averages' reciprocity (MFV_CHECK_BSDF_AVG;
// Walter et al. 2007 eq. 21's η_o², generalized reciprocity integrated over
// both directions): T_avg = 2 ∫ E_T(μ) μ dμ of the light from below
// (relative index 1/η) less that from above (η) over η², each μ drawn with
// density 2μ and its o from the proposal above: the mean is 0 exactly.
static inline real bsdf_avg_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  uint4 u = mfv_philox(seed, s->stream, spec_draw(s, 2u), index);
  real mu_below = sqrt(u01_open(u.x)), mu_above = sqrt(u01_open(u.y));
  real leaving = bsdf_flux_at(s, mfv_philox(seed, s->stream, spec_draw(s, 0u), index), mu_below, MFV_SIDE_BELOW,
                              MFV_LOBE_TRANSMIT);
  real entering = bsdf_flux_at(s, mfv_philox(seed, s->stream, spec_draw(s, 1u), index), mu_above, MFV_SIDE_ABOVE,
                               MFV_LOBE_TRANSMIT);
  real eta = s->eta;  // in real: a float eta's square (1.33²) is not a float, and the double twin keeps its digits
  return leaving - entering / (eta * eta);
}

// One sample of the weak white furnace on the transmitted side
// (MFV_CHECK_MASKING_T; Heitz 2014 eq. 19 for o below the surface):
// ∫ G1(o, m) max(0, -o·m) D(m) dm = |o·n|, o at cos_o below, with the G1 the
// BTDF masks a direction below the surface with (btdf_eval_c: the Smith G1
// at |o·n|, χ+((o·m)/(o·n)) its orientation test), m from the mixture.
static inline real masking_t_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  uint4 r = mfv_philox(seed, s->stream, spec_draw(s, 0u), index);
  real u_pick = u01_open(r.y), u_phi = u01_open(r.z), u_r = u01_open(r.w);
  real co = s->cos_o, ox = sqrt(sin2_from_cos(co)), oz = -co;
  real c, s2;
  real3 m = sample_m(u_pick, u_phi, u_r, s->width, &c, &s2);
  real om = ox * m.x + oz * m.z;
  if (om >= R(0.0)) return R(0.0);  // χ+: o below sees the facets with o·m < 0
#ifdef MFV_USER_BRDF
  // mfv check: the user's G1 and D (their G1 asked for v below the surface)
  real g1 = spec_G1(s, (real3)(ox, R(0.0), oz), m, co, c, om), dm = spec_D(s, m, c, s2);
#else
  real g1 = eval_G1_aniso(s->g, co, R(0.0), R(0.0), s->pg, s->pg), dm = eval_D(s->d, c, s2, s->pd);
#endif
  return g1 * dm * -om / (pdf_m(c, s2, s->width) * co);
}

// ---- bsdf_furnace's flux (MFV_CHECK_BSDF_FLUX; host: IntegralKind::BsdfFlux) --
// The estimator's own exact dielectric Fresnel (Walter et al. 2007 eq. 22,
// written here, never the BSDF's F): reflectance at cos c = i·m with the
// relative index eta seen from i; 1 under total internal reflection.
static inline real flux_fresnel(real c, real eta) {
  real g2 = eta * eta - R(1.0) + c * c;
  if (g2 <= R(0.0)) return R(1.0);
  real g = sqrt(g2), a = (g - c) / (g + c), b = (c * (g + c) - R(1.0)) / (c * (g - c) + R(1.0));
  return min(R(0.5) * a * a * (R(1.0) + b * b), R(1.0));
}

// The chance that a share picks reflection at a facet with i·m = c: the
// lobe's own hemisphere where the integral keeps one lobe; for the whole
// sphere (MFV_LOBE_ALL) the estimator's Fresnel for the visible normals (so
// that a correct GGX model's weight is G2/G1) and 1/2 for the defensive pair.
static inline real flux_p_reflect(uint lobe, bool vis, real c, real eta) {
  if (lobe == MFV_LOBE_REFLECT) return R(1.0);
  if (lobe == MFV_LOBE_TRANSMIT) return R(0.0);
  return vis ? flux_fresnel(c, eta) : R(0.5);
}

// The three proposals' density of o (o_z > 0: reflected about h = i + o
// normalized, Jacobian 1/(4 o·h), eq. 14; o_z < 0: refracted through
// h = -(i + eta o) normalized, turned to +z, Jacobian eta² |o·h| / |i + eta o|²,
// eq. 17), weighted by the mixture c = (15/16, 1/32, 1/32): (a) a visible
// normal of the GGX shape at i (vis_pdf_i is its reflected density, 1/(4 i·h)
// of the normal's), (b) Cauchy slopes, (c) the cosine lobe, each times its
// chance of o's side.
static inline real flux_mis_pdf(real ix, real iz, real ox, real oy, real oz, real w, real eta, uint lobe) {
  real so2 = sin2_from_cos(iz), hx, hy, hz;
  if (oz > R(0.0)) {
    real oh = R(0.5) * normalize_sum(ix + ox, oy, iz + oz, &hx, &hy, &hz);
    if (!(oh > R(0.0))) return R(0.0);
    real hs2 = hx * hx + hy * hy, ih = ix * hx + iz * hz;
    return MIS_C_VIS * flux_p_reflect(lobe, true, ih, eta) * vis_pdf_i(hz, hs2, iz, so2, w) +
           MIS_C_SLOPE * flux_p_reflect(lobe, false, ih, eta) * pdf_slope(hz, hs2, w) / (R(4.0) * oh) +
           MIS_C_COS * flux_p_reflect(lobe, false, ih, eta) * oz * MFV_INV_PI;
  }
  real cos_share = MIS_C_COS * (R(1.0) - flux_p_reflect(lobe, false, R(1.0), eta)) * -oz * MFV_INV_PI;
  real len = normalize_sum(ix + eta * ox, eta * oy, iz + eta * oz, &hx, &hy, &hz);
  if (!(len > R(0.0))) return cos_share;
  if (hz < R(0.0)) hx = -hx, hy = -hy, hz = -hz;
  real ih = ix * hx + iz * hz, oh = ox * hx + oy * hy + oz * hz;
  if (!(ih > R(0.0) && oh < R(0.0))) return cos_share;
  real hs2 = hx * hx + hy * hy, jac = eta * eta * -oh / (len * len);
  return cos_share +
         MIS_C_VIS * (R(1.0) - flux_p_reflect(lobe, true, ih, eta)) * R(4.0) * ih * vis_pdf_i(hz, hs2, iz, so2, w) * jac +
         MIS_C_SLOPE * (R(1.0) - flux_p_reflect(lobe, false, ih, eta)) * pdf_slope(hz, hs2, w) * jac;
}

// Sobol's third dimension at index k (Joe & Kuo 2008: x² + x + 1, m = 1, 3):
// the XOR of the direction numbers v_j of k's set bits, v_j = v_{j-1} ^
// v_{j-2} ^ (v_{j-2} >> 2). With owen_sobol_2d's two it is a 3D Sobol net,
// so the side picked for the whole sphere is stratified with the normal
// (a second scramble of dimension 1 instead tied the side to the azimuth:
// 30x the replicate spread, measured).
static inline uint sobol_dim3(uint k) {
  uint x = 0u, a = 0x80000000u, b = 0xC0000000u;
  for (int j = 0; j < 32; ++j) {
    if ((k >> j) & 1u) x ^= a;
    uint next = b ^ a ^ (a >> 2);
    a = b;
    b = next;
  }
  return x;
}

// The direction o one share of bsdf_furnace's proposal draws for the light
// from i = (ix, 0, iz) above (relative index eta seen from i) from the
// uniforms (u_phi, u_r) of its normal and u_c of its side: the cosine lobe
// (vis and cosine false: Cauchy slopes), o reflected about (eq. 39) or
// refracted through (eq. 40) the normal m by flux_p_reflect. 0 where the
// draw gives no direction (a facet facing away, total internal reflection
// on the refracted side, o on the wrong side): the proposal is a
// sub-probability, flux_mis_pdf its density (mfv samplers tests both).
static inline bool flux_mis_direction(bool vis, bool cosine, real u_phi, real u_r, real u_c, real ix, real iz, real w,
                                      real eta, uint lobe, real* pox, real* poy, real* poz) {
  real ox, oy, oz;
  if (cosine) {
    cosine_direction(u_phi, u_r, &ox, &oy, &oz);
    if (!(u_c < flux_p_reflect(lobe, false, R(1.0), eta))) oz = -oz;
  } else {
    real mx, my, mz, s2;
    if (vis) sample_vis_c(ix, R(0.0), iz, u_phi, u_r, w, &mx, &my, &mz);
    else sample_m_c(false, u_phi, u_r, w, &mx, &my, &mz, &s2);
    real im = ix * mx + iz * mz;
    if (!(im > R(0.0))) return false;  // a facet facing away (or a degenerate one): no output
    if (u_c < flux_p_reflect(lobe, vis, im, eta)) {
      ox = R(2.0) * im * mx - ix, oy = R(2.0) * im * my, oz = R(2.0) * im * mz - iz;
      if (!(oz > R(0.0))) return false;
    } else {
      real kk = R(1.0) / eta, t2 = R(1.0) - kk * kk * (R(1.0) - im * im);
      if (t2 <= R(0.0)) return false;
      real a = kk * im - sqrt(t2);
      ox = a * mx - kk * ix, oy = a * my, oz = a * mz - kk * iz;
      if (!(oz < R(0.0))) return false;
    }
  }
  *pox = ox, *poy = oy, *poz = oz;
  return true;
}

// Point k of n of a replicate with seeds `shift` (the points and shares of
// albedo_mis_microfacet: 4n/5 visible normals, n/10 Cauchy slopes, n/10 the
// cosine lobe, each on Owen-scrambled Sobol points, multi-sample MIS with
// the balance heuristic; Veach 1997 eq. 9.13): the flux f(i, o)|o·n| / q of
// the light from i at cos_i on `side`, in `lobe`. A normal m gives o
// reflected (eq. 39) or refracted (eq. 40, none under total internal
// reflection) by the lobe, or for the whole sphere by Sobol's third
// dimension (Owen-scrambled) against flux_p_reflect. The BSDF sees i on its
// own side (the frame mirrored back, as bsdf_flux_at). A wrong model enters
// only the numerator; the defensive pair bounds f/q by 32 f/p_defensive.
// Twin: flux_mis in host/reference/transmission.cpp.
static inline real bsdf_flux_mis(__global const IntegralSpec* s, uint4 shift, uint k, uint n) {
  uint n_def = n / 10u, n_vis = 8u * n_def;
  bool vis = k < n_vis, cosine = k >= n_vis + n_def;
  uint j = vis ? k : cosine ? k - n_vis - n_def : k - n_vis;
  real u_phi, u_r, u_c;
  owen_sobol_2d(j, vis ? shift.x : cosine ? shift.w : shift.z, vis ? shift.y : cosine ? shift.z : shift.w, &u_phi, &u_r);
  u_c = u01_open(reverse_bits32(owen_hash(reverse_bits32(sobol_dim3(j)), vis ? shift.z : cosine ? shift.y : shift.x)));
  const real below = s->side == MFV_SIDE_BELOW ? R(-1.0) : R(1.0);
  const real eta = s->side == MFV_SIDE_BELOW ? R(1.0) / s->eta : s->eta;  // seen from i
  const uint lobe = s->lobe;
  real iz = s->cos_o, ix = sqrt(sin2_from_cos(iz)), w = s->width;
  real ox, oy, oz;
  if (!flux_mis_direction(vis, cosine, u_phi, u_r, u_c, ix, iz, w, eta, lobe, &ox, &oy, &oz)) return R(0.0);
  real q = flux_mis_pdf(ix, iz, ox, oy, oz, w, eta, lobe);
  if (!(q > R(0.0))) return R(0.0);
  real f = spec_bsdf_value(s, oz > R(0.0), ix, R(0.0), below * iz, ox, oy, below * oz);
  real share = vis ? R(1.171875) : R(0.3125);  // c_t n / n_t: (15/16)(5/4), (1/32) 10 on the albedo's points
  return share * f * fabs(oz) / q;
}

// Sample `index` = r n + k (n = s->points): point k of replicate r.
static inline real bsdf_flux_value(__global const IntegralSpec* s, ulong seed, ulong index) {
  uint n = s->points;
  return bsdf_flux_mis(s, mis_shift(s, seed, (uint)(index / n)), (uint)(index % n), n);
}
