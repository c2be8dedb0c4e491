// Scenes as they ship (issue 21) and strict scene parsing (issue 17): the
// corpus in tests/data/corpus (written by make_corpus.py, structured like the
// public sample scenes) loads with no .bin and no images beside it; images,
// where present, give each textured parameter its real range, and where absent
// [0, factor] is checked and every absent image is named; every range is
// checked at its ends and inside; each KHR material extension is accounted for
// per material; a bad number is one line naming file, material and field.
#include "kernel_dir.hpp"
#include "run_mfv.hpp"
#include "scene/scene.hpp"
#include "scene/scene_filters.hpp"
#include "scene/texture_range.hpp"
#include "scene_files.hpp"
#include "util/error.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

using namespace mfv;
using namespace mfv::test;

namespace {

const std::string kCorpus = std::string(MFV_TEST_DATA_DIR) + "/corpus";
const std::vector<std::string> kScenes = {"helmet",    "flight",      "aniso_strength", "ior_grid", "roughness",
                                          "clearcoat", "sheen_chair", "specular",       "sheen",    "coat_aniso",
                                          "transmission", "volume"};

bool any_has(const std::vector<std::string>& lines, const std::string& what) {
  return std::any_of(lines.begin(), lines.end(), [&](auto& l) { return l.find(what) != std::string::npos; });
}

bool has_point(const SceneMaterial& m, double metallic, double alpha) {
  auto c = m.channels();
  return std::any_of(c.begin(), c.end(), [&](auto& p) { return p.metallic == metallic && p.alpha == Approx(alpha); });
}

}  // namespace

TEST_CASE("every corpus scene loads with no .bin and no images beside it", "[scene][corpus]") {
  for (auto& name : kScenes) {
    Scratch t;
    const std::string alone = t.copy(kCorpus + "/" + name + ".gltf");
    INFO(name);
    Scene s = load_scene(alone);  // buffers are never read: absent.bin is not needed
    CHECK_FALSE(s.materials.empty());
    // every absent image a checked parameter reads is named, one line each
    nlohmann::json j = nlohmann::json::parse(slurp(alone));
    std::set<std::string> read_uris;
    for (auto& m : j["materials"]) {
      auto slot = [&](const nlohmann::json& parent, const char* key) {
        if (parent.contains(key))
          read_uris.insert(j["images"][j["textures"][parent[key]["index"].get<int>()]["source"].get<int>()]["uri"]);
      };
      if (m.contains("pbrMetallicRoughness")) {
        slot(m["pbrMetallicRoughness"], "baseColorTexture");
        slot(m["pbrMetallicRoughness"], "metallicRoughnessTexture");
      }
      if (m.contains("extensions") && m["extensions"].contains("KHR_materials_specular"))
        slot(m["extensions"]["KHR_materials_specular"], "specularTexture");
      if (m.contains("extensions") && m["extensions"].contains("KHR_materials_anisotropy"))
        slot(m["extensions"]["KHR_materials_anisotropy"], "anisotropyTexture");
      if (m.contains("extensions") && m["extensions"].contains("KHR_materials_sheen")) {
        auto& sh = m["extensions"]["KHR_materials_sheen"];
        const bool on = sh.contains("sheenColorFactor") &&
                        (sh["sheenColorFactor"][0].get<double>() > 0 || sh["sheenColorFactor"][1].get<double>() > 0 ||
                         sh["sheenColorFactor"][2].get<double>() > 0);
        if (on) slot(sh, "sheenRoughnessTexture");  // read only where the sheen is on
      }
    }
    CHECK(s.warnings.size() == read_uris.size());
    for (auto& uri : read_uris) CHECK(any_has(s.warnings, "'" + uri + "' is not beside the scene"));
  }
}

