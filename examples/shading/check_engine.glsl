// mfv check adapter for examples/shading/engine_brdf.glsl (GLSL, checked as it is):
//   mfv check --include examples/shading/engine_brdf.glsl --brdf examples/shading/check_engine.glsl \
//             --as ggx/smith_ggx_correlated/schlick --map alpha=roughness^2
// mfv: param roughness 0.0316 1 default 0.5 perceptual
// mfv: param f0 0 1 default 0.04
vec3 brdf(vec3 wi, vec3 wo, float params[6]) {
    PixelParams p;
    p.diffuseColor = vec3(0.0);
    p.roughness = params[0];
    p.alpha = params[0] * params[0];
    p.f0 = vec3(params[1]);
    p.f90 = 1.0;
    return surfaceShading(p, wi, wo);
}
float D(vec3 m, float params[6]) {
    if (m.z <= 0.0) return 0.0;
    float a = params[0] * params[0];
    return D_GGX(a, m.z, m.x * m.x + m.y * m.y);
}
