// G terms: Smith Lambda and G1 for one direction (argument NoV = cos θ), and
// the full G2 for a pair (NoL, NoV, NoH, VoH; VoH = LoH for the half vector).
// G2 functions return G itself, not the visibility G/(4 NoL NoV).
// Reference twin: host/reference/terms_g.cpp.

MFV_TERMS_BEGIN  // inlined where the host asks (common.cl)

// ---- Lambda and G1 ------------------------------------------------------

static inline real Lambda_ggx(real NoV, real alpha) {
  // Walter et al. 2007 eq. 34 via Heitz 2014 eq. 72: Λ = (-1 + sqrt(1 + α² tan²θ)) / 2,
  // rearranged as x / (2 (1 + sqrt(1 + x))) with x = α² tan²θ: no cancellation at small x.
  if (NoV >= R(1.0)) return R(0.0);             // seed 000: (v·n) rounding above 1 -> G1 = 1
  if (NoV <= R(0.0)) return INFINITY;           // θ -> π/2: Λ -> ∞, so G1 -> 0
  real x = alpha * alpha * tan2_from_cos(NoV);
  // Near grazing tan²θ overflows (cos²θ underflows below n·v ~ 1e-19 in float)
  // while Λ itself need not: there sqrt(1 + x) = sqrt(x) to the last bit, so
  // Λ = α tanθ / 2, formed without squaring (inf only where Λ overflows).
  if (isinf(x)) return R(0.5) * alpha * sqrt(sin2_from_cos(NoV)) / NoV;
  return x / (R(2.0) * (R(1.0) + sqrt(R(1.0) + x)));
}

static inline real Lambda_beckmann(real NoV, real alpha) {
  // Walter et al. 2007 eq. 25 (exact Smith for Beckmann): a = 1/(α tanθ),
  // Λ = (erf(a) - 1)/2 + exp(-a²)/(2 a √π), with erf(a) - 1 = -erfc(a).
  if (NoV >= R(1.0)) return R(0.0);             // seed 000: rounding above 1 -> G1 = 1
  if (NoV <= R(0.0)) return INFINITY;           // θ -> π/2: Λ -> ∞
  real s2 = sin2_from_cos(NoV);
  if (s2 <= R(0.0)) return R(0.0);              // seed 000: tanθ = 0, do not divide by it
  real a = NoV / (alpha * sqrt(s2));
  return R(0.5) * (mfv_exp(-a * a) / (a * MFV_SQRT_PI) - mfv_erfc(a));
}

static inline real G1_smith_ggx(real NoV, real alpha) {
  // seed 000 "GGX": 2 / (1 + sqrt(1 + α² tan²θ)) = 1 / (1 + Λ)
  return R(1.0) / (R(1.0) + Lambda_ggx(NoV, alpha));
}

static inline real G1_smith_beckmann(real NoV, real alpha) {
  // Smith 1967 / Walter et al. 2007 eq. 24: G1 = 1 / (1 + Λ)
  return R(1.0) / (R(1.0) + Lambda_beckmann(NoV, alpha));
}

static inline real G1_rational_beckmann(real a) {
  // seed 000: (3.535a + 2.181a²) / (1 + 2.276a + 2.577a²) for a < 1.6, else 1
  if (a >= R(1.6)) return R(1.0);
  return (R(3.535) * a + R(2.181) * a * a) / (R(1.0) + R(2.276) * a + R(2.577) * a * a);
}

static inline real G1_smith_beckmann_approx(real NoV, real alpha) {
  // seed 000 "Beckman" G1 with a = 1/(α tanθ)
  if (NoV >= R(1.0)) return R(1.0);             // seed 000: rounding above 1 -> 1
  if (NoV <= R(0.0)) return R(0.0);             // grazing: a -> 0, rational -> 0
  real s2 = sin2_from_cos(NoV);
  if (s2 <= R(0.0)) return R(1.0);              // seed 000: tanθ = 0 -> 1
  return G1_rational_beckmann(NoV / (alpha * sqrt(s2)));
}

static inline real G1_smith_phong(real NoV, real alpha_p) {
  // seed 000 "Phong": the Beckmann rational with a = sqrt(αp/2 + 1) / tanθ
  if (NoV >= R(1.0)) return R(1.0);
  if (NoV <= R(0.0)) return R(0.0);
  real s2 = sin2_from_cos(NoV);
  if (s2 <= R(0.0)) return R(1.0);
  return G1_rational_beckmann(sqrt(R(0.5) * alpha_p + R(1.0)) * NoV / sqrt(s2));
}

// ---- G2 ---------------------------------------------------------------
// Below the horizon (NoL or NoV <= 0) every G2 is 0: no light, no view.

