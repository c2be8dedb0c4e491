#include "scene/scene.hpp"

#include "catalog/roughness.hpp"
#include "runtime/error.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace mfv {

bool GltfChannelParams::operator==(const GltfChannelParams& o) const {
  return alpha == o.alpha && metallic == o.metallic && base == o.base && f0 == o.f0 && f0_max == o.f0_max &&
         weight == o.weight && alpha_b == o.alpha_b;
}

std::vector<GltfChannelParams> SceneMaterial::channels() const {
  // KHR_materials_ior: f0 = ((ior - 1)/(ior + 1))², ior = 0 giving 1 (the
  // specular-glossiness conversion); KHR_materials_specular: dielectric F0 =
  // min(f0 · specularColor, 1) per channel, the base weighted by the largest.
  const double r = factors.ior == 0 ? 1.0 : (factors.ior - 1.0) / (factors.ior + 1.0);
  std::array<double, 3> f0;
  for (int k = 0; k < 3; ++k) f0[k] = std::min(r * r * factors.specular_color[k], 1.0);
  const double f0_max = std::max({f0[0], f0[1], f0[2]});
  // KHR_materials_anisotropy: alpha_t = mix(alpha, 1, strength²) along the
  // anisotropy direction, alpha_b = alpha across it. anisotropyRotation turns
  // that direction about n within the tangent plane; the model is evaluated
  // in the anisotropy direction's own frame (t = +x), where the BRDF does not
  // depend on the rotation: it only changes which mesh azimuth the checks'
  // light (in the t-n plane, the rougher axis) stands for, so the checks are
  // run at rotation 0 and the rotation is recorded, not integrated.
  const double s2 = factors.anisotropy_strength * factors.anisotropy_strength;
  const double alpha_t = s2 > 0.0 ? alpha + (1.0 - alpha) * s2 : alpha;
  const double alpha_b = s2 > 0.0 ? alpha : 0.0;
  std::vector<GltfChannelParams> out;
  for (int k = 0; k < 3; ++k) {
    GltfChannelParams c{alpha_t, factors.metallic, factors.base[k], f0[k], f0_max, factors.specular, alpha_b};
    if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
  }
  return out;
}

const Model& gltf_model() { return *try_find_model("gltf"); }

Expect gltf_energy_expect(const GltfChannelParams& c) {
  const bool plain = c.metallic >= 1.0 || (1.0 - c.metallic) * c.base <= 0.0 || c.weight <= 0.0;
  return plain ? Expect::Hold : Expect::May;
}

std::string SceneMaterial::model() const { return gltf ? "gltf" : d->id + "/" + g->id + "/" + f->id; }

namespace {

std::string channel_names(int k) { return k == 0 ? "r" : k == 1 ? "g" : "b"; }

void check_unit(const std::string& material, const std::string& what, double v) {
  if (!(v >= 0.0 && v <= 1.0))
    throw Error(fmt::format("material '{}': {} = {} is out of range [0, 1]", material, what, v));
}

// glTF roughness to the model's alpha, with the float32 floor.
void set_alpha_from_roughness(SceneMaterial& m) {
  m.alpha = m.factors.roughness * m.factors.roughness;  // glTF Appendix B: alpha = roughness²
  if (m.alpha < kSceneMinAlpha) {
    m.warnings.push_back(fmt::format(
        "roughness {:g} gives alpha = {:g}, below {:g}, the narrowest lobe the float32 estimators resolve: checked "
        "at alpha = {:g} (roughness 0.01)",
        m.factors.roughness, m.alpha, kSceneMinAlpha, kSceneMinAlpha));
    m.alpha = kSceneMinAlpha;
  }
}

}  // namespace

