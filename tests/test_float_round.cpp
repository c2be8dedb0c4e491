// through_float (util/float_round.hpp) rounds every component to float, also
// in the pattern GCC 12.2's SLP vectorizer miscompiles: two adjacent vec3
// round trips, whose x, y pairs it stored unrounded.
#include "util/float_round.hpp"

#include <catch2/catch.hpp>

namespace {

// noinline: the pair is vectorized here, as in mfv check's agreement, not folded into the caller's constants.
__attribute__((noinline)) void round_pair(glm::dvec3* a, glm::dvec3* b, const glm::dvec3& p, const glm::dvec3& q) {
  *a = mfv::through_float(p);
  *b = mfv::through_float(q);
}

}  // namespace

TEST_CASE("through_float rounds to float in double, also where GCC 12 vectorizes a pair", "[float_round]") {
  const glm::dvec3 p(0.1, 0.2, 0.3), q(0.4, 0.5, 0.6);  // none is a float
  glm::dvec3 a, b;
  round_pair(&a, &b, p, q);
  for (int i = 0; i < 3; ++i) {
    INFO("component " << i);
    CHECK(a[i] == static_cast<double>(static_cast<float>(p[i])));
    CHECK(b[i] == static_cast<double>(static_cast<float>(q[i])));
    CHECK(a[i] != p[i]);  // rounded, not passed through
  }
  CHECK(mfv::through_float(1.0 / 3.0) == static_cast<double>(1.0f / 3.0f));
}
