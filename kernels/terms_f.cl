// F terms: Fresnel reflectance of one colour channel at the microfacet,
// argument VoH = cos of the angle of incidence on the facet. An RGB material
// is three channels. Reference twin: host/reference/terms_f.cpp.

MFV_TERMS_BEGIN  // inlined where the host asks (common.cl)

static inline real F_none(real VoH, real unused0, real unused1) {
  // F = 1: the white furnace's perfect reflector
  return R(1.0);
}

static inline real F_schlick(real VoH, real f0, real unused) {
  // seed 000 / Schlick 1994: F0 + (1 - F0)(1 - l·h)^5
  real m = R(1.0) - saturate(VoH);
  real m2 = m * m;
  return f0 + (R(1.0) - f0) * (m2 * m2 * m);
}

static inline real F_dielectric(real VoH, real eta, real unused) {
  // seed 000 exact form: g = sqrt(η² - 1 + c²), c = |l·h|,
  // F = ½ (g-c)²/(g+c)² (1 + ((c(g+c) - 1)/(c(g-c) + 1))²).
  // Seed 001 prints c(g-c) - 1 and g² = η² + c² + 1: typos; this is the physics.
  real c = min(fabs(VoH), R(1.0));
  // η² - 1 as (η - 1)(η + 1): exact near η = 1, where η·η - 1 cancels unless
  // the compiler happens to fuse it into an FMA (issue 19: 807 ulps without).
  real g2 = (eta - R(1.0)) * (eta + R(1.0)) + c * c;
  if (g2 <= R(0.0) && eta < R(1.0)) return R(1.0);  // sinθt >= 1: total internal reflection
  // η >= 1 has g² >= c² >= 0; it reads 0 only where c² underflowed at η = 1.
  real g = sqrt(max(g2, R(0.0)));
  if (g + c <= R(0.0)) return R(1.0);           // c = 0 on η = 1: the grazing limit, as the reference
  // g - c = (η² - 1)/(g + c): as printed it cancels for η near 1, where F -> 0.
  real g_minus_c = (eta - R(1.0)) * (eta + R(1.0)) / (g + c);
  real a = g_minus_c / (g + c);
  real b = (c * (g + c) - R(1.0)) / (c * g_minus_c + R(1.0));
  return R(0.5) * a * a * (R(1.0) + b * b);
}

static inline real F_conductor(real VoH, real n, real k) {
  // Exact unpolarised Fresnel for a complex index n + ik in real arithmetic
  // (Born and Wolf §14.2; form of Lagarde 2013, "Memo on Fresnel equations"):
  // a²+b² = sqrt(t0² + 4n²k²), t0 = n²-k²-s², a² - b² = t0, ab = nk,
  // Rs = (a²+b² - 2ac + c²)/(a²+b² + 2ac + c²),
  // Rp = Rs (c²(a²+b²) - 2ac s² + s⁴)/(c²(a²+b²) + 2ac s² + s⁴).
  // Written as sums of squares, Rs = ((a-c)² + b²)/((a+c)² + b²) and
  // Rp/Rs = ((ac-s²)² + b²c²)/((ac+s²)² + b²c²), so nothing cancels when the
  // conductor is nearly a dielectric (n ~ 1, k ~ 0), where the printed form
  // loses every digit in float.
  real c = saturate(VoH);
  real c2 = c * c;
  real s2 = sin2_from_cos(c);
  real n2k2 = n * n * k * k;
  // e = n² - k² - 1 formed directly (exact-ish near n = 1), and
  // t0 = n² - k² - s² = e + c² from whichever side does not cancel: e + c²
  // towards grazing, (n-k)(n+k) - s² towards normal incidence.
  real e = (n - R(1.0)) * (n + R(1.0)) - k * k;
  real t0 = c2 < R(0.5) ? e + c2 : (n - k) * (n + k) - s2;
  real a2b2 = sqrt(t0 * t0 + R(4.0) * n2k2);
  real a2, b2;  // each from the side where it does not cancel
  if (t0 >= R(0.0)) {
    b2 = a2b2 + t0 > R(0.0) ? R(2.0) * n2k2 / (a2b2 + t0) : R(0.0);
    a2 = t0 + b2;
  } else {
    a2 = R(2.0) * n2k2 / (a2b2 - t0);
    b2 = a2 - t0;
  }
  real a = sqrt(a2);
  real den_s = sqr(a + c) + b2;
  // a = b = 0 only for n = 1, k = 0 (no interface): F = 0, and at c = 0 the
  // grazing limit 1, as the reference (c² may have underflowed to make den_s 0).
  if (den_s <= R(0.0)) return c > R(0.0) ? R(0.0) : R(1.0);
  // a - c = (a² - c²)/(a + c); a² - c² = e + b² where b² is small (t0 >= 0),
  // else a² and c² are both accurate and their difference is safer.
  real a_minus_c = a + c > R(0.0) ? (t0 >= R(0.0) ? e + b2 : a2 - c2) / (a + c) : R(0.0);  // a = c = 0: n < 1, k = 0 at c = 0
  real rs = (sqr(a_minus_c) + b2) / den_s;
  real rp = rs * (sqr(a * c - s2) + b2 * c2) / (sqr(a * c + s2) + b2 * c2);
  return R(0.5) * (rp + rs);
}

static inline real F_schlick_f90(real VoH, real f0, real f90) {
  // Schlick 1994's Fresnel approximation with the grazing value f90 in
  // place of 1 (Burley 2012 §5.3 uses it so for his diffuse; engines ship it):
  // F = f0 + (f90 - f0)(1 - v.h)^5, evaluated as f0 (1 - w) + f90 w, w = m^5,
  // m = 1 - v.h, with 1 - w = c (1 + m + m^2 + m^3 + m^4) (c = v.h exact):
  // two non-negative terms, so nothing cancels when f90 < f0.
  real c = saturate(VoH);
  real m = R(1.0) - c;
  real m2 = m * m;
  real w = m2 * m2 * m;
  real u = c * (R(1.0) + m + m2 + m2 * m + m2 * m2);
  return f0 * u + f90 * w;
}

static inline real F_schlick_sg(real VoH, real f0, real unused) {
  // Karis 2013, "Real Shading in Unreal Engine 4", Specular BRDF, Fresnel (the
  // spherical-Gaussian fit of Schlick's (1 - v.h)^5, after Lagarde 2012):
  // F = f0 + (1 - f0) 2^((-5.55473 v.h - 6.98316) v.h)
  // 2^x as mfv_exp(x ln 2): no library call in float programs (common.cl)
  real c = saturate(VoH);
  return f0 + (R(1.0) - f0) * mfv_exp((R(-5.55473) * c - R(6.98316)) * c * R(0.69314718055994531));
}

MFV_TERMS_END
