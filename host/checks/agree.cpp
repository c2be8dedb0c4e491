#include "checks/agree.hpp"

#include "catalog/bsdfs.hpp"
#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "checks/pointwise.hpp"
#include "checks/pointwise_inputs.hpp"
#include "checks/streams.hpp"
#include "reference/brdf.hpp"
#include "reference/btdf.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/integrator.hpp"
#include "util/error.hpp"
#include "util/parallel.hpp"
#include "util/progress.hpp"

#include <glm/geometric.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <thread>

namespace mfv {
namespace {

using namespace pw;  // the record's named slots and modes (kernels/abi/pointwise.h)

constexpr int kRecord = PW_RECORD;  // floats per record
constexpr int kSlots = 6;           // D param, G param, F p0, F p1, kd, p5 (a whole model: its p[0..5])

struct Case {
  std::string name;
  EvalMode mode;
  const Term* d = nullptr;
  const Term* g = nullptr;
  const Term* f = nullptr;
  double ulp_budget = 0, abs_floor = 0;
  const Model* model = nullptr;
  const Bsdf* bsdf = nullptr;  // mode Btdf
};

std::vector<Case> make_cases(const AgreeOptions& opt) {
  std::vector<Case> cases;
  for (auto& t : catalog()) {
    if (t.aniso) {
      // both widths and the tangent components; the G2 is covered by the BRDFs below
      if (t.kind == Kind::D)
        cases.push_back({fmt::format("D {}", t.id), EvalMode::DAniso, &t, nullptr, nullptr, t.ulp_budget, t.abs_floor});
      else
        cases.push_back(
            {fmt::format("G1 {}", t.id), EvalMode::G1Aniso, nullptr, &t, nullptr, t.ulp_budget, t.abs_floor});
      continue;
    }
    EvalMode m = t.kind == Kind::D ? EvalMode::D : t.kind == Kind::G ? EvalMode::G : EvalMode::F;
    Case c{fmt::format("{} {}", kind_name(t.kind), t.id), m, nullptr, nullptr, nullptr, t.ulp_budget, t.abs_floor};
    (t.kind == Kind::D ? c.d : t.kind == Kind::G ? c.g : c.f) = &t;
    cases.push_back(c);
    if (!t.g1_kernel_fn.empty() && t.id != "smith_ggx_correlated")  // shares smith_ggx's G1
      cases.push_back({fmt::format("G1 {}", t.id), EvalMode::G1, nullptr, &t, nullptr, t.ulp_budget, t.abs_floor});
  }
  if (opt.combinations)
    for (auto* d : terms_of(Kind::D))
      for (auto* g : terms_of(Kind::G))
        for (auto* f : terms_of(Kind::F))
          cases.push_back({fmt::format("BRDF {}/{}/{}", d->id, g->id, f->id), EvalMode::Brdf, d, g, f,
                           d->ulp_budget + g->ulp_budget + f->ulp_budget + 8,
                           std::max({d->abs_floor, g->abs_floor, f->abs_floor})});
  if (opt.combinations)  // anisotropic D with its own Smith G, every F
    for (auto* d : aniso_terms_of(Kind::D))
      for (auto* g : aniso_terms_of(Kind::G))
        for (auto* f : terms_of(Kind::F))
          if (g->fit_for(d->id))
            cases.push_back({fmt::format("BRDF {}/{}/{}", d->id, g->id, f->id), EvalMode::BrdfAniso, d, g, f,
                             d->ulp_budget + g->ulp_budget + f->ulp_budget + 8,
                             std::max({d->abs_floor, g->abs_floor, f->abs_floor})});
  for (auto& m : models()) {
    Case c{fmt::format("MODEL {}", m.id), EvalMode::Model, nullptr, nullptr, nullptr, m.ulp_budget, m.abs_floor};
    c.model = &m;
    cases.push_back(c);
  }
  for (auto& b : bsdfs())  // the rough dielectric BTDFs, known-bad ones too (they agree with their twins)
    cases.push_back({fmt::format("BTDF {}", b.id), EvalMode::Btdf, b.d, b.g, &find_term("dielectric"), b.ulp_budget,
                     b.abs_floor, nullptr, &b});
  if (!opt.only.empty()) {
    std::vector<Case> kept;
    for (auto& c : cases)
      for (auto& o : opt.only)
        if (c.name.find(o) != std::string::npos) {
          kept.push_back(c);
          break;
        }
    if (kept.empty() && !opt.only_may_match_none) throw Error("--only matches no agreement case (see 'mfv list')");
    cases = kept;
  }
  return cases;
}

// w / |w| as kernels/agree.cl unit_exact forms it in double: the same
// correctly rounded operations in the same order (x86-64 has no FMA to
// contract into by default), so both sides see the bit-identical unit vector.
glm::dvec3 unit_exact(const glm::dvec3& w) {
  const double n2 = w.x * w.x + w.y * w.y + w.z * w.z;
  const double n = std::sqrt(n2);
  return {w.x / n, w.y / n, w.z / n};
}

// The cosines brdf_eval_c (kernels/brdf.cl) forms from a record's light and
// view, in exact arithmetic at exactly the recorded numbers (made unit with
// unit_exact in float64 builds, as the kernel does): n·l = l_z, n·v = v_z,
// h = (l + v)/|l + v|, v·h = |l + v|/2. The float record is unit only to a
// few float ulps, and how few depends on the device's sin, cos and pow
// (OpenCL allows 4, 4 and 16 ulps): Intel's CPU runtime leaves |l| up to
// 1 + 7e-7 (6 ulps). Made unit first, the reference moved v·h by that much,
// and near a conductor's critical angle (n = 0.25, k = 0.06, v·h = 0.958,
// dF/dv·h x v·h/F = 17) F moved 7e-6 relative, which the 2-ulp conditioning
// allowance does not cover: agree then measured the record's rounding, not
// the kernel's (issue 19: BRDF phong/cook_torrance/conductor failed on Intel
// at 233 ulps from the unit-direction reference; on that record PoCL's
// kernel is 117 ulps from it and 21 from the value at the recorded numbers:
// tests/test_agree_record_inputs.cpp). wi, wo receive the directions used.
ref::Shading record_shading(const double* in, bool fp64, glm::dvec3& wi, glm::dvec3& wo) {
  wi = glm::dvec3(in[PW_WI_X], in[PW_WI_Y], in[PW_WI_Z]), wo = glm::dvec3(in[PW_WO_X], in[PW_WO_Y], in[PW_WO_Z]);
  if (fp64) wi = unit_exact(wi), wo = unit_exact(wo);
  const glm::dvec3 sum = wi + wo;
  const double len = glm::length(sum);
  return {wi.z, wo.z, sum.z / len, std::min(0.5 * len, 1.0)};
}

// The reference value of one record, with every input optionally scaled by
// (1 + bump) one at a time: index -1 means no bump.
struct Evaluator {
  const Case& c;
  const float* r;
  bool fp64 = false;
  double eval(int bump_index, double bump) const {
    // the record's inputs: the geometry, p[0..5] and PW_ALPHA_Y = PW_P6 (in + PW_P0 is a model's p[0..6])
    double in[PW_P6 + 1];
    for (int k = 0; k <= PW_P6; ++k) in[k] = r[k];
    if (aniso() && bump_index >= 0 && bump_index < 13) in[bump_index] *= 1.0 + bump;
    // inputs 0..3 are the cosines; for the BRDF they are derived from wi, wo
    // below and bumped there (index 11..14), so float rounding inside the
    // kernel's half-vector formation is covered too.
    // A whole model's direction components are bumped by an absolute amount:
    // rounding a unit vector moves each component by ~eps of its length, not
    // of the component (a small z is as uncertain as a large x).
    if (directions() && bump_index >= 0 && bump_index < 6)
      in[bump_index] += bump;
    else if (!aniso() && bump_index >= 0 && bump_index < (directions() ? 13 : 11))
      in[bump_index] *= 1.0 + bump;
    switch (c.mode) {
      case EvalMode::DAniso: {
        // The kernels take the recorded h as if unit; both anisotropic D forms
        // (GGX: 1/(π ax ay k²), k = c² + (hx/ax)² + (hy/ay)²; Beckmann:
        // exp(-((hx/ax)² + (hy/ay)²)/c²)/(π ax ay c⁴)) are homogeneous of
        // degree -4 in h, so at the recorded h they are exactly D(ĥ)/|h|⁴:
        // the reference at the kernel's own inputs, not at the rounding of
        // the half vector (issue 19). |h|⁴ differs from 1 by ~4e-7 in float.
        const glm::dvec3 h(in[PW_AUX_X], in[PW_AUX_Y], in[PW_NOH]);
        const double len2 = glm::dot(h, h);
        return c.d->ref_d_aniso(h, in[PW_PD], in[PW_ALPHA_Y]) / (len2 * len2);
      }
      case EvalMode::G1Aniso:
        return c.g->ref_g1_aniso(glm::dvec3(in[PW_AUX_X], in[PW_AUX_Y], in[PW_NOV]), in[PW_PG], in[PW_ALPHA_Y]);
      case EvalMode::BrdfAniso: {
        // as kernels/agree.cl and the whole models: the record's directions as
        // they are in float32 (made unit in float64 builds), the half vector
        // formed from them (nearly opposite l and v leave it ill-conditioned)
        ref::BrdfSpec s{c.d, c.g, c.f, in[PW_PD], in[PW_PG], in[PW_F0], in[PW_F1], in[PW_KD]};
        s.pd2 = s.pg2 = in[PW_ALPHA_Y];
        glm::dvec3 wi, wo;
        const ref::Shading sh = record_shading(in, fp64, wi, wo);
        if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;
        const glm::dvec3 sum = wi + wo;
        return s.kd / M_PI + ref::eval_d(s, sum / glm::length(sum)) * c.f->ref_f(sh.VoH, s.f0, s.f1) *
                                 ref::eval_g(s, wi, wo, sh) / (4.0 * sh.NoL * sh.NoV);
      }
      case EvalMode::D: return c.d->ref_d(in[PW_NOH], in[PW_PD]);
      case EvalMode::G: return c.g->ref_g(in[PW_NOL], in[PW_NOV], in[PW_NOH], in[PW_VOH], in[PW_PG]);
      case EvalMode::G1: return c.g->ref_g1(in[PW_NOV], in[PW_PG]);
      case EvalMode::F: return c.f->ref_f(in[PW_VOH], in[PW_F0], in[PW_F1]);
      case EvalMode::Model: {
        // as kernels/agree.cl: the float record's directions as they are in
        // float32 (the model's formula then sees the kernel's own inputs, not
        // unit vectors 1e-7 away), made unit in float64 as the kernel does
        glm::dvec3 wi(in[PW_WI_X], in[PW_WI_Y], in[PW_WI_Z]), wo(in[PW_WO_X], in[PW_WO_Y], in[PW_WO_Z]);
        if (fp64) wi = unit_exact(wi), wo = unit_exact(wo);
        return c.model->ref(wi, wo, in + PW_P0);
      }
      case EvalMode::Btdf: {
        // as the whole models: the record's directions as they are (made unit in float64)
        glm::dvec3 wi(in[PW_WI_X], in[PW_WI_Y], in[PW_WI_Z]), wo(in[PW_WO_X], in[PW_WO_Y], in[PW_WO_Z]);
        if (fp64) wi = unit_exact(wi), wo = unit_exact(wo);
        ref::BtdfSpec s{c.d, c.g, c.bsdf->form, c.bsdf->variant, in[PW_PD], in[PW_PG], in[PW_F0]};
        // inputs 13 and 14: the tilt of h_t, as the kernel's rounding of s = η_i i + η_o o
        // moves it: (η_i + η_o) units over |s|. |s| cancels where o ~ -i and η ~ 1,
        // so that a lobe far narrower than one rounding of the directions is
        // stepped over by their bumps (as the BRDF's bumped n.h, index 13)
        if (bump_index == 13) {
          const double ei = wi.z > 0 ? 1.0 : s.eta, eo = wo.z > 0 ? 1.0 : s.eta;
          s.h_tilt = bump * (ei + eo) / glm::length(ei * wi + eo * wo);
        }
        if (bump_index == 14) s.f_cos_bump = bump;  // F's facet cosine, as the BRDF's bumped v·h
        // input 15: the TIR test itself, g² within its derived float rounding
        // (1 - F at its extremes there: near a small η's critical angle 1 - F
        // peaks inside that interval, which no bump of one input reaches)
        if (bump_index == 15) s.g2_slack = std::copysign(btdf_tir_rounding(s.eta, wi, wo, fp64), bump);
        return ref::btdf(s, wi, wo);
      }
      case EvalMode::Brdf: {
        ref::BrdfSpec s{c.d, c.g, c.f, in[PW_PD], in[PW_PG], in[PW_F0], in[PW_F1], in[PW_KD]};
        glm::dvec3 wi, wo;
        ref::Shading sh =
            record_shading(in, fp64, wi, wo);  // sin2H < 0: D from NoH alone, so that bumping NoH moves it
        if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;
        double* cs[4] = {&sh.NoL, &sh.NoV, &sh.NoH, &sh.VoH};
        if (bump_index >= 11 && bump_index < 15) *cs[bump_index - 11] *= 1.0 + bump;
        return ref::brdf(s, sh);
      }
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
  // a whole model's or a BTDF's record: two directions, their components bumped absolutely
  bool directions() const { return c.mode == EvalMode::Model || c.mode == EvalMode::Btdf; }
  bool aniso() const {
    return c.mode == EvalMode::DAniso || c.mode == EvalMode::G1Aniso || c.mode == EvalMode::BrdfAniso;
  }
  int inputs() const {
    return aniso()                        ? 13
           : c.mode == EvalMode::Brdf     ? 15
           : c.mode == EvalMode::Btdf     ? 16
           : directions()                 ? 13
                                          : 11;
  }
};

std::string describe(const Case& c, const float* r, double k, double ref) {
  std::string in;
  if (c.mode == EvalMode::Brdf || c.mode == EvalMode::Model || c.mode == EvalMode::BrdfAniso ||
      c.mode == EvalMode::Btdf)
    in = fmt::format("wi=({:a}, {:a}, {:a}) wo=({:a}, {:a}, {:a})", r[PW_WI_X], r[PW_WI_Y], r[PW_WI_Z], r[PW_WO_X],
                     r[PW_WO_Y], r[PW_WO_Z]);
  else
    in = fmt::format("NoL={:a} NoV={:a} NoH={:a} VoH={:a}", r[PW_NOL], r[PW_NOV], r[PW_NOH], r[PW_VOH]);
  std::string ps;
  const char* slot[kSlots] = {"pD", "pG", "f0", "f1", "kd", "p5"};
  for (int s = 0; s < kSlots; ++s) ps += fmt::format(" {}={:a}", slot[s], r[PW_P0 + s]);
  if (c.mode == EvalMode::Model && r[PW_P6] != 0.0f) ps += fmt::format(" p6={:a}", r[PW_P6]);
  if (c.mode == EvalMode::DAniso || c.mode == EvalMode::G1Aniso || c.mode == EvalMode::BrdfAniso)
    ps += fmt::format(" h.x|v.x={:a} h.y|v.y={:a} alpha_y={:a}", r[PW_AUX_X], r[PW_AUX_Y], r[PW_ALPHA_Y]);
  return fmt::format("{}{} kernel={:a} reference={:a}", in, ps, k, ref);
}

struct Stats {
  std::vector<double> rel;
  double max_rel = 0, max_ulps = 0, worst_score = -1;
  uint64_t failures = 0;
  std::string worst;
};

// ftz_floor: FLT_MIN on a float32 run where the device flushes subnormals
// (CL_FP_DENORM absent): a value below FLT_MIN may read as 0 there, an error
// of at most FLT_MIN that the format allows; 0 elsewhere. It does not cover a
// flushed intermediate that a formula then scales up (that is a real error:
// kernels/terms_d.cl D_beckmann rescales instead).
void check_range(const Case& c, const float* rec, size_t begin, size_t end, bool fp64, double ftz_floor, Stats& st) {
  for (size_t i = begin; i < end; ++i) {
    const float* r = rec + i * kRecord;
    double k = record_value(r);
    Evaluator ev{c, r, fp64};
    double ref = ev.eval(-1, 0.0);
    const PointError e = point_error(k, ref, fp64);
    const double diff = e.diff, ulps = e.ulps, rel = e.rel;
    st.rel.push_back(rel);
    st.max_rel = std::max(st.max_rel, rel);
    st.max_ulps = std::max(st.max_ulps, ulps);
    // In float64 the double reference rounds as much as the kernel does, so
    // the two budgets add up; in float32 the reference's share is negligible.
    double allowed = std::max({(fp64 ? 2.0 : 1.0) * c.ulp_budget * ulp_of(ref, fp64), c.abs_floor, ftz_floor});
    bool fail = !(diff <= allowed);
    if (fail && std::isfinite(ref) && std::isfinite(k)) {
      // Conditioning allowance: what the exact function itself does when one
      // input moves by 2 units of rounding. A kernel within twice that is as
      // good as its format allows at this input.
      // Whole models form their cosines (v·r, n·h) from three products and
      // a normalisation each: several roundings of the inputs' scale, which
      // a lobe (v·r)^n multiplies by n; their bump is 4 units, not 2.
      const double units = ev.directions() ? 4 : 2;
      const double dev = input_sensitivity(
          ev.inputs(), units, fp64, [&](int j, double b) { return ev.eval(j, b); }, ref);
      fail = diff > std::max(allowed, 2.0 * dev);
    }
    double score = fail ? 1e300 + ulps : ulps;
    if (fail) st.failures++;
    if (score > st.worst_score || (std::isnan(ulps) && st.worst.empty())) {
      st.worst_score = score;
      st.worst = describe(c, r, k, ref);
    }
  }
}

// One thread's statistics added to the case's.
void merge(Stats& total, const Stats& p) {
  total.rel.insert(total.rel.end(), p.rel.begin(), p.rel.end());
  total.max_rel = std::max(total.max_rel, p.max_rel);
  total.max_ulps = std::max(total.max_ulps, p.max_ulps);
  total.failures += p.failures;
  if (p.worst_score > total.worst_score) {
    total.worst_score = p.worst_score;
    total.worst = p.worst;
  }
}

AgreeResult result_of(const Case& c, Stats& total, uint64_t samples) {
  AgreeResult r;
  r.name = c.name;
  r.samples = samples;
  r.ulp_budget = c.ulp_budget;
  r.max_rel = total.max_rel;
  r.max_ulps = total.max_ulps;
  r.failures = total.failures;
  r.worst = total.worst;
  auto mid = total.rel.begin() + total.rel.size() / 2;
  std::nth_element(total.rel.begin(), mid, total.rel.end());
  r.median_rel = *mid;
  return r;
}

cl::Program build_agree_program(Runtime& rt, bool fp64);

// Each case's Philox stream is a hash of its name (checks/streams.hpp), not
// its position in the list: adding a term, selecting cases with --only, or
// running a shard's part leaves every other case's inputs, and so its
// record, unchanged.
std::vector<uint32_t> case_streams(const std::vector<Case>& cases) {
  std::vector<uint32_t> streams;
  std::map<uint32_t, std::string> seen;
  for (const Case& c : cases) {
    const uint32_t st = static_cast<uint32_t>(stream_of_key("agree " + c.name));
    if (auto [it, fresh] = seen.emplace(st, c.name); !fresh)
      throw Error(fmt::format("internal: agree cases '{}' and '{}' hash to one stream", it->second, c.name));
    streams.push_back(st);
  }
  return streams;
}

}  // namespace

UnitPlan agree_plan(const AgreeOptions& opt) {
  const std::vector<Case> cases = make_cases(opt);
  const std::vector<uint32_t> streams = case_streams(cases);
  UnitPlan plan;
  PlanDigest d;
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    d.text(c.name), d.value(int(c.mode)), d.value(c.ulp_budget), d.value(c.abs_floor), d.value(streams[i]);
    plan.cost.push_back(opt.samples);
  }
  d.value(opt.samples), d.value(opt.fp64);
  plan.hash = d.hex();
  return plan;
}

AgreeReport run_agree(Runtime& rt, const AgreeOptions& opt, std::pair<size_t, size_t> part) {
  if (opt.samples == 0) throw Error("--samples must be at least 1");
  if (opt.fp64 && !rt.device().fp64)
    throw Error(fmt::format("device '{}' has no cl_khr_fp64; run without --fp64", rt.device().name));
  auto cases = make_cases(opt);

  AgreeReport rep;
  if (cases.empty()) return rep;  // only_may_match_none
  auto build0 = rt.build_stats().seconds;
  cl::Program prog = build_agree_program(rt, opt.fp64);
  rep.build_seconds = rt.build_stats().seconds - build0;
  cl::Kernel kern(prog, "agree_eval");

  const size_t chunk = static_cast<size_t>(std::min<uint64_t>(opt.samples, 1u << 18));
  // read and written: agree_eval evaluates each record from what it stored
  cl::Buffer rec_buf(rt.context(), CL_MEM_READ_WRITE, chunk * kRecord * sizeof(float));
  cl::Buffer range_buf(rt.context(), CL_MEM_READ_ONLY, sizeof(DrawRanges));
  std::vector<float> rec(chunk * kRecord);
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  const double ftz_floor = !opt.fp64 && !rt.device().fp32_denorms ? std::numeric_limits<float>::min() : 0.0;

  const std::vector<uint32_t> streams = case_streams(cases);
  const size_t hi = std::min(part.second, cases.size());
  progress::Task task("agree: cases", hi - std::min(part.first, hi));
  for (size_t ci = part.first; ci < hi; ++ci) {
    const Case& c = cases[ci];
    const DrawRanges ranges =
        draw_ranges(c.d, c.g, c.f, c.model, c.mode == EvalMode::Brdf || c.mode == EvalMode::BrdfAniso,
                    c.bsdf ? &c.bsdf->eta : nullptr);
    rt.queue().enqueueWriteBuffer(range_buf, CL_TRUE, 0, sizeof(ranges), ranges.data());

    Stats total;
    total.rel.reserve(opt.samples);
    for (uint64_t first = 0; first < opt.samples; first += chunk) {
      size_t n = static_cast<size_t>(std::min<uint64_t>(chunk, opt.samples - first));
      // Sentinel: an unwritten record reads as NaN and cannot pass.
      rt.queue().enqueueFillBuffer(rec_buf, std::numeric_limits<float>::quiet_NaN(), 0, n * kRecord * sizeof(float));
      kern.setArg(0, static_cast<cl_ulong>(opt.seed));
      kern.setArg(1, static_cast<cl_uint>(streams[ci]));
      kern.setArg(2, static_cast<cl_ulong>(first));
      kern.setArg(3, static_cast<cl_int>(c.mode));
      kern.setArg(4, static_cast<cl_int>(c.model ? int(c.model->number()) : c.d ? term_index(*c.d) : 0));
      kern.setArg(5, static_cast<cl_int>(c.g ? term_index(*c.g) : 0));
      kern.setArg(6, static_cast<cl_int>(c.bsdf ? c.bsdf->code() : c.f ? term_index(*c.f) : 0));
      kern.setArg(7, range_buf);
      kern.setArg(8, rec_buf);
      auto t0 = std::chrono::steady_clock::now();
      rt.queue().enqueueNDRangeKernel(kern, cl::NullRange, cl::NDRange(n));
      rt.queue().enqueueReadBuffer(rec_buf, CL_TRUE, 0, n * kRecord * sizeof(float), rec.data());
      auto t1 = std::chrono::steady_clock::now();
      std::vector<Stats> part(threads);
      parallel_for(threads, threads, [&](size_t t) {
        check_range(c, rec.data(), n * t / threads, n * (t + 1) / threads, opt.fp64, ftz_floor, part[t]);
      });
      auto t2 = std::chrono::steady_clock::now();
      rep.kernel_seconds += std::chrono::duration<double>(t1 - t0).count();
      rep.reference_seconds += std::chrono::duration<double>(t2 - t1).count();
      for (auto& p : part) merge(total, p);
    }
    rep.results.push_back(result_of(c, total, opt.samples));
    rep.samples += opt.samples;
    task.advance(1);
  }
  return rep;
}

namespace {
cl::Program build_agree_program(Runtime& rt, bool fp64) {
  std::vector<std::string> defines;
  if (fp64) defines.push_back("MFV_DOUBLE");
  return rt.build(catalog_sources({"btdf.cl", "pointwise.cl", "agree.cl"}), defines, generate_dispatch(TermSelection::all()),
                  kDispatchBefore);
}
}  // namespace

PointValue eval_point(Runtime& rt, const PointSpec& p, bool fp64) {
  if (fp64 && !rt.device().fp64)
    throw Error(fmt::format("device '{}' has no cl_khr_fp64; run without --fp64", rt.device().name));
  cl::Program prog = build_agree_program(rt, fp64);
  cl::Kernel kern(prog, "eval_records");
  FloatRecord rec{};
  for (int k = 0; k < 6; ++k) rec[size_t(k)] = p.inputs[k];
  for (int k = 0; k < PW_PARAMS; ++k) rec[size_t(PW_P0 + k)] = p.params[k];
  rec[PW_VALUE] = std::numeric_limits<float>::quiet_NaN();  // sentinel
  cl::Buffer buf(rt.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(rec), rec.data());
  kern.setArg(0, static_cast<cl_int>(p.mode));
  kern.setArg(1, static_cast<cl_int>(p.model ? int(p.model->number()) : p.d ? term_index(*p.d) : 0));
  kern.setArg(2, static_cast<cl_int>(p.g ? term_index(*p.g) : 0));
  kern.setArg(3, static_cast<cl_int>(p.bsdf ? p.bsdf->code() : p.f ? term_index(*p.f) : 0));
  kern.setArg(4, buf);
  rt.queue().enqueueNDRangeKernel(kern, cl::NullRange, cl::NDRange(1));
  rt.queue().enqueueReadBuffer(buf, CL_TRUE, 0, sizeof(rec), rec.data());
  Case c{"point", p.mode, p.d, p.g, p.f, 0, 0, p.model, p.bsdf};
  PointValue r;
  r.kernel = record_value(rec.data());
  r.reference = Evaluator{c, rec.data(), fp64}.eval(-1, 0.0);
  const PointError e = point_error(r.kernel, r.reference, fp64);
  r.ulps = e.ulps;
  r.rel = e.rel;
  return r;
}

cl::Program build_pointwise_program(Runtime& rt, bool fp64) { return build_agree_program(rt, fp64); }

RecordAllowance btdf_record_allowance(const Bsdf& b, const float* rec, bool fp64, double ftz_floor, bool conditioned) {
  const Case c{b.id, EvalMode::Btdf, b.d, b.g, &find_term("dielectric"), b.ulp_budget, b.abs_floor, nullptr, &b};
  const Evaluator ev{c, rec, fp64};
  RecordAllowance a;
  a.reference = ev.eval(-1, 0.0);
  // as check_range: the ULP budget (or the floors), then twice the conditioning at 4 roundings
  a.allowed = std::max({(fp64 ? 2.0 : 1.0) * c.ulp_budget * ulp_of(a.reference, fp64), c.abs_floor, ftz_floor});
  if (conditioned && std::isfinite(a.reference))
    a.allowed = std::max(a.allowed, 2.0 * input_sensitivity(
                                              ev.inputs(), 4, fp64, [&](int j, double bump) { return ev.eval(j, bump); },
                                              a.reference));
  return a;
}

}  // namespace mfv
