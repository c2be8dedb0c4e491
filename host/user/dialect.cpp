#include "user/dialect.hpp"

#include "user/dialect_detail.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>

namespace mfv {

bool floating_literal(const std::string& t) {
  if (t.size() > 1 && t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) return false;
  return t.find_first_of(".eE") != std::string::npos;
}

const char* dialect_name(Dialect d) { return d == Dialect::Glsl ? "glsl" : d == Dialect::Hlsl ? "hlsl" : "opencl"; }

Dialect dialect_of(const std::string& name, const std::string& path) {
  if (name == "glsl") return Dialect::Glsl;
  if (name == "hlsl") return Dialect::Hlsl;
  if (name == "opencl") return Dialect::OpenCL;
  if (!name.empty()) throw Error(fmt::format("--dialect {}: name glsl, hlsl or opencl", name));
  std::string ext = std::filesystem::path(path).extension().string();
  for (const char* e : {".glsl", ".frag", ".fs", ".vert", ".comp", ".glslinc"})
    if (ext == e) return Dialect::Glsl;
  for (const char* e : {".hlsl", ".fx", ".hlsli", ".fxh"})
    if (ext == e) return Dialect::Hlsl;
  return Dialect::OpenCL;
}

using namespace dialect_detail;

namespace {

const std::string kPrefix = "mfv_u_";
bool contract_name(const std::string& n) {
  return n == "brdf" || n == "btdf" || n == "bsdf" || n == "D" || n == "G1";
}

// The vector/scalar type names of glsl and hlsl, as OpenCL C spells them.
std::string scalar_or_vector(const std::string& n, Dialect d) {
  static const std::regex glsl("(b|i|u|d)?vec([234])"),
      hlsl("(float|half|min16float|min10float|int|uint|bool|double)([234])?");
  std::smatch m;
  if (d == Dialect::Glsl && std::regex_match(n, m, glsl)) {
    std::string p = m.str(1);
    return (p == "i" || p == "b" ? "int" : p == "u" ? "uint" : p == "d" ? "double" : "float") + m.str(2);
  }
  if (d == Dialect::Hlsl && std::regex_match(n, m, hlsl)) {
    std::string p = m.str(1);
    return (p == "half" || p == "min16float" || p == "min10float" ? "float" : p == "bool" ? "int" : p) + m.str(2);
  }
  return "";
}

bool matrix_type(const std::string& n, Dialect d) {
  static const std::regex glsl("d?mat[234](x[234])?"), hlsl("(float|half|double|min16float)[234]x[234]");
  return std::regex_match(n, d == Dialect::Glsl ? glsl : hlsl);
}

// Built-ins the dialect names otherwise, or with overloads OpenCL C lacks
// (kernels/user_prelude.cl defines the mfv_g_ ones).
const std::map<std::string, std::string>& builtins(Dialect d) {
  static const std::map<std::string, std::string> glsl = {
      {"abs", "mfv_g_abs"},     {"atan", "mfv_g_atan"},   {"pow", "mfv_g_pow"},           {"mod", "mfv_g_mod"},
      {"fract", "mfv_g_fract"}, {"inversesqrt", "rsqrt"}, {"saturate", "mfv_g_saturate"}, {"min", "mfv_g_min"},
      {"max", "mfv_g_max"},     {"clamp", "mfv_g_clamp"}, {"mix", "mfv_g_mix"},           {"reflect", "mfv_g_reflect"},
      {"step", "mfv_g_step"},   {"floatBitsToUint", "as_uint"}, {"floatBitsToInt", "as_int"},
      {"uintBitsToFloat", "as_float"}, {"intBitsToFloat", "as_float"}};
  static const std::map<std::string, std::string> hlsl = {
      {"abs", "mfv_g_abs"},           {"pow", "mfv_g_pow"},     {"frac", "mfv_g_fract"},      {"lerp", "mfv_g_mix"},
      {"saturate", "mfv_g_saturate"}, {"rcp", "mfv_g_rcp"},     {"mad", "mfv_g_mad"},         {"min", "mfv_g_min"},
      {"max", "mfv_g_max"},           {"clamp", "mfv_g_clamp"}, {"reflect", "mfv_g_reflect"}, {"step", "mfv_g_step"},
      {"asfloat", "as_float"},        {"asuint", "as_uint"},    {"asint", "as_int"},          {"sincos", "mfv_g_sincos"}};
  static const std::map<std::string, std::string> none;
  return d == Dialect::Glsl ? glsl : d == Dialect::Hlsl ? hlsl : none;
}

// The code tokens (no comments or directives) of the active branches.
std::vector<const Token*> code_tokens(const ReadUnit& u) {
  std::vector<const Token*> out;
  for (size_t k = 0; k < u.tokens.size(); ++k) {
    const Token& t = u.tokens[k];
    if (u.active[k] && t.kind != Token::LineComment && t.kind != Token::BlockComment && t.kind != Token::Directive)
      out.push_back(&t);
  }
  return out;
}

// The name of a parameter declaration: its last identifier before any '['.
size_t param_name(const std::vector<const Token*>& toks, std::pair<size_t, size_t> p, bool& array) {
  size_t end = p.second;
  array = false;
  for (size_t k = p.first; k < p.second; ++k)
    if (toks[k]->text == "[") {
      end = k, array = true;
      break;
    }
  for (size_t k = end; k-- > p.first;)
    if (toks[k]->kind == Token::Ident) return k;
  return p.second;
}

bool has_out(const std::vector<const Token*>& toks, std::pair<size_t, size_t> p) {
  for (size_t k = p.first; k < p.second; ++k)
    if (toks[k]->text == "out" || toks[k]->text == "inout") return true;
  return false;
}

// File-scope function definitions or prototypes: the index of each name token.
std::vector<size_t> functions_at_file_scope(const std::vector<const Token*>& toks) {
  std::vector<size_t> out;
  int depth = 0;
  for (size_t k = 0; k < toks.size(); ++k) {
    const std::string& s = toks[k]->text;
    if (s == "{") ++depth;
    if (s == "}") --depth;
    if (depth != 0 || toks[k]->kind != Token::Ident || k == 0 || k + 1 >= toks.size() || !is(toks[k + 1], "("))
      continue;
    if (toks[k - 1]->kind != Token::Ident && !is(toks[k - 1], "*")) continue;
    size_t close = matching(toks, k + 1);
    if (close + 1 < toks.size() && (is(toks[close + 1], "{") || is(toks[close + 1], ";"))) out.push_back(k);
  }
  return out;
}

}  // namespace

namespace dialect_detail {

bool is(const Token* t, const char* s) { return t && t->text == s; }

size_t matching(const std::vector<const Token*>& toks, size_t open) {
  const std::string o = toks[open]->text, c = o == "(" ? ")" : o == "[" ? "]" : "}";
  int depth = 0;
  for (size_t k = open; k < toks.size(); ++k) {
    if (toks[k]->text == o) ++depth;
    if (toks[k]->text == c && --depth == 0) return k;
  }
  return toks.size();
}

std::vector<std::pair<size_t, size_t>> parameters(const std::vector<const Token*>& toks, size_t open, size_t close) {
  std::vector<std::pair<size_t, size_t>> out;
  size_t start = open + 1;
  int depth = 0;
  for (size_t k = open + 1; k <= close; ++k) {
    const std::string& s = toks[k]->text;
    if (s == "(" || s == "[" || s == "{") ++depth;
    if ((s == ")" || s == "]" || s == "}") && k != close) --depth;
    if ((s == "," && depth == 0) || k == close) {
      if (k > start) out.push_back({start, k});
      start = k + 1;
    }
  }
  if (out.size() == 1 && out[0].second - out[0].first == 1 && toks[out[0].first]->text == "void") out.clear();
  return out;
}

}  // namespace dialect_detail

std::string canonical_type(const std::string& t) {
  for (Dialect d : {Dialect::Glsl, Dialect::Hlsl}) {
    std::string s = scalar_or_vector(t, d);
    if (!s.empty()) return s;
  }
  return t;
}

UserNames user_names(const ReadSources& src, Dialect d) {
  UserNames n;
  if (d == Dialect::Hlsl) n.out_params.push_back({"sincos", {3, {1, 2}}});  // sincos(x, out s, out c)
  for (auto& u : src.units) {
    auto toks = code_tokens(u);
    for (size_t k : functions_at_file_scope(toks)) {
      const std::string& name = toks[k]->text;
      if (!contract_name(name)) n.functions.insert(name);
      if (d == Dialect::OpenCL) continue;
      auto ps = parameters(toks, k + 1, matching(toks, k + 1));
      std::vector<size_t> outs;
      for (size_t i = 0; i < ps.size(); ++i) {
        bool array = false;
        param_name(toks, ps[i], array);
        if (has_out(toks, ps[i]) && !array) outs.push_back(i);
      }
      if (!outs.empty()) n.out_params.push_back({name, {ps.size(), outs}});
    }
    int depth = 0;
    for (size_t k = 0; k + 1 < toks.size(); ++k) {
      if (is(toks[k], "{")) ++depth;
      if (is(toks[k], "}")) --depth;
      if (depth == 0 && is(toks[k], "struct") && toks[k + 1]->kind == Token::Ident) n.structs.insert(toks[k + 1]->text);
      if (depth == 0 && d != Dialect::OpenCL && is(toks[k], "const") &&
          (k == 0 || is(toks[k - 1], ";") || is(toks[k - 1], "}") || is(toks[k - 1], "static")))
        for (size_t j = k + 1; j + 1 < toks.size() && !is(toks[j], ";"); ++j)
          if (toks[j]->kind == Token::Ident && (is(toks[j + 1], "=") || is(toks[j + 1], "["))) {
            n.constants.insert(toks[j]->text);
            break;
          }
    }
  }
  return n;
}

std::string translate(const ReadSources& src, size_t at, Dialect d, const UserNames& names) {
  const ReadUnit& u = src.units[at];
  auto toks = code_tokens(u);
  std::vector<Edit> edits;
  auto set = [&](const Token* t, std::string s) { edits.push_back({t->begin, t->end - t->begin, std::move(s)}); };
  auto before = [&](const Token* t, std::string s) { edits.push_back({t->begin, 0, std::move(s)}); };
  auto fail = [&](const Token* t, const std::string& what) {
    return Error(fmt::format("{}:{}: {} (not supported by mfv check's {} dialect; see docs/cli/check.md)", u.path,
                             t->line, what, dialect_name(d)));
  };
  const bool shading = d != Dialect::OpenCL;
  std::set<std::string> body_outs;  // out parameters of the function whose body is being read
  std::set<size_t> done;            // tokens already rewritten
  int depth = 0;
  auto fns = functions_at_file_scope(toks);
  matrix_edits(toks, d, edits, done, [&](const Token* t, const std::string& what) { throw fail(t, what); });
  splat_edits(toks, d, edits, done);
  for (size_t k = 0; k < toks.size(); ++k) {
    const Token* t = toks[k];
    const std::string& s = t->text;
    if (s == "{") ++depth;
    if (s == "}" && --depth == 0) body_outs.clear();
    if (done.count(k)) continue;
    const Token* prev = k ? toks[k - 1] : nullptr;
    const bool member = is(prev, ".") || (is(prev, ">") && k > 1 && is(toks[k - 2], "-"));
    const bool call = k + 1 < toks.size() && is(toks[k + 1], "(");
    if (shading && t->kind == Token::Number && floating_literal(s)) {
      std::string v = s;
      std::string low = v;
      std::transform(low.begin(), low.end(), low.begin(), ::tolower);
      if (low.size() > 2 && low.compare(low.size() - 2, 2, "lf") == 0)
        v.resize(v.size() - 2);
      else if (low.back() == 'h' || low.back() == 'f' || low.back() == 'l')
        v.pop_back();
      set(t, v + "f");
      continue;
    }
    if (t->kind != Token::Ident || member) continue;
    if (names.guarded.count(s) && depth > 0 && k + 1 < toks.size() && is(toks[k + 1], "[")) {
      size_t close = matching(toks, k + 1);
      if (close < toks.size()) {
        edits.push_back({toks[k + 1]->end, 0, "MFV_PARAM_INDEX("});
        before(toks[close], ")");
      }
    }
    // a file-scope function's header: out parameters become pointers
    if (shading && std::find(fns.begin(), fns.end(), k) != fns.end()) {
      size_t close = matching(toks, k + 1);
      bool definition = close + 1 < toks.size() && is(toks[close + 1], "{");
      for (auto p : parameters(toks, k + 1, close)) {
        bool array = false;
        size_t nm = param_name(toks, p, array);
        if (!has_out(toks, p) || nm >= p.second) continue;
        if (!array) {
          before(toks[nm], "*");
          if (definition) body_outs.insert(toks[nm]->text);
        }
        for (size_t j = p.first; j < p.second; ++j)
          if (is(toks[j], "out") || is(toks[j], "inout"))
            set(toks[j], std::string(toks[j]->text.size(), ' ')), done.insert(j);
      }
      if (!contract_name(s)) set(t, kPrefix + s);
      continue;
    }
    if (body_outs.count(s) && depth > 0) {
      set(t, "(*" + s + ")");
      continue;
    }
    if (shading && call && depth > 0) {
      // a call of a user function with out parameters: those arguments by address
      const std::vector<size_t>* outs = nullptr;
      size_t close = matching(toks, k + 1);
      auto args = parameters(toks, k + 1, close);
      for (auto& [fn, sig] : names.out_params)
        if (fn == s && sig.first == args.size()) {
          if (outs && *outs != sig.second)
            throw fail(t, fmt::format("overloads of '{}' with out parameters at different places", s));
          outs = &sig.second;
        }
      if (outs)
        for (size_t i : *outs) {
          before(toks[args[i].first], "&(");
          before(toks[args[i].second], ")");
        }
    }
    if (names.structs.count(s) && call && !is(prev, "struct")) {
      // a struct's constructor: a compound literal
      size_t close = matching(toks, k + 1);
      edits.push_back({t->begin, toks[k + 1]->end - t->begin, "((" + kPrefix + s + "){"});
      set(toks[close], "})");
      done.insert(k + 1);
      continue;
    }
    if (names.structs.count(s) && is(prev, "struct") && depth == 0 && k + 1 < toks.size() && is(toks[k + 1], "{")) {
      // struct S { ... };  ->  typedef struct S { ... } S;
      size_t close = matching(toks, k + 1);
      before(prev, "typedef ");
      set(t, kPrefix + s);
      if (close + 1 < toks.size() && is(toks[close + 1], ";")) before(toks[close + 1], " " + kPrefix + s);
      continue;
    }
    if (names.functions.count(s) || names.structs.count(s) || names.constants.count(s)) {
      set(t, kPrefix + s);
      continue;
    }
    if (!shading) continue;
    if (matrix_type(s, d)) throw fail(t, fmt::format("'{}' (matrices other than 2x2, 3x3 and 4x4)", s));
    std::string sv = scalar_or_vector(s, d);
    const bool scalar = s == "float" || s == "int" || s == "uint" || s == "bool" || s == "double";
    if ((!sv.empty() || scalar || names.structs.count(s)) && k + 3 < toks.size() && is(toks[k + 1], "[") &&
        depth > 0) {
      // glsl's array constructor T[N](a, b, ...): a brace initializer
      size_t close = matching(toks, k + 1);
      if (close + 1 < toks.size() && is(toks[close + 1], "(")) {
        edits.push_back({t->begin, toks[close + 1]->end - t->begin, "{"});
        set(toks[matching(toks, close + 1)], "}");
        for (size_t j = k; j <= close + 1; ++j) done.insert(j);
        done.insert(matching(toks, close + 1));
        continue;
      }
    }
    if (!sv.empty()) {
      bool vector = std::isdigit(static_cast<unsigned char>(sv.back()));
      if (call) {
        size_t close = matching(toks, k + 1);
        if (vector && sv.rfind("float", 0) == 0) {
          set(t, "mfv_vec" + sv.substr(5));
        } else {  // scalar (or integer vector) constructor: a conversion
          edits.push_back({t->begin, toks[k + 1]->end - t->begin, "((" + sv + ")("});
          set(toks[close], "))");
          done.insert(k + 1);
        }
      } else if (sv != s) {
        set(t, sv);
      }
      continue;
    }
    if (s == "in" || s == "highp" || s == "mediump" || s == "lowp" || s == "precise" ||
        (d == Dialect::Hlsl && (s == "inline" || s == "uniform"))) {
      set(t, std::string(s.size(), ' '));
      continue;
    }
    if (s == "precision" && depth == 0) {
      for (size_t j = k; j < toks.size(); ++j) {
        set(toks[j], "");
        done.insert(j);
        if (is(toks[j], ";")) break;
      }
      continue;
    }
    if (d == Dialect::Hlsl && is(prev, "[") && k + 1 < toks.size() &&
        (s == "unroll" || s == "loop" || s == "branch" || s == "flatten" || s == "fastopt")) {
      // [unroll], [loop(n)], ...: attributes of the statement that follows
      size_t j = k + 1;
      if (is(toks[j], "(")) j = matching(toks, j) + 1;
      if (j < toks.size() && is(toks[j], "]")) {
        for (size_t i = k - 1; i <= j; ++i) set(toks[i], ""), done.insert(i);
        continue;
      }
    }
    if (s == "const" && depth == 0 && (k == 0 || is(prev, ";") || is(prev, "}") || is(prev, "static"))) {
      // a file-scope constant: a macro where it is one line, else __constant
      size_t semi = k;
      while (semi < toks.size() && !is(toks[semi], ";")) ++semi;
      size_t eq = k;
      while (eq < semi && !is(toks[eq], "=")) ++eq;
      bool one_line = semi < toks.size() && toks[semi]->line == t->line && eq < semi && eq > k + 1;
      int paren = 0;  // a comma inside a constructor's parentheses is not a second declarator
      for (size_t j = eq; j < semi && one_line; ++j) {
        paren += is(toks[j], "(") - is(toks[j], ")");
        if ((is(toks[j], ",") && paren == 0) || is(toks[j], "[")) one_line = false;
      }
      if (one_line) {
        for (size_t j = eq + 1; j < semi && one_line; ++j) one_line = toks[j]->line == t->line;
      }
      const size_t first = is(prev, "static") ? k - 1 : k;  // the statement's first token
      if (one_line && (first == 0 || toks[first - 1]->line < toks[first]->line)) {
        std::string type;
        bool matrix = false;  // no cast to a struct: the constructor's value
        for (size_t j = k + 1; j + 1 < eq; ++j) {
          if (supported_matrix(toks[j]->text, d)) {  // its type's edit gives way to this one
            matrix = true;
            edits.erase(std::remove_if(edits.begin(), edits.end(),
                                       [&](const Edit& e) { return e.at == toks[j]->begin && e.len; }),
                        edits.end());
          }
          std::string sj = scalar_or_vector(toks[j]->text, d);
          type += (type.empty() ? "" : " ") +
                  (sj.empty() ? (names.structs.count(toks[j]->text) ? kPrefix : "") + toks[j]->text : sj);
          set(toks[j], "");
          done.insert(j);
        }
        if (is(prev, "static")) set(prev, "");
        set(t, "#define");
        set(toks[eq], matrix ? "((" : "((" + type + ")(");
        set(toks[semi], "))");
        done.insert(eq);
        done.insert(semi);
        continue;
      }
      if (is(prev, "static")) set(prev, "");
      set(t, "__constant");
      continue;
    }
    auto b = builtins(d).find(s);
    if (b != builtins(d).end() && call) set(t, b->second);
  }
  // directives: those the OpenCL C compiler does not know go; a macro's body
  // (on one line) gets the literals, names, constructors and built-ins of code
  for (size_t k = 0; k < u.tokens.size() && shading; ++k) {
    const Token& t = u.tokens[k];
    if (t.kind != Token::Directive || !u.active[k]) continue;
    if (std::regex_search(t.text, std::regex("^#\\s*(version|extension)\\b"))) {
      edits.push_back({t.begin, t.end - t.begin, ""});
      continue;
    }
    std::smatch m;
    static const std::regex def("^#\\s*define\\s+[A-Za-z_][A-Za-z0-9_]*(\\([^)]*\\))?");
    // the body as written, over its line splices (token offsets into the file)
    const std::string raw = u.text.substr(t.begin, t.end - t.begin);
    if (!std::regex_search(raw, m, def)) continue;
    const size_t base = t.begin + size_t(m.length(0));
    auto body = tokenize(u.path, raw.substr(size_t(m.length(0))));
    for (size_t j = 0; j < body.size(); ++j) {
      const Token& b = body[j];
      const std::string& s = b.text;
      const bool call = j + 1 < body.size() && body[j + 1].text == "(";
      const bool member = j > 0 && body[j - 1].text == ".";
      std::string to;
      if (b.kind == Token::Number && floating_literal(s)) {
        to = s;
        while (!to.empty() && std::isalpha(static_cast<unsigned char>(to.back())) && to.back() != 'e' &&
               to.back() != 'E')
          to.pop_back();
        to += "f";
      } else if (b.kind == Token::Ident && !member) {
        std::string sv = scalar_or_vector(s, d);
        auto bi = builtins(d).find(s);
        if (names.functions.count(s) || names.structs.count(s) || names.constants.count(s))
          to = kPrefix + s;
        else if (!sv.empty() && call && sv.rfind("float", 0) == 0 && sv.size() == 6)
          to = "mfv_vec" + sv.substr(5);
        else if (!sv.empty() && call && sv.size() <= 6)
          to = "(" + sv + ")";
        else if (!sv.empty())
          to = sv;
        else if (bi != builtins(d).end() && call)
          to = bi->second;
      }
      if (!to.empty() && to != s) edits.push_back({base + b.begin, b.end - b.begin, to});
    }
  }
  // by offset; at one offset, insertions (in the order made) before the replacement
  std::stable_sort(edits.begin(), edits.end(),
                   [](const Edit& a, const Edit& b) { return a.at < b.at || (a.at == b.at && a.len == 0 && b.len); });
  std::string out;
  size_t pos = 0;
  for (auto& e : edits) {
    if (e.at < pos) continue;  // overlapping (never by construction)
    out += u.text.substr(pos, e.at - pos) + e.text;
    pos = e.at + e.len;
  }
  return out + u.text.substr(pos);
}

// PoCL's own names of the built-ins (_cl_clamp) and where its headers spell them go too.
std::string user_terms(const std::string& log) {
  static const std::regex renamed("\\bmfv_u_|\\bmfv_g_|\\b_cl_(?=[a-z])| <Spelling=[^>]*>");
  return std::regex_replace(log, renamed, "");
}

}  // namespace mfv
