// mfv check --brdf FILE.cl: bounds for the user's params[k] reads. Built only
// with -DMFV_USER_BRDF, right before the user's file, in which host/user/
// (guard_param_reads) rewrote every `params[k]` as
// `params[MFV_PARAM_INDEX(k)]`. An index outside the declared parameters
// [0, MFV_USER_NPARAMS) reads the poison slot params[MFV_USER_PARAMS], a NaN
// (kernels/user_brdf.cl), so the value the code computes from it is NaN and
// every check fails on it instead of reading 0 and passing (issue 17).

#define MFV_USER_PARAMS 6

static inline long mfv_param_index(long k) { return k >= 0 && k < MFV_USER_NPARAMS ? k : MFV_USER_PARAMS; }
#define MFV_PARAM_INDEX(k) mfv_param_index((long)(k))

// The user's scalar type: float, or double in the double twin (-DMFV_USER_TWIN,
// host/user/user_twin.hpp), where kernels/user_prelude.cl maps the file's
// float types to double. The adapters (kernels/user_brdf.cl) convert the
// estimators' directions to it: correctly rounded where they are double.
#ifdef MFV_USER_TWIN
typedef double mfv_ufloat;
typedef double3 mfv_ufloat3;
#define convert_mfv_ufloat3 convert_double3
#else
typedef float mfv_ufloat;
typedef float3 mfv_ufloat3;
#define convert_mfv_ufloat3 convert_float3
#endif
