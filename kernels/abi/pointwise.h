// The pointwise record: one layout for every kernel-against-reference
// harness (mfv agree, mfv stability, mfv eval and the census and agreement
// of mfv check), shared by the OpenCL C kernels (kernels/pointwise.cl,
// agree.cl, stability.cl, user_brdf.cl) and the C++ host
// (host/checks/pointwise.hpp). Plain C that both languages read: the host
// includes it as "abi/pointwise.h" and the kernel loader
// (runtime/opencl.cpp) pastes it where a kernel file includes it.
//
// A record is PW_RECORD numbers. Its element type is the harness's: float
// where the inputs are drawn or written in float (agree, eval, check: the
// reference then reads exactly the float-rounded inputs), `real` where a
// sweep is laid out in the working precision (stability).
#ifndef MFV_ABI_POINTWISE_H
#define MFV_ABI_POINTWISE_H

#ifdef __cplusplus
namespace mfv::pw {
#endif

// What a record evaluates: one term, one assembled D x G x F BRDF, one whole
// model (`d` carries the model's number), one alternative formulation of
// mfv stability (kernels/stability_variants.cl) or one rough dielectric BTDF.
enum PwMode {
  PW_D = 0,
  PW_G = 1,
  PW_F = 2,
  PW_G1 = 3,
  PW_BRDF = 4,
  PW_MODEL = 5,
  PW_D_ANISO = 6,  // anisotropic terms (Term::aniso) with both widths
  PW_G1_ANISO = 7,
  PW_BRDF_ANISO = 8,
  PW_VARIANT = 9,
  PW_BTDF = 10  // the rough dielectric BTDF (kernels/btdf.cl): `f` carries its code (abi/bsdf.h), PW_F0 eta
};

// Named slots. The geometry is either two directions (BRDF, MODEL, the half
// vector variants) or, for a single term, the cosines it takes.
enum PwSlot {
  PW_WI_X = 0,  // wi (the light) in the local frame n = +z
  PW_WI_Y = 1,
  PW_WI_Z = 2,
  PW_WO_X = 3,  // wo (the view)
  PW_WO_Y = 4,
  PW_WO_Z = 5,
  PW_NOL = 0,  // term records: the cosines
  PW_NOV = 1,
  PW_NOH = 2,
  PW_VOH = 3,
  PW_SIN2H = 4,  // mode D: |n x h|^2 beside NoH (stability forms it on the host, agree from NoH)
  PW_AUX_X = 4,  // D_ANISO: h.x, h.y; G1_ANISO: v.x, v.y (tangent frame t = +x, b = +y)
  PW_AUX_Y = 5,
  PW_H_X = 0,  // variant D_ggx: the half vector (h.x, 0, h.z)
  PW_H_Z = 2,
  PW_P0 = 6,   // parameters p[0..6]; a whole model reads them as its p[0..6]
  PW_PD = 6,   // the D's parameter (its width alpha_x in the anisotropic modes)
  PW_PG = 7,   // the G's parameter
  PW_F0 = 8,   // the F's first and second parameter
  PW_F1 = 9,
  PW_KD = 10,  // the Lambertian share of an assembled BRDF
  PW_P5 = 11,
  PW_P6 = 12,
  PW_ALPHA_Y = 12,  // the second width of the anisotropic modes (D's and G's alike)
  PW_M_X = 13,      // mfv check: a microfacet normal m for D(m) and G1(v, m)
  PW_M_Y = 14,
  PW_M_Z = 15,
  PW_VALUE = 16,     // the kernel's value (pre-filled with NaN: unwritten cannot pass)
  PW_VALUE_LO = 17,  // value - (float)value where a double value sits in a float record
  PW_BRDF_R = 18,    // mfv check: brdf(wi, wo) per channel, D(m), G1(wo, m), G1(wi, m)
  PW_BRDF_G = 19,
  PW_BRDF_B = 20,
  PW_USER_D = 21,
  PW_USER_G1_WO = 22,
  PW_USER_G1_WI = 23,
  PW_RECORD = 24
};

// Parameters in a record (p[0..6]) and the draw ranges of mfv agree: per
// parameter (lo, hi, log flag), PW_PARAMS of them.
enum PwCounts { PW_PARAMS = 7, PW_RANGE = 3 * 7 };

#ifdef __cplusplus
}  // namespace mfv::pw
#endif

#endif  // MFV_ABI_POINTWISE_H
