// The one width mapping (catalog/catalog.hpp Roughness, catalog/roughness.hpp):
// terms and whole models map their native roughness onto alpha by the same
// functions, and each mapping inverts the other way.
#include "catalog/models.hpp"
#include "catalog/roughness.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace mfv;

TEST_CASE("every width mapping inverts: alpha -> native -> alpha", "[catalog][roughness]") {
  for (Roughness r : {Roughness::Alpha, Roughness::PhongExponent, Roughness::Rho, Roughness::BeckmannM,
                      Roughness::Perceptual, Roughness::MirrorExponent, Roughness::HalfCosine})
    for (double alpha : {1e-3, 0.01, 0.1, 0.3, 0.7, 1.0}) {
      INFO("mapping " << static_cast<int>(r) << " alpha " << alpha);
      // tan(acos t) = sqrt(1 - t²)/t at t = 1/sqrt(1 + alpha²) ~ 1 - alpha²/2: 1 - t² cancels to a relative
      // error of about 2^-52/alpha² (2.2e-10 at alpha 1e-3); the other mappings lose a few roundings.
      const double tol = r == Roughness::HalfCosine ? 1e-9 : 1e-12;
      CHECK(alpha_from_native(r, native_from_alpha(r, alpha)) == Approx(alpha).epsilon(tol));
    }
  CHECK(native_from_alpha(Roughness::None, 0.3) == 0.0);
}

TEST_CASE("the mappings follow their formulas", "[catalog][roughness]") {
  CHECK(alpha_from_native(Roughness::Perceptual, 0.5) == 0.25);                // alpha = r² (Burley 2012)
  CHECK(alpha_from_native(Roughness::PhongExponent, 2.0) == std::sqrt(0.5));   // sqrt(2/(e+2))
  CHECK(alpha_from_native(Roughness::MirrorExponent, 0.5) == std::sqrt(0.5));  // the (n.h)^(4e) lobe
  CHECK(alpha_from_native(Roughness::HalfCosine, 0.6) == Approx(4.0 / 3.0));   // tan(acos 0.6)
  CHECK(std::isfinite(alpha_from_native(Roughness::HalfCosine, 1.0)));         // t clamped below 1
  CHECK(alpha_from_native(Roughness::HalfCosine, 0.0) == Approx(std::sqrt(1 - 1e-6) / 1e-3));  // and above 0
}

// The proposal widths of whole models, as the former per-model Width enum gave them.
TEST_CASE("whole models take their proposal width through the shared mapping", "[catalog][roughness][models]") {
  auto width = [](const char* id, ModelParams p) { return try_find_model(id)->proposal_width(p.data()); };
  CHECK(width("lambert", {1.0}) == 1.0);                                              // no lobe
  CHECK(width("phong_004", {1.0, 20.0}) == alpha_from_phong_exponent(4.0 * 20.0));    // (v.r)^n
  CHECK(width("gltf", {0.73, 1, 1, 0.04, 0.04, 1, 0.25}) == std::sqrt(0.73 * 0.25));  // anisotropic pair
  CHECK(width("gltf", {0.25, 1, 1, 0.04, 0.04, 1, 0.0}) == 0.25);                     // isotropic
  CHECK(width("gltf_clearcoat", {0.25, 1, 1, 0.04, 0.04, 0.01, 1}) == 0.01);          // the narrower lobe
  CHECK(width("radiance_002", {0.8, 0.0, 0.5}) == 0.25);                              // perceptual r
}
