/* The rough dielectric BSDF's codes (kernels/btdf.cl, host/catalog/bsdfs.*,
 * host/reference/btdf.*): which G2 form a BTDF takes and which known-bad
 * variant, if any, it plants. One integer: the form in bit 0, the variant
 * above it (code = form | variant << 1). Plain C, read by both languages. */
#ifndef MFV_ABI_BSDF_H
#define MFV_ABI_BSDF_H

#define MFV_BTDF_SEPARABLE 0  /* G2 = G1(i, m) G1(o, m) (Walter et al. 2007 eq. 23) */
#define MFV_BTDF_CORRELATED 1 /* G2 = 1 / (1 + Λ(i) + Λ(o)) (height-correlated; pbrt-v4, Heitz 2014 eq. 99) */

/* Known-bad variants (catalog entries that must fail their check). */
#define MFV_BTDF_OK 0
#define MFV_BTDF_BAD_F_AT_N 1      /* F(n·i) in place of F(i·h) */
#define MFV_BTDF_BAD_NO_ETA2 2     /* η_o² missing from the numerator */
#define MFV_BTDF_BAD_JACOBIAN 3    /* (i·h + o·h)² in place of (η_i i·h + η_o o·h)² */
#define MFV_BTDF_BAD_SAME_SIDE 4   /* refracted directions on the incident side of m counted */
#define MFV_BTDF_VARIANTS 5

#define MFV_BTDF_CODE(form, variant) ((form) | ((variant) << 1))

#endif /* MFV_ABI_BSDF_H */