void validate_gltf_factors(const std::string& name, const GltfFactors& f) {
  for (int k = 0; k < 3; ++k) check_unit(name, "baseColorFactor." + channel_names(k), f.base[k]);
  check_unit(name, "metallicFactor", f.metallic);
  check_unit(name, "roughnessFactor", f.roughness);
  if (!(f.ior == 0.0 || (f.ior >= 1.0 && std::isfinite(f.ior))))
    throw Error(fmt::format("material '{}': KHR_materials_ior ior = {} is out of range (1 or more, or 0)", name, f.ior));
  check_unit(name, "KHR_materials_specular specularFactor", f.specular);
  check_unit(name, "KHR_materials_anisotropy anisotropyStrength", f.anisotropy_strength);
  if (!std::isfinite(f.anisotropy_rotation))
    throw Error(fmt::format("material '{}': KHR_materials_anisotropy anisotropyRotation = {} is not finite", name,
                            f.anisotropy_rotation));
  for (int k = 0; k < 3; ++k)
    if (!(f.specular_color[k] >= 0.0 && std::isfinite(f.specular_color[k])))
      throw Error(fmt::format("material '{}': KHR_materials_specular specularColorFactor.{} = {} must be a finite "
                              "number >= 0",
                              name, channel_names(k), f.specular_color[k]));
}

namespace {

// ---- glTF ------------------------------------------------------------------

// Extensions that change nothing mfv checks (geometry, image encodings,
// texture coordinates, emission) or that it models.
const std::set<std::string> kModelled = {"KHR_materials_ior", "KHR_materials_specular", "KHR_materials_anisotropy"};
const std::set<std::string> kHarmless = {"KHR_mesh_quantization",     "KHR_draco_mesh_compression",
                                         "EXT_meshopt_compression",   "KHR_texture_transform",
                                         "KHR_texture_basisu",        "EXT_texture_webp",
                                         "KHR_materials_emissive_strength", "KHR_lights_punctual",
                                         "KHR_materials_variants",    "EXT_mesh_gpu_instancing"};

// Images are never decoded: mfv reads factors, not textures.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

double number(const tinygltf::Value& obj, const std::string& key, double fallback, const std::string& material) {
  if (!obj.Has(key)) return fallback;
  const tinygltf::Value& v = obj.Get(key);
  if (!v.IsNumber()) throw Error(fmt::format("material '{}': {} is not a number", material, key));
  return v.GetNumberAsDouble();
}

std::array<double, 3> number3(const tinygltf::Value& obj, const std::string& key, std::array<double, 3> fallback,
                              const std::string& material) {
  if (!obj.Has(key)) return fallback;
  const tinygltf::Value& v = obj.Get(key);
  if (!v.IsArray() || v.ArrayLen() != 3)
    throw Error(fmt::format("material '{}': {} must be an array of 3 numbers", material, key));
  std::array<double, 3> out;
  for (int k = 0; k < 3; ++k) {
    if (!v.Get(k).IsNumber()) throw Error(fmt::format("material '{}': {} must be an array of 3 numbers", material, key));
    out[size_t(k)] = v.Get(k).GetNumberAsDouble();
  }
  return out;
}

bool has_texture(const tinygltf::Value& obj, const std::string& key) {
  return obj.Has(key) && obj.Get(key).IsObject() && obj.Get(key).Has("index");
}

SceneMaterial from_gltf(const tinygltf::Material& gm, size_t index) {
  SceneMaterial m;
  m.name = gm.name.empty() ? fmt::format("material #{}", index) : gm.name;
  m.origin = fmt::format("materials[{}]", index);
  const auto& pbr = gm.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() != 4)
    throw Error(fmt::format("material '{}': baseColorFactor must have 4 components", m.name));
  for (int k = 0; k < 3; ++k) m.factors.base[size_t(k)] = pbr.baseColorFactor[size_t(k)];
  m.factors.metallic = pbr.metallicFactor;
  m.factors.roughness = pbr.roughnessFactor;
  if (pbr.metallicRoughnessTexture.index >= 0)
    m.warnings.push_back(fmt::format(
        "roughness and metallic come from texture {} (metallicRoughnessTexture), which mfv does not sample: checked "
        "at the factors roughness {:g}, metallic {:g}, which the texture scales down",
        pbr.metallicRoughnessTexture.index, m.factors.roughness, m.factors.metallic));
  if (pbr.baseColorTexture.index >= 0)
    m.warnings.push_back(fmt::format("base colour comes from texture {} (baseColorTexture), not sampled: checked at "
                                     "baseColorFactor, the largest value the texture can give",
                                     pbr.baseColorTexture.index));
  for (auto& [ext, v] : gm.extensions) {
    if (ext == "KHR_materials_ior") {
      m.factors.ior = number(v, "ior", 1.5, m.name);
    } else if (ext == "KHR_materials_specular") {
      m.factors.specular = number(v, "specularFactor", 1.0, m.name);
      m.factors.specular_color = number3(v, "specularColorFactor", {1, 1, 1}, m.name);
      for (const char* t : {"specularTexture", "specularColorTexture"})
        if (has_texture(v, t))
          m.warnings.push_back(fmt::format("{} is not sampled: checked at the factors", t));
    } else if (ext == "KHR_materials_anisotropy") {
      m.factors.anisotropy_strength = number(v, "anisotropyStrength", 0.0, m.name);
      m.factors.anisotropy_rotation = number(v, "anisotropyRotation", 0.0, m.name);
      if (m.factors.anisotropy_rotation != 0.0)
        m.warnings.push_back(fmt::format("anisotropyRotation {:g} turns the lobe about n: checked in the anisotropy "
                                         "direction's own frame, where the BRDF does not depend on it",
                                         m.factors.anisotropy_rotation));
      if (has_texture(v, "anisotropyTexture"))
        m.warnings.push_back(fmt::format("anisotropyTexture is not sampled: checked at anisotropyStrength {:g}, "
                                         "which the texture's strength channel scales down",
                                         m.factors.anisotropy_strength));
    } else if (kHarmless.count(ext) == 0) {
      m.warnings.push_back(fmt::format("uses {}, which mfv does not model: checked without it (a viewer that "
                                       "ignores an optional extension is conformant)",
                                       ext));
    }
  }
  validate_gltf_factors(m.name, m.factors);
  set_alpha_from_roughness(m);
  return m;
}

