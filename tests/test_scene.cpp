// mfv run --scene (issue 7): glTF (.gltf, .glb) and material files map to the
// right models and parameters; only what the scene uses is run; bad input is
// one line and exit 2 with earlier results untouched; the glTF model's kernel
// agrees with its reference and every scene check fails on a planted defect.
#include "kernel_dir.hpp"
#include "run_mfv.hpp"
#include "scene/scene.hpp"
#include "scene_files.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace mfv;
using namespace mfv::test;
namespace fs = std::filesystem;

namespace {

const std::string kData = std::string(MFV_TEST_DATA_DIR);

// scene.gltf with `edit` applied to its JSON.
std::string edited_gltf(const Scratch& t, const std::string& name, void (*edit)(nlohmann::json&)) {
  nlohmann::json j = nlohmann::json::parse(slurp(kData + "/scene.gltf"));
  edit(j);
  return t.file(name, j.dump());
}

}  // namespace

TEST_CASE("glTF materials map to the glTF BRDF's parameters", "[scene]") {
  Scene s = load_scene(kData + "/scene.gltf");
  CHECK(s.format == "gltf");
  CHECK(s.materials_in_file == 4);
  // the mesh uses materials 0, 2, 3 and one primitive has none (the default material); 1 is unused
  REQUIRE(s.materials.size() == 4);
  for (auto& m : s.materials) CHECK(m.name != "unused chrome");

  const SceneMaterial& plastic = named(s, "red plastic");  // dielectric, core spec: ior 1.5 -> f0 0.04
  CHECK(plastic.alpha == Approx(0.25));
  auto ch = plastic.channels();
  REQUIRE(ch.size() == 2);  // r = 0.8, g = b = 0.1
  CHECK(ch[0].f0 == Approx(0.04));
  CHECK(ch[0].base == Approx(0.8));
  CHECK(ch[0].metallic == 0.0);
  CHECK(ch[0].weight == 1.0);
  CHECK(plastic.warnings.empty());

  // metallic, roughness from an embedded 2x2 texture: G spans [128, 255]/255, B = 1 (issue 21)
  const SceneMaterial& gold = named(s, "gold");
  CHECK(gold.alpha == Approx(0.09));
  CHECK(gold.roughness.lo == Approx(0.3 * 128 / 255.0));
  CHECK(gold.roughness.hi == Approx(0.3));
  CHECK_FALSE(gold.metallic.varies());
  CHECK(gold.alphas().size() == 4);  // the ends and two points inside
  CHECK(gold.channels().size() == 3 * 4);
  CHECK(gold.warnings.empty());

  const SceneMaterial& glass = named(s, "coated glass");  // KHR_materials_ior 1.8, KHR_materials_specular
  auto gc = glass.channels();
  REQUIRE(gc.size() == 2);  // specularColor (1, 0.5, 0.5)
  const double f0_ior = std::pow(0.8 / 2.8, 2);
  CHECK(gc[0].f0 == Approx(f0_ior));
  CHECK(gc[1].f0 == Approx(0.5 * f0_ior));
  CHECK(gc[1].f0_max == Approx(f0_ior));  // the base is weighted by the largest channel's Fresnel
  CHECK(gc[0].weight == Approx(0.7));

  const SceneMaterial& def = named(s, "default material");  // glTF default: metallic 1, roughness 1
  CHECK(def.alpha == 1.0);
  CHECK(def.factors.metallic == 1.0);
}

TEST_CASE("KHR_materials_anisotropy maps to alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha", "[scene]") {
  Scene s = load_scene(kData + "/aniso.gltf");
  REQUIRE(s.materials.size() == 4);                          // a material library: every material
  const SceneMaterial& brushed = named(s, "brushed steel");  // roughness 0.5, strength 0.8, rotation 0.5
  auto ch = brushed.channels();
  REQUIRE(ch.size() == 1);
  CHECK(ch[0].alpha == Approx(0.25 + 0.75 * 0.64));  // alpha_t = 0.73
  CHECK(ch[0].alpha_b == Approx(0.25));
  CHECK(ch[0].params()[6] == Approx(0.25));  // the model's p[6]
  REQUIRE(brushed.warnings.size() == 1);
  CHECK(brushed.warnings[0].find("anisotropyRotation 0.5") != std::string::npos);

  // strength 1 from an absent texture: checked over [0, 1], alpha_t from 0.04 (isotropic) to 1
  const SceneMaterial& textured = named(s, "textured brushed");
  CHECK(textured.anisotropy_strength.lo == 0.0);
  CHECK(textured.anisotropy_strength.hi == 1.0);
  auto tc = textured.channels();
  REQUIRE(tc.size() == 4);
  CHECK(tc[0].alpha == Approx(0.04));
  CHECK(tc[0].alpha_b == 0.0);
  CHECK(tc[3].alpha == Approx(1.0));
  CHECK(tc[3].alpha_b == Approx(0.04));
  REQUIRE(textured.account.size() == 1);
  CHECK(textured.account[0].find("image 0 'brushed_direction.png' is not beside the scene") != std::string::npos);
  CHECK(s.warnings.size() == 1);  // the absent image, once, with the material it scales

  // strength 0 is today's isotropic material, parameter for parameter (p[6] = 0)
  auto iso = named(s, "isotropic steel").channels(), plain = named(s, "plain steel").channels();
  REQUIRE(iso.size() == 1);
  CHECK(iso == plain);
  CHECK(iso[0].alpha_b == 0.0);
  CHECK(iso[0].alpha == Approx(0.25));
}

