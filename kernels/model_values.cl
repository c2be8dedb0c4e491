// The fast path of `integrate` for whole models (Model::number() != 0): the
// iid albedo integrals of mfv run's energy and closed_form checks
// (MFV_CHECK_ALBEDO, isotropic proposal, light in the xz-plane, one width
// > 0; host: Integrator values_kernel) with one sample per work-item, stored
// and reduced by sum_values, as albedo_values (kernels/albedo.cl).
// MFV_MODEL_ALBEDO_VALUES(NAME, MODEL) defines the kernel for the constant
// model id MODEL, one per model (runtime/specialize.cpp, PoCL only), where
// eval_model's switch folds to the one model and PoCL vectorizes the
// work-group loop. There is no generic instance: Intel's CPU runtime
// miscompiled one taking (int)s->model (NaN and wrong albedos in
// tests/test_portability.cpp's closed_form run), so a program without the
// specializations leaves whole models to `integrate` (Integrator::run).
// Needs albedo.cl and integrate.cl (MFV_SAMPLE_VALUES) before it.

#ifndef MFV_USER_BRDF
// albedo_value's general path (kernels/albedo.cl) for a whole model at
// phi_o = 0 and width > 0, by components and with selects: the same
// operations in the same order (spec_view at phi_o = 0 is (so, 0, co);
// sample_m and pdf_m at w > 0 are sample_m_c and pdf_mix(pdf_slope)), so
// `integrate` and this path give the same sample to the bit.
static inline MFV_ALWAYS_INLINE real model_albedo_value_c(int model, __global const IntegralSpec* s, real u_branch,
                                                          real u_pick, real u_phi, real u_r) {
  real w = s->width, oz = s->cos_o, ox = sqrt(sin2_from_cos(oz)), oy = R(0.0);
  real cx, cy, cz;
  cosine_direction(u_phi, u_r, &cx, &cy, &cz);
  real mx, my, c, s2;
  sample_m_c(u_pick < MIX_COS, u_phi, u_r, w, &mx, &my, &c, &s2);
  real om2 = R(2.0) * (ox * mx + oy * my + oz * c);  // o reflected about m
  bool lobe = u_branch < MIX_I_COS;
  real ix = lobe ? cx : om2 * mx - ox, iy = lobe ? cy : om2 * my - oy, iz = lobe ? cz : om2 * c - oz;
  real hx, hy, hz;
  real oh = R(0.5) * normalize_sum(ix + ox, iy + oy, iz + oz, &hx, &hy, &hz);  // as albedo_weight
  real pm = pdf_mix(hz, pdf_slope(hz, hx * hx + hy * hy, w));
  // spec_brdf: the fixed direction o is the light, the sampled i the view
  real p[7] = {s->p[0], s->p[1], s->p[2], s->p[3], s->p[4], s->p[5], s->p[6]};
  real f = eval_model(model, (real3)(ox, oy, oz), (real3)(ix, iy, iz), p) * iz / albedo_pdf(iz, oh, pm);
  return iz <= R(0.0) ? R(0.0) : f;  // select form: the parameters' loads unconditional (models.cl above_horizons)
}

// MFV_SAMPLE_VALUES drawing with mfv_philox_split (kernels/rng.cl, the
// same bits as mfv_philox): in the branch-free model code LLVM's SLP pass
// pairs mfv_philox's two 64-bit products of a round into a <2 x i64>
// multiply, a vector value PoCL's work-item vectorizer refuses
// (skylake-avx512 lost every model kernel so); the split form's 32-bit
// words are not paired.
#define MFV_MODEL_ALBEDO_VALUES(NAME, MODEL)               \
  MFV_SAMPLE_VALUES_DRAWN(NAME, mfv_philox_split,          \
                          model_albedo_value_c(MODEL, s, u01_open(r.x), u01_open(r.y), u01_open(r.z), u01_open(r.w)))
#endif
