// glTF 2.0 (.gltf, .glb) materials, read from the JSON alone (issue 21): mfv
// checks materials, so buffers are never loaded (a .gltf whose .bin is absent
// reads), and images only where a texture scales a checked parameter: then its
// texels give the range, else [0, factor] is checked. Every number is a finite
// JSON number and every array has the spec's length (issue 17).
//
// Spec references: glTF 2.0 §3.9 (materials, default values), §3.8 (textures,
// images: uri or bufferView, PNG/JPEG), §4.4 (GLB: 12-byte header, JSON chunk,
// optional BIN chunk); the KHR_materials_* extension specifications.
#include "scene/scene.hpp"

#include "scene/gltf_file.hpp"
#include "scene/json_input.hpp"
#include "scene/texture_range.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>
#include <set>

namespace mfv {
namespace {

using nlohmann::json;

// Extensions mfv models (their parameters enter the glTF model)...
const std::set<std::string> kModelled = {"KHR_materials_ior", "KHR_materials_specular", "KHR_materials_anisotropy",
                                         "KHR_materials_sheen"};
// ... that it accounts for per material without a surface check (see account_extension) ...
const std::set<std::string> kAccounted = {"KHR_materials_clearcoat", "KHR_materials_transmission",
                                          "KHR_materials_volume", "KHR_materials_emissive_strength",
                                          "KHR_materials_unlit"};
// ... and that change nothing a BSDF check sees (geometry, texture coordinates, encodings, lights, instancing).
const std::set<std::string> kHarmless = {
    "KHR_mesh_quantization", "KHR_draco_mesh_compression", "EXT_meshopt_compression",
    "KHR_texture_transform", "KHR_texture_basisu",         "EXT_texture_webp",
    "KHR_lights_punctual",   "KHR_materials_variants",     "EXT_mesh_gpu_instancing"};

// Where a field sits, for messages: material 'x' (materials[3]): pbrMetallicRoughness.roughnessFactor
std::string at(const SceneMaterial& m, const std::string& field) {
  return fmt::format("material '{}' ({}): {}", m.name, m.origin, field);
}

double number_or(const json& obj, const char* key, double fallback, const SceneMaterial& m, const std::string& prefix) {
  return obj.contains(key) ? finite_number(obj[key], at(m, prefix + key)) : fallback;
}

const json& object_or_empty(const json& obj, const char* key, const std::string& where) {
  static const json empty = json::object();
  if (!obj.contains(key)) return empty;
  if (!obj[key].is_object()) throw Error(fmt::format("{}{} = {} is not an object", where, key, json_shown(obj[key])));
  return obj[key];
}

// A texture's channel c scales `factor`: the range [texels] x factor, or
// [0, factor] where the image cannot be read. srgb: colour textures (spec §3.9.2).
struct TextureSlot {
  const char* field;  // "metallicRoughnessTexture"
  int channel;        // 0..3 = R, G, B, A
  bool srgb;
};

ParamRange textured(const SceneMaterial& m, Images& images, const json& parent, const std::string& prefix,
                    const TextureSlot& slot, double factor, std::vector<std::string>& notes) {
  ParamRange r{factor, factor, "factor"};
  if (!parent.contains(slot.field)) return r;
  const json& info = parent[slot.field];
  const std::string where = at(m, prefix + slot.field);
  if (!info.is_object() || !info.contains("index")) throw Error(where + " is not a textureInfo with an index");
  const size_t t = json_index(info["index"], where + ".index");
  const json& tex = element(images.f, "textures", t, where);
  const char* ch = "RGBA" + slot.channel;
  if (!tex.contains("source")) {
    r = {0.0, factor, fmt::format("texture {} has no PNG/JPEG source: [0, factor {:g}]", t, factor)};
    notes.push_back(
        fmt::format("{} {}: texture {} has no PNG/JPEG source: checked over [0, {:g}]", prefix, slot.field, t, factor));
    return r;
  }
  const size_t src = json_index(tex["source"], fmt::format("{}: textures[{}].source", images.f.path, t));
  const ImageInfo& im = images.get(src);
  if (!im.ranges) {
    auto& users = images.missing_users[src];
    const std::string user = fmt::format("material '{}' {}", m.name, slot.field);
    if (std::find(users.begin(), users.end(), user) == users.end()) users.push_back(user);  // once, not per channel
    r = {0.0, factor, fmt::format("{} unread: [0, factor {:g}]", im.label, factor)};
    notes.push_back(fmt::format("{}{} reads {}: {}; checked over the whole range [0, {:g}]", prefix, slot.field,
                                im.label, im.missing, factor));
    return r;
  }
  double lo = im.ranges->rgba[size_t(slot.channel)].lo, hi = im.ranges->rgba[size_t(slot.channel)].hi;
  if (slot.srgb) lo = srgb_to_linear(lo), hi = srgb_to_linear(hi);
  r = {lo * factor, hi * factor,
       fmt::format("{} {}{}: [{:.4g}, {:.4g}] x factor {:g}", im.label, *ch, slot.srgb ? " (sRGB decoded)" : "", lo, hi,
                   factor)};
  notes.push_back(fmt::format("{}{}: {} channel {} spans [{:.4g}, {:.4g}]{}: checked over [{:.4g}, {:.4g}]", prefix,
                              slot.field, im.label, *ch, lo, hi, slot.srgb ? " (sRGB decoded)" : "", r.lo, r.hi));
  return r;
}

void check_unit_range(const SceneMaterial& m, const std::string& field, double v) {
  if (!(v >= 0.0 && v <= 1.0)) throw Error(fmt::format("{} = {:g} is out of range [0, 1]", at(m, field), v));
}

// Extensions accounted for without a surface check; sets m.not_checked where the material cannot be checked.
void account_extension(SceneMaterial& m, const std::string& ext, const json& v) {
  const std::string p = ext + ".";
  if (ext == "KHR_materials_unlit") {
    m.not_checked =
        "KHR_materials_unlit: no BSDF (shaded by the base colour alone): nothing to check on a surface BSDF";
  } else if (ext == "KHR_materials_volume") {
    const double th = number_or(v, "thicknessFactor", 0.0, m, p);
    if (th < 0.0) throw Error(fmt::format("{} = {:g} is negative", at(m, p + "thicknessFactor"), th));
    m.account.push_back(
        "KHR_materials_volume: the medium under the surface (attenuation, thickness): nothing to "
        "check on a surface BSDF");
  } else if (ext == "KHR_materials_emissive_strength") {
    const double s = number_or(v, "emissiveStrength", 1.0, m, p);
    if (s < 0.0) throw Error(fmt::format("{} = {:g} is negative", at(m, p + "emissiveStrength"), s));
    m.account.push_back(
        "KHR_materials_emissive_strength: emission, not reflection: nothing to check on a surface BSDF");
  }
}

// KHR_materials_transmission: transmission = transmissionFactor x
// transmissionTexture.r (linear). Thin-walled unless KHR_materials_volume
// gives a thickness (its spec: thicknessFactor 0 is thin-walled): then the
// transmission lobe is the specular lobe mirrored through the surface, the
// catalog's "gltf_transmission" model; with thickness > 0 the surface is a
// refracting boundary, the catalog's rough dielectric BSDF (Walter et al.
// 2007) at eta = ior and alpha = roughness² (issue 29).
void read_transmission(SceneMaterial& m, Images& images, const json& v, const json& volume) {
  const std::string p = "KHR_materials_transmission.";
  const double t = number_or(v, "transmissionFactor", 0.0, m, p);
  check_unit_range(m, p + "transmissionFactor", t);
  const double thickness = number_or(volume, "thicknessFactor", 0.0, m, "KHR_materials_volume.");
  if (!(t > 0.0)) {  // factor 0: no transmission, whatever the texture
    if (!v.empty())
      m.account.push_back("KHR_materials_transmission: transmissionFactor 0, no transmission: the surface is checked");
    return;
  }
  m.transmission = textured(m, images, v, p, {"transmissionTexture", 0, false}, t, m.account);
  std::string why;  // what the transmitting models do not layer
  if (m.anisotropy_strength.hi > 0.0) why = "KHR_materials_anisotropy";
  if (m.clearcoat.hi > 0.0) why = "KHR_materials_clearcoat";
  if (m.sheen_checked) why = "KHR_materials_sheen";
  for (size_t k = 0; k < 3; ++k)
    if (m.specular.lo != 1.0 || m.specular.hi != 1.0 || m.specular_color[k].lo != 1.0 || m.specular_color[k].hi != 1.0)
      why = "KHR_materials_specular";
  if (thickness > 0.0 && !(m.factors.ior > 1.0))
    why = fmt::format("KHR_materials_ior ior {:g} (a refracting boundary needs ior > 1)", m.factors.ior);
  if (!why.empty()) {
    m.not_checked = fmt::format(
        "KHR_materials_transmission (transmissionFactor {:g}) with {}: mfv's transmitting models take an isotropic "
        "base with specularFactor 1 and no coat or sheen; not checked (and never as a metal)",
        t, why);
    return;
  }
  if (thickness > 0.0) {
    m.volume_checked = true;
    m.account.push_back(fmt::format(
        "KHR_materials_transmission with KHR_materials_volume thicknessFactor {:g}: a refracting boundary, checked "
        "as the rough dielectric BSDF of Walter et al. 2007 (walter_ggx_correlated) at eta = ior {:g}, entering and "
        "leaving, at every roughness point: bsdf_furnace, bsdf_avg_reciprocity, transmission_masking",
        thickness, m.factors.ior));
    return;
  }
  m.thin_checked = true;
  m.account.push_back(fmt::format(
      "KHR_materials_transmission, thin-walled (no KHR_materials_volume thickness): checked as the "
      "gltf_transmission model (the specular lobe mirrored through the surface) over transmission [{:.4g}, {:.4g}], "
      "energy R + T <= 1 and reciprocity; and R + T = the F = 1 albedo of the same D and Vis at ior {:g} with a "
      "white base, full transmission and no metal (closed_form) at every roughness point",
      m.transmission.lo, m.transmission.hi, m.factors.ior));
}

// KHR_materials_clearcoat: clearcoat = clearcoatFactor x clearcoatTexture.r,
// clearcoatRoughness = clearcoatRoughnessFactor x clearcoatRoughnessTexture.g
// (both linear); checked through "gltf_clearcoat", whose base is isotropic
// with specularFactor 1.
void read_clearcoat(SceneMaterial& m, Images& images, const json& v) {
  const std::string p = "KHR_materials_clearcoat.";
  const double c = number_or(v, "clearcoatFactor", 0.0, m, p), r = number_or(v, "clearcoatRoughnessFactor", 0.0, m, p);
  check_unit_range(m, p + "clearcoatFactor", c);
  check_unit_range(m, p + "clearcoatRoughnessFactor", r);
  if (!(c > 0.0)) return;  // clearcoatFactor 0 disables the layer (the spec), whatever its texture
  m.clearcoat = textured(m, images, v, p, {"clearcoatTexture", 0, false}, c, m.account);
  m.clearcoat_roughness = textured(m, images, v, p, {"clearcoatRoughnessTexture", 1, false}, r, m.account);
  if (m.specular.lo != 1.0 || m.specular.hi != 1.0) {
    m.account.push_back(
        "KHR_materials_clearcoat: the coat is NOT checked: the gltf_clearcoat models layer it over a "
        "base with specularFactor 1, and this base is not one");
    return;
  }
  m.coat_checked = true;
  const bool aniso = m.anisotropy_strength.hi > 0.0;
  m.account.push_back(
      fmt::format("KHR_materials_clearcoat: checked as the {} model (fresnel_coat over "
                  "the base) over clearcoat [{:.4g}, {:.4g}], clearcoatRoughness [{:.4g}, {:.4g}]",
                  aniso ? "gltf_clearcoat_aniso (anisotropic base) and gltf_clearcoat" : "gltf_clearcoat",
                  m.clearcoat.lo, m.clearcoat.hi, m.clearcoat_roughness.lo, m.clearcoat_roughness.hi));
  if (m.clearcoat_roughness.lo * m.clearcoat_roughness.lo < kSceneMinAlpha)
    m.warnings.push_back(
        fmt::format("clearcoatRoughness {:g} gives a coat alpha below {:g}: the coat is checked at "
                    "alpha = {:g} (clearcoatRoughness 0.01)",
                    m.clearcoat_roughness.lo, kSceneMinAlpha, kSceneMinAlpha));
}

// KHR_materials_sheen: sheenColor = sheenColorFactor x sheenColorTexture.rgb
// (sRGB), sheenRoughness = sheenRoughnessFactor x sheenRoughnessTexture.a
// (linear); checked through "gltf_sheen" (the Charlie lobe with the spec's
// albedo scaling over an isotropic base). A black sheenColor disables the layer.
void read_sheen(SceneMaterial& m, Images& images, const json& v) {
  const std::string p = "KHR_materials_sheen.";
  std::vector<double> col{0, 0, 0};
  if (v.contains("sheenColorFactor")) col = number_array(v["sheenColorFactor"], 3, at(m, p + "sheenColorFactor"));
  for (int k = 0; k < 3; ++k) check_unit_range(m, fmt::format("{}sheenColorFactor[{}]", p, k), col[size_t(k)]);
  const double r = number_or(v, "sheenRoughnessFactor", 0.0, m, p);
  check_unit_range(m, p + "sheenRoughnessFactor", r);
  if (!(col[0] > 0 || col[1] > 0 || col[2] > 0))
    return;  // sheenColorFactor 0 (the default): no sheen, whatever the texture
  for (size_t k = 0; k < 3; ++k)
    m.sheen_color[k] = textured(m, images, v, p, {"sheenColorTexture", int(k), true}, col[k], m.account);
  m.sheen_roughness = textured(m, images, v, p, {"sheenRoughnessTexture", 3, false}, r, m.account);
  m.sheen_checked = true;
  m.account.push_back(fmt::format(
      "KHR_materials_sheen: checked as the gltf_sheen model (Charlie sheen over the base, albedo scaling 1 - "
      "max3(sheenColor) E_sheen) over sheenColor [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}], "
      "sheenRoughness [{:.4g}, {:.4g}]{}",
      m.sheen_color[0].lo, m.sheen_color[0].hi, m.sheen_color[1].lo, m.sheen_color[1].hi, m.sheen_color[2].lo,
      m.sheen_color[2].hi, m.sheen_roughness.lo, m.sheen_roughness.hi,
      m.anisotropy_strength.hi > 0.0 ? " (over the isotropic base points only: an anisotropic base is not layered)"
                                     : ""));
  const double floor = gltf_sheen_model().params[4].lo;
  if (m.sheen_roughness.lo < floor)
    m.warnings.push_back(
        fmt::format("sheenRoughness {:g} is below {:g}, where the Charlie lobe is a sliver at the "
                    "horizon: the sheen is checked at {:g}",
                    m.sheen_roughness.lo, floor, floor));
}

SceneMaterial from_gltf(const json& jm, size_t index, Images& images) {
  SceneMaterial m;
  m.origin = fmt::format("materials[{}]", index);
  if (!jm.is_object()) throw Error(fmt::format("{} is not an object", m.origin));
  if (jm.contains("name") && !jm["name"].is_string())
    throw Error(fmt::format("{}.name = {} is not a string", m.origin, json_shown(jm["name"])));
  m.name = jm.contains("name") && !jm["name"].get<std::string>().empty() ? jm["name"].get<std::string>()
                                                                         : fmt::format("material #{}", index);
  const json& pbr = object_or_empty(jm, "pbrMetallicRoughness", at(m, ""));
  const std::string pp = "pbrMetallicRoughness.";
  if (pbr.contains("baseColorFactor")) {
    const auto b = number_array(pbr["baseColorFactor"], 4, at(m, pp + "baseColorFactor"));  // RGBA (§3.9.2)
    for (size_t k = 0; k < 3; ++k) m.factors.base[k] = b[k];
    check_unit_range(m, pp + "baseColorFactor[3]", b[3]);
  }
  m.factors.metallic = number_or(pbr, "metallicFactor", 1.0, m, pp);
  m.factors.roughness = number_or(pbr, "roughnessFactor", 1.0, m, pp);
  const json& ext = object_or_empty(jm, "extensions", at(m, ""));
  for (auto& [name, v] : ext.items())
    if (!v.is_object()) throw Error(fmt::format("{} is not an object", at(m, "extensions." + name)));
  auto ext_of = [&](const char* e) -> const json& {
    static const json empty = json::object();
    return ext.contains(e) ? ext[e] : empty;
  };
  const json& ior = ext_of("KHR_materials_ior");
  const json& spec = ext_of("KHR_materials_specular");
  const json& aniso = ext_of("KHR_materials_anisotropy");
  m.factors.ior = number_or(ior, "ior", 1.5, m, "KHR_materials_ior.");
  if (ext.contains("KHR_materials_ior")) {
    // the catalog's exact dielectric F takes eta in [0.1, 10]; ior 0 is the specular-glossiness f0 = 1
    m.ior_exact = m.factors.ior >= 1.0 && m.factors.ior <= 10.0;
    m.account.push_back(m.ior_exact ? fmt::format("KHR_materials_ior: ior {:g} through Schlick's f0 (the spec) and "
                                                  "also the exact dielectric Fresnel at eta = {:g} "
                                                  "(ggx/smith_ggx_correlated/dielectric): energy at every roughness "
                                                  "point",
                                                  m.factors.ior, m.factors.ior)
                                    : fmt::format("KHR_materials_ior: ior {:g} through Schlick's f0 only (the exact "
                                                  "dielectric F takes eta in [1, 10])",
                                                  m.factors.ior));
  }
  m.factors.specular = number_or(spec, "specularFactor", 1.0, m, "KHR_materials_specular.");
  if (spec.contains("specularColorFactor")) {
    const auto c = number_array(spec["specularColorFactor"], 3, at(m, "KHR_materials_specular.specularColorFactor"));
    for (size_t k = 0; k < 3; ++k) m.factors.specular_color[k] = c[k];
  }
  m.factors.anisotropy_strength = number_or(aniso, "anisotropyStrength", 0.0, m, "KHR_materials_anisotropy.");
  m.factors.anisotropy_rotation = number_or(aniso, "anisotropyRotation", 0.0, m, "KHR_materials_anisotropy.");
  validate_gltf_factors(fmt::format("material '{}' ({})", m.name, m.origin), m.factors);
  set_factor_ranges(m);

  // Textures scale the factors (glTF §3.9.2: metallicRoughnessTexture G = roughness,
  // B = metallic; baseColorTexture sRGB; KHR_materials_specular: specularTexture A,
  // specularColorTexture sRGB RGB; KHR_materials_anisotropy: anisotropyTexture B = strength).
  std::vector<std::string>& notes = m.account;
  for (size_t k = 0; k < 3; ++k)
    m.base[k] = textured(m, images, pbr, pp, {"baseColorTexture", int(k), true}, m.factors.base[k], notes);
  m.roughness = textured(m, images, pbr, pp, {"metallicRoughnessTexture", 1, false}, m.factors.roughness, notes);
  m.metallic = textured(m, images, pbr, pp, {"metallicRoughnessTexture", 2, false}, m.factors.metallic, notes);
  m.specular =
      textured(m, images, spec, "KHR_materials_specular.", {"specularTexture", 3, false}, m.factors.specular, notes);
  for (size_t k = 0; k < 3; ++k)
    m.specular_color[k] = textured(m, images, spec, "KHR_materials_specular.", {"specularColorTexture", int(k), true},
                                   m.factors.specular_color[k], notes);
  m.anisotropy_strength = textured(m, images, aniso, "KHR_materials_anisotropy.", {"anisotropyTexture", 2, false},
                                   m.factors.anisotropy_strength, notes);
  // notes of colour textures come once per channel: keep one of each
  std::vector<std::string> unique;
  for (auto& n : notes)
    if (std::find(unique.begin(), unique.end(), n) == unique.end()) unique.push_back(n);
  notes = unique;

  // KHR_materials_specular: dielectric F0 = min(f0_ior · specularColor, 1) per channel, the spec's own clamp: said
  // where it acts
  const double r = m.factors.ior == 0 ? 1.0 : (m.factors.ior - 1.0) / (m.factors.ior + 1.0);
  for (size_t k = 0; k < 3; ++k)
    if (r * r * m.specular_color[k].hi > 1.0)
      m.warnings.push_back(
          fmt::format("KHR_materials_specular: f0 x specularColor = {:g} x {:g} = {:g} in channel {} "
                      "is clamped to 1 (the extension's min(f0 x specularColor, 1))",
                      r * r, m.specular_color[k].hi, r * r * m.specular_color[k].hi, "rgb"[k]));
  if (m.factors.anisotropy_rotation != 0.0)
    m.warnings.push_back(
        fmt::format("anisotropyRotation {:g} turns the lobe about n: checked in the anisotropy "
                    "direction's own frame, where the BRDF does not depend on it",
                    m.factors.anisotropy_rotation));
  read_clearcoat(m, images, ext_of("KHR_materials_clearcoat"));
  read_sheen(m, images, ext_of("KHR_materials_sheen"));
  read_transmission(m, images, ext_of("KHR_materials_transmission"), ext_of("KHR_materials_volume"));
  for (auto& [name, v] : ext.items()) {
    if (kModelled.count(name)) continue;
    if (kAccounted.count(name))
      account_extension(m, name, v);
    else if (name.rfind("KHR_materials_", 0) == 0 || name.rfind("EXT_materials_", 0) == 0)
      m.not_checked = fmt::format("{} changes the BSDF and mfv does not model it: not checked", name);
    else if (!kHarmless.count(name))
      m.account.push_back(fmt::format("{}: not a material extension mfv knows; the BSDF is checked without it", name));
  }
  note_alpha_floor(m);
  return m;
}

// The glTF default material (spec §3.9.6): base colour 1, metallic 1, roughness 1.
SceneMaterial default_gltf_material() {
  SceneMaterial m;
  m.name = "default material";
  m.origin = "mesh primitives without a material (glTF default material)";
  set_factor_ranges(m);
  note_alpha_floor(m);
  return m;
}

struct Usage {
  std::set<size_t> materials;
  bool default_used = false;
  std::set<size_t> seen_nodes;
};

void collect_node(const GltfFile& f, size_t node, Usage& u) {
  if (!u.seen_nodes.insert(node).second) return;
  const json& n = element(f, "nodes", node, "a scene");
  if (n.contains("mesh")) {
    const size_t mi = json_index(n["mesh"], fmt::format("{}: nodes[{}].mesh", f.path, node));
    const json& mesh = element(f, "meshes", mi, fmt::format("nodes[{}]", node));
    if (!mesh.contains("primitives") || !mesh["primitives"].is_array())
      throw Error(fmt::format("{}: meshes[{}].primitives is not an array", f.path, mi));
    for (size_t p = 0; p < mesh["primitives"].size(); ++p) {
      const json& prim = mesh["primitives"][p];
      if (prim.is_object() && prim.contains("material"))
        u.materials.insert(
            json_index(prim["material"], fmt::format("{}: meshes[{}].primitives[{}].material", f.path, mi, p)));
      else
        u.default_used = true;
    }
  }
  if (n.contains("children")) {
    if (!n["children"].is_array()) throw Error(fmt::format("{}: nodes[{}].children is not an array", f.path, node));
    for (auto& c : n["children"])
      collect_node(f, json_index(c, fmt::format("{}: nodes[{}].children", f.path, node)), u);
  }
}

// The materials the scene's nodes use; a file without meshes is a material library (all of them).
Usage used_materials(const GltfFile& f) {
  Usage u;
  const json& mats = top_array(f, "materials");
  if (top_array(f, "meshes").empty()) {
    for (size_t i = 0; i < mats.size(); ++i) u.materials.insert(i);
    return u;
  }
  std::vector<size_t> roots;
  const json& scenes = top_array(f, "scenes");
  auto scene_nodes = [&](size_t s) {
    const json& sc = element(f, "scenes", s, "the file");
    if (sc.contains("nodes"))
      for (auto& n : sc["nodes"]) roots.push_back(json_index(n, fmt::format("{}: scenes[{}].nodes", f.path, s)));
  };
  if (f.j.contains("scene"))
    scene_nodes(json_index(f.j["scene"], f.path + ": scene"));
  else
    for (size_t s = 0; s < scenes.size(); ++s) scene_nodes(s);
  if (scenes.empty())  // no scene: every node
    for (size_t i = 0; i < top_array(f, "nodes").size(); ++i) roots.push_back(i);
  for (size_t r : roots) collect_node(f, r, u);
  for (size_t i : u.materials)
    if (i >= mats.size())
      throw Error(fmt::format("{}: a mesh primitive names material {}, but the file has {}", f.path, i, mats.size()));
  return u;
}

}  // namespace

Scene load_gltf(const std::string& path, bool binary) {
  const GltfFile f = read_gltf_file(path, binary);
  Scene sc;
  sc.path = path;
  sc.format = binary ? "glb" : "gltf";
  if (f.j.contains("extensionsRequired")) {
    if (!f.j["extensionsRequired"].is_array()) throw Error(path + ": extensionsRequired is not an array");
    for (auto& e : f.j["extensionsRequired"]) {
      const std::string ext = e.is_string() ? e.get<std::string>() : json_shown(e);
      if (!kModelled.count(ext) && !kAccounted.count(ext) && !kHarmless.count(ext))
        throw Error(
            fmt::format("{} requires extension {}, which mfv neither models nor accounts for (it models "
                        "KHR_materials_ior, KHR_materials_specular, KHR_materials_anisotropy; see docs/scenes.md)",
                        path, ext));
    }
  }
  const Usage u = used_materials(f);
  const json& mats = top_array(f, "materials");
  sc.materials_in_file = mats.size();
  Images images{f, {}, {}};
  for (size_t i : u.materials) sc.materials.push_back(from_gltf(mats[i], i, images));
  if (u.default_used) sc.materials.push_back(default_gltf_material());
  if (sc.materials.empty()) throw Error(fmt::format("{}: the scene uses no material (no mesh, no material)", path));
  // every image that could not be read, once each, with the materials it scales
  for (auto& [i, users] : images.missing_users) {
    std::string who;
    for (auto& w : users) who += (who.empty() ? "" : ", ") + w;
    sc.warnings.push_back(
        fmt::format("{}: its textured parameters are checked over [0, factor] ({})", images.cache.at(i).missing, who));
  }
  return sc;
}

}  // namespace mfv
