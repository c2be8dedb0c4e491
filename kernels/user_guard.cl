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