// The glTF default material (spec 3.9.6): base colour 1, metallic 1, roughness 1.
SceneMaterial default_gltf_material() {
  SceneMaterial m;
  m.name = "default material";
  m.origin = "mesh primitives without a material (glTF default material)";
  set_alpha_from_roughness(m);
  return m;
}

void collect_node(const tinygltf::Model& model, int node, std::set<int>& used, bool& default_used,
                  std::set<int>& seen) {
  if (node < 0 || size_t(node) >= model.nodes.size() || !seen.insert(node).second) return;
  const auto& n = model.nodes[size_t(node)];
  if (n.mesh >= 0 && size_t(n.mesh) < model.meshes.size())
    for (auto& prim : model.meshes[size_t(n.mesh)].primitives) {
      if (prim.material >= 0) used.insert(prim.material);
      else default_used = true;
    }
  for (int c : n.children) collect_node(model, c, used, default_used, seen);
}

Scene load_gltf(const std::string& path, bool binary) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                   : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  auto first_line = [](std::string s) {
    s = s.substr(0, s.find('\n'));
    return s.empty() ? std::string("unknown reason") : s;
  };
  if (!ok) throw Error(fmt::format("{}: not a valid glTF {} file: {}", path, binary ? "binary (.glb)" : "JSON (.gltf)",
                                   first_line(err)));
  Scene sc;
  sc.path = path;
  sc.format = binary ? "glb" : "gltf";
  if (!warn.empty()) sc.warnings.push_back("tinygltf: " + first_line(warn));
  for (auto& ext : model.extensionsRequired)
    if (kModelled.count(ext) == 0 && kHarmless.count(ext) == 0)
      throw Error(fmt::format("{} requires extension {}, which mfv does not model (it models KHR_materials_ior, "
                              "KHR_materials_specular; KHR_materials_anisotropy)",
                              path, ext));
  // The materials the scene's nodes use; a file without meshes is a material library (all of them).
  std::set<int> used;
  bool default_used = false;
  if (model.meshes.empty()) {
    for (size_t i = 0; i < model.materials.size(); ++i) used.insert(int(i));
  } else {
    std::set<int> seen;
    std::vector<int> roots;
    if (model.defaultScene >= 0 && size_t(model.defaultScene) < model.scenes.size())
      roots = model.scenes[size_t(model.defaultScene)].nodes;
    else
      for (auto& s : model.scenes) roots.insert(roots.end(), s.nodes.begin(), s.nodes.end());
    if (model.scenes.empty())  // no scene: every node
      for (size_t i = 0; i < model.nodes.size(); ++i) roots.push_back(int(i));
    for (int r : roots) collect_node(model, r, used, default_used, seen);
  }
  sc.materials_in_file = model.materials.size();
  for (int i : used) {
    if (size_t(i) >= model.materials.size())
      throw Error(fmt::format("{}: a mesh primitive names material {}, but the file has {}", path, i,
                              model.materials.size()));
    sc.materials.push_back(from_gltf(model.materials[size_t(i)], size_t(i)));
  }
  if (default_used) sc.materials.push_back(default_gltf_material());
  if (sc.materials.empty()) throw Error(fmt::format("{}: the scene uses no material (no mesh, no material)", path));
  return sc;
}

