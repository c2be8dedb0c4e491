// KHR_materials_transmission in scenes (issue 29): thin-walled materials are
// checked as the catalog's gltf_transmission model (the specular lobe mirrored
// through the surface), with R + T = the F = 1 albedo of the same D and Vis as
// a verdict (closed_form); with KHR_materials_volume thickness > 0 the surface
// is a refracting boundary, the Walter BSDF at eta = ior (bsdf_furnace,
// transmission_masking, bsdf_avg_reciprocity). Each is shown passing the
// corpus scenes and failing a planted defect.
#include "catalog/models.hpp"
#include "kernel_dir.hpp"
#include "plants.hpp"
#include "reference/model_gltf.hpp"
#include "run_mfv.hpp"
#include "scene/scene.hpp"
#include "scene_files.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

using namespace mfv;
using namespace mfv::test;

namespace {

const std::string kCorpus = std::string(MFV_TEST_DATA_DIR) + "/corpus";

bool mentions(const std::vector<std::string>& lines, const std::string& what) {
  for (auto& l : lines)
    if (l.find(what) != std::string::npos) return true;
  return false;
}

// The transmission scene's first material with one field replaced.
std::string with_transmission(const Scratch& t, const nlohmann::json& ext) {
  nlohmann::json j = nlohmann::json::parse(slurp(kCorpus + "/transmission.gltf"));
  j["materials"][0]["extensions"] = ext;
  return t.file("bad.gltf", j.dump());
}

}  // namespace

TEST_CASE("transmitting materials load as thin-walled or as refracting boundaries, each named per material",
          "[scene][corpus][transmission]") {
  Scene thin = load_scene(kCorpus + "/transmission.gltf");
  const SceneMaterial& film = named(thin, "clear film");
  CHECK(film.thin_checked);
  CHECK_FALSE(film.volume_checked);
  CHECK(film.not_checked.empty());
  CHECK(film.model() == "gltf_transmission");
  CHECK(mentions(film.account, "thin-walled (no KHR_materials_volume thickness): checked as the gltf_transmission"));
  // one identity point per roughness point: white base, full transmission, no metal, f0 of its ior
  REQUIRE(film.thin_identity_points().size() == 1);
  CHECK(film.thin_identity_points()[0][0] == Approx(0.09));
  CHECK(film.thin_identity_points()[0][3] == Approx(0.04));
  CHECK(named(thin, "frosted film").thin_identity_points()[0][3] == Approx(std::pow(0.33 / 2.33, 2)));
  // energy and reciprocity run on the transmitting model, at the ends of transmission
  for (const WholePoint& w : named(thin, "tinted sheet").whole_points()) {
    CHECK(w.model->id == "gltf_transmission");
    CHECK(w.p[4] == 0.5);
  }

  Scene vol = load_scene(kCorpus + "/volume.gltf");
  const SceneMaterial& water = named(vol, "water");
  CHECK(water.volume_checked);
  CHECK_FALSE(water.thin_checked);
  CHECK(water.model() == "walter_ggx_correlated");
  CHECK(water.whole_points().empty());  // a boundary is not checked as a BRDF
  CHECK(mentions(water.account, "at eta = ior 1.33"));
}

TEST_CASE("the thin-walled model folds R + T into the F = 1 lobe of the same D and Vis, pointwise",
          "[scene][transmission][reference]") {
  // F and 1 - F of one mirrored half vector add to 1: with a white base, full
  // transmission and no metal the folded BSDF is D Vis itself, at every f0
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto dir = [&] {
    const double z = u(rng), phi = 2 * M_PI * u(rng), s = std::sqrt(1 - z * z);
    return glm::dvec3(s * std::cos(phi), s * std::sin(phi), z);
  };
  for (int k = 0; k < 2000; ++k) {
    const glm::dvec3 l = dir(), v = dir();
    const double alpha = 0.01 + u(rng), f0 = u(rng);
    const double thin[7] = {alpha, 0.0, 1.0, f0, 1.0, 0.0, 0.0};
    const double white[7] = {alpha, 1.0, 1.0, 0.04, 0.04, 1.0, 0.0};
    const double lobe = ref::model_gltf(l, v, white);
    CHECK(ref::model_gltf_transmission(l, v, thin) == Approx(lobe).epsilon(1e-12).margin(1e-300));
  }
  CHECK(try_find_model("gltf_transmission") != nullptr);
}

TEST_CASE("bad transmission and volume values are one error line, exit 2", "[cli][scene][errors][transmission]") {
  Scratch t;
  const std::vector<std::pair<nlohmann::json, std::string>> cases = {
      {{{"KHR_materials_transmission", {{"transmissionFactor", 1.5}}}}, "transmissionFactor = 1.5 is out of range"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", "1"}}}}, "transmissionFactor"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", -0.1}}}}, "out of range [0, 1]"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
        {"KHR_materials_volume", {{"thicknessFactor", -1.0}}}},
       "thicknessFactor = -1 is negative"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}, {"KHR_materials_ior", {{"ior", 0.5}}}},
       "ior = 0.5 is out of range"},
  };
  for (auto& [ext, what] : cases) {
    INFO(ext.dump());
    auto r = run_mfv("run --scene " + with_transmission(t, ext) + " --check closed_form --out " + (t / "out"));
    CHECK(r.code == 2);
    CHECK(r.out.find("mfv: error: ") != std::string::npos);
    CHECK(r.out.find(what) != std::string::npos);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
  // a refracting boundary at ior 1 (index matched: a Dirac no BTDF represents) is said, not checked
  Scene s = load_scene(with_transmission(t, {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                             {"KHR_materials_volume", {{"thicknessFactor", 1.0}}},
                                             {"KHR_materials_ior", {{"ior", 1.0}}}}));
  CHECK(s.materials[0].not_checked.find("a refracting boundary needs ior > 1") != std::string::npos);
}

