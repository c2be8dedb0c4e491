// HLSL matrices of engines' shading files that mfv check covers, in one file
// written for the tests (not copied from any engine): float2x2 and float4x4
// built row by row (HLSL's constructors fill rows), mul(M, v) = (row_i . v),
// mul(v, M) = sum v_i row_i, M[i] a row, the truncating cast (float3x3)M and
// transpose; sincos and swizzles of a scalar (x.xxx). The BRDF is a Lambert
// (Lambert 1760) times a factor that is 1 under HLSL's conventions and -1
// where any one reads a transposed matrix (a min, so that two wrong
// conventions cannot cancel), which the finite check's negative values catch
// (tests/test_check_dialects.cpp checks it, and plants a column-read
// float2x2).
// mfv: param roughness 0.05 1 default 0.5 roughness
static const float PI = 3.14159265;

float conventions() {
    float2x2 R = float2x2(0.8, -0.6, 0.6, 0.8);                  // rows (0.8, -0.6), (0.6, 0.8)
    float y = mul(R, float2(1, 0)).y / 0.6;                      // row 1 . (1, 0): 1 (by columns: -1)
    float4x4 T = float4x4(1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);  // a translation in row 0
    float x = mul(T, float4(0, 0, 0, 1)).x / 0.5;                // 1 (by columns: 0)
    float w = mul(float4(1, 0, 0, 0), T).w / 0.5;                // sum v_i row_i = row 0: 1 (by columns: 0)
    float3x3 U = (float3x3)mul(transpose(T), transpose(T));      // upper-left: the identity
    float sn, cs;
    sincos(0.6435011, sn, cs);                                   // (0.6, 0.8): its out arguments
    float3 k = (sn / 0.6).xxx * float2(1, 0).xxx;                // swizzles of a scalar and of a vector's x
    float sc = step(abs(k.z - 1) + abs(cs - 0.8), 1e-4);         // 1 (swapped: 0)
    float ok = min(min(0.5 * (y + 1), min(x, w)), min(min(U[2][2], T[3][3]), sc));  // each 1 or 0
    return 2 * ok - 1;
}

float3 brdf(float3 wi, float3 wo, float params[6]) {
    if (wi.z <= 0 || wo.z <= 0) return 0;
    return conventions() / PI;
}