TEST_CASE("a .glb container reads as its .gltf does, and roughness 0 is checked at the floor with a warning", "[scene]") {
  Scratch t;
  nlohmann::json j = nlohmann::json::parse(slurp(kData + "/scene.gltf"));
  j["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"] = 0.0;
  Scene s = load_scene(t.file("scene.glb", glb_of(j.dump())));
  CHECK(s.format == "glb");
  REQUIRE(s.materials.size() == 4);
  const SceneMaterial& plastic = named(s, "red plastic");
  CHECK(plastic.alpha == kSceneMinAlpha);
  REQUIRE(plastic.warnings.size() == 1);
  CHECK(plastic.warnings[0].find("checked at alpha = 0.0001") != std::string::npos);
}

TEST_CASE("material files name D, G, F and native parameters", "[scene]") {
  Scene s = load_scene(kData + "/materials.json");
  CHECK(s.format == "materials");
  REQUIRE(s.materials.size() == 4);
  const SceneMaterial& steel = named(s, "brushed steel");
  CHECK_FALSE(steel.gltf);
  CHECK(steel.model() == "ggx/smith_ggx_correlated/conductor");
  CHECK(steel.pd == Approx(0.2));
  CHECK(steel.pg == Approx(0.2));
  CHECK(steel.f0 == Approx(2.87));
  CHECK(steel.f1 == Approx(3.0));
  const SceneMaterial& phong = named(s, "old phong");
  CHECK(phong.pd == 100);
  CHECK(phong.pg == 100);                                // smith_phong takes alpha_p too
  CHECK(phong.alpha == Approx(std::sqrt(2.0 / 102.0)));  // the width, for the proposal
  CHECK(phong.kd == 0.5);
  CHECK(named(s, "white plastic").channels().size() == 1);  // a grey material is one channel
}

