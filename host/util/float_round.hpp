// Rounding to float precision in double: through_float(x) is double(float(x)),
// in a form the optimizer cannot drop.
//
// GCC 12.2 (Debian 12.2.0-14, x86-64, -O2 and -O3) miscompiles the plain
// round trip where the SLP vectorizer pairs it. Reduced:
//
//   struct V { double x, y, z; };
//   static V rt(const V& v) { return {double(float(v.x)), double(float(v.y)), double(float(v.z))}; }
//   void two(V* a, V* b, const V& p, const V& q) { *a = rt(p); *b = rt(q); }
//
// stores p.x, p.y, q.x and q.y unrounded (3 of 6 components of
// {0.1 ... 0.6} wrong; -O1, -fno-tree-slp-vectorize and clang 14 round all
// six). The vectorizer writes the x, y pair as (vector(2) double)(vector(2)
// float) v, correctly (the slp2 dump), and a later GIMPLE fold removes the
// two conversions as if they were an identity (they are gone after dse5).
// mfv check's agreement met it: its reference ran on unrounded directions.
// The empty asm below makes the float a value the compiler must produce,
// so both conversions stay; it costs no memory traffic (unlike a volatile).
// tests/test_float_round.cpp holds the reduced case.
#pragma once

#include <glm/vec3.hpp>

namespace mfv {

inline double through_float(double x) {
  float f = static_cast<float>(x);
  __asm__("" : "+g"(f));  // the float must exist (GCC 12.2 bug above)
  return static_cast<double>(f);
}

inline glm::dvec3 through_float(const glm::dvec3& v) {
  return glm::dvec3(through_float(v.x), through_float(v.y), through_float(v.z));
}

}  // namespace mfv
