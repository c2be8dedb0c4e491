// GLSL constructs of engines' shading files that mfv check covers, in one
// file written for the tests (not copied from any engine): file-scope const
// matrices and vectors built by constructors with several arguments, a
// function returning mat3, a product chain transpose(m) * m * IDENTITY,
// m[i][j], floatBitsToUint/uintBitsToFloat, a mat2 rotation and a mat4
// translation (column-major: GLSL 4.60 §5.4.2) with mat4(mat3) and
// mat3(mat4), array constructors float[3](...) and scalar swizzles. The BRDF
// is a Lambert of albedo dot(LUMA, 1) = 1 (Lambert 1760) times a factor that
// is 1 under GLSL's conventions and -1 under a transposed one, which the
// finite check's negative values catch (tests/test_check_dialects.cpp checks
// it, and plants a row-major mat2).
// mfv: param roughness 0.05 1 default 0.5 roughness
const mat3 IDENTITY = mat3(1.0);
const vec3 LUMA = vec3(0.2126, 0.7152, 0.0722);
mat3 frameOf(vec3 n) {
    vec3 t = normalize(cross(abs(n.x) > 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0), n));
    return mat3(t, cross(n, t), n);
}
mat2 rotation(float a) {
    float c = cos(a), s = sin(a);
    return mat2(c, s, -s, c);  // columns (c, s) and (-s, c)
}
// 1 under column-major matrices (m * v sums v's weights of the columns),
// -1 where any one reads a transposed or unfilled matrix (a min, so that
// two wrong conventions cannot cancel)
float conventions() {
    mat2 r = rotation(0.3);
    float y = (r * vec2(1.0, 0.0)).y / sin(0.3);           // 1 (row-major: -1)
    mat2 rr = transpose(r) * r;                             // identity
    mat4 T = mat4(1.0);
    T[3] = vec4(0.5, 0.0, 0.0, 1.0);                        // a translation column
    float x = (T * vec4(0.0, 0.0, 0.0, 1.0)).x / 0.5;       // 1 (row-major: 0)
    float w = (vec4(1.0, 0.0, 0.0, 0.0) * T).w / 0.5;       // v * T = (v . T[i]): 1 (as T * v: 0)
    mat4 F = mat4(frameOf(vec3(0.0, 0.0, 1.0)));            // upper-left, identity elsewhere
    mat3 back = mat3(F * T);                                // the frame again
    float weights[3] = float[3](0.25, 0.5, 0.25);           // an array constructor
    vec2 pair[2] = vec2[](vec2(1.0, 0.0), vec2(0.0));
    float sum = (weights[0] + weights[1] + weights[2] + pair[1].y).xxx.z * pair[0].xx.y;  // 1
    float ok = min(min(0.5 * (y + 1.0), min(x, w)), min(min(rr[1][1], F[3][3]), min(back[2][2], sum)));  // each 1 or 0
    return 2.0 * ok - 1.0;
}
float lambertish(vec3 wi, vec3 wo) {
    mat3 m = frameOf(vec3(0.0, 0.0, 1.0));
    m = transpose(m) * m * IDENTITY;
    float k = m[2][2] * dot(LUMA, vec3(1.0)) * conventions();
    uint bits = floatBitsToUint(k);
    return uintBitsToFloat(bits) / 3.14159265;
}
vec3 brdf(vec3 wi, vec3 wo, float params[6]) {
    if (wi.z <= 0.0 || wo.z <= 0.0) return vec3(0.0);
    return vec3(lambertish(wi, wo));
}
