// mfv check --brdf FILE.cl: the user's OpenCL C file, its functions and its
// parameters, checked against the contract (docs/cli/check.md) before
// anything is built, so that a missing function, a wrong signature or a
// missing parameter gets one line naming the cause.
#pragma once

#include "catalog/catalog.hpp"
#include "user/dialect.hpp"

#include <functional>
#include <string>
#include <vector>

namespace mfv {

struct UserParam {
  std::string name;
  double lo = 0, hi = 0, value = 0;  // range and default
  bool fixed = false;                // --param NAME=V: this value in every check
  // How the parameter sets the estimator's proposal width (the estimators
  // use the width, never the formula: docs/design.md §3): None, Alpha
  // (width = value) or Perceptual (width = value²).
  Roughness role = Roughness::None;
  // The relative index eta = eta_below / eta_above of a btdf or bsdf
  // (`eta` in its declaration, or --eta NAME): the transmission checks read
  // it (docs/cli/check.md, "Transmission: btdf and bsdf").
  bool is_eta = false;
  int line = 0;  // line of its `// mfv: param` declaration; 0 = from the command line
  // The values the checks use: the default, or the grid of a swept parameter.
  std::vector<double> ends() const;  // lo and hi (one value if fixed or lo == hi)
};

// One source the compiler reads (an --include file, then the main file),
// translated from its dialect, each params[k] read bounds-checked
// (kernels/user_guard.cl), with its #include "FILE"s in place.
struct UserSource {
  std::string name, text;
};

struct UserBrdf {
  std::string path, name;  // name: the file's stem, used as the model name
  Dialect dialect = Dialect::OpenCL;
  std::vector<UserSource> sources;  // in the order the compiler reads them, the main file last
  // Which of the contract's functions the file defines: brdf (wi, wo above),
  // btdf (wi and wo on opposite sides, radiance form), or one bsdf for both.
  bool has_brdf = false, has_btdf = false, has_bsdf = false;
  bool has_d = false, has_g1 = false;
  bool transmits() const { return has_btdf || has_bsdf; }
  // The reflection on both sides of the interface, as bsdf_furnace needs it:
  // bsdf, or brdf beside a btdf (then brdf is asked below the surface too).
  bool reflects_both_sides() const { return has_bsdf || (has_brdf && has_btdf); }
  int eta = -1;  // index of the relative index parameter (UserParam::is_eta), -1: none
  // The indices the transmission checks take: the eta parameter's range ends
  // and its default (its value alone where fixed).
  std::vector<double> eta_values() const;
  std::vector<UserParam> params;                          // params[k] of the contract
  int roughness = -1;                                     // index of the width parameter, -1: none declared
  double width(const std::vector<double>& values) const;  // proposal width at these parameter values (<= 0: mixture)
  // With --as: the claimed catalog D's proposal width (Term::proposal: a
  // sheen's grazing lobe, not the normal's) at these values; <= 0 where the
  // mapped value leaves the term's range, and the declared roughness then.
  std::function<double(const std::vector<double>&)> claimed_width;
  std::vector<double> defaults() const;
};

// At most this many parameters (IntegralSpec carries p[0..5]).
constexpr size_t kUserMaxParams = 6;

struct UserParamArgs {
  std::vector<std::string> params;    // --param NAME=V or NAME=LO:HI
  std::string roughness;              // --roughness NAME (width = value) or NAME^2 (width = value²)
  std::string eta;                    // --eta NAME: the relative index of a btdf or bsdf
  std::string dialect;                // --dialect glsl|hlsl|opencl ("": from the extension)
  std::vector<std::string> defines;   // --define NAME=VALUE (or NAME: 1)
  std::vector<std::string> includes;  // --include FILE, read before the file
};

// Reads and checks FILE against the contract; throws mfv::Error (one line,
// exit 2) on any violation.
UserBrdf load_user_brdf(const std::string& path, const UserParamArgs& args);

}  // namespace mfv
