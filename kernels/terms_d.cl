// D terms: microfacet normal distributions, D(m) normalised so that
// the projected area integrates to one:  ∫ D(m) (m·n) dm = 1.
// Arguments: NoH = cos(theta_h) and sin2H = sin²(theta_h) = |n×h|², formed by
// the caller from the half vector's components (h.x² + h.y²): near the normal
// float cannot hold 1 - NoH (it rounds to 0 below ~6e-8), but it holds sin²
// to full relative precision, so peaks as narrow as alpha = 1e-7 resolve.
// Every term returns 0 below the horizon and treats NoH above 1 as 1.
// Select form: each term computes its value, then selects 0 below the
// horizon (no early return). A return before the parameter is read leaves
// that read (a load from the IntegralSpec) in a conditional block, and on
// AVX2 targets (PoCL's haswell), which have no cheap masked gather, LLVM's
// cost model then keeps the whole work-item loop scalar (docs/performance.md,
// "AVX2"). The values are the same to the bit.
// Reference twin: host/reference/terms_d.cpp.

MFV_TERMS_BEGIN  // inlined where the host asks (common.cl)

static inline real D_phong(real NoH, real sin2H, real alpha_p) {
  // seed 000 "Phong" and seed 003 "Blinn microfacet distribution": (ap+2)/(2π) (n·h)^ap
  // (n·h)^ap = exp(ap log cos): log_cos keeps the tiny sin² of a sharp lobe
  real d = (alpha_p + R(2.0)) * (R(0.5) * MFV_INV_PI) * mfv_exp(alpha_p * log_cos(min(NoH, R(1.0)), sin2H));
  return NoH <= R(0.0) ? R(0.0) : d;  // below the horizon (select form: see MFV_TERMS_BEGIN)
}

// exp(-x) / s for the Beckmann lobes, without a subnormal intermediate: for
// x > 64, exp(-x) = exp(64 - x) exp(-64), and exp(-64)/s is formed first
// (s is small exactly where such a D is large: 1e-44 / 1e-14 = 1e-30), so a
// device that flushes subnormals (many GPUs) still gets D ~ 1e-30 right
// (issue 19). x - 64 is exact for x in [32, 128] (Sterbenz), exp(-64) is one
// rounded constant: a few ulps in all.
static inline real beckmann_exp_over(real x, real s) {
  // θ -> π/2: the exponential vanishes faster than cos⁴θ, so D -> 0; returning
  // here avoids 0/0 once cos⁴θ underflows (n·h below ~1e-10 in float).
  bool far = x > R(64.0);
  real e = mfv_exp(far ? R(64.0) - x : -x);
  real scaled = e * (R(1.603810890548638e-28) / s), plain = e / s;  // exp(-64), rounded
  real r = far ? scaled : plain;
  return e == R(0.0) ? R(0.0) : r;
}

static inline real D_beckmann(real NoH, real sin2H, real alpha) {
  // seed 000 "Beckman": exp(-tan²θ/α²) / (π α² cos⁴θ)
  real c2 = sqr(min(NoH, R(1.0)));
  real a2 = alpha * alpha;
  real d = beckmann_exp_over(sin2H / (c2 * a2), MFV_PI * a2 * c2 * c2);
  return NoH <= R(0.0) ? R(0.0) : d;
}

static inline real D_ggx(real NoH, real sin2H, real alpha) {
  // seed 000 "GGX", second form α²/(π((n·h)²(α²-1)+1)²), rewritten as
  // α²/(π(c²α² + s²)²) with s² = |n×h|²: no cancellation as c -> 1.
  real c = min(NoH, R(1.0));
  // divide by α² first so α⁴ never underflows: 1/(π α² (c² + s²/α²)²)
  real a2 = alpha * alpha;
  real k = c * c + sin2H / a2;
  real d = R(1.0) / (MFV_PI * a2 * k * k);
  return NoH <= R(0.0) ? R(0.0) : d;  // below the horizon (select form: see MFV_TERMS_BEGIN)
}

