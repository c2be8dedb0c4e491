#include "user/source_reader.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

namespace mfv {

int line_of(const std::string& t, size_t pos) {
  return 1 + int(std::count(t.begin(), t.begin() + long(std::min(pos, t.size())), '\n'));
}

namespace {

bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// A cursor over the text that steps over line splices (backslash-newline).
struct Cursor {
  const std::string& t;
  size_t i = 0;
  int line = 1;
  void skip_splices() {
    while (i + 1 < t.size() && t[i] == '\\' &&
           (t[i + 1] == '\n' || (t[i + 1] == '\r' && i + 2 < t.size() && t[i + 2] == '\n'))) {
      i += t[i + 1] == '\n' ? 2 : 3;
      ++line;
    }
  }
  bool done() {
    skip_splices();
    return i >= t.size();
  }
  char peek(size_t k = 0) {
    skip_splices();
    size_t j = i;
    for (size_t n = 0; n < k; ++n) {
      ++j;
      while (j + 1 < t.size() && t[j] == '\\' && t[j + 1] == '\n') j += 2;
    }
    return j < t.size() ? t[j] : '\0';
  }
  char get() {
    skip_splices();
    char c = t[i++];
    if (c == '\n') ++line;
    return c;
  }
};

}  // namespace

std::vector<Token> tokenize(const std::string& path, const std::string& text) {
  std::vector<Token> out;
  Cursor c{text};
  bool line_start = true;  // only whitespace since the last newline: a '#' starts a directive
  while (!c.done()) {
    char ch = c.peek();
    if (ch == '\n') {
      c.get();
      line_start = true;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(ch))) {
      c.get();
      continue;
    }
    Token tok{Token::Punct, c.i, c.i, c.line, ""};
    auto take = [&] { tok.text += c.get(); };
    if (ch == '/' && c.peek(1) == '/') {
      tok.kind = Token::LineComment;
      while (!c.done() && c.peek() != '\n') take();
    } else if (ch == '/' && c.peek(1) == '*') {
      tok.kind = Token::BlockComment;
      take(), take();
      for (;;) {
        if (c.done())
          throw Error(
              fmt::format("{}:{}: this /* comment never ends (no */ before the end of the file)", path, tok.line));
        if (c.peek() == '*' && c.peek(1) == '/') {
          take(), take();
          break;
        }
        take();
      }
    } else if (ch == '#' && line_start) {
      // the whole directive, to the end of its (spliced) line; comments in it are blanked
      tok.kind = Token::Directive;
      while (!c.done() && c.peek() != '\n') {
        if (c.peek() == '/' && c.peek(1) == '*') {
          int l = c.line;
          c.get(), c.get();
          while (!c.done() && !(c.peek() == '*' && c.peek(1) == '/')) c.get();
          if (c.done()) throw Error(fmt::format("{}:{}: this /* comment never ends", path, l));
          c.get(), c.get();
          tok.text += ' ';
        } else if (c.peek() == '/' && c.peek(1) == '/') {
          while (!c.done() && c.peek() != '\n') c.get();
        } else {
          take();
        }
      }
    } else if (ch == '"' || ch == '\'') {
      tok.kind = ch == '"' ? Token::String : Token::Char;
      take();
      for (;;) {
        if (c.done() || c.peek() == '\n')
          throw Error(fmt::format("{}:{}: this {} literal never ends on its line", path, tok.line,
                                  ch == '"' ? "string" : "character"));
        char d = c.peek();
        take();
        if (d == '\\' && !c.done())
          take();
        else if (d == ch)
          break;
      }
    } else if (ident_start(ch)) {
      tok.kind = Token::Ident;
      while (!c.done() && ident_char(c.peek())) take();
    } else if (std::isdigit(static_cast<unsigned char>(ch)) ||
               (ch == '.' && std::isdigit(static_cast<unsigned char>(c.peek(1))))) {
      // a preprocessing number: digits, letters, '.', and a sign after an exponent letter
      tok.kind = Token::Number;
      while (!c.done()) {
        char d = c.peek();
        if (ident_char(d) || d == '.') {
          take();
        } else if ((d == '+' || d == '-') && !tok.text.empty() &&
                   std::string("eEpP").find(tok.text.back()) != std::string::npos) {
          take();
        } else {
          break;
        }
      }
    } else {
      take();
    }
    line_start = tok.kind == Token::BlockComment && line_start && tok.text.find('\n') == std::string::npos;
    tok.end = c.i;
    out.push_back(tok);
  }
  return out;
}

