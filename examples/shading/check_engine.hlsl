// mfv check adapter for examples/shading/engine_brdf.hlsl (HLSL, checked as it is):
//   mfv check --include examples/shading/engine_brdf.hlsl --brdf examples/shading/check_engine.hlsl \
//             --as ggx/smith_ggx_correlated/schlick --map alpha=roughness^2
// mfv: param roughness 0.0316 1 default 0.5 perceptual
// mfv: param f0 0.02 1 default 0.04
float3 brdf(float3 wi, float3 wo, float params[6])
{
    return StandardShading((float3)params[1], params[0], wi, wo);
}
float D(float3 m, float params[6])
{
    float a = params[0] * params[0];
    return m.z > 0 ? D_GGX(a * a, m.z, m.x * m.x + m.y * m.y) : 0;
}
