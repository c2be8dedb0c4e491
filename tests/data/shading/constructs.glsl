// GLSL constructs of engines' shading files that mfv check covers, in one
// file written for the tests (not copied from any engine): file-scope const
// matrices and vectors built by constructors with several arguments, a
// function returning mat3, a product chain transpose(m) * m * IDENTITY,
// m[i][j], floatBitsToUint/uintBitsToFloat. The BRDF is a Lambert of albedo
// dot(LUMA, 1) = 1 (Lambert 1760): tests/test_check_dialects.cpp checks it.
// mfv: param roughness 0.05 1 default 0.5 roughness
const mat3 IDENTITY = mat3(1.0);
const vec3 LUMA = vec3(0.2126, 0.7152, 0.0722);
mat3 frameOf(vec3 n) {
    vec3 t = normalize(cross(abs(n.x) > 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0), n));
    return mat3(t, cross(n, t), n);
}
float lambertish(vec3 wi, vec3 wo) {
    mat3 m = frameOf(vec3(0.0, 0.0, 1.0));
    m = transpose(m) * m * IDENTITY;
    float k = m[2][2] * dot(LUMA, vec3(1.0));
    uint bits = floatBitsToUint(k);
    return uintBitsToFloat(bits) / 3.14159265;
}
vec3 brdf(vec3 wi, vec3 wo, float params[6]) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return vec3(0.0);
    return vec3(lambertish(wi, wo));
}