namespace {

// ---- #if expressions ---------------------------------------------------------

struct Macro {
  bool function_like = false;
  std::string body;
};
using Macros = std::map<std::string, Macro>;

// Integer constant expressions of #if/#elif, after `defined` and macro expansion.
class CondEval {
 public:
  CondEval(std::vector<std::string> toks, std::string where) : t_(std::move(toks)), where_(std::move(where)) {}
  long long run() {
    long long v = ternary();
    if (k_ != t_.size()) fail(fmt::format("unexpected '{}'", t_[k_]));
    return v;
  }

 private:
  std::vector<std::string> t_;
  std::string where_;
  size_t k_ = 0;
  [[noreturn]] void fail(const std::string& why) { throw Error(fmt::format("{}: #if: {}", where_, why)); }
  bool eat(const char* s) {
    if (k_ < t_.size() && t_[k_] == s) return ++k_, true;
    return false;
  }
  long long ternary() {
    long long c = binary(0);
    if (!eat("?")) return c;
    long long a = ternary();
    if (!eat(":")) fail("'?' without ':'");
    long long b = ternary();
    return c ? a : b;
  }
  long long binary(int level) {
    static const std::vector<std::vector<std::string>> ops = {
        {"||"},       {"&&"},     {"|"},          {"^"}, {"&"}, {"==", "!="}, {"<", ">", "<=", ">="},
        {"<<", ">>"}, {"+", "-"}, {"*", "/", "%"}};
    if (level == int(ops.size())) return unary();
    long long v = binary(level + 1);
    for (;;) {
      std::string op;
      for (auto& o : ops[size_t(level)])
        if (k_ < t_.size() && t_[k_] == o) op = o;
      if (op.empty()) return v;
      ++k_;
      long long r = binary(level + 1);
      if ((op == "/" || op == "%") && r == 0) fail("division by zero");
      v = op == "||"   ? (v || r)
          : op == "&&" ? (v && r)
          : op == "|"  ? (v | r)
          : op == "^"  ? (v ^ r)
          : op == "&"  ? (v & r)
          : op == "==" ? (v == r)
          : op == "!=" ? (v != r)
          : op == "<"  ? (v < r)
          : op == ">"  ? (v > r)
          : op == "<=" ? (v <= r)
          : op == ">=" ? (v >= r)
          : op == "<<" ? (v << r)
          : op == ">>" ? (v >> r)
          : op == "+"  ? (v + r)
          : op == "-"  ? (v - r)
          : op == "*"  ? (v * r)
          : op == "/"  ? (v / r)
                       : (v % r);
    }
  }
  long long unary() {
    if (eat("!")) return !unary();
    if (eat("-")) return -unary();
    if (eat("+")) return unary();
    if (eat("~")) return ~unary();
    if (eat("(")) {
      long long v = ternary();
      if (!eat(")")) fail("missing ')'");
      return v;
    }
    if (k_ >= t_.size()) fail("the expression ends early");
    std::string n = t_[k_++];
    if (!std::isdigit(static_cast<unsigned char>(n[0]))) fail(fmt::format("'{}' is not an integer", n));
    while (!n.empty() && std::string("uUlL").find(n.back()) != std::string::npos) n.pop_back();
    try {
      size_t used = 0;
      long long v = std::stoll(n, &used, 0);
      if (used != n.size()) throw std::invalid_argument(n);
      return v;
    } catch (const std::exception&) {
      fail(fmt::format("'{}' is not an integer", n));
    }
  }
};

// Splits a directive's operand text into preprocessor tokens (identifiers,
// numbers, two-character operators, single characters).
std::vector<std::string> pp_tokens(const std::string& s) {
  std::vector<std::string> out;
  for (size_t i = 0; i < s.size();) {
    char c = s[i];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (ident_char(c)) {
      size_t j = i;
      while (j < s.size() && (ident_char(s[j]) || (std::isdigit(static_cast<unsigned char>(s[i])) && s[j] == '.'))) ++j;
      out.push_back(s.substr(i, j - i));
      i = j;
    } else {
      static const char* two[] = {"||", "&&", "==", "!=", "<=", ">=", "<<", ">>"};
      std::string t(1, c);
      for (const char* o : two)
        if (s.compare(i, 2, o) == 0) t = o;
      out.push_back(t);
      i += t.size();
    }
  }
  return out;
}

// `defined NAME`, `defined(NAME)` and macros expanded; a name left over is
// not defined: an error, as the compiler's -Werror=undef.
std::vector<std::string> expand(const std::vector<std::string>& in, const Macros& m, const std::string& where,
                                std::set<std::string>& busy) {
  std::vector<std::string> out;
  for (size_t k = 0; k < in.size(); ++k) {
    const std::string& t = in[k];
    if (t == "defined") {
      bool paren = k + 1 < in.size() && in[k + 1] == "(";
      size_t at = k + (paren ? 2 : 1);
      if (at >= in.size() || !ident_start(in[at][0]))
        throw Error(fmt::format("{}: #if: 'defined' needs a name", where));
      out.push_back(m.count(in[at]) ? "1" : "0");
      k = at + (paren ? 1 : 0);
      continue;
    }
    if (!ident_start(t[0])) {
      out.push_back(t);
      continue;
    }
    auto it = m.find(t);
    if (it == m.end() || busy.count(t))
      throw Error(
          fmt::format("{}: #if reads '{}', which is not defined (an error, as with -Werror=undef: define it "
                      "in the file or with --define {}=VALUE)",
                      where, t, t));
    if (it->second.function_like)
      throw Error(fmt::format("{}: #if calls the function-like macro '{}', which mfv check's reader does not expand",
                              where, t));
    busy.insert(t);
    auto sub = expand(pp_tokens(it->second.body), m, where, busy);
    busy.erase(t);
    if (sub.empty()) throw Error(fmt::format("{}: #if: '{}' is defined empty", where, t));
    out.push_back("(");
    out.insert(out.end(), sub.begin(), sub.end());
    out.push_back(")");
  }
  return out;
}

// ---- reading files -------------------------------------------------------------

struct Reader {
  Macros macros;
  std::vector<ReadUnit> units;
  std::vector<std::string> stack;  // files being read (an include cycle is an error)