static inline real D_blinn_rho(real NoH, real sin2H, real rho) {
  // seed 004 Cook-Torrance, "blinn version": (h·n)^(2/ρ² - 2) / (π ρ²)
  real r2 = rho * rho;
  // (h·n)^e = exp(e log cos), e = 2/ρ² - 2, as in D_phong
  real d = mfv_exp((R(2.0) / r2 - R(2.0)) * log_cos(min(NoH, R(1.0)), sin2H)) / (MFV_PI * r2);
  return NoH <= R(0.0) ? R(0.0) : d;
}

static inline real D_beckmann_ct82(real NoH, real sin2H, real m) {
  // seed 001 as written: exp(-(tanδ/m)²) / (4 m² cos⁴δ). Known bad: the 4 in
  // place of π makes ∫ D cos = π/4 (Cook and Torrance 1982 omit the π).
  real c2 = sqr(min(NoH, R(1.0)));
  real m2 = m * m;
  real e = mfv_exp(-sin2H / (c2 * m2));
  real d = e / (R(4.0) * m2 * c2 * c2);
  d = e == R(0.0) ? R(0.0) : d;  // θ -> π/2: D -> 0, and no 0/0 (as D_beckmann)
  return NoH <= R(0.0) ? R(0.0) : d;
}

// ---- Anisotropic D (tangent frame t = +x, b = +y, n = +z) ----------------
// Arguments: NoH = h.z and the half vector's tangent components hx = h·t,
// hy = h·b, widths ax along t and ay along b. Stretching the slopes by
// (1/ax, 1/ay) maps each onto its isotropic shape of width 1, hence the
// 1/(ax ay) normalisation (Heitz 2014, "Understanding the masking-shadowing
// function", anisotropic distributions). ax = ay gives D_ggx / D_beckmann.

static inline real D_ggx_aniso(real NoH, real hx, real hy, real ax, real ay) {
  // Burley 2012 appendix B (GTR2 aniso); Heitz 2014 anisotropic GGX:
  // 1 / (π ax ay cos⁴θ (1 + tan²θ (cos²φ/ax² + sin²φ/ay²))²)
  //   = 1 / (π ax ay ((n·h)² + (h·t/ax)² + (h·b/ay)²)²)   (unit h)
  if (NoH <= R(0.0)) return R(0.0);
  real c = min(NoH, R(1.0));
  real tx = hx / ax, ty = hy / ay;  // divided first, as D_ggx: no ax⁴ underflow
  real k = c * c + tx * tx + ty * ty;
  return R(1.0) / (MFV_PI * ax * ay * k * k);
}

static inline real D_beckmann_aniso(real NoH, real hx, real hy, real ax, real ay) {
  // Heitz 2014 anisotropic Beckmann (Ward's exponent, seed 004):
  // exp(-tan²θ (cos²φ/ax² + sin²φ/ay²)) / (π ax ay cos⁴θ)
  //   = exp(-((h·t/ax)² + (h·b/ay)²) / (n·h)²) / (π ax ay (n·h)⁴)
  if (NoH <= R(0.0)) return R(0.0);
  real c2 = sqr(min(NoH, R(1.0)));
  real tx = hx / ax, ty = hy / ay;
  return beckmann_exp_over((tx * tx + ty * ty) / c2, MFV_PI * ax * ay * c2 * c2);
}

// ---- Sheen ------------------------------------------------------------------

static inline real D_charlie(real NoH, real sin2H, real alpha) {
  // Estevez and Kulla 2017 eq. 2 ("Charlie" sheen; KHR_materials_sheen
  // "Sheen distribution", alphaG = sheenRoughness): (2 + 1/α) sin^(1/α)θ / (2π).
  // sin^(1/α) = exp(log(sin²θ) / (2α)); log(sin²θ) = log1p(-cos²θ) where
  // sin²θ is near 1 (the lobe's mass for small α sits at grazing m), so the
  // exponent up to 1/(2α) = 500 does not amplify a rounded sin²θ.
  if (NoH <= R(0.0)) return R(0.0);
  real c = min(NoH, R(1.0));
  real log_s2 = sin2H > R(0.5) ? mfv_log1p(-c * c) : mfv_log(sin2H);
  return (R(2.0) + R(1.0) / alpha) * (R(0.5) * MFV_INV_PI) * mfv_exp(R(0.5) / alpha * log_s2);
}

MFV_TERMS_END
