// The token-level pieces host/user/dialect.cpp and dialect_matrix.cpp share:
// edits of a unit's text (by offsets into it) and bracket walking over its
// code tokens.
#pragma once

#include "user/dialect.hpp"

#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace mfv::dialect_detail {

// Replace [at, at + len) by text; len 0 inserts (before any replacement at `at`).
struct Edit {
  size_t at, len;
  std::string text;
};

bool is(const Token* t, const char* s);
// Index of the token closing the bracket opened at `open`, or toks.size().
size_t matching(const std::vector<const Token*>& toks, size_t open);
// The parameters (or arguments) of the list opened at `open`: [first, last) token ranges.
std::vector<std::pair<size_t, size_t>> parameters(const std::vector<const Token*>& toks, size_t open, size_t close);

// The square matrices of glsl (mat2..mat4) and hlsl (float2x2..float4x4):
// their types, constructors, transpose, column (glsl) or row (hlsl)
// indexing, glsl's `*` products and hlsl's mul(), as calls of
// kernels/user_prelude.cl's mfv_matN functions. Appends the edits and marks the tokens it rewrote in `done`;
// `refuse(token, what)` throws the error for a construct it does not cover.
void matrix_edits(const std::vector<const Token*>& toks, Dialect d, std::vector<Edit>& edits, std::set<size_t>& done,
                  const std::function<void(const Token*, const std::string&)>& refuse);

// Swizzles that repeat one component (x.xxx, v.rr): mfv_splatN(x), a
// scalar's splat or a vector's first component's, as both languages read
// them (OpenCL C has no swizzles of a scalar). After matrix_edits.
void splat_edits(const std::vector<const Token*>& toks, Dialect d, std::vector<Edit>& edits, std::set<size_t>& done);

// glsl matN/matNxN, hlsl floatNxN (and half/min16float), N = 2, 3, 4: the
// matrices mfv covers; their size N, or 0 for any other name.
int supported_matrix(const std::string& name, Dialect d);

}  // namespace mfv::dialect_detail
