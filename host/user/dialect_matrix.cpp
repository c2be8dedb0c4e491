// mfv check's square matrices in glsl and hlsl (TBN frames, transforms): the GLSL 4.60
// spec §5.4.2 (constructors, column-major), §5.10 (m * v, v * m, m * m) and
// §8.6 (transpose); HLSL's float3x3 (row-major constructors), mul() and
// transpose() intrinsics. kernels/user_prelude.cl's mfv_matN holds N
// vectors c[N]: glsl's columns, hlsl's rows; the constructors fill c in
// the order the arguments come in both, and the products follow from it.
#include "user/dialect_detail.hpp"

#include <fmt/format.h>

#include <regex>

namespace mfv::dialect_detail {
namespace {

bool binary_end(const Token* t) {
  return t->kind == Token::Number || (t->kind == Token::Ident && t->text != "return") || t->text == ")" ||
         t->text == "]";
}

// A token that can begin an operand (after a cast's closing parenthesis).
bool binary_start(const Token* t) {
  return t->kind == Token::Number || t->kind == Token::Ident || t->text == "(" || t->text == "-" || t->text == "+";
}

bool multiplicative(const std::vector<const Token*>& toks, size_t k) {
  const std::string& s = toks[k]->text;
  return (s == "*" || s == "/" || s == "%") && k > 0 && binary_end(toks[k - 1]) && k + 1 < toks.size() &&
         !is(toks[k + 1], "=");
}

// The index of the opening bracket of the one closed at `close`.
size_t opening(const std::vector<const Token*>& toks, size_t close) {
  const std::string c = toks[close]->text, o = c == ")" ? "(" : "[";
  int depth = 0;
  for (size_t k = close + 1; k-- > 0;) {
    if (toks[k]->text == c) ++depth;
    if (toks[k]->text == o && --depth == 0) return k;
  }
  return 0;
}

bool type_name(const Token* t, Dialect d) {
  static const std::regex glsl("(b|i|u|d)?vec[234]|float|int|uint|d?mat[234](x[234])?"),
      hlsl("(float|half|min16float|int|uint|double)([234](x[234])?)?");
  return t->kind == Token::Ident && std::regex_match(t->text, d == Dialect::Glsl ? glsl : hlsl);
}

// The first token of the unary expression (a postfix chain after any
// prefix operators and casts) that ends at `end`.
size_t operand_start(const std::vector<const Token*>& toks, size_t end, Dialect d) {
  size_t j = end;
  for (;;) {
    if (is(toks[j], ")") || is(toks[j], "]")) {
      j = opening(toks, j);
      if (j > 0 && (toks[j - 1]->kind == Token::Ident || is(toks[j - 1], "]") || is(toks[j - 1], ")")) &&
          !is(toks[j - 1], "return")) {
        --j;
        continue;  // a call or an index: its callee or indexed expression
      }
    }
    if (j > 1 && is(toks[j - 1], ".")) {
      j -= 2;
      continue;
    }
    break;
  }
  for (;;) {
    if (j > 2 && is(toks[j - 1], ")") && is(toks[j - 3], "(") && type_name(toks[j - 2], d)) {
      j -= 3;  // a cast
    } else if (j > 0 && (is(toks[j - 1], "-") || is(toks[j - 1], "+") || is(toks[j - 1], "!")) &&
               (j == 1 || !binary_end(toks[j - 2]))) {
      j -= 1;  // a prefix operator
    } else {
      return j;
    }
  }
}

// The last token of the unary expression that starts at `begin`.
size_t operand_end(const std::vector<const Token*>& toks, size_t begin, Dialect d) {
  size_t j = begin;
  while (j < toks.size() && (is(toks[j], "-") || is(toks[j], "+") || is(toks[j], "!"))) ++j;
  while (j + 3 < toks.size() && is(toks[j], "(") && type_name(toks[j + 1], d) && is(toks[j + 2], ")")) j += 3;
  if (j >= toks.size()) return toks.size() - 1;
  if (is(toks[j], "(")) j = matching(toks, j);
  for (;;) {
    if (j + 1 >= toks.size()) return j;
    const Token* n = toks[j + 1];
    if (is(n, "(") || is(n, "["))
      j = matching(toks, j + 1);
    else if (is(n, ".") && j + 2 < toks.size())
      j += 2;
    else
      return j;
    if (j >= toks.size()) return toks.size() - 1;
  }
}

}  // namespace

int supported_matrix(const std::string& n, Dialect d) {
  static const std::regex glsl("mat([234])(x([234]))?"), hlsl("(float|half|min16float)([234])x([234])");
  std::smatch m;
  if (d == Dialect::Glsl && std::regex_match(n, m, glsl) && (!m[3].matched || m.str(1) == m.str(3)))
    return std::stoi(m.str(1));
  if (d == Dialect::Hlsl && std::regex_match(n, m, hlsl) && m.str(2) == m.str(3)) return std::stoi(m.str(2));
  return 0;
}

void matrix_edits(const std::vector<const Token*>& toks, Dialect d, std::vector<Edit>& edits, std::set<size_t>& done,
                  const std::function<void(const Token*, const std::string&)>& refuse) {
  if (d == Dialect::OpenCL) return;
  // The names of matrices: variables, members, parameters and functions declared with a matrix type.
  std::set<std::string> names;
  bool any = false;
  for (size_t k = 0; k + 1 < toks.size(); ++k)
    if (supported_matrix(toks[k]->text, d)) {
      any = true;
      if (toks[k + 1]->kind == Token::Ident) names.insert(toks[k + 1]->text);
    }
  if (!any) return;
  auto matrix_in = [&](size_t a, size_t b) {
    for (size_t j = a; j <= b; ++j)
      if (supported_matrix(toks[j]->text, d) || names.count(toks[j]->text) || is(toks[j], "transpose") ||
          is(toks[j], "mul"))
        return true;
    return false;
  };
  for (size_t k = 0; k < toks.size(); ++k) {
    const Token* t = toks[k];
    const bool call = k + 1 < toks.size() && is(toks[k + 1], "(");
    const bool member = k > 0 && is(toks[k - 1], ".");
    if (int n = supported_matrix(t->text, d); n && k > 0 && is(toks[k - 1], "(") && k + 2 < toks.size() &&
                                                is(toks[k + 1], ")") && binary_start(toks[k + 2])) {
      // hlsl's cast (float3x3)M: the constructor of M, which truncates to the upper-left part
      edits.push_back({toks[k - 1]->begin, toks[k + 1]->end - toks[k - 1]->begin, fmt::format("mfv_mat{}_make(", n)});
      edits.push_back({toks[operand_end(toks, k + 2, d)]->end, 0, ")"});
      done.insert(k - 1), done.insert(k), done.insert(k + 1);
    } else if (int n = supported_matrix(t->text, d)) {
      edits.push_back({t->begin, t->end - t->begin, fmt::format(call ? "mfv_mat{}_make" : "mfv_mat{}", n)});
      done.insert(k);
    } else if (call && !member && (is(t, "transpose") || (d == Dialect::Hlsl && is(t, "mul")))) {
      edits.push_back({t->begin, t->end - t->begin, is(t, "mul") ? "mfv_hmul" : "mfv_transpose"});
      done.insert(k);
    } else if (names.count(t->text) && k + 1 < toks.size() && is(toks[k + 1], "[") && !call) {
      edits.push_back({t->end, 0, ".c"});  // a column (glsl) or row (hlsl)
    }
  }
  // `*` chains with a matrix operand: left to right, each product a call of mfv_mul
  std::set<size_t> seen;
  for (size_t k = 1; k + 1 < toks.size(); ++k) {
    if (is(toks[k], "*") && is(toks[k + 1], "=") && k + 2 < toks.size() &&
        (matrix_in(operand_start(toks, k - 1, d), k - 1) || matrix_in(k + 2, operand_end(toks, k + 2, d))))
      refuse(toks[k], "'*=' with a matrix (write m = m * x)");
    if (!multiplicative(toks, k) || seen.count(k)) continue;
    size_t start = operand_start(toks, k - 1, d);
    while (start > 1 && multiplicative(toks, start - 1)) start = operand_start(toks, start - 2, d);
    std::vector<size_t> ops, ends;
    size_t end = operand_end(toks, start, d);
    ends.push_back(end);
    while (end + 1 < toks.size() && multiplicative(toks, end + 1)) {
      ops.push_back(end + 1);
      seen.insert(end + 1);
      end = operand_end(toks, end + 2, d);
      ends.push_back(end);
    }
    if (ops.empty() || !matrix_in(start, end)) continue;
    if (d == Dialect::Hlsl) {
      // refused where an operand is itself a matrix (a name, a constructor, a transpose)
      for (size_t i = 0; i < ends.size(); ++i) {
        size_t a = i ? ops[i - 1] + 1 : start, b = ends[i];
        while (a < b && (is(toks[a], "-") || is(toks[a], "+"))) ++a;
        if (supported_matrix(toks[a]->text, d) || is(toks[a], "transpose") ||
            (names.count(toks[b]->text) && (a == b || is(toks[b - 1], "."))))
          refuse(toks[a], "'*' with a matrix (componentwise in HLSL: write mul(a, b))");
      }
      continue;
    }
    std::string open;
    for (size_t i = ops.size(); i-- > 0;) open += is(toks[ops[i]], "*") ? "mfv_mul(" : "(";
    edits.push_back({toks[start]->begin, 0, open});
    for (size_t i = 0; i < ops.size(); ++i) {
      if (is(toks[ops[i]], "*")) {
        edits.push_back({toks[ops[i]]->begin, 1, ","});
        done.insert(ops[i]);
      }
      edits.push_back({toks[ends[i + 1]]->end, 0, ")"});
    }
  }
}

void splat_edits(const std::vector<const Token*>& toks, Dialect d, std::vector<Edit>& edits, std::set<size_t>& done) {
  if (d == Dialect::OpenCL) return;
  static const std::regex repeated("x{2,4}|r{2,4}");
  for (size_t k = 2; k < toks.size(); ++k) {
    if (!is(toks[k - 1], ".") || toks[k]->kind != Token::Ident || !std::regex_match(toks[k]->text, repeated)) continue;
    if (toks[k - 2]->kind == Token::Number) continue;  // 1.xx is no swizzle
    size_t start = operand_start(toks, k - 2, d);
    edits.push_back({toks[start]->begin, 0, fmt::format("mfv_splat{}(", toks[k]->text.size())});
    edits.push_back({toks[k - 1]->begin, toks[k]->end - toks[k - 1]->begin, ")"});
    done.insert(k - 1), done.insert(k);
  }
}

}  // namespace mfv::dialect_detail
