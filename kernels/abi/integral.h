/* The layout kernels/integrate*.cl and the host share (docs/design.md,
 * "Layout"): one definition, included by the OpenCL C (Runtime::build expands
 * `#include "abi/..."` from the embedded or --kernel-dir files) and by the C++
 * (host/runtime/integrator.hpp, with kernels/ on the include path). Plain C:
 * no C++ and no OpenCL C beyond the typedefs below. tests/test_abi.cpp checks
 * on the device that sizeof and every field's offset match the host's. */
#ifndef MFV_ABI_INTEGRAL_H
#define MFV_ABI_INTEGRAL_H

#ifdef __OPENCL_C_VERSION__
typedef int mfv_i32;
typedef uint mfv_u32;
#define MFV_INIT(v)
#else
#include <stdint.h>
typedef int32_t mfv_i32;
typedef uint32_t mfv_u32;
#define MFV_INIT(v) = v /* C++ default member initializer; none in OpenCL C */
namespace mfv {
#endif

/* IntegralSpec::check: which integral (host: IntegralKind, ref::Integral). */
#define MFV_CHECK_D_NORM 0          /* ∫ D(m)(m·n) dm = 1, stratified radius */
#define MFV_CHECK_MASKING 1         /* weak white furnace (Heitz 2014 eq. 19) */
#define MFV_CHECK_ALBEDO 2          /* E(o) by the defensive mixture, iid */
/* mfv energy: the albedo with a visible-normal proposal on randomized-QMC
 * points; each integral is one randomization (its stream picks the shift). */
#define MFV_CHECK_ALBEDO_RQMC 3     /* E(o) at cos_o, as MFV_CHECK_ALBEDO */
#define MFV_CHECK_EAVG_RQMC 4       /* E_avg = ∫ E(μ) 2μ dμ: μ with density 2μ, stratified */
#define MFV_CHECK_ALBEDO_RQMC_B 5   /* sample_values only: the split sum's B of MFV_CHECK_ALBEDO_RQMC */
#define MFV_CHECK_ALBEDO_MIS 6      /* mfv run's albedo: three proposals by multi-sample MIS on RQMC replicates */

/* IntegralSpec::estimator: mfv convergence's estimators (0: the check's own;
 * host: ref::Estimator). */
#define MFV_EST_OWN 0u
#define MFV_EST_UNIFORM 1u           /* uniform hemisphere, pdf 1/(2π) */
#define MFV_EST_COSINE 2u            /* cosine-weighted hemisphere (Malley), pdf cos/π */
#define MFV_EST_DSAMPLE_GGX 3u       /* albedo only: h ~ D_w(h)(h·n) of the GGX shape */
#define MFV_EST_DSAMPLE_BECKMANN 4u  /* albedo only: the same with the Beckmann shape */
#define MFV_EST_VNDF 5u              /* albedo only: visible normals of the GGX shape (Heitz 2018) */
#define MFV_EST_RQMC 6u              /* 2D Kronecker points with a Philox Cranley-Patterson shift */

/* IntegralSpec::model: 0 is the microfacet D×G×F BRDF; 1 .. END-1 the
 * catalog's whole models (Model::number, kernels/models.cl). */
#define MFV_MODEL_MICROFACET 0u
#define MFV_MODEL_CATALOG_END 1000u

/* The sums an integration kernel leaves per work-group (integrate,
 * sum_values, sum_pairs): MFV_SUM_SLOTS acc_t values, group-major. The
 * second holds the sum of squares (iid), of squared differences of
 * neighbouring strata (stratified), or the split sum's B (ALBEDO_RQMC). */
#define MFV_SLOT_SUM 0
#define MFV_SLOT_SUMSQ 1
#define MFV_SUM_SLOTS 2

/* One integral: twenty 4-byte fields, no padding. */
typedef struct IntegralSpec IntegralSpec;
struct IntegralSpec {
  mfv_i32 check MFV_INIT(0);  /* MFV_CHECK_* */
  mfv_i32 d MFV_INIT(0), g MFV_INIT(0), f MFV_INIT(0);  /* catalog term ids (term_index); model 0 only */
  /* D's and G's native parameter, F's two, the Lambertian kd; a whole model
   * (or user code) reads its p[0..6] from pd, pg, f0, f1, kd, p5, pd2. */
  float pd MFV_INIT(0), pg MFV_INIT(0), f0 MFV_INIT(0), f1 MFV_INIT(0);
  float kd MFV_INIT(0);
  float width MFV_INIT(0.1f);  /* the proposal's width (an alpha; <= 0: a mixture of widths) */
  float cos_o MFV_INIT(1);     /* the fixed direction's cosine (view; a whole model's light) */
  float p5 MFV_INIT(0);        /* the sixth parameter of a whole model or user BRDF */
  mfv_u32 stream MFV_INIT(0);  /* Philox stream: the integral's id in its run */
  mfv_u32 strata MFV_INIT(0);  /* samples of a stratified integral (set by the integrator); 0 = iid;
                                  ALBEDO_MIS: points per replicate */
  mfv_u32 model MFV_INIT(0);   /* MFV_MODEL_MICROFACET, a catalog model, or user code */
  mfv_u32 channel MFV_INIT(0); /* mfv check: the RGB channel (0..2) of the user's BRDF */
  /* Anisotropic integrals (pd2 > 0; 0 leaves every isotropic one untouched):
   * D's second width alpha_y (a whole model's p[6]); the proposals are then
   * stretched to (width, pd2). */
  float pd2 MFV_INIT(0);
  float phi_o MFV_INIT(0);     /* the view's azimuth about n (0: in the xz-plane) */
  mfv_u32 estimator MFV_INIT(0);  /* MFV_EST_* */
  float pg2 MFV_INIT(0);       /* an anisotropic G's second width alpha_y */
};

#ifndef __OPENCL_C_VERSION__
}  /* namespace mfv */
#endif
#undef MFV_INIT
#endif /* MFV_ABI_INTEGRAL_H */
