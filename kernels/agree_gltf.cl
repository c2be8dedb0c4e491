// Pointwise agreement of the glTF metallic-roughness model (model_gltf.cl)
// with its reference twin (host/checks/agree_gltf.cpp): the directions of
// agree_eval, parameters across the model's whole range.
//
// Record (16 floats): [0..5] wi.xyz, wo.xyz; [6..11] alpha, metallic, base,
// f0, f0_max, weight; [12] value (float part), [13] remainder; [14..15] unused.
#ifdef MFV_WITH_GLTF
__kernel void agree_gltf(ulong seed, uint stream, ulong first, __global float* rec) {
  size_t i = get_global_id(0);
  uint4 rp, rk;
  real3 wi, wo, h;
  agree_draw(seed, stream, first + i, &rp, &rk, &wi, &wo, &h);
  __global float* r = rec + i * AGREE_RECORD;
  r[0] = wi.x; r[1] = wi.y; r[2] = wi.z;
  r[3] = wo.x; r[4] = wo.y; r[5] = wo.z;
  // roughness log-uniform in [0.01, 1], so alpha = roughness² spans [1e-4, 1]
  real rough = exp(log(R(0.01)) * u01_open(rp.x));
  real f0 = u01_open(rp.w);
  r[6] = rough * rough;
  r[7] = u01_open(rp.y);                         // metallic
  r[8] = u01_open(rp.z);                         // base colour channel
  r[9] = f0;                                     // dielectric F0 of this channel
  r[10] = f0 + u01_open(rk.x) * (R(1.0) - f0);  // the largest channel's F0, >= f0
  r[11] = u01_open(rk.y);                        // specular weight
  r[14] = 0.0f;
  r[15] = 0.0f;
  // evaluated from the float record, as agree_eval does
  real3 a = (real3)(r[0], r[1], r[2]), b = (real3)(r[3], r[4], r[5]);
#ifdef MFV_DOUBLE
  a = normalize(a);
  b = normalize(b);
#endif
  store_value(r, model_gltf_pbr(a, b, r[6], r[7], r[8], r[9], r[10], r[11]));
}
#endif