TEST_CASE("bad scenes: one line, exit 2, earlier results untouched", "[scene][cli]") {
  Scratch t;
  const std::string out = (t.dir / "out").string();
  fs::create_directories(out);
  const std::string before = "{\"earlier\": true}";
  t.file("out/results.json", before);
  struct Bad {
    std::string file, expect;
  };
  std::vector<Bad> bad = {
      {(t.dir / "missing.gltf").string(), "no such file"},
      {t.file("broken.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"materials\": ["), "not a valid glTF JSON"},
      {t.file("broken.glb", "glTF\x02\x00\x00\x00garbage"), "not a valid glTF binary"},
      {t.file("scene.obj", "o cube"), "unknown format"},
      {edited_gltf(t, "required.gltf",
                   [](nlohmann::json& j) { j["extensionsRequired"].push_back("EXT_not_a_real_extension"); }),
       "requires extension EXT_not_a_real_extension"},
      {edited_gltf(t, "aniso.gltf",
                   [](nlohmann::json& j) {
                     j["materials"][0]["extensions"]["KHR_materials_anisotropy"] = {{"anisotropyStrength", 1.5}};
                   }),
       "KHR_materials_anisotropy anisotropyStrength = 1.5 is out of range"},
      {edited_gltf(t, "rough.gltf",
                   [](nlohmann::json& j) { j["materials"][2]["pbrMetallicRoughness"]["roughnessFactor"] = 1.5; }),
       "roughnessFactor = 1.5 is out of range"},
      {edited_gltf(t, "ior.gltf",
                   [](nlohmann::json& j) { j["materials"][3]["extensions"]["KHR_materials_ior"]["ior"] = 0.5; }),
       "ior = 0.5 is out of range"},
      {t.file("m1.json",
              "{\"materials\": [{\"name\": \"x\", \"d\": \"ggx\", \"g\": \"smith\", \"f\": \"none\", "
              "\"alpha\": 0.1}]}"),
       "unknown G term 'smith'"},
      {t.file("m2.json",
              "{\"materials\": [{\"name\": \"x\", \"d\": \"ggx\", \"g\": \"smith_ggx\", \"f\": \"schlick\", "
              "\"alpha\": 0.1}]}"),
       "needs parameter f0"},
      {t.file("m3.json", "{\"materials\": [{\"name\": \"x\", \"model\": \"gltf\", \"roughnes\": 0.1}]}"),
       "unknown key 'roughnes'"},
      {t.file("m4.json", "{\"materials\": [{\"name\": \"x\", \"model\": \"gltf\", \"metallic\": -0.1}]}"),
       "metallicFactor = -0.1 is out of range"},
      {t.file("m5.json", "{\"materials\": [ {\"name\": "), "malformed JSON"},
  };
  for (auto& b : bad) {
    INFO(b.file);
    auto r = run_mfv("run --scene " + b.file + " --out " + out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
    CHECK(r.out.find(b.expect) != std::string::npos);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
  CHECK(slurp(out + "/results.json") == before);
  // the same loader behind mfv energy and mfv stability
  CHECK(run_mfv("energy --scene " + bad[6].file).code == 2);
  CHECK(run_mfv("stability --scene " + bad[4].file).code == 2);
  CHECK(run_mfv("run --scene " + kData + "/scene.gltf --model ggx").code == 2);
}

TEST_CASE("the glTF model's kernel agrees with its reference and a planted Fresnel-mix bug does not",
          "[device][scene][agree]") {
  auto ok = run_mfv("agree --only 'MODEL gltf' --samples 50000");
  INFO(ok.out);
  CHECK(ok.code == 0);
  // mfv agree on the glTF model with `from` replaced by `to` in its kernel only
  auto planted_agree = [](const std::string& from, const std::string& to) {
    const test::PlantedKernelDir planted("model_gltf.cl", from, to);
    auto bad = run_mfv("--kernel-dir " + planted.path() + " agree --only 'MODEL gltf' --samples 50000");
    INFO(bad.out);
    return bad.code;
  };
  // the diffuse base weighted by this channel's Fresnel instead of the largest channel's
  CHECK(planted_agree("(R(1.0) - weight * fr_max)", "(R(1.0) - weight * fr)") == 1);
  // KHR_materials_anisotropy: alpha_t and alpha_b swapped in the kernel's D only
  CHECK(planted_agree("D_ggx_aniso(h.z, h.x, h.y, alpha, alpha_b)", "D_ggx_aniso(h.z, h.x, h.y, alpha_b, alpha)") == 1);
}

TEST_CASE("mfv run --scene runs only the scene's sets and reports per material", "[device][scene]") {
  Scratch t;
  const std::string out = (t.dir / "out").string();
  auto r = run_mfv("run --scene " + kData +
                   "/materials.json --check furnace --check energy --check energy_diffuse --check reciprocity "
                   "--seed 3 --out " +
                   out);
  INFO(r.out);
  CHECK(r.code == 0);
  nlohmann::json j = nlohmann::json::parse(slurp(out + "/results.json"));
  const auto& sc = j["scene"];
  REQUIRE(sc["materials"].size() == 4);
  std::map<std::string, nlohmann::json> by_name;
  for (auto& m : sc["materials"]) by_name[m["name"]] = m;
  auto verdict = [&](const std::string& mat, const std::string& check) {
    for (auto& c : by_name[mat]["checks"])
      if (c["check"] == check) return c["verdict"].get<std::string>();
    return std::string("none");
  };
  // a white dielectric gains energy at grazing view through fresnel_mix (the spec says so): expected
  CHECK(verdict("white plastic", "energy") == "xfail");
  CHECK(verdict("chrome", "energy") == "pass");
  CHECK(verdict("chrome", "furnace") == "pass");
  CHECK(verdict("brushed steel", "energy") == "pass");
  CHECK(verdict("old phong", "energy_diffuse") != "none");
  CHECK(verdict("white plastic", "reciprocity") == "pass");
  // white plastic and chrome share roughness 0.2: one furnace set serves both
  CHECK(by_name["white plastic"]["checks"][0]["set"] == by_name["chrome"]["checks"][0]["set"]);
  double loss = by_name["chrome"]["checks"][0]["energy_loss_normal"];
  CHECK(std::fabs(loss) < 0.05);  // GGX at alpha 0.04 loses almost nothing at normal view
  for (auto& lo : sc["left_out"]) CHECK(lo["integrals_run"].get<uint64_t>() < lo["integrals_full"].get<uint64_t>());
  CHECK(sc["kernel_builds"]["run"].get<int>() == 4);
  // furnace: isotropic, anisotropic and sheen plans; energy: D x G x F, whole models and
  // the engines' own lobes (sheen source); energy_diffuse and reciprocity: one each
  CHECK(sc["kernel_builds"]["full"].get<int>() == 8);
  CHECK(sc["seconds"]["scene"].get<double>() > 0);
  CHECK(slurp(out + "/report.md").find("### chrome") != std::string::npos);
}

TEST_CASE("scene checks fail on a planted glTF model: energy gain and asymmetry", "[device][scene][planted]") {
  // the specular lobe 30 % too bright, and f(i, o) != f(o, i)
  const test::PlantedKernelDir planted(
      "model_gltf.cl", "    spec = over_4_cosines(D_ggx(h.z, s2, alpha)",
      "    spec = R(1.3) * (R(1.0) + R(0.05) * NoL) * over_4_cosines(D_ggx(h.z, s2, alpha)");
  Scratch t;
  auto r = run_mfv("--kernel-dir " + planted.path() + " run --scene " + kData +
                   "/materials.json --check furnace --check reciprocity --seed 3 --out " + (t.dir / "o").string());
  INFO(r.out);
  CHECK(r.code == 1);
  nlohmann::json j = nlohmann::json::parse(slurp(t.dir / "o" / "results.json"));
  for (auto& m : j["scene"]["materials"]) {
    if (m["model"] != "gltf") continue;
    for (auto& c : m["checks"]) CHECK(c["verdict"] == "FAIL");
  }
}
