// An engine-style HLSL shading library (written for mfv's tests in the way
// real-time engines write theirs; not copied from any engine). Checked as
// it is: examples/shading/check_engine.hlsl is the adapter.
//
// Terms: GGX D (Walter et al. 2007 eq. 33), height-correlated Smith
// visibility (Heitz 2014 eq. 99), Schlick's Fresnel (Schlick 1994 eq. 15)
// with the f90 an engine derives from f0 (saturate(50 f0.g)), and a
// Charlie sheen lobe (Estevez and Kulla 2017) with Neubelt and Pettineo's
// visibility (2013) that some engines clamp.

#ifndef SHADING_HAS_SHEEN
#define SHADING_HAS_SHEEN 0
#endif

static const float PI = 3.1415926535897932f;

struct BxDFContext
{
    float NoL;
    float NoV;
    float NoH;
    float VoH;
    float SinH2;
};

void InitBxDFContext(inout BxDFContext Context, float3 L, float3 V)
{
    float3 S = L + V;
    float Len = length(S);
    float3 H = S / Len;
    Context.NoL = L.z;
    Context.NoV = V.z;
    Context.NoH = H.z;
    Context.VoH = min(0.5 * Len, 1.0);
    Context.SinH2 = H.x * H.x + H.y * H.y;
}

float Pow5(float x)
{
    float xx = x * x;
    return xx * xx * x;
}

// GGX from the half vector's cosine and sine squared (no cancellation near the normal)
float D_GGX(float a2, float NoH, float SinH2)
{
    float k = NoH * NoH + SinH2 / a2;
    return rcp(PI * a2 * k * k);
}

float Vis_SmithJointExact(float a2, float NoV, float NoL)
{
    float Vis_SmithV = NoL * sqrt(NoV * (NoV - NoV * a2) + a2);
    float Vis_SmithL = NoV * sqrt(NoL * (NoL - NoL * a2) + a2);
    return 0.5 * rcp(max(Vis_SmithV + Vis_SmithL, 1e-30));  // no infinity where both cosines underflow
}

float3 F_Schlick(float3 SpecularColor, float VoH)
{
    float Fc = Pow5(1 - VoH);
    // f90 from the specular color: anything below 2 % reflectance is a shadow
    return saturate(50.0 * SpecularColor.g) * Fc + (1 - Fc) * SpecularColor;
}

float3 SpecularGGX(float Roughness, float3 SpecularColor, BxDFContext Context)
{
    float a = Roughness * Roughness;
    float a2 = a * a;
    float D = D_GGX(a2, Context.NoH, Context.SinH2);
    float Vis = Vis_SmithJointExact(a2, Context.NoV, Context.NoL);
    float3 F = F_Schlick(SpecularColor, Context.VoH);
    return (D * Vis) * F;
}

float3 StandardShading(float3 SpecularColor, float Roughness, float3 L, float3 V)
{
    if (L.z <= 0 || V.z <= 0)
        return float3(0, 0, 0);
    BxDFContext Context;
    InitBxDFContext(Context, L, V);
    return SpecularGGX(Roughness, SpecularColor, Context);
}
