// An engine-style HLSL sheen lobe (written for mfv's tests; not copied from
// any engine), checked as it is with its adapter at the end:
//   mfv check --brdf examples/shading/sheen.hlsl
// Charlie sheen distribution (Estevez and Kulla 2017, eq. 2) and Neubelt and
// Pettineo's visibility 1 / (4 (n.l + n.v - n.l n.v)) (2013, "Crafting a
// next-gen material pipeline for The Order: 1886"), saturated to at most 1 as
// engines ship it (the form is unbounded where both cosines go to 0). At
// sheen roughness >= 0.3 the lobe keeps E <= 1; used down to 0.07 it gains
// energy at grazing views (tests/test_check_dialects.cpp's plant
// hlsl_sheen_saturate_gains fails the furnace).
// mfv: param SheenRoughness 0.3 1 default 0.5 roughness
// mfv: param SheenColor 0 1 default 1

static const float PI = 3.14159265358979;

float D_Charlie(float Roughness, float NoH)
{
    float InvAlpha = rcp(Roughness);
    float Cos2h = NoH * NoH;
    float Sin2h = max(1 - Cos2h, 0.0078125);  // 2^-7: keeps the power finite in fp16
    return (2 + InvAlpha) * pow(Sin2h, InvAlpha * 0.5) / (2 * PI);
}

float Vis_Neubelt(float NoV, float NoL)
{
    return saturate(rcp(4 * (NoL + NoV - NoL * NoV)));
}

float3 SheenLobe(float3 SheenColor, float Roughness, float NoV, float NoL, float NoH)
{
    return SheenColor * (D_Charlie(Roughness, NoH) * Vis_Neubelt(NoV, NoL));
}

float3 brdf(float3 wi, float3 wo, float params[6])
{
    if (wi.z <= 0 || wo.z <= 0)
        return 0;
    float3 H = normalize(wi + wo);
    return SheenLobe((float3)params[1], params[0], wo.z, wi.z, H.z);
}
