// D terms: microfacet normal distributions, D(m) normalised so that
// the projected area integrates to one:  ∫ D(m) (m·n) dm = 1.
// Argument NoH = cos(theta_h); every term returns 0 below the horizon and
// treats NoH rounded above 1 as 1. Reference twin: host/reference/terms_d.cpp.

static inline real D_phong(real NoH, real alpha_p) {
  // seed 000 "Phong" and seed 003 "Blinn microfacet distribution": (ap+2)/(2π) (n·h)^ap
  if (NoH <= R(0.0)) return R(0.0);
  return (alpha_p + R(2.0)) * (R(0.5) * MFV_INV_PI) * pow(min(NoH, R(1.0)), alpha_p);
}

static inline real D_beckmann(real NoH, real alpha) {
  // seed 000 "Beckman": exp(-tan²θ/α²) / (π α² cos⁴θ)
  if (NoH <= R(0.0)) return R(0.0);
  real c2 = sqr(min(NoH, R(1.0)));
  real a2 = alpha * alpha;
  return exp(-sin2_from_cos(NoH) / (c2 * a2)) / (MFV_PI * a2 * c2 * c2);
}

static inline real D_ggx(real NoH, real alpha) {
  // seed 000 "GGX", second form α²/(π((n·h)²(α²-1)+1)²), rewritten as
  // α²/(π(c²α² + s²)²) with s² = (1-c)(1+c): no cancellation as c -> 1.
  if (NoH <= R(0.0)) return R(0.0);
  real c = min(NoH, R(1.0));
  // divide by α² first so α⁴ never underflows: 1/(π α² (c² + s²/α²)²)
  real a2 = alpha * alpha;
  real k = c * c + sin2_from_cos(c) / a2;
  return R(1.0) / (MFV_PI * a2 * k * k);
}

static inline real D_blinn_rho(real NoH, real rho) {
  // seed 004 Cook-Torrance, "blinn version": (h·n)^(2/ρ² - 2) / (π ρ²)
  if (NoH <= R(0.0)) return R(0.0);
  real r2 = rho * rho;
  return pow(min(NoH, R(1.0)), R(2.0) / r2 - R(2.0)) / (MFV_PI * r2);
}

static inline real D_beckmann_ct82(real NoH, real m) {
  // seed 001 as written: exp(-(tanδ/m)²) / (4 m² cos⁴δ). Known bad: the 4 in
  // place of π makes ∫ D cos = π/4 (Cook and Torrance 1982 omit the π).
  if (NoH <= R(0.0)) return R(0.0);
  real c2 = sqr(min(NoH, R(1.0)));
  real m2 = m * m;
  return exp(-sin2_from_cos(NoH) / (c2 * m2)) / (R(4.0) * m2 * c2 * c2);
}