  size_t read(const std::string& path, const std::string& from) {
    std::ifstream in(path);
    if (!in || std::filesystem::is_directory(path))
      throw Error(from.empty() ? fmt::format("--brdf {}: cannot read that file", path)
                               : fmt::format("{}: cannot read {}", from, path));
    if (std::find(stack.begin(), stack.end(), path) != stack.end())
      throw Error(fmt::format("{}: #include \"{}\" includes itself (a cycle)", from, path));
    if (stack.size() > 32) throw Error(fmt::format("{}: #include nested deeper than 32 files", from));
    std::stringstream ss;
    ss << in.rdbuf();
    size_t at = units.size();
    units.push_back({});
    units[at].path = path;
    units[at].text = ss.str();
    stack.push_back(path);
    scan(at);
    stack.pop_back();
    return at;
  }

  void scan(size_t at) {
    const std::string path = units[at].path, text = units[at].text;
    std::vector<Token> toks = tokenize(path, text);
    std::string code = text;
    auto blank = [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i)
        if (code[i] != '\n') code[i] = ' ';
    };
    struct Cond {
      bool parent_active, active, taken, seen_else;
      int line;
    };
    std::vector<Cond> conds;
    auto active = [&] { return conds.empty() || conds.back().active; };
    std::vector<bool> act(toks.size(), false);
    std::vector<std::pair<int, std::string>> mfv_lines, includes;
    for (size_t k = 0; k < toks.size(); ++k) {
      const Token& t = toks[k];
      const std::string where = fmt::format("{}:{}", path, t.line);
      if (t.kind != Token::Directive) {
        act[k] = active();
        if (!act[k] || t.kind == Token::LineComment || t.kind == Token::BlockComment) {
          blank(t.begin, t.end);
        } else if (t.kind == Token::String || t.kind == Token::Char) {
          blank(t.begin + 1, t.end - 1);  // the quotes stay: a literal is still one expression
        }
        if (act[k] && t.kind == Token::LineComment) {
          size_t p = 2;
          while (p < t.text.size() && std::isspace(static_cast<unsigned char>(t.text[p]))) ++p;
          if (t.text.compare(p, 4, "mfv:") == 0) {
            std::string body = t.text.substr(p + 4);
            body.erase(0, body.find_first_not_of(" \t"));
            body.erase(body.find_last_not_of(" \t\r") + 1);
            mfv_lines.push_back({t.line, body});
          }
        }
        continue;
      }
      blank(t.begin, t.end);
      act[k] = active();
      std::string d = t.text.substr(1);
      d.erase(0, d.find_first_not_of(" \t"));
      size_t e = 0;
      while (e < d.size() && ident_char(d[e])) ++e;
      const std::string name = d.substr(0, e);
      std::string rest = d.substr(e);
      rest.erase(0, rest.find_first_not_of(" \t"));
      rest.erase(rest.find_last_not_of(" \t\r") + 1);
      auto eval = [&] {
        std::set<std::string> busy;
        return CondEval(expand(pp_tokens(rest), macros, where, busy), where).run() != 0;
      };
      auto first_name = [&] {
        auto p = pp_tokens(rest);
        if (p.empty() || !ident_start(p[0][0])) throw Error(fmt::format("{}: #{} needs a name", where, name));
        return p[0];
      };
      if (name == "if" || name == "ifdef" || name == "ifndef") {
        bool parent = active();
        bool v = parent && (name == "if"      ? eval()
                            : name == "ifdef" ? macros.count(first_name()) > 0
                                              : macros.count(first_name()) == 0);
        conds.push_back({parent, v, v, false, t.line});
      } else if (name == "elif" || name == "else") {
        if (conds.empty() || conds.back().seen_else)
          throw Error(fmt::format("{}: #{} without a matching #if", where, name));
        Cond& c = conds.back();
        bool v = c.parent_active && !c.taken && (name == "else" || eval());
        c.active = v;
        c.taken = c.taken || v;
        c.seen_else = name == "else";
      } else if (name == "endif") {
        if (conds.empty()) throw Error(fmt::format("{}: #endif without a matching #if", where));
        conds.pop_back();
      } else if (!active()) {
        continue;
      } else if (name == "define") {
        size_t n = 0;
        while (n < rest.size() && ident_char(rest[n])) ++n;
        if (n == 0) throw Error(fmt::format("{}: #define needs a name", where));
        Macro m;
        m.function_like = n < rest.size() && rest[n] == '(';
        m.body = rest.substr(n);
        if (m.function_like) m.body = m.body.substr(std::min(m.body.size(), m.body.find(')') + 1));
        macros[rest.substr(0, n)] = m;
      } else if (name == "undef") {
        macros.erase(first_name());
      } else if (name == "include") {
        if (rest.size() < 2 || rest[0] != '"' || rest.find('"', 1) == std::string::npos)
          throw Error(
              fmt::format("{}: #include {}: mfv check reads #include \"FILE\" (relative to this file); give "
                          "other files with --include FILE",
                          where, rest));
        std::string f = rest.substr(1, rest.find('"', 1) - 1);
        std::filesystem::path p = std::filesystem::path(path).parent_path() / f;
        includes.push_back({t.line, p.lexically_normal().string()});
        read(includes.back().second, where);
      }
    }
    if (!conds.empty())
      throw Error(fmt::format("{}:{}: this #if has no #endif before the end of the file", path, conds.back().line));
    ReadUnit& u = units[at];
    u.code = code;
    u.tokens = std::move(toks);
    u.active = std::move(act);
    u.mfv_lines = std::move(mfv_lines);
    u.includes = std::move(includes);
  }
};

}  // namespace