// ---- native material file (JSON) -------------------------------------------

using nlohmann::json;

double json_number(const json& j, const std::string& key, const std::string& material) {
  if (!j.is_number()) throw Error(fmt::format("material '{}': {} must be a number", material, key));
  return j.get<double>();
}

std::array<double, 3> json_rgb(const json& j, const std::string& key, const std::string& material) {
  if (j.is_number()) {
    double v = j.get<double>();
    return {v, v, v};
  }
  if (!j.is_array() || j.size() != 3)
    throw Error(fmt::format("material '{}': {} must be a number or an array of 3 numbers", material, key));
  return {json_number(j[0], key, material), json_number(j[1], key, material), json_number(j[2], key, material)};
}

void reject_unknown_keys(const json& j, const std::set<std::string>& known, const std::string& material) {
  for (auto& [k, v] : j.items())
    if (known.count(k) == 0) {
      std::string list;
      for (auto& s : known) list += (list.empty() ? "" : ", ") + s;
      throw Error(fmt::format("material '{}': unknown key '{}' (keys: {})", material, k, list));
    }
}

const Term& named_term(const json& j, const char* key, Kind kind, const std::string& material) {
  if (!j.contains(key) || !j[key].is_string())
    throw Error(fmt::format("material '{}': needs \"{}\" naming a {} term (see 'mfv list')", material, key,
                            kind_name(kind)));
  const std::string id = j[key].get<std::string>();
  if (const Term* t = try_find_term(id, kind)) return *t;
  std::string known;
  for (auto* t : terms_of(kind)) known += (known.empty() ? "" : ", ") + t->id;
  throw Error(fmt::format("material '{}': unknown {} term '{}' (known: {})", material, kind_name(kind), id, known));
}