TEST_CASE("textured roughness is checked down to 0 and textured metallic at 0 and 1", "[scene][corpus]") {
  Scratch t;
  Scene s = load_scene(t.copy(kCorpus + "/helmet.gltf"));
  const SceneMaterial& h = named(s, "helmet");
  // no image: the whole range [0, factor] of each textured parameter
  CHECK(h.roughness.lo == 0.0);
  CHECK(h.roughness.hi == 1.0);
  CHECK(h.metallic.lo == 0.0);
  CHECK(h.metallic.hi == 1.0);
  for (auto& b : h.base) CHECK((b.lo == 0.0 && b.hi == 1.0));
  const auto alphas = h.alphas();  // roughness 0 (at the float32 floor), 1/3, 2/3, 1
  REQUIRE(alphas.size() == 4);
  CHECK(alphas[0] == kSceneMinAlpha);
  CHECK(alphas[1] == Approx(1.0 / 9));
  CHECK(alphas[3] == 1.0);
  for (double a : alphas) {
    CHECK(has_point(h, 0.0, a));  // a dielectric at every roughness point
    CHECK(has_point(h, 1.0, a));  // and a metal
  }
  CHECK(any_has(h.warnings, "roughness 0 gives alpha = 0"));
  CHECK(any_has(h.account, "checked over the whole range [0, 1]"));
}

TEST_CASE("images beside the scene give each textured parameter its texels' range", "[scene][corpus]") {
  Scene s = load_scene(kCorpus + "/helmet.gltf");
  const SceneMaterial& h = named(s, "helmet");
  CHECK(s.warnings.empty());  // normal, occlusion and emissive images scale nothing a BSDF check sees
  // mr.png: G = 51..230 (roughness), B = 0..255 (metallic), stored linear
  CHECK(h.roughness.lo == Approx(51 / 255.0));
  CHECK(h.roughness.hi == Approx(230 / 255.0));
  CHECK(h.metallic.lo == 0.0);
  CHECK(h.metallic.hi == 1.0);
  // albedo.png is sRGB: R = 40..200 decoded to linear
  CHECK(h.base[0].lo == Approx(srgb_to_linear(40 / 255.0)));
  CHECK(h.base[0].hi == Approx(srgb_to_linear(200 / 255.0)));
  CHECK(h.base[2].hi == Approx(srgb_to_linear(60 / 255.0)));
  CHECK(h.alphas().front() == Approx(0.04));  // roughness 0.2: no floor, no warning
  CHECK(h.warnings.empty());
  // the specular map's alpha channel (128..255) scales specularFactor; the anisotropy map's B the strength
  Scene sp = load_scene(kCorpus + "/specular.gltf");
  CHECK(named(sp, "textured specular").specular.lo == Approx(128 / 255.0));
  Scene an = load_scene(kCorpus + "/aniso_strength.gltf");
  CHECK(named(an, "strength texture").anisotropy_strength.lo == Approx(64 / 255.0));
}

TEST_CASE("a .glb reads images from its BIN chunk and names them where the chunk is absent", "[scene][corpus]") {
  const std::string png = slurp(kCorpus + "/mr.png");
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"materials", {{{"name", "m"}, {"pbrMetallicRoughness", {{"metallicRoughnessTexture", {{"index", 0}}}}}}}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"bufferView", 0}, {"mimeType", "image/png"}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", png.size()}}}},
      {"buffers", {{{"byteLength", png.size()}}}}};
  Scratch t;
  Scene with = load_scene(t.file("with.glb", glb_of(j.dump(), png)));
  CHECK(named(with, "m").roughness.lo == Approx(51 / 255.0));
  Scene without = load_scene(t.file("without.glb", glb_of(j.dump())));
  CHECK(named(without, "m").roughness.lo == 0.0);
  REQUIRE(without.warnings.size() == 1);
  CHECK(without.warnings[0].find("image 0 'embedded' sits in buffer 0, which is absent") != std::string::npos);
}