ReadSources read_sources(const std::string& path, const ReadOptions& opt) {
  Reader r;
  for (auto& [name, value] : opt.defines) r.macros[name] = {false, value};
  ReadSources out;
  for (auto& inc : opt.includes) out.top.push_back(r.read(inc, "--include"));
  out.top.push_back(r.read(path, ""));
  out.units = std::move(r.units);
  return out;
}

std::string with_includes(const std::vector<ReadUnit>& units, const std::vector<std::string>& texts, size_t at) {
  const ReadUnit& u = units[at];
  if (u.includes.empty()) return texts[at];
  std::istringstream in(texts[at]);
  std::string out;
  int n = 0;
  size_t next = at + 1;  // included units follow their includer in reading order
  std::set<size_t> used;
  for (std::string line; std::getline(in, line);) {
    ++n;
    bool inc = false;
    for (auto& [l, p] : u.includes)
      if (l == n) {
        // the unit read for this include: the next one with that path not yet used
        size_t k = next;
        while (k < units.size() && (units[k].path != p || used.count(k))) ++k;
        if (k == units.size()) break;
        used.insert(k);
        out += fmt::format("#line 1 \"{}\"\n{}\n#line {} \"{}\"\n", p, with_includes(units, texts, k), n + 1, u.path);
        inc = true;
      }
    if (!inc) out += line + "\n";
  }
  return out;
}

}  // namespace mfv
