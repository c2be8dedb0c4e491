// An engine-style HLSL file (written for mfv's tests in the way real-time
// engines write theirs; not copied from any engine) that shades in a
// tangent frame: a float3x3 of the frame's rows, directions taken into it
// by mul() on either side, saturate, lerp, rsqrt, static const, inline and
// a function-like macro. Checked as it is, with its adapter at the end:
//   mfv check --brdf examples/shading/frame_ggx.hlsl --as ggx/smith_ggx_correlated/schlick --map alpha=roughness^2
// tests/data/shading/frame_ggx_port.cl (PORT_HLSL=1) is its hand port; the
// two give the same values (tests/test_check_dialects.cpp).
//
// Terms: GGX D (Walter et al. 2007 eq. 33), height-correlated Smith
// visibility (Heitz 2014 eq. 99), Schlick's Fresnel (Schlick 1994 eq. 15).
// mfv: param Roughness 0.0316 1 default 0.5 perceptual
// mfv: param F0 0 1 default 0.04

#ifndef FRAME_TILT
#define FRAME_TILT 0.0
#endif

static const float PI = 3.14159265358979;
static const float TangentRotation = 0.6435011;
#define Square(x) ((x) * (x))

inline float D_GGX(float a, float NoH, float SinH2)
{
    float a2 = a * a;
    float k = Square(NoH) + SinH2 / a2;
    return 1.0 / (PI * a2 * k * k);
}

inline float Vis_SmithJointExact(float a, float NoV, float NoL)
{
    float a2 = a * a;
    float lv = NoL * sqrt(NoV * NoV * (1.0 - a2) + a2);
    float ll = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
    return 0.5 / max(lv + ll, 1e-30);
}

float3x3 GetTangentBasis(float3 N)
{
    float Phi = atan2(sin(TangentRotation), cos(TangentRotation));
    float3 T0 = float3(cos(Phi), sin(Phi), 0);
    float3 T = normalize(T0 - N * dot(N, T0));
    float3 B = cross(N, T);
    return float3x3(T, B, N);  // rows
}

float3 ShadeInFrame(float3x3 TangentBasis, float Roughness, float3 SpecularColor, float3 L, float3 V)
{
    // world to tangent space: TangentBasis * x, written both ways engines write it
    float3 TL = mul(TangentBasis, L);
    float3 TV = mul(V, transpose(TangentBasis));
    float3x3 I = mul(transpose(TangentBasis), TangentBasis);  // the identity, up to rounding
    if (TL.z <= 0 || TV.z <= 0)
        return 0;
    float3 S = TL + TV;
    float Len = length(S);
    float3 H = S / Len;
    float a = Square(Roughness);
    float D = D_GGX(a, H.z, H.x * H.x + H.y * H.y);
    float Vis = Vis_SmithJointExact(a, TV.z, TL.z);
    float Fc = pow(1 - min(0.5 * Len, 1.0), 5.0);
    float3 F = lerp(SpecularColor, float3(1, 1, 1), Fc);
    return D * Vis * F * saturate(dot(I[2], float3(0, 0, 1)));
}

float3 brdf(float3 wi, float3 wo, float params[6])
{
    float3 N = float3(FRAME_TILT, 0, 1);
    N = N * rsqrt(dot(N, N));
    return ShadeInFrame(GetTangentBasis(N), params[0], (float3)params[1], wi, wo);
}

float D(float3 m, float params[6])
{
    return m.z > 0 ? D_GGX(Square(params[0]), m.z, m.x * m.x + m.y * m.y) : 0;
}
