#include "user/user_brdf.hpp"

#include "user/source_reader.hpp"

#include "catalog/roughness.hpp"
#include "util/error.hpp"
#include "util/parse.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <cctype>
#include <regex>
#include <sstream>

namespace mfv {

std::vector<double> UserParam::ends() const {
  if (fixed || lo == hi) return {value};
  return {lo, hi};
}

double UserBrdf::width(const std::vector<double>& values) const {
  if (claimed_width) {
    const double w = claimed_width(values);
    if (w > 0) return w;
  }
  if (roughness < 0) return 0.0;  // no declared roughness: the estimators' mixture of widths
  double v = values[size_t(roughness)];
  return alpha_from_native(params[size_t(roughness)].role, v);
}

std::vector<double> UserBrdf::eta_values() const {
  if (eta < 0) return {};
  const UserParam& p = params[size_t(eta)];
  if (p.fixed || p.lo == p.hi) return {p.value};
  std::vector<double> v = {p.lo, p.value, p.hi};
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

std::vector<double> UserBrdf::defaults() const {
  std::vector<double> v;
  for (auto& p : params) v.push_back(p.value);
  return v;
}

namespace {

// The three functions of the contract, as docs/cli/check.md states them.
struct Contract {
  const char* name;
  const char* ret;
  std::vector<std::string> types;
  const char* text;
};
const std::vector<Contract>& contracts() {
  static const std::vector<Contract> c = {
      {"brdf", "float3", {"float3", "float3", "float*"}, "float3 brdf(float3 wi, float3 wo, const float* params)"},
      {"D", "float", {"float3", "float*"}, "float D(float3 m, const float* params)"},
      {"G1", "float", {"float3", "float3", "float*"}, "float G1(float3 v, float3 m, const float* params)"},
      {"btdf", "float3", {"float3", "float3", "float*"}, "float3 btdf(float3 wi, float3 wo, const float* params)"},
      {"bsdf", "float3", {"float3", "float3", "float*"}, "float3 bsdf(float3 wi, float3 wo, const float* params)"},
  };
  return c;
}

std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (char ch : s) {
    if (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_') {
      cur += ch;
    } else {
      if (!cur.empty()) out.push_back(cur), cur.clear();
      if (ch == '*' || ch == '[') out.push_back(std::string(1, ch == '[' ? '*' : ch));
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

bool qualifier(const std::string& w) {
  static const char* q[] = {"const",    "static",    "inline",  "__inline",      "restrict",     "__restrict",
                            "volatile", "__private", "private", "__attribute__", "overloadable", "in",
                            "highp",    "mediump",   "lowp",    "precise"};
  return std::find(std::begin(q), std::end(q), w) != std::end(q);
}

// One parameter's type with qualifiers and its name dropped ("const float *p",
// "float p[]" -> "float*"; the name goes to `name`).
std::string param_type(const std::string& decl, std::string& name) {
  std::vector<std::string> ids;
  size_t stars = 0;
  for (auto& w : words(decl)) {
    if (w == "*")
      ++stars;
    else if (!qualifier(w) && !std::isdigit(static_cast<unsigned char>(w[0])))  // float p[6]: a pointer
      ids.push_back(canonical_type(w));
  }
  name.clear();
  if (ids.size() >= 2) name = ids.back(), ids.pop_back();
  std::string type;
  for (auto& w : ids) type += w;
  return type + std::string(stars, '*');
}

struct Found {
  bool defined = false;
  size_t unit = 0;  // the file that defines it (ReadSources::units)
  int line = 0;
  std::string params_name;  // name of its `const float*` argument
};

// Finds the definition of `c` in the comment-free text and checks its signature.
Found find_function(const std::string& path, const std::string& code, const Contract& c) {
  Found f;
  const std::regex def(std::string("([A-Za-z_][A-Za-z0-9_\\s\\*]*?)\\b") + c.name + "\\s*\\(([^()]*)\\)\\s*\\{");
  std::smatch m;
  if (!std::regex_search(code, m, def)) return f;
  f.defined = true;
  f.line = line_of(code, size_t(m.position(0) + m.length(1)));
  std::string found = std::regex_replace(m.str(0).substr(0, m.str(0).size() - 1), std::regex("\\s+"), " ");
  auto bad = [&](const std::string& why) {
    return Error(fmt::format("{}:{}: {} must be '{}'{}; found '{}'", path, f.line, c.name, c.text, why, found));
  };
  std::string ret;
  for (auto& w : words(m.str(1)))
    if (!qualifier(w) && w != "__kernel" && w != "kernel") ret = canonical_type(w);
  auto decls = split(m.str(2), ',');
  if (decls.size() == 1 && words(decls[0]) == std::vector<std::string>{"void"}) decls.clear();
  if (ret != c.ret || decls.size() != c.types.size()) throw bad("");
  for (size_t i = 0; i < decls.size(); ++i) {
    if (decls[i].find("__global") != std::string::npos || decls[i].find("global ") != std::string::npos ||
        decls[i].find("__constant") != std::string::npos || decls[i].find("__local") != std::string::npos)
      throw bad(" (params is a private pointer: no address-space qualifier)");
    std::string name;
    if (param_type(decls[i], name) != c.types[i]) throw bad("");
    if (c.types[i] == "float*") f.params_name = name;
  }
  return f;
}

// `// mfv: param NAME LO HI [default V] [roughness|perceptual|eta]`
UserParam parse_declaration(const UserBrdf& u, int line, const std::string& body) {
  auto where = fmt::format("{}:{}", u.path, line);
  std::istringstream in(body);
  std::vector<std::string> t;
  for (std::string w; in >> w;) t.push_back(w);
  const std::string form = "// mfv: param NAME LO HI [default V] [roughness|perceptual|eta]";
  if (t.empty() || t[0] != "param")
    throw Error(fmt::format("{}: unknown mfv directive '{}' (the form is '{}')", where, body, form));
  if (t.size() < 4)
    throw Error(fmt::format("{}: '{}' needs a name, a lower and an upper end ('{}')", where, body, form));
  UserParam p;
  p.name = t[1];
  p.line = line;
  if (!std::regex_match(p.name, std::regex("[A-Za-z_][A-Za-z0-9_]*")))
    throw Error(fmt::format("{}: parameter name '{}' is not an identifier", where, p.name));
  p.lo = parse_number(where + ": " + p.name + " lower end", t[2]);
  p.hi = parse_number(where + ": " + p.name + " upper end", t[3]);
  p.value = 0.5 * (p.lo + p.hi);
  for (size_t i = 4; i < t.size(); ++i) {
    if (t[i] == "default" && i + 1 < t.size())
      p.value = parse_number(where + ": " + p.name + " default", t[++i]);
    else if (t[i] == "roughness")
      p.role = Roughness::Alpha;
    else if (t[i] == "perceptual")
      p.role = Roughness::Perceptual;
    else if (t[i] == "eta")
      p.is_eta = true;
    else
      throw Error(fmt::format("{}: unexpected '{}' in '{}' (the form is '{}')", where, t[i], body, form));
  }
  if (!std::isfinite(p.lo) || !std::isfinite(p.hi) || p.lo > p.hi)
    throw Error(fmt::format("{}: {} has the range [{}, {}]; give finite LO <= HI", where, p.name, p.lo, p.hi));
  if (!(p.value >= p.lo && p.value <= p.hi))
    throw Error(fmt::format("{}: {} default {} is outside [{}, {}]", where, p.name, p.value, p.lo, p.hi));
  if (p.role != Roughness::None && !(p.lo > 0))
    throw Error(fmt::format("{}: roughness {} must be positive (range [{}, {}]); a zero width is a mirror", where,
                            p.name, p.lo, p.hi));
  return p;
}

UserParam* find_param(UserBrdf& u, const std::string& name) {
  for (auto& p : u.params)
    if (p.name == name) return &p;
  return nullptr;
}

// --param NAME=V fixes a parameter; NAME=LO:HI narrows a declared range or
// declares a new parameter (the next index).
void apply_cli_param(UserBrdf& u, const std::string& arg) {
  auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0)
    throw Error(fmt::format("--param wants NAME=VALUE or NAME=LO:HI, got '{}'", arg));
  std::string name = arg.substr(0, eq), val = arg.substr(eq + 1);
  auto range = split(val, ':');
  const std::string what = "--param " + name;
  UserParam* p = find_param(u, name);
  if (range.size() == 1) {
    double v = parse_number(what, val);
    if (!std::isfinite(v)) throw Error(fmt::format("{} = {} is not a finite number", what, val));
    if (p) {
      if (v < p->lo || v > p->hi)
        throw Error(fmt::format("{} = {} is out of range [{}, {}] ({}:{})", what, v, p->lo, p->hi, u.path, p->line));
      p->value = v;
      p->fixed = true;
      return;
    }
    u.params.push_back({name, v, v, v, true, Roughness::None, false, 0});
    return;
  }
  if (range.size() != 2) throw Error(fmt::format("{}: '{}' is neither a value nor LO:HI", what, val));
  double lo = parse_number(what + " lower end", range[0]), hi = parse_number(what + " upper end", range[1]);
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
    throw Error(fmt::format("{} = {}: give finite LO <= HI", what, val));
  if (p) {
    if (lo < p->lo || hi > p->hi)
      throw Error(fmt::format("{} = {} reaches outside the declared range [{}, {}] ({}:{})", what, val, p->lo, p->hi,
                              u.path, p->line));
    p->lo = lo;
    p->hi = hi;
    p->value = std::clamp(p->value, lo, hi);
    return;
  }
  u.params.push_back({name, lo, hi, 0.5 * (lo + hi), false, Roughness::None, false, 0});
}

}  // namespace

UserBrdf load_user_brdf(const std::string& path, const UserParamArgs& args) {
  UserBrdf u;
  u.path = path;
  u.name = std::filesystem::path(path).stem().string();
  u.dialect = dialect_of(args.dialect, path);
  ReadOptions ropt;
  for (auto& d : args.defines) {
    auto eq = d.find('=');
    std::string name = d.substr(0, eq);
    if (!std::regex_match(name, std::regex("[A-Za-z_][A-Za-z0-9_]*")))
      throw Error(fmt::format("--define {}: give NAME=VALUE or NAME (NAME an identifier)", d));
    ropt.defines[name] = eq == std::string::npos ? "1" : d.substr(eq + 1);
  }
  ropt.includes = args.includes;
  ReadSources src = read_sources(path, ropt);
  const ReadUnit& main = src.units[src.top.back()];

  // Declarations, in file order (their order is the params[] index): the
  // `// mfv:` line comments of the main file's active code.
  for (auto& [n, body] : main.mfv_lines) {
    UserParam p = parse_declaration(u, n, body);
    if (find_param(u, p.name)) throw Error(fmt::format("{}:{}: parameter {} is declared twice", path, n, p.name));
    u.params.push_back(p);
  }
  for (auto& a : args.params) apply_cli_param(u, a);
  if (!args.roughness.empty()) {
    std::string name = args.roughness;
    Roughness role = Roughness::Alpha;
    if (name.size() > 2 && name.compare(name.size() - 2, 2, "^2") == 0)
      name.resize(name.size() - 2), role = Roughness::Perceptual;
    UserParam* p = find_param(u, name);
    if (!p)
      throw Error(
          fmt::format("--roughness {}: no parameter of that name (declare it in the file or with --param)", name));
    for (auto& q : u.params) q.role = Roughness::None;
    p->role = role;
  }
  for (size_t i = 0; i < u.params.size(); ++i) {
    if (u.params[i].role == Roughness::None) continue;
    if (u.roughness >= 0)
      throw Error(fmt::format("{}: both {} and {} are marked as the roughness; mark one", path,
                              u.params[size_t(u.roughness)].name, u.params[i].name));
    if (!(u.params[i].lo > 0))
      throw Error(fmt::format("roughness {} must be positive (range [{}, {}])", u.params[i].name, u.params[i].lo,
                              u.params[i].hi));
    u.roughness = int(i);
  }
  if (!args.eta.empty()) {
    UserParam* p = find_param(u, args.eta);
    if (!p)
      throw Error(fmt::format("--eta {}: no parameter of that name (declare it in the file or with --param)", args.eta));
    for (auto& q : u.params) q.is_eta = false;
    p->is_eta = true;
  }
  for (size_t i = 0; i < u.params.size(); ++i) {
    const UserParam& p = u.params[i];
    if (!p.is_eta) continue;
    if (u.eta >= 0)
      throw Error(fmt::format("{}: both {} and {} are marked as eta; mark one", path, u.params[size_t(u.eta)].name,
                              p.name));
    if (p.role != Roughness::None)
      throw Error(fmt::format("{}: {} is marked both as the roughness and as eta; mark one", path, p.name));
    // eta = eta_below / eta_above: positive; at 1 (index matched) the rough
    // BTDF is a Dirac in o = -i that no function value represents
    if (!(p.lo > 0) || !(p.lo > 1 || p.hi < 1))
      throw Error(fmt::format("eta {} = [{}, {}] must be positive and lie on one side of 1 (at eta = 1 the index "
                              "is matched: the rough BTDF is a Dirac at wo = -wi, no function value)",
                              p.name, p.lo, p.hi));
    u.eta = int(i);
  }
  if (u.params.size() > kUserMaxParams)
    throw Error(
        fmt::format("{} declares {} parameters; mfv check passes at most {}", path, u.params.size(), kUserMaxParams));

  // Functions and signatures, in whichever file defines them.
  auto find = [&](const Contract& c) {
    for (size_t i = 0; i < src.units.size(); ++i) {
      Found f = find_function(src.units[i].path, src.units[i].code, c);
      if (f.defined) {
        f.unit = i;
        return f;
      }
    }
    return Found{};
  };
  Found fb = find(contracts()[0]);
  Found fd = find(contracts()[1]);
  Found fg = find(contracts()[2]);
  Found ft = find(contracts()[3]);
  Found fs = find(contracts()[4]);
  if (!fb.defined && !ft.defined && !fs.defined)
    throw Error(fmt::format("{} defines no '{}' (the function mfv check verifies), nor a '{}' or '{}' (see "
                            "docs/cli/check.md)",
                            path, contracts()[0].text, contracts()[3].text, contracts()[4].text));
  if (fs.defined && (fb.defined || ft.defined))
    throw Error(fmt::format("{}:{}: bsdf covers both hemispheres; define bsdf alone, or brdf and btdf", path, fs.line));
  u.has_brdf = fb.defined;
  u.has_btdf = ft.defined;
  u.has_bsdf = fs.defined;
  u.has_d = fd.defined;
  u.has_g1 = fg.defined;
  if (u.transmits() && u.eta < 0)
    throw Error(fmt::format("{} defines {} but no parameter is its relative index eta = eta_below / eta_above: "
                            "declare '// mfv: param eta LO HI default V eta' or mark one with --eta NAME",
                            path, u.has_bsdf ? "bsdf" : "btdf"));
  if (!u.transmits() && u.eta >= 0)
    throw Error(fmt::format("{}: {} is marked as eta, the relative index of a btdf or bsdf, but the file defines "
                            "neither",
                            path, u.params[size_t(u.eta)].name));
  UserNames names = user_names(src, u.dialect);
  for (const Found* f : {&fb, &fd, &fg, &ft, &fs})
    if (f->defined && !f->params_name.empty()) names.guarded.insert(f->params_name);
  // Every params[k] the code reads must be declared.
  for (const Found* f : {&fb, &fd, &fg, &ft, &fs}) {
    if (!f->defined || f->params_name.empty()) continue;
    const std::string& code = src.units[f->unit].code;
    const std::regex use("\\b" + f->params_name + "\\s*\\[\\s*([0-9]+)\\s*\\]");
    for (auto it = std::sregex_iterator(code.begin(), code.end(), use); it != std::sregex_iterator(); ++it) {
      size_t k = std::stoul((*it)[1].str());
      if (k < u.params.size()) continue;
      // `float params[6]` in a parameter list declares, it does not read
      size_t w = size_t(it->position(0));
      while (w > 0 && std::isspace(static_cast<unsigned char>(code[w - 1]))) --w;
      if (w >= 5 && code.compare(w - 5, 5, "float") == 0) continue;
      std::string names;
      for (auto& p : u.params) names += (names.empty() ? "" : ", ") + p.name;
      throw Error(fmt::format(
          "{}:{}: the code reads {}[{}] but {} parameter{} declared{}{}{}; add "
          "'// mfv: param NAME LO HI default V' or pass --param NAME=LO:HI",
          src.units[f->unit].path, line_of(code, size_t(it->position(0))), f->params_name, k, u.params.size(),
          u.params.size() == 1 ? " is" : "s are", names.empty() ? "" : " (", names, names.empty() ? "" : ")"));
    }
  }
  // The sources the compiler reads, translated line for line.
  std::vector<std::string> texts;
  for (size_t i = 0; i < src.units.size(); ++i) texts.push_back(translate(src, i, u.dialect, names));
  for (size_t i : src.top) u.sources.push_back({src.units[i].path, with_includes(src.units, texts, i)});
  // --define reaches the compiler as it reached the reader: before the first
  // file, its floating value in float for glsl/hlsl (as the files' literals)
  std::string head;
  for (auto& [name, value] : ropt.defines)
    head += fmt::format("#define {} {}{}\n", name, value,
                        u.dialect != Dialect::OpenCL && floating_literal(value) &&
                                std::isdigit(static_cast<unsigned char>(value.back()))
                            ? "f"
                            : "");
  if (!head.empty() && !u.sources.empty())
    u.sources.front().text = head + fmt::format("#line 1 \"{}\"\n", u.sources.front().name) + u.sources.front().text;
  return u;
}

}  // namespace mfv