SceneMaterial material_from_json(const json& j, size_t index) {
  if (!j.is_object()) throw Error(fmt::format("materials[{}] is not an object", index));
  SceneMaterial m;
  m.origin = fmt::format("materials[{}]", index);
  if (!j.contains("name") || !j["name"].is_string())
    throw Error(fmt::format("materials[{}]: needs a \"name\" (string)", index));
  m.name = j["name"].get<std::string>();
  const std::string model = j.contains("model") && j["model"].is_string() ? j["model"].get<std::string>() : "dgf";
  if (model == "gltf") {
    reject_unknown_keys(j, {"name", "model", "baseColor", "metallic", "roughness", "ior", "specular", "specularColor"},
                        m.name);
    if (j.contains("baseColor")) m.factors.base = json_rgb(j["baseColor"], "baseColor", m.name);
    if (j.contains("metallic")) m.factors.metallic = json_number(j["metallic"], "metallic", m.name);
    if (j.contains("roughness")) m.factors.roughness = json_number(j["roughness"], "roughness", m.name);
    if (j.contains("ior")) m.factors.ior = json_number(j["ior"], "ior", m.name);
    if (j.contains("specular")) m.factors.specular = json_number(j["specular"], "specular", m.name);
    if (j.contains("specularColor")) m.factors.specular_color = json_rgb(j["specularColor"], "specularColor", m.name);
    validate_gltf_factors(m.name, m.factors);
    set_alpha_from_roughness(m);
    return m;
  }
  if (model != "dgf")
    throw Error(fmt::format("material '{}': unknown model '{}' (models: gltf, or D/G/F terms without \"model\")",
                            m.name, model));
  reject_unknown_keys(j, {"name", "model", "d", "g", "f", "alpha", "params", "kd"}, m.name);
  m.gltf = false;
  m.d = &named_term(j, "d", Kind::D, m.name);
  m.g = &named_term(j, "g", Kind::G, m.name);
  m.f = &named_term(j, "f", Kind::F, m.name);
  std::map<std::string, double> params;
  if (j.contains("params")) {
    if (!j["params"].is_object()) throw Error(fmt::format("material '{}': params must be an object", m.name));
    for (auto& [k, v] : j["params"].items()) params[k] = json_number(v, "params." + k, m.name);
  }
  const bool has_alpha = j.contains("alpha");
  const double alpha = has_alpha ? json_number(j["alpha"], "alpha", m.name) : 0.0;
  if (has_alpha && !(alpha > 0 && std::isfinite(alpha)))
    throw Error(fmt::format("material '{}': alpha = {} must be a positive number", m.name, alpha));
  std::set<std::string> used;
  // A term's native parameter: named in params, else converted from alpha (roughness terms), else missing.
  auto native = [&](const Term& t, size_t i) {
    const Param& p = t.params[i];
    double v;
    if (auto it = params.find(p.name); it != params.end()) {
      v = it->second;
      used.insert(p.name);
    } else if (i == 0 && has_alpha && t.roughness != Roughness::None) {
      v = std::min(native_from_alpha(t.roughness, alpha), p.hi);
    } else {
      throw Error(fmt::format("material '{}': {} {} needs parameter {} (in \"params\"{})", m.name, kind_name(t.kind),
                              t.id, p.name, t.roughness != Roughness::None ? " or from \"alpha\"" : ""));
    }
    try {
      validate_param(t, i, v);
    } catch (const Error& e) {
      throw Error(fmt::format("material '{}': {}", m.name, e.what()));
    }
    return v;
  };
  m.pd = native(*m.d, 0);
  if (!m.g->params.empty()) m.pg = native(*m.g, 0);
  if (m.f->params.size() > 0) m.f0 = native(*m.f, 0);
  if (m.f->params.size() > 1) m.f1 = native(*m.f, 1);
  for (auto& [k, v] : params)
    if (used.count(k) == 0)
      throw Error(fmt::format("material '{}': parameter '{}' belongs to none of {}", m.name, k, m.model()));
  m.alpha = m.d->roughness == Roughness::PhongExponent ? alpha_from_phong_exponent(m.pd) : m.pd;
  if (j.contains("kd")) {
    m.kd = json_number(j["kd"], "kd", m.name);
    check_unit(m.name, "kd", m.kd);
  }
  return m;
}

Scene load_material_file(const std::string& path, const std::string& text) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(fmt::format("{}: malformed JSON: {}", path, e.what()));
  }
  if (!j.is_object() || !j.contains("materials") || !j["materials"].is_array() || j["materials"].empty())
    throw Error(fmt::format("{}: a material file holds {{\"materials\": [ ... ]}} with at least one material", path));
  Scene sc;
  sc.path = path;
  sc.format = "materials";
  std::set<std::string> names;
  for (size_t i = 0; i < j["materials"].size(); ++i) {
    SceneMaterial m = material_from_json(j["materials"][i], i);
    if (!names.insert(m.name).second) throw Error(fmt::format("{}: two materials are named '{}'", path, m.name));
    sc.materials.push_back(std::move(m));
  }
  sc.materials_in_file = sc.materials.size();
  return sc;
}

}  // namespace

Scene load_scene(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error(fmt::format("--scene {}: no such file", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(fmt::format("--scene {}: cannot read the file", path));
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".gltf") return load_gltf(path, false);
  if (ext == ".glb") return load_gltf(path, true);
  if (ext == ".json") {
    std::stringstream ss;
    ss << in.rdbuf();
    return load_material_file(path, ss.str());
  }
  throw Error(fmt::format("--scene {}: unknown format '{}' (expected .gltf, .glb or a material file .json)", path, ext));
}

}  // namespace mfv