TEST_CASE("mfv run --scene passes thin-walled transmission and fails a lobe whose half vector is not mirrored",
          "[device][scene][corpus][transmission][planted]") {
  Scratch t;
  const std::string scene = t.copy(kCorpus + "/transmission.gltf");
  auto run = [&](const std::string& kernel_dir) {
    return run_mfv((kernel_dir.empty() ? "" : "--kernel-dir " + kernel_dir + " ") + "run --scene " + scene +
                   " --check closed_form energy reciprocity --seed 3 --out " + (t / "out"));
  };
  auto good = run("");
  INFO(good.out);
  CHECK(good.code == 0);
  CHECK(good.out.find("pass   closed_form") != std::string::npos);
  CHECK(good.out.find("material 'clear film' [materials[0]] pass: gltf_transmission") != std::string::npos);
  // the transmitted half's lobe (D, Vis and F) at the half vector of the light below, not of its mirror
  const PlantedKernelDir planted(
      "model_gltf.cl", "  real through = (R(1.0) - metallic) * (R(1.0) - fr) * transmission * base * spec;",
      "  real s2b, VoHb;\n"
      "  real3 hb = half_vector(l, (real3)(v.x, v.y, -v.z), &s2b, &VoHb);\n"
      "  real xb = R(1.0) - VoHb, frb = f0 + (R(1.0) - f0) * xb * xb * xb * xb * xb;\n"
      "  real specb = over_4_cosines(D_ggx(hb.z, s2b, alpha) * G_smith_ggx_correlated(NoL, NoV, hb.z, VoHb, alpha),\n"
      "                              NoL, NoV);\n"
      "  real through = (R(1.0) - metallic) * (R(1.0) - frb) * transmission * base * specb;");
  auto bad = run(planted.path());
  INFO(bad.out);
  CHECK(bad.code == 1);
  CHECK(bad.out.find("FAIL   closed_form") != std::string::npos);
}

TEST_CASE("mfv run --scene checks a volume material as the Walter BSDF at its ior and fails a BTDF without eta^2",
          "[device][scene][corpus][transmission][planted]") {
  Scratch t;
  const std::string scene = t.copy(kCorpus + "/volume.gltf");
  auto run = [&](const std::string& kernel_dir) {
    return run_mfv((kernel_dir.empty() ? "" : "--kernel-dir " + kernel_dir + " ") + "run --scene " + scene +
                   " --check bsdf_furnace transmission_masking bsdf_avg_reciprocity --seed 3 --out " + (t / "out"));
  };
  auto good = run("");
  INFO(good.out);
  CHECK(good.code == 0);
  CHECK(good.out.find("set: walter_ggx_correlated eta=1.33 alpha=0.09") != std::string::npos);
  CHECK(good.out.find("FAIL   ") == std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(slurp(t.dir / "out" / "results.json"));
  CHECK(j["scene"]["materials"][1]["model"] == "walter_ggx_correlated");
  auto planted = test::planted(kBtdfEtaNotSquared);
  auto bad = run(planted.path());
  INFO(bad.out);
  CHECK(bad.code == 1);
  CHECK(bad.out.find("FAIL   bsdf_furnace") != std::string::npos);
}

TEST_CASE("mfv stability --scene sweeps a volume material's Walter BSDF at its alpha and ior and a thin-walled one's model",
          "[device][scene][corpus][transmission][stability][planted]") {
  Scratch t;
  auto sweep = [&](const std::string& scene, const std::string& kernel_dir) {
    const Run r = run_mfv((kernel_dir.empty() ? "" : "--kernel-dir " + kernel_dir + " ") + "stability --scene " +
                          t.copy(kCorpus + "/" + scene) + " --out " + (t / "out"));
    return std::make_pair(r, nlohmann::json::parse(slurp(t.dir / "out" / "stability.json")));
  };
  auto scene_region = [](const nlohmann::json& j) {
    for (auto& c : j["cases"])
      if (c["name"] == "BTDF walter_ggx_correlated")
        for (auto& r : c["regions"])
          if (r["region"] == "scene") return r;
    return nlohmann::json();
  };
  {
    const auto [r, j] = sweep("volume.gltf", "");
    INFO(r.out);
    CHECK(r.code == 0);
    CHECK(r.out.find("material 'water': refracting (KHR_materials_volume): BTDF walter_ggx_correlated in its region "
                     "'scene' at (alpha 0.09, eta 1.33)") != std::string::npos);
    const nlohmann::json s = scene_region(j);
    REQUIRE(s.is_object());
    CHECK(s["inputs"].get<std::string>().find("(alpha 0.25, eta 1.5) (alpha 0.09, eta 1.33)") != std::string::npos);
    CHECK(s["points"] == 92);  // 2 materials x (16 refracted + 7 near-critical) x both sides
    CHECK(s["nan"] == 0);
    CHECK(s["inf"] == 0);
    CHECK(s["breaks"] == 0);
  }
  {
    const auto [r, j] = sweep("transmission.gltf", "");
    INFO(r.out);
    CHECK(r.code == 0);
    CHECK(r.out.find("MODEL gltf_transmission") != std::string::npos);
    CHECK(!scene_region(j).is_object());  // thin-walled: no refracting boundary
  }
  {
    // the region sees a BTDF whose critical angle is off (1e-5 in g²)
    auto planted = test::planted(kBtdfCriticalAngleShifted);
    const auto [r, j] = sweep("volume.gltf", planted.path());
    const nlohmann::json s = scene_region(j);
    REQUIRE(s.is_object());
    CAPTURE(s.dump());
    CHECK(s["breaks"].get<int>() > 0);
  }
}