static inline real G_implicit(real NoL, real NoV, real NoH, real VoH, real unused) {
  // seed 000 "V(L,V) = 1": G = (n·l)(n·v)
  // select form (terms_d.cl); fmin(a, b) <= 0 is a <= 0 || b <= 0, NaN
  // included, without two compares SLP would pair into a <2 x i1>
  return fmin(NoL, NoV) <= R(0.0) ? R(0.0) : NoL * NoV;
}

static inline real G_kelemen(real NoL, real NoV, real NoH, real VoH, real unused) {
  // seed 000: G / ((L·N)(V·N)) ≈ 1 / (L·H)²  (Kelemen and Szirmay-Kalos 2001)
  // (n·l / l·h)(n·v / v·h): the same product, without the underflow of
  // (n·l)(n·v) and (l·h)² at grazing, where each quotient stays near 1.
  // The second quotient passes through a select that the horizon select
  // below makes moot (VoH <= 0 returns 0 either way; NaN keeps the
  // quotient): two fdivs multiplied are a pair LLVM's SLP pass packs into
  // one <2 x float> division on haswell (AVX2), which kept every albedo
  // kernel of a program with this G scalar there (docs/performance.md,
  // "AVX2"). The same floats.
  real qv = VoH <= R(0.0) ? R(0.0) : NoV / VoH;
  real g = (NoL / VoH) * qv;
  return fmin(fmin(NoL, NoV), VoH) <= R(0.0) ? R(0.0) : g;  // select form, as G_implicit
}

static inline real G_cook_torrance(real NoL, real NoV, real NoH, real VoH, real unused) {
  // seeds 001, 003, 004 (V-cavity, Torrance-Sparrow 1967):
  // min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h)), using v·h = l·h
  real k = R(2.0) * NoH / VoH;
  real g = min(R(1.0), k * min(NoV, NoL));
  return fmin(fmin(NoL, NoV), VoH) <= R(0.0) ? R(0.0) : g;  // select form, as G_implicit
}

static inline real G_smith_beckmann_approx(real NoL, real NoV, real NoH, real VoH, real alpha) {
  // seed 000 Smith form G = G1(L) G1(V), rational Beckmann G1
  real g = G1_smith_beckmann_approx(NoL, alpha) * G1_smith_beckmann_approx(NoV, alpha);
  return fmin(fmin(NoL, NoV), VoH) <= R(0.0) ? R(0.0) : g;  // select form, as G_implicit
}

static inline real G_smith_beckmann(real NoL, real NoV, real NoH, real VoH, real alpha) {
  // Walter et al. 2007 eq. 23, separable: G1(L) G1(V) with exact Λ
  if (NoL <= R(0.0) || NoV <= R(0.0) || VoH <= R(0.0)) return R(0.0);
  return G1_smith_beckmann(NoL, alpha) * G1_smith_beckmann(NoV, alpha);
}

static inline real G_smith_phong(real NoL, real NoV, real NoH, real VoH, real alpha_p) {
  // seed 000 "Phong": Smith form with the Phong G1
  real g = G1_smith_phong(NoL, alpha_p) * G1_smith_phong(NoV, alpha_p);
  return fmin(fmin(NoL, NoV), VoH) <= R(0.0) ? R(0.0) : g;  // select form, as G_implicit
}

static inline real G_smith_ggx(real NoL, real NoV, real NoH, real VoH, real alpha) {
  // seed 000 "GGX", separable Smith: G1(L) G1(V)
  if (NoL <= R(0.0) || NoV <= R(0.0) || VoH <= R(0.0)) return R(0.0);
  return G1_smith_ggx(NoL, alpha) * G1_smith_ggx(NoV, alpha);
}

static inline real G_smith_ggx_correlated(real NoL, real NoV, real NoH, real VoH, real alpha) {
  // Heitz 2014 eq. 99 (height-correlated): 1 / (1 + Λ(L) + Λ(V))
  real g = R(1.0) / (R(1.0) + Lambda_ggx(NoL, alpha) + Lambda_ggx(NoV, alpha));
  // select form, as G_implicit, with the compare written `> 0 ? g : 0`: as
  // `<= 0 ? 0 : g` SLP paired it with D's horizon select and the albedo
  // kernels stayed scalar (docs/performance.md, "AVX2")
  return fmin(fmin(NoL, NoV), VoH) > R(0.0) ? g : R(0.0);
}

