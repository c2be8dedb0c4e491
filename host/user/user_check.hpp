// mfv check --brdf FILE.cl: the conformance checks of mfv run on a user's
// BRDF (furnace, energy, reciprocity, the NaN/Inf census over the stability
// sweep's extreme directions, d_norm and masking when D and G1 are given,
// pointwise agreement with a claimed catalog model), with the same
// verdicts, reports and exit codes.
#pragma once

#include "checks/suite.hpp"
#include "user/claim.hpp"
#include "user/user_brdf.hpp"

#include <optional>
#include <string>
#include <vector>

namespace mfv {

struct UserCheckOptions {
  uint64_t seed = 1;
  double scale = 1.0;
  double family_alpha = 1e-6;
  std::vector<std::string> checks;  // empty: every check the file supports
  std::vector<int> channels = {0, 1, 2};
};

const std::vector<std::string>& user_checks();  // the registry's kinds with kSourceUser: d_norm ... agree, finite

// Relative error beyond input conditioning above which a user BRDF does not
// implement its claimed model (float code measures ~1e-6; see docs/cli/check.md).
constexpr double kAgreeBound = 1e-4;
// Reciprocity of user code: float code that forms v.h as dot(wo, h) (the
// common form) on directions unit only to 1e-7 is asymmetric by ~1e-3 at
// grazing mirror pairs (measured 1.08e-3), where |wi + wo| is small; a BRDF
// asymmetric by formula (F at n.v) measures 1. The catalog's kernels, which
// form v.h as |wi + wo|/2, are held to kReciprocityBound (1e-4).
constexpr double kUserReciprocityBound = 1e-2;

// The least time limit of a step of mfv check (user/time_limit.hpp): a BRDF
// that never returns is stopped after between this and twice this.
constexpr double kMinStepSeconds = 30;

// Throws mfv::Error (exit 2) for a check the file cannot run or a build failure.
SuiteReport run_user_check(Runtime& rt, const UserBrdf& u, const std::optional<Claim>& claim,
                           const UserCheckOptions& opt);

// The SuiteOptions the shared report writers read (seed, scale, checks).
SuiteOptions suite_options_of(const UserCheckOptions& opt);

}  // namespace mfv