TEST_CASE("each KHR material extension is accounted for per material", "[scene][corpus]") {
  Scene f = load_scene(kCorpus + "/flight.gltf");
  const SceneMaterial& lenses = named(f, "lenses");
  // glass lenses with a volume: a refracting boundary, the Walter BSDF at eta = ior (issue 29)
  CHECK(lenses.not_checked.empty());
  CHECK(lenses.volume_checked);
  CHECK(lenses.model() == "walter_ggx_correlated");
  CHECK(any_has(lenses.account, "a refracting boundary, checked as the rough dielectric BSDF"));
  CHECK(any_has(lenses.account, "KHR_materials_volume: the medium under the surface"));
  CHECK(named(f, "leather").not_checked.empty());
  // two absent metal-rough maps, one line each with the materials they scale
  CHECK(f.warnings.size() == 2);
  CHECK(any_has(f.warnings, "'flight_rubber_mr.png' is not beside the scene"));
  CHECK(any_has(f.warnings, "material 'metal parts' metallicRoughnessTexture"));

  // KHR_materials_clearcoat: checked through gltf_clearcoat, the coat's roughness 0 at the float32 floor
  Scene c = load_scene(kCorpus + "/clearcoat.gltf");
  const SceneMaterial& hard = named(c, "coat 1.0 rough 0.0");
  CHECK(hard.coat_checked);
  CHECK(hard.coat_alphas() == std::vector<double>{kSceneMinAlpha});
  CHECK(any_has(hard.warnings, "the coat is checked at alpha = 0.0001"));
  REQUIRE(hard.whole_points().size() == 2);  // base r 0.6 and g = b 0.1
  CHECK(hard.whole_points()[0].model->id == "gltf_clearcoat");
  CHECK(hard.whole_points()[0].p[6] == 1.0);  // clearcoat
  CHECK(named(c, "coat 0.5 rough 0.3").coat_alphas()[0] == Approx(0.09));
  Scene sh = load_scene(kCorpus + "/sheen_chair.gltf");
  CHECK(any_has(named(sh, "fabric").account, "KHR_materials_sheen: checked as the gltf_sheen model"));
  CHECK(named(sh, "fabric").whole_points().back().model->id == "gltf_sheen");
  CHECK(named(sh, "legs").account.empty());

  // KHR_materials_specular: f0 x specularColor above 1 is the spec's clamp, and said
  Scene sp = load_scene(kCorpus + "/specular.gltf");
  CHECK(any_has(named(sp, "over one").warnings, "f0 x specularColor = 0.04 x 25 = 1 in channel r is clamped to 1"));
  CHECK(named(sp, "tinted").warnings.empty());

  // KHR_materials_ior: also through the exact dielectric Fresnel
  Scene ior = load_scene(kCorpus + "/ior_grid.gltf");
  CHECK(named(ior, "ior 1.33 rough 0.5").ior_exact);
  CHECK(any_has(named(ior, "ior 2.0 rough 0.1").account, "exact dielectric Fresnel at eta = 2"));
  CHECK_FALSE(named(sp, "tinted").ior_exact);  // no KHR_materials_ior: Schlick at f0 0.04 only

  Scratch t;
  nlohmann::json j = nlohmann::json::parse(slurp(kCorpus + "/ior_grid.gltf"));
  j["materials"][0]["extensions"]["KHR_materials_unlit"] = nlohmann::json::object();
  j["materials"][1]["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", 5}};
  j["materials"][2]["extensions"]["KHR_materials_iridescence"] = {{"iridescenceFactor", 1}};
  Scene e = load_scene(t.file("ext.gltf", j.dump()));
  CHECK(e.materials[0].not_checked.find("nothing to check on a surface BSDF") != std::string::npos);
  CHECK(any_has(e.materials[1].account, "KHR_materials_emissive_strength: emission"));
  CHECK(e.materials[2].not_checked.find("KHR_materials_iridescence changes the BSDF") != std::string::npos);
}