static inline real G_hammon_002(real NoL, real NoV, real NoH, real VoH, real alpha) {
  // seed 002 `geometry`: visibility V = 0.5 / max(0.01, mix(2 NoL NoV, NoL + NoV, α))
  // (Hammon 2017's approximation); G = 4 NoL NoV V.
  real v = R(0.5) / max(R(0.01), mix(R(2.0) * NoL * NoV, NoL + NoV, alpha));
  real g = R(4.0) * NoL * NoV * v;
  return fmin(NoL, NoV) <= R(0.0) ? R(0.0) : g;  // select form, as G_implicit
}

static inline real G_hammon_clamped(real NoL, real NoV, real NoH, real VoH, real alpha) {
  // Hammon 2017, "PBR Diffuse Lighting for GGX+Smith Microsurfaces", slide
  // "Approximating G2" (his fit of height-correlated Smith-GGX):
  // G ~ 2 (n.l)(n.v) / lerp(2 (n.l)(n.v), n.l + n.v, α), with an engine's clamp:
  // both cosines of the fit taken in [1e-4, 1] (engines floor n.v there), the
  // outer 4 (n.l)(n.v) saturated. Symmetric in l and v, so reciprocal.
  real l = saturate(NoL), v = saturate(NoV);
  real cl = max(l, R(1e-4)), cv = max(v, R(1e-4));
  // lerp written as two non-negative terms: no cancellation
  real den = R(2.0) * cl * cv * (R(1.0) - alpha) + (cl + cv) * alpha;
  real g = R(2.0) * l * v / den;
  return fmin(NoL, NoV) <= R(0.0) ? R(0.0) : g;  // select form, as G_implicit
}

// ---- Anisotropic Smith (tangent frame t = +x, b = +y, n = +z) -----------
// Heitz 2014 ("Understanding the masking-shadowing function", anisotropic
// distributions): the Λ of an anisotropic GGX or Beckmann is the isotropic Λ
// at the projected width α_o = sqrt(cos²φ_o ax² + sin²φ_o ay²) of the
// direction's azimuth φ_o. With the direction's components (vx, vy, NoV):
// α_o² tan²θ_o = ((ax vx)² + (ay vy)²) / NoV², no angle formed.

static inline real Lambda_ggx_aniso(real NoV, real vx, real vy, real ax, real ay) {
  if (NoV >= R(1.0)) return R(0.0);             // rounding above 1 -> G1 = 1 (seed 000)
  if (NoV <= R(0.0)) return INFINITY;           // θ -> π/2: Λ -> ∞
  // α_o² sin²θ_o in one expression (a fused multiply-add, as D_ggx_aniso's
  // k): the sum of two separate squares was a 2-lane pair for LLVM's SLP
  // pass, which kept the anisotropic glTF models' kernels scalar on AVX2
  real tx = ax * vx, ty = ay * vy;
  real q = tx * tx + ty * ty;
  real x = q / (NoV * NoV);
  // cos² underflows (NoV below ~1e-19): Λ = α_o tanθ / 2, as Lambda_ggx
  if (isinf(x)) return R(0.5) * sqrt(q) / NoV;
  return x / (R(2.0) * (R(1.0) + sqrt(R(1.0) + x)));
}

static inline real Lambda_beckmann_aniso(real NoV, real vx, real vy, real ax, real ay) {
  if (NoV >= R(1.0)) return R(0.0);
  if (NoV <= R(0.0)) return INFINITY;
  real q = sqr(ax * vx) + sqr(ay * vy);
  if (q <= R(0.0)) return R(0.0);               // tanθ = 0: do not divide by it (seed 000)
  real a = NoV / sqrt(q);                       // 1 / (α_o tanθ_o)
  return R(0.5) * (mfv_exp(-a * a) / (a * MFV_SQRT_PI) - mfv_erfc(a));
}

static inline real G1_smith_ggx_aniso(real NoV, real vx, real vy, real ax, real ay) {
  return R(1.0) / (R(1.0) + Lambda_ggx_aniso(NoV, vx, vy, ax, ay));
}

static inline real G1_smith_beckmann_aniso(real NoV, real vx, real vy, real ax, real ay) {
  return R(1.0) / (R(1.0) + Lambda_beckmann_aniso(NoV, vx, vy, ax, ay));
}

// G2, separable as G_smith_ggx (Walter et al. 2007 eq. 23): G1(l) G1(v).
static inline real G_smith_ggx_aniso(real3 l, real3 v, real VoH, real ax, real ay) {
  if (l.z <= R(0.0) || v.z <= R(0.0) || VoH <= R(0.0)) return R(0.0);
  return G1_smith_ggx_aniso(l.z, l.x, l.y, ax, ay) * G1_smith_ggx_aniso(v.z, v.x, v.y, ax, ay);
}

