// mfv check --dialect glsl|hlsl|opencl: a shading file compiled as it is.
// The user's files are translated token by token, line for line (so build
// logs keep their lines), and compiled after kernels/user_prelude.cl, whose
// types, constructors and built-ins are the dialect's:
//  - every function, struct and file-scope constant the files define is
//    renamed mfv_u_NAME (brdf, D and G1 excepted), so no name of the file
//    clashes with the suite's (saturate, sqr, ...) or the OpenCL built-ins;
//  - glsl/hlsl: vecN/floatN types and constructors, unsuffixed literals in
//    float, `in`/`out`/`inout` parameters (out ones passed by pointer),
//    structs as bare type names and their constructors, file-scope
//    constants, precision qualifiers, the built-ins that OpenCL C lacks or
//    names otherwise (mix/lerp, fract/frac, inversesqrt, two-argument atan,
//    mod, saturate, abs on floats, ...).
// docs/cli/check.md lists what each dialect covers and what it refuses.
#pragma once

#include "user/source_reader.hpp"

#include <set>
#include <string>
#include <vector>

namespace mfv {

enum class Dialect { OpenCL = 0, Glsl = 1, Hlsl = 2 };

const char* dialect_name(Dialect d);
// --dialect NAME, or from the file's extension (.glsl .frag .fs .vert .comp
// -> glsl; .hlsl .fx .hlsli -> hlsl; anything else opencl); throws on an
// unknown name.
Dialect dialect_of(const std::string& name, const std::string& path);

// The contract's type names in the dialect's spelling, as float3 etc.
std::string canonical_type(const std::string& type);

// The names the user's files define at file scope (renamed mfv_u_NAME).
struct UserNames {
  std::set<std::string> functions, structs, constants;
  // Functions with out/inout parameters: name -> (arity, out positions).
  std::vector<std::pair<std::string, std::pair<size_t, std::vector<size_t>>>> out_params;
  // The contract functions' params arguments: every NAME[k] read becomes
  // NAME[MFV_PARAM_INDEX(k)], bounds-checked (kernels/user_guard.cl).
  std::set<std::string> guarded;
};
UserNames user_names(const ReadSources& src, Dialect d);

// The text of unit `at` as the compiler reads it, line for line. Throws
// mfv::Error naming the file, line and construct the dialect refuses.
std::string translate(const ReadSources& src, size_t at, Dialect d, const UserNames& names);

// A decimal floating literal (1.0, 2e-3, .5f; not a hex float or an integer).
bool floating_literal(const std::string& t);

// A build log with the renamings undone (mfv_u_NAME -> NAME).
std::string user_terms(const std::string& log);

}  // namespace mfv
