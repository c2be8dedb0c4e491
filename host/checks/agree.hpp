// Pointwise agreement (issue 2, part 5): every term and every D x G x F BRDF
// evaluated by the kernel and by the double reference on identical inputs.
#pragma once

#include "abi/pointwise.h"
#include "checks/unit_plan.hpp"
#include "runtime/opencl.hpp"

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace mfv {

struct AgreeOptions {
  uint64_t seed = 1;
  uint64_t samples = 1000000;     // per case
  bool fp64 = false;              // run the kernel in double (needs cl_khr_fp64)
  bool combinations = true;       // all D x G x F BRDFs, besides the single terms
  std::vector<std::string> only;  // restrict to cases whose name contains one of these
  bool only_may_match_none = false;  // mfv run --model: `only` matching no case leaves none (else an error)
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
  std::vector<std::string> shards;  // mfv agree --merge: one line per shard (index, file, variable, device)
};

// Cases [part.first, part.second) of the whole plan's (mfv agree --shard,
// docs/scale.md): each case's inputs come from its own Philox stream, keyed
// by its name, so a shard's cases are the whole run's, value for value.
AgreeReport run_agree(Runtime& rt, const AgreeOptions& opt,
                      std::pair<size_t, size_t> part = {0, std::numeric_limits<size_t>::max()});
// The whole plan's cases as units, each costing its samples (one launch
// and reference pass per input), and a digest of the cases, their streams,
// samples and precision.
UnitPlan agree_plan(const AgreeOptions& opt);

// One point evaluated by the kernel and the reference (mfv eval), through
// the records of mfv agree (kernels/abi/pointwise.h): for a BRDF or a whole
// model `inputs` are wi.xyz, wo.xyz; for a term NoL, NoV, NoH, VoH (the
// anisotropic modes: h.x|v.x, h.y|v.y in [4], [5]); `params` are p[0..6]
// (D param, G param, F p0, F p1, kd, p5, and p6: a whole model's p[6], the
// anisotropic modes' alpha_y).
struct Term;
struct Model;
struct Bsdf;
// = PW_* of kernels/abi/pointwise.h
enum class EvalMode {
  D = pw::PW_D,
  G = pw::PW_G,
  F = pw::PW_F,
  G1 = pw::PW_G1,
  Brdf = pw::PW_BRDF,
  Model = pw::PW_MODEL,
  DAniso = pw::PW_D_ANISO,
  G1Aniso = pw::PW_G1_ANISO,
  BrdfAniso = pw::PW_BRDF_ANISO,
  Btdf = pw::PW_BTDF  // `bsdf` names the BTDF; inputs wi.xyz, wo.xyz; params[2] = eta
};
struct PointSpec {
  EvalMode mode = EvalMode::Brdf;
  const Term* d = nullptr;
  const Term* g = nullptr;
  const Term* f = nullptr;
  const Model* model = nullptr;
  const Bsdf* bsdf = nullptr;
  float inputs[6] = {0, 0, 1, 0, 0, 1};
  float params[pw::PW_PARAMS] = {0, 0, 0, 0, 0, 0, 0};
};
// The kernel's and the reference's value at one point (not the suite's
// PointResult, checks/suite.hpp, which is one integral's verdict).
struct PointValue {
  double kernel = 0, reference = 0, rel = 0, ulps = 0;
};
PointValue eval_point(Runtime& rt, const PointSpec& p, bool fp64);

// The program of mfv agree and mfv eval (its kernel eval_records evaluates
// records in place: kernels/agree.cl).
cl::Program build_pointwise_program(Runtime& rt, bool fp64);
// What mfv agree allows a kernel's value of the BTDF b at one record
// (kernels/abi/pointwise.h, mode PW_BTDF): the reference there and the error
// allowed, its ULP budget (or the absolute and flush-to-zero floors) and,
// where `conditioned`, twice what the exact function moves when one input
// moves by 4 roundings (its conditioning allowance): bsdf_reciprocity's
// account of the kernel (checks/bsdf_reciprocity.cpp).
struct RecordAllowance {
  double reference = 0, allowed = 0;
};
RecordAllowance btdf_record_allowance(const Bsdf& b, const float* rec, bool fp64, double ftz_floor, bool conditioned);

}  // namespace mfv