TEST_CASE("ranges are deduplicated across materials and stability sweeps each scene's own points", "[scene][corpus]") {
  Scene r = load_scene(kCorpus + "/roughness.gltf");
  Scene i = load_scene(kCorpus + "/ior_grid.gltf");
  StabilityOptions a, b;
  scene_stability_options(r, a);
  scene_stability_options(i, b);
  REQUIRE(a.model_points.size() == 1);
  REQUIRE(b.model_points.size() == 1);
  CHECK(a.model_points[0].second != b.model_points[0].second);
  // every point once, though the metal rows and the textured material share their metal points
  auto pts = a.model_points[0].second;
  std::sort(pts.begin(), pts.end());
  CHECK(std::adjacent_find(pts.begin(), pts.end()) == pts.end());
}

TEST_CASE("bad numbers in scenes and material files: one line naming file, material and field, exit 2",
          "[scene][cli]") {
  Scratch t;
  auto gltf = [&](const std::string& name, const std::string& pbr, const std::string& ext = "") {
    return t.file(name,
                  "{\"asset\": {\"version\": \"2.0\"}, \"materials\": [{\"name\": \"m\", "
                  "\"pbrMetallicRoughness\": {" +
                      pbr + "}" + (ext.empty() ? "" : ", \"extensions\": {" + ext + "}") + "}]}");
  };
  auto file = [&](const std::string& name, const std::string& mat) {
    return t.file(name, "{\"materials\": [{\"name\": \"m\", " + mat + "}]}");
  };
  struct Bad {
    std::string path, expect;
  };
  std::vector<Bad> bad = {
      {file("overflow.json", "\"model\": \"gltf\", \"roughness\": 1e400"), "materials[0].roughness: number overflow"},
      {gltf("overflow.gltf", "\"roughnessFactor\": 1e400"), "pbrMetallicRoughness.roughnessFactor: number overflow"},
      {gltf("nan.gltf", "\"roughnessFactor\": \"NaN\""),
       "material 'm' (materials[0]): pbrMetallicRoughness.roughnessFactor = \"NaN\" is not a number"},
      {gltf("null.gltf", "\"roughnessFactor\": null"), "roughnessFactor = null is not a number"},
      {gltf("true.gltf", "\"roughnessFactor\": true"), "roughnessFactor = true is not a number"},
      {gltf("metal.gltf", "\"metallicFactor\": \"0.2\""), "metallicFactor = \"0.2\" is not a number"},
      {gltf("red.gltf", "\"baseColorFactor\": \"red\""), "baseColorFactor = \"red\" must be an array of 4 numbers"},
      {gltf("rgb.gltf", "\"baseColorFactor\": [1, 1, 1]"), "baseColorFactor = [1,1,1] must be an array of 4 numbers"},
      {gltf("five.gltf", "\"baseColorFactor\": [1, 1, 1, 1, 1], \"roughnessFactor\": 0.3"),
       "must be an array of 4 numbers"},
      {gltf("ior.gltf", "", "\"KHR_materials_ior\": {\"ior\": \"1.5\"}"),
       "KHR_materials_ior.ior = \"1.5\" is not a number"},
      {file("string.json", "\"model\": \"gltf\", \"metallic\": \"1\""),
       "material 'm': metallic = \"1\" is not a number"},
      {file("alpha.json", "\"d\": \"ggx\", \"g\": \"smith_ggx\", \"f\": \"none\", \"alpha\": 1e30"),
       "alpha = 1e+30 gives D ggx alpha"},
      {file("phong.json", "\"d\": \"phong\", \"g\": \"smith_phong\", \"f\": \"none\", \"alpha\": 1e-9"),
       "alpha = 1e-09 gives D phong alpha_p"},
  };
  for (auto& b : bad) {
    INFO(b.path);
    try {
      load_scene(b.path);
      FAIL("accepted");
    } catch (const Error& e) {
      const std::string what = e.what();
      INFO(what);
      CHECK(what.rfind(b.path, 0) == 0);  // the file first
      CHECK(what.find(b.expect) != std::string::npos);
    }
  }
  // the crash of issue 17 (exit 134): every --scene command now exits 2 with one line
  for (const char* cmd : {"run", "energy", "stability"}) {
    auto r = run_mfv(std::string(cmd) + " --scene " + bad[0].path);
    INFO(r.out);
    CHECK(r.code == 2);
    CHECK(r.out.rfind("mfv: error: ", 0) == 0);
    CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 1);
  }
}

