#include "scene/scene.hpp"

#include "catalog/roughness.hpp"
#include "scene/json_input.hpp"
#include "util/error.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

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

const Model& gltf_model() { return *try_find_model("gltf"); }
const Model& gltf_clearcoat_model() { return *try_find_model("gltf_clearcoat"); }
const Model& gltf_sheen_model() { return *try_find_model("gltf_sheen"); }
const Model& gltf_clearcoat_aniso_model() { return *try_find_model("gltf_clearcoat_aniso"); }
const Model& gltf_transmission_model() { return *try_find_model("gltf_transmission"); }

Expect gltf_energy_expect(const GltfChannelParams& c) {
  const bool plain = c.metallic >= 1.0 || (1.0 - c.metallic) * c.base <= 0.0 || c.weight <= 0.0;
  return plain ? Expect::Hold : Expect::May;
}

std::string SceneMaterial::model() const {
  if (thin_checked) return "gltf_transmission";
  if (volume_checked) return "walter_ggx_correlated";
  return gltf ? "gltf" : d->id + "/" + g->id + "/" + f->id;
}

namespace {

std::string channel_names(int k) { return k == 0 ? "r" : k == 1 ? "g" : "b"; }

void check_unit(const std::string& who, const std::string& what, double v) {
  if (!(v >= 0.0 && v <= 1.0)) throw Error(fmt::format("{}: {} = {} is out of range [0, 1]", who, what, v));
}

}  // namespace

void validate_gltf_factors(const std::string& name, const GltfFactors& f) {  // name: "material 'x' (materials[2])"
  for (int k = 0; k < 3; ++k) check_unit(name, "baseColorFactor." + channel_names(k), f.base[k]);
  check_unit(name, "metallicFactor", f.metallic);
  check_unit(name, "roughnessFactor", f.roughness);
  if (!(f.ior == 0.0 || (f.ior >= 1.0 && std::isfinite(f.ior))))
    throw Error(fmt::format("{}: KHR_materials_ior ior = {} is out of range (1 or more, or 0)", name, f.ior));
  check_unit(name, "KHR_materials_specular specularFactor", f.specular);
  check_unit(name, "KHR_materials_anisotropy anisotropyStrength", f.anisotropy_strength);
  if (!std::isfinite(f.anisotropy_rotation))
    throw Error(
        fmt::format("{}: KHR_materials_anisotropy anisotropyRotation = {} is not finite", name, f.anisotropy_rotation));
  for (int k = 0; k < 3; ++k)
    if (!(f.specular_color[k] >= 0.0 && std::isfinite(f.specular_color[k])))
      throw Error(
          fmt::format("{}: KHR_materials_specular specularColorFactor.{} = {} must be a finite "
                      "number >= 0",
                      name, channel_names(k), f.specular_color[k]));
}

namespace {

// ---- native material file (JSON) -------------------------------------------

using nlohmann::json;

double json_number(const json& j, const std::string& key, const std::string& material) {
  return finite_number(j, fmt::format("material '{}': {}", material, key));
}

std::array<double, 3> json_rgb(const json& j, const std::string& key, const std::string& material) {
  if (j.is_number()) {
    const double v = json_number(j, key, material);
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
    throw Error(
        fmt::format("material '{}': needs \"{}\" naming a {} term (see 'mfv list')", material, key, kind_name(kind)));
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
    validate_gltf_factors("material '" + m.name + "'", m.factors);
    set_factor_ranges(m);
    note_alpha_floor(m);
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
      // no clamp: a width outside the term's range is an error naming both (issue 17)
      v = native_from_alpha(t.roughness, alpha);
      if (!(v >= p.lo && v <= p.hi))
        throw Error(fmt::format("material '{}': alpha = {:g} gives {} {} {} = {:g}, outside its range [{:g}, {:g}]",
                                m.name, alpha, kind_name(t.kind), t.id, p.name, v, p.lo, p.hi));
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
  const json j = parse_json_strict(path, text);
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
  try {
    if (ext == ".gltf") return load_gltf(path, false);
    if (ext == ".glb") return load_gltf(path, true);
    if (ext == ".json") {
      std::stringstream ss;
      ss << in.rdbuf();
      return load_material_file(path, ss.str());
    }
  } catch (const Error& e) {
    // every message names the file (issue 17): file, material, field
    const std::string what = e.what();
    if (what.rfind(path, 0) == 0) throw;
    throw Error(path + ": " + what);
  }
  throw Error(
      fmt::format("--scene {}: unknown format '{}' (expected .gltf, .glb or a material file .json)", path, ext));
}

}  // namespace mfv
