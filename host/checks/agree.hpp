// Pointwise agreement (issue 2, part 5): every term and every D x G x F BRDF
// evaluated by the kernel and by the double reference on identical inputs.
#pragma once

#include "runtime/opencl.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mfv {

struct AgreeOptions {
  uint64_t seed = 1;
  uint64_t samples = 1000000;  // per case
  bool fp64 = false;           // run the kernel in double (needs cl_khr_fp64)
  bool combinations = true;    // all D x G x F BRDFs, besides the single terms
  std::vector<std::string> only;  // restrict to cases whose name contains one of these
};

struct AgreeResult {
  std::string name;  // "D ggx", "G1 smith_ggx", "BRDF ggx/smith_ggx/schlick"
  uint64_t samples = 0;
  double max_rel = 0, median_rel = 0, max_ulps = 0;
  double ulp_budget = 0;
  uint64_t failures = 0;  // samples beyond budget and conditioning allowance
  std::string worst;      // worst failing (else worst overall) input, hex-float
  bool pass() const { return failures == 0; }
};

struct AgreeReport {
  std::vector<AgreeResult> results;
  double kernel_seconds = 0, reference_seconds = 0, build_seconds = 0;
  uint64_t samples = 0;
};

AgreeReport run_agree(Runtime& rt, const AgreeOptions& opt);

// One point evaluated by the kernel and the reference (mfv eval). A record
// holds the inputs as kernels/agree.cl lays them out: for a BRDF wi.xyz,
// wo.xyz; for a term NoL, NoV, NoH, VoH; then D param, G param, F p0, F p1, kd.
// A whole model (Model) takes wi.xyz, wo.xyz and its p[0..6] in params.
struct Term;
struct Model;
// = AGREE_* of kernels/agree.cl; the *Aniso modes take an anisotropic term's
// directions (D: h in inputs [4], [5], [2]; G1: v in [4], [5], [1]) and its
// alpha_y in params[6].
enum class EvalMode { D = 0, G = 1, F = 2, G1 = 3, Brdf = 4, Model = 5, DAniso = 6, G1Aniso = 7, BrdfAniso = 8 };
struct PointSpec {
  EvalMode mode = EvalMode::Brdf;
  const Term* d = nullptr;
  const Term* g = nullptr;
  const Term* f = nullptr;
  const Model* model = nullptr;
  float inputs[6] = {0, 0, 1, 0, 0, 1};
  float params[7] = {0, 0, 0, 0, 0, 0, 0};  // [6]: a whole model's p[6] (record slot 14)
};
struct PointResult {
  double kernel = 0, reference = 0, rel = 0, ulps = 0;
};
PointResult eval_point(Runtime& rt, const PointSpec& p, bool fp64);

// ULP of a float (or double) at |x|: the spacing of the format just above |x|.
double ulp_of(double x, bool fp64);

}  // namespace mfv