static inline real G_smith_beckmann_aniso(real3 l, real3 v, real VoH, real ax, real ay) {
  if (l.z <= R(0.0) || v.z <= R(0.0) || VoH <= R(0.0)) return R(0.0);
  return G1_smith_beckmann_aniso(l.z, l.x, l.y, ax, ay) * G1_smith_beckmann_aniso(v.z, v.x, v.y, ax, ay);
}

// ---- Sheen --------------------------------------------------------------------

// Estevez and Kulla 2017 §3: the fit of ln Λ of the Charlie D,
// L(x) = a/(1 + b x^c) + d x + e, coefficients of α = 1 and α = 0 mixed by
// (1 − α)² (KHR_materials_sheen "Sheen visibility").
static inline real charlie_L(real x, real alpha) {
  real t = (R(1.0) - alpha) * (R(1.0) - alpha);
  real a = mix(R(21.5473), R(25.3245), t), b = mix(R(3.82987), R(3.32435), t);
  real c = mix(R(0.19823), R(0.16801), t), d = mix(R(-1.97760), R(-1.27393), t);
  real e = mix(R(-4.32054), R(-4.85967), t);
  return a / (R(1.0) + b * mfv_pow(x, c)) + d * x + e;
}

static inline real Lambda_charlie(real NoV, real alpha) {
  // exp(L(cosθ)) below cosθ = 0.5, exp(2 L(0.5) − L(1 − cosθ)) above
  if (NoV <= R(0.0)) return INFINITY;
  real c = min(NoV, R(1.0));
  // L at the one argument the side needs (c or 1 − c), the side chosen after:
  // the same floats as evaluating L at both and selecting, but one L, not
  // two that LLVM's SLP pass paired into 2-lane vectors (gltf_sheen's
  // kernels scalar; docs/performance.md)
  bool low = c < R(0.5);
  real l = charlie_L(low ? c : R(1.0) - c, alpha);
  return mfv_exp(low ? l : R(2.0) * charlie_L(R(0.5), alpha) - l);
}

static inline real G1_charlie(real NoV, real alpha) {
  // select form: an early return here kept this G's masking and AlbedoMis
  // kernels scalar on AVX2 (8-wide on AVX-512; docs/performance.md). At and
  // below the horizon Λ is ∞ and g is 0 already; the select says so.
  real g = R(1.0) / (R(1.0) + Lambda_charlie(NoV, alpha));
  return NoV <= R(0.0) ? R(0.0) : g;
}

static inline real G_charlie_sheen(real NoL, real NoV, real NoH, real VoH, real alpha) {
  // KHR_materials_sheen "Sheen visibility" (Charlie): V = 1/((1 + Λ(v) + Λ(l)) 4 (n·v)(n·l)),
  // returned as G = 4 (n·l)(n·v) V = 1/(1 + Λ(l) + Λ(v))
  // select form, as G1_charlie's
  real g = R(1.0) / (R(1.0) + (Lambda_charlie(NoL, alpha) + Lambda_charlie(NoV, alpha)));  // symmetric in l, v to the bit
  return ((NoL <= R(0.0)) | (NoV <= R(0.0)) | (VoH <= R(0.0))) ? R(0.0) : g;
}

static inline real G_neubelt_sheen(real NoL, real NoV, real NoH, real VoH, real unused) {
  // Neubelt and Pettineo 2013, "Crafting a Next-Gen Material Pipeline for The
  // Order: 1886", cloth BRDF visibility (after Ashikhmin and Premoze 2007):
  // V = 1 / (4 (n.l + n.v - (n.l)(n.v))), returned as G = 4 (n.l)(n.v) V.
  // Cosines above 1 (rounding) are taken as 1. (l + v) - l v loses at most
  // one bit (l v <= (l + v) / 2); G = (lo / den) hi: the quotient lies in
  // (0, 1] (den >= hi), so l v never underflows at grazing, and the form is
  // symmetric in l and v to the bit (reciprocity). lo = min(l, v) and
  // hi = max(l, v) are formed from fmin/fmax of the cosines, lo clamped by
  // hi: the same floats as clamping each cosine first, but no two like
  // operations side by side, which LLVM's SLP pass packed into a 2-lane
  // vector and which kept every generic kernel of a program with this G
  // scalar on AVX2 (docs/performance.md).
  real hi = min(fmax(NoL, NoV), R(1.0));
  real lo = min(fmin(NoL, NoV), hi);
  real den = (lo + hi) - lo * hi;
  real g = (lo / den) * hi;
  return fmin(NoL, NoV) <= R(0.0) ? R(0.0) : g;  // select form, as G_implicit
}

MFV_TERMS_END