// ---- device: the corpus run as a user would -------------------------------------

namespace {

nlohmann::json results_of(const Scratch& t) { return nlohmann::json::parse(slurp(t.dir / "out" / "results.json")); }

std::vector<std::string> verdicts_of(const nlohmann::json& material, const std::string& check) {
  std::vector<std::string> out;
  for (auto& c : material["checks"])
    if (c["check"] == check) out.push_back(c["verdict"]);
  return out;
}

}  // namespace

TEST_CASE("a multi-material scene without .bin or images: per-material account, the volume's medium skipped in JUnit",
          "[device][scene][corpus]") {
  Scratch t;
  const std::string scene = t.copy(kCorpus + "/flight.gltf");
  auto r = run_mfv("run --scene " + scene + " --check reciprocity --seed 5 --out " + (t.dir / "out").string());
  INFO(r.out);
  CHECK(r.code == 0);
  CHECK(r.out.find("material 'lenses' [materials[5]] pass: walter_ggx_correlated") != std::string::npos);
  CHECK(r.out.find("account: KHR_materials_transmission with KHR_materials_volume") != std::string::npos);
  const std::string junit = slurp(t.dir / "out" / "junit.xml");
  CHECK(junit.find("<testcase classname=\"scene\" name=\"material lenses\"><skipped message=\"KHR_materials_volume: "
                   "the medium under the surface") != std::string::npos);
  CHECK(junit.find("skipped=\"1\"") != std::string::npos);
  const std::string md = slurp(t.dir / "out" / "report.md");
  CHECK(md.find("- account: checked over roughness [0, 1]") != std::string::npos);
  nlohmann::json j = results_of(t);
  for (auto& m : j["scene"]["materials"]) {
    INFO(m["name"]);
    if (m["name"] == "lenses") CHECK(m["checks"].empty());
    // textured: both metallic ends at every roughness point, with its own reciprocity set each
    else
      CHECK(verdicts_of(m, "reciprocity").size() >= 8);
  }
}

TEST_CASE("textured roughness down to 0 catches a defect only narrow lobes show, the factor alone does not",
          "[device][scene][corpus][planted]") {
  // the specular lobe 50 % too bright below alpha 0.002 only
  const test::PlantedKernelDir planted(
      "model_gltf.cl", "    spec = over_4_cosines(D_ggx(h.z, s2, alpha)",
      "    spec = (alpha < R(0.002) ? R(1.5) : R(1.0)) * over_4_cosines(D_ggx(h.z, s2, alpha)");
  Scratch t;
  const std::string textured = t.copy(kCorpus + "/helmet.gltf");  // roughness texture absent: [0, 1]
  nlohmann::json j = nlohmann::json::parse(slurp(textured));
  j["materials"][0]["pbrMetallicRoughness"].erase("metallicRoughnessTexture");  // the factors alone: roughness 1
  const std::string factor = t.file("factor.gltf", j.dump());
  auto run = [&](const std::string& scene) {
    return run_mfv("--kernel-dir " + planted.path() + " run --scene " + scene +
                   " --check energy --seed 5 --scale 0.5 --out " + (t.dir / "out").string());
  };
  auto bad = run(textured);
  INFO(bad.out);
  CHECK(bad.code == 1);
  CHECK(bad.out.find("FAIL   energy") != std::string::npos);
  auto missed = run(factor);
  INFO(missed.out);
  CHECK(missed.out.find("FAIL   energy") == std::string::npos);
}

