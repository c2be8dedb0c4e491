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
/* The rough dielectric BSDF (bsdf, eta, side; kernels/transmission.cl): */
#define MFV_CHECK_BSDF_FLUX 7       /* E_R or E_T (lobe) of the light from the fixed direction, o over the sphere, iid */
#define MFV_CHECK_MASKING_T 8       /* the weak white furnace for o below the surface (the BTDF's G1), iid */
#define MFV_CHECK_BSDF_AVG 9        /* T_avg(1/eta) - T_avg(eta)/eta^2: the averages' reciprocity, iid */

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
 * sum_values, sum_pairs, sum_rqmc): MFV_SUM_SLOTS acc_t values, group-major.
 * MFV_SLOT_SUM is the sum of the samples. What MFV_SLOT_SECOND holds depends
 * on the check, one meaning each:
 *   D_NORM (stratified), EAVG_RQMC:  Σ (x_2i - x_2i+1)², neighbouring strata
 *   MASKING, ALBEDO (iid):           Σ x², the sum of squares
 *   ALBEDO_RQMC:                     Σ B, the split sum's B on the same points
 *   ALBEDO_MIS:                      Σ x² of one replicate (the host uses only
 *                                    the replicates' sums: their spread)
 *   BSDF_FLUX, MASKING_T, BSDF_AVG:  Σ x², the sum of squares (iid)
 * A new check states its own here (docs/adding-a-check.md). */
#define MFV_SLOT_SUM 0
#define MFV_SLOT_SECOND 1
#define MFV_SUM_SLOTS 2

/* IntegralSpec::side: which side of the surface the fixed direction is on. */
#define MFV_SIDE_ABOVE 1   /* above (n·o > 0): reflection, or transmission entering */
#define MFV_SIDE_BELOW (-1) /* below (n·o < 0): transmission leaving the medium */

/* IntegralSpec::lobe: which part of a BSDF's flux an integral takes. */
#define MFV_LOBE_ALL 0u        /* the whole BSDF (every integral that is no BSDF's) */
#define MFV_LOBE_REFLECT 1u    /* E_R: the reflected flux (o on the fixed direction's side) */
#define MFV_LOBE_TRANSMIT 2u   /* E_T: the transmitted flux (o on the other side) */

/* One integral: thirty-three 4-byte words, no padding. Every field has one
 * meaning; a check that needs another quantity gets a field of its own
 * (tests/test_abi.cpp lists every field once and checks its offset on the
 * device). */
typedef struct IntegralSpec IntegralSpec;
struct IntegralSpec {
  /* -- what is integrated -- */
  mfv_i32 check MFV_INIT(0);      /* MFV_CHECK_* */
  mfv_u32 model MFV_INIT(0);      /* MFV_MODEL_MICROFACET, a catalog model (1..999), or user code */
  mfv_u32 estimator MFV_INIT(0);  /* MFV_EST_* */
  mfv_u32 channel MFV_INIT(0);    /* mfv check: the RGB channel (0..2) of the user's BRDF */
  /* -- the microfacet D x G x F BRDF (model 0 only; 0 for every other model) -- */
  mfv_i32 d MFV_INIT(0), g MFV_INIT(0), f MFV_INIT(0);  /* catalog term ids (term_index) */
  float pd MFV_INIT(0), pg MFV_INIT(0);  /* D's and G's native parameter (alpha_x where anisotropic) */
  float pd2 MFV_INIT(0), pg2 MFV_INIT(0); /* an anisotropic D's and G's alpha_y (0: isotropic) */
  float f0 MFV_INIT(0), f1 MFV_INIT(0);  /* F's two parameters */
  float kd MFV_INIT(0);                  /* the Lambertian albedo added (kd/pi) */
  /* -- a whole model's or user code's parameters p[0..6] (model > 0 only) -- */
  float p[7] MFV_INIT({0});
  /* -- the interface (transmission checks; reflection leaves the defaults) -- */
  float eta MFV_INIT(1);          /* relative IOR eta_t / eta_i, seen from the fixed direction's side */
  mfv_i32 side MFV_INIT(1);       /* MFV_SIDE_ABOVE or MFV_SIDE_BELOW: the fixed direction's side */
  mfv_i32 bsdf MFV_INIT(-1);      /* MFV_BTDF_CODE (abi/bsdf.h) of the rough dielectric BSDF of d and g; -1: none */
  mfv_u32 lobe MFV_INIT(0);       /* MFV_LOBE_*: the part of the BSDF's flux integrated */
  /* -- the fixed direction (the view; a whole model's light) -- */
  float cos_o MFV_INIT(1);        /* its cosine to n (> 0; `side` says which hemisphere) */
  float phi_o MFV_INIT(0);        /* its azimuth about n (0: in the xz-plane) */
  /* -- the proposal -- */
  float width MFV_INIT(0.1f);     /* its width along x (an alpha; <= 0: a mixture of widths) */
  float width_y MFV_INIT(0);      /* its width along y: > 0 stretches it to (width, width_y); 0: isotropic */
  /* -- the samples -- */
  mfv_u32 stream MFV_INIT(0);     /* Philox counter word 2: the low 32 bits of the integral's stream */
  mfv_u32 stream_hi MFV_INIT(0);  /* the stream's high bits (< 2^24), in counter word 3 above the draw (rng.cl) */
  mfv_u32 strata MFV_INIT(0);     /* samples of a stratified integral (set by the integrator); 0 = iid */
  mfv_u32 points MFV_INIT(0);     /* ALBEDO_MIS: points per RQMC replicate (set by the integrator) */
};

#ifndef __OPENCL_C_VERSION__
}  /* namespace mfv */
#endif
#undef MFV_INIT
#endif /* MFV_ABI_INTEGRAL_H */