TEST_CASE("stability --scene differs between scenes with different materials", "[device][scene][corpus]") {
  auto a = run_mfv("stability --scene " + kCorpus + "/roughness.gltf");
  auto b = run_mfv("stability --scene " + kCorpus + "/ior_grid.gltf");
  INFO(a.out << b.out);
  CHECK(a.code == 0);
  CHECK(b.code == 0);
  auto model_line = [](const std::string& out) {
    const size_t at = out.find("MODEL gltf ");
    return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
  };
  REQUIRE_FALSE(model_line(a.out).empty());
  CHECK(model_line(a.out) != model_line(b.out));  // the model swept at each scene's own points
  // plain metallic-roughness materials: no clearcoat or sheen model is swept (issue 27)
  for (const char* other : {"MODEL gltf_clearcoat", "MODEL gltf_sheen"}) {
    CHECK(a.out.find(other) == std::string::npos);
    CHECK(b.out.find(other) == std::string::npos);
  }
  CHECK(a.out.find("material 'textured roughness': 4 points") != std::string::npos);
}

TEST_CASE("energy --scene: rounding is no gain, anisotropy is sampled and kept at F = 1, only written files are listed",
          "[device][scene][energy]") {
  Scratch t;
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"materials",
       {// Lambert with base 1 (no specular layer): E = 1 exactly, up to float rounding (issue 21: flagged GAINS)
        {{"name", "lambert white"},
         {"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 0.5}}},
         {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}},
        // strength 1 over roughness 0.3: alpha_t 1, alpha_b 0.09 (issue 21: standard errors 0.17-0.35, F = 1 isotropic)
        {{"name", "brushed"},
         {"pbrMetallicRoughness", {{"metallicFactor", 1.0}, {"roughnessFactor", 0.3}}},
         {"extensions", {{"KHR_materials_anisotropy", {{"anisotropyStrength", 1.0}}}}}},
        // a white dielectric gains through fresnel_mix: energy --scene and run --scene must agree on it
        {{"name", "white plastic"}, {"pbrMetallicRoughness", {{"metallicFactor", 0.0}, {"roughnessFactor", 0.2}}}}}}};
  const std::string scene = t.file("energy.gltf", j.dump());
  auto r = run_mfv("energy --scene " + scene + " --grid 16x2 --out " + (t.dir / "e").string());
  INFO(r.out);
  CHECK(r.code == 0);
  auto line_of = [&](const std::string& start) {
    const size_t at = r.out.find(start);
    return at == std::string::npos ? std::string() : r.out.substr(at, r.out.find('\n', at) - at);
  };
  // "E_avg 0.6143 ± 6.1e-04" of a line: mean and standard error
  auto eavg = [](const std::string& line) {
    double mean = 0, se = 0;
    const size_t at = line.find("E_avg ");
    if (at != std::string::npos) std::sscanf(line.c_str() + at, "E_avg %lf \u00b1 %lf", &mean, &se);
    return std::make_pair(mean, se);
  };
  const std::string lambert = line_of("material lambert white (gltf point");
  REQUIRE_FALSE(lambert.empty());
  CHECK(std::fabs(eavg(lambert).first - 1.0) < 5 * eavg(lambert).second);
  CHECK(lambert.find("GAINS") == std::string::npos);
  CHECK(lambert.find("gains") == std::string::npos);
  const std::string white = line_of("material brushed (F = 1 at alpha_t 1, alpha_b 0.09)");
  const std::string own = line_of("material brushed (gltf point");
  REQUIRE_FALSE(white.empty());
  REQUIRE_FALSE(own.empty());
  // the same white metal: the F = 1 line and the material's own agree (0.9969 vs 0.614 before), within
  // 5 combined standard errors; both near the 0.614 of alpha_t 1, alpha_b 0.09
  const auto [w, w_se] = eavg(white);
  const auto [o, o_se] = eavg(own);
  CHECK(w_se > 0);
  CHECK(std::fabs(w - o) < 5 * std::hypot(w_se, o_se));
  CHECK(std::fabs(w - 0.614) < 0.01);
  CHECK(white.find("UNRESOLVED") == std::string::npos);
  const std::string plastic = line_of("material white plastic (gltf point");
  CHECK(plastic.find("gains energy beyond noise, as the catalog expects there") != std::string::npos);
  // the files line names what was written, and nothing else
  const std::string wrote = line_of("wrote ");
  CHECK(wrote.find("kulla_conty.h") == std::string::npos);
  CHECK(wrote.find("plots/") == std::string::npos);
  CHECK(std::filesystem::exists(t.dir / "e" / "csv" / "models.csv"));
  CHECK_FALSE(std::filesystem::exists(t.dir / "e" / "kulla_conty.h"));
  CHECK(slurp(t.dir / "e" / "report.md").find("kulla_conty.h") == std::string::npos);
  // run --scene on the same scene: what energy reports as an expected gain is an expected failure there
  auto run = run_mfv("run --scene " + scene + " --check energy --seed 5 --out " + (t.dir / "out").string());
  INFO(run.out);
  const nlohmann::json res = results_of(t);  // kept: a range-for over a temporary's member dangles
  for (auto& m : res["scene"]["materials"])
    if (m["name"] == "white plastic") CHECK(verdicts_of(m, "energy") == std::vector<std::string>{"xfail"});
}

TEST_CASE("the clearcoat model's kernel agrees with its reference and a planted coat weight does not",
          "[device][scene][agree]") {
  auto ok = run_mfv("agree --only 'MODEL gltf_clearcoat' --samples 50000");
  INFO(ok.out);
  CHECK(ok.code == 0);
  // the base not darkened by the coat's share: (1 - weight) dropped
  const test::PlantedKernelDir planted("model_gltf.cl", "(R(1.0) - weight) * material + weight * layer;",
                                       "material + weight * layer;");
  auto bad = run_mfv("--kernel-dir " + planted.path() + " agree --only 'MODEL gltf_clearcoat' --samples 50000");
  INFO(bad.out);
  CHECK(bad.code == 1);
}

// The planted coat (the base not darkened by the coat's share) is caught by the
// kernel-vs-reference comparison on the same samples (relative 0.73); the energy
// check alone has little power at grazing V for a coat of alpha 0.01 (standard
// errors 0.2-0.3 there: one proposal width for two lobes), reported in docs/scenes.md.
TEST_CASE("coated materials are checked with their coat lobe, and a planted coat fails the run",
          "[device][scene][corpus][planted]") {
  Scratch t;
  nlohmann::json j = nlohmann::json::parse(slurp(kCorpus + "/clearcoat.gltf"));
  j["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 1.0;  // a coated metal: E <= 1 must hold
  // coat roughness 0.1, not 0: at the float32 floor alpha 1e-4 the kernel and the reference disagree at grazing
  // light (2.8e-2 > 5e-3), as for the glTF model's own lobe (reported, not this test's subject)
  j["materials"][0]["extensions"]["KHR_materials_clearcoat"]["clearcoatRoughnessFactor"] = 0.1;
  const std::string scene = t.file("coat.gltf", j.dump());
  auto ok =
      run_mfv("run --scene " + scene + " --check energy --check d_norm --seed 5 --out " + (t.dir / "out").string());
  INFO(ok.out);
  CHECK(ok.code == 0);
  CHECK(ok.out.find("gltf_clearcoat alpha=") != std::string::npos);
  CHECK(ok.out.find("set: ggx alpha=0.09") != std::string::npos);  // the 0.5 coat's roughness 0.3: its own D
  const test::PlantedKernelDir planted("model_gltf.cl", "(R(1.0) - weight) * material + weight * layer;",
                                       "material + weight * layer;");
  auto bad = run_mfv("--kernel-dir " + planted.path() + " run --scene " + scene + " --check energy --seed 5 --out " +
                     (t.dir / "out").string());
  INFO(bad.out);
  CHECK(bad.code == 1);
  CHECK(bad.out.find("x its derived bound (FAILED) at energy gltf_clearcoat") != std::string::npos);
}

TEST_CASE("KHR_materials_ior is checked through the exact dielectric Fresnel as well", "[device][scene][corpus]") {
  Scratch t;
  auto r = run_mfv("run --scene " + kCorpus + "/ior_grid.gltf --check energy --seed 5 --scale 0.5 --out " +
                   (t.dir / "out").string());
  INFO(r.out);
  CHECK(r.code == 0);
  size_t exact = 0;
  const nlohmann::json j = results_of(t);  // kept: a range-for over a temporary's member dangles
  for (auto& m : j["scene"]["materials"])
    for (auto& c : m["checks"])
      if (c["set"].get<std::string>().rfind("ggx/smith_ggx_correlated/dielectric", 0) == 0) {
        ++exact;
        CHECK(c["verdict"] == "pass");
      }
  CHECK(exact == 6);  // each material's one roughness, at its own ior
}

TEST_CASE("sheen materials are checked with their lobe at the ends of their ranges", "[scene][corpus][sheen]") {
  Scene s = load_scene(kCorpus + "/sheen.gltf");
  const SceneMaterial& red = named(s, "red sheen chrome");
  REQUIRE(red.sheen_checked);
  // the red channel (sheen 1, others 0) and the green and blue (sheen 0, others 1), at sheenRoughness 0.3
  auto pts = red.sheen_points();
  auto has = [&](double sheen, double others) {
    return std::any_of(pts.begin(), pts.end(),
                       [&](auto& p) { return p[5] == sheen && p[6] == others && p[4] == Approx(0.3); });
  };
  CHECK(has(1.0, 0.0));
  CHECK(has(0.0, 1.0));
  size_t sheen_points = 0;
  for (auto& w : red.whole_points()) sheen_points += w.model->id == "gltf_sheen";
  CHECK(sheen_points == pts.size());
  // a textured sheen roughness down to 0: checked from the Charlie D's floor 1e-3 up, and said
  const SceneMaterial& tex = named(s, "textured sheen roughness");
  CHECK(tex.sheen_roughness.lo == 0.0);
  CHECK(any_has(tex.warnings, "sheenRoughness 0 is below 0.001"));
  bool grazing_gain = false;
  for (auto& w : tex.whole_points())
    if (w.model->id == "gltf_sheen" && w.p[4] == Approx(1e-3)) grazing_gain = grazing_gain || w.energy == Expect::May;
  CHECK(grazing_gain);  // E_sheen > 1 at grazing there (the fitted Lambda): may gain, said why
  // sheenColorFactor 0 disables the layer
  CHECK_FALSE(named(s, "sheen off").sheen_checked);
  CHECK(named(s, "velvet").sheen_checked);
}

TEST_CASE("a clearcoat over an anisotropic base is checked with both lobes", "[scene][corpus][clearcoat]") {
  Scene s = load_scene(kCorpus + "/coat_aniso.gltf");
  const SceneMaterial& m = named(s, "coated brushed metal");
  REQUIRE(m.coat_checked);
  CHECK(any_has(m.account, "gltf_clearcoat_aniso"));
  // alpha_t = mix(0.25, 1, 0.64) = 0.73, alpha_b = 0.25, the coat 0.09, clearcoat 1
  auto pts = m.coat_aniso_points();
  REQUIRE_FALSE(pts.empty());
  CHECK(std::any_of(pts.begin(), pts.end(), [](auto& p) {
    return p[0] == Approx(0.73) && p[6] == Approx(0.25) && p[4] == Approx(0.09) && p[5] == 1.0;
  }));
  size_t aniso = 0;
  for (auto& w : m.whole_points()) aniso += w.model->id == "gltf_clearcoat_aniso";
  CHECK(aniso == pts.size());
}
