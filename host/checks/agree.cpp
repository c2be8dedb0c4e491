#include "checks/agree.hpp"

#include "catalog/catalog.hpp"
#include "catalog/models.hpp"
#include "reference/brdf.hpp"
#include "runtime/dispatch.hpp"
#include "runtime/error.hpp"
#include "util/progress.hpp"

#include <glm/geometric.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <thread>

namespace mfv {
namespace {

// = EvalMode, = AGREE_* in agree.cl; the *Aniso modes take both widths of an
// anisotropic term (Term::aniso), alpha_y in record slot 14.
enum Mode { kD = 0, kG = 1, kF = 2, kG1 = 3, kBrdf = 4, kModel = 5, kDAniso = 6, kG1Aniso = 7, kBrdfAniso = 8 };
constexpr int kRecord = 16;   // floats per record, see kernels/agree.cl
constexpr int kSlots = 6;     // D param, G param, F p0, F p1, kd, p5 (a whole model: its p[0..5])
constexpr int kRangeSlots = 7;  // and a whole model's p[6] (record slot 14; kernels/agree.cl)

struct Case {
  std::string name;
  Mode mode;
  const Term* d = nullptr;
  const Term* g = nullptr;
  const Term* f = nullptr;
  double ulp_budget = 0, abs_floor = 0;
  const Model* model = nullptr;
};

// Sampling range of one parameter: log-uniform where it spans decades.
void put_range(std::array<float, 3 * kRangeSlots>& r, int slot, const Param* p) {
  double lo = p ? p->lo : 0.0, hi = p ? p->hi : 1.0;
  bool log_scale = hi > 100.0 * std::max(lo, 1e-300);
  if (log_scale && lo <= 0.0) lo = 1e-3 * std::max(1.0, hi * 1e-6);  // an exponent from 0: sample from ~1
  r[3 * slot] = static_cast<float>(lo);
  r[3 * slot + 1] = static_cast<float>(hi);
  r[3 * slot + 2] = log_scale ? 1.0f : 0.0f;
}

const Param* param(const Term* t, size_t i) { return t && i < t->params.size() ? &t->params[i] : nullptr; }

std::vector<Case> make_cases(const AgreeOptions& opt) {
  std::vector<Case> cases;
  for (auto& t : catalog()) {
    if (t.aniso) {
      // both widths and the tangent components; the G2 is covered by the BRDFs below
      if (t.kind == Kind::D)
        cases.push_back({fmt::format("D {}", t.id), kDAniso, &t, nullptr, nullptr, t.ulp_budget, t.abs_floor});
      else
        cases.push_back({fmt::format("G1 {}", t.id), kG1Aniso, nullptr, &t, nullptr, t.ulp_budget, t.abs_floor});
      continue;
    }
    Mode m = t.kind == Kind::D ? kD : t.kind == Kind::G ? kG : kF;
    Case c{fmt::format("{} {}", kind_name(t.kind), t.id), m, nullptr, nullptr, nullptr, t.ulp_budget, t.abs_floor};
    (t.kind == Kind::D ? c.d : t.kind == Kind::G ? c.g : c.f) = &t;
    cases.push_back(c);
    if (!t.g1_kernel_fn.empty() && t.id != "smith_ggx_correlated")  // shares smith_ggx's G1
      cases.push_back({fmt::format("G1 {}", t.id), kG1, nullptr, &t, nullptr, t.ulp_budget, t.abs_floor});
  }
  if (opt.combinations)
    for (auto* d : terms_of(Kind::D))
      for (auto* g : terms_of(Kind::G))
        for (auto* f : terms_of(Kind::F))
          cases.push_back({fmt::format("BRDF {}/{}/{}", d->id, g->id, f->id), kBrdf, d, g, f,
                           d->ulp_budget + g->ulp_budget + f->ulp_budget + 8,
                           std::max({d->abs_floor, g->abs_floor, f->abs_floor})});
  if (opt.combinations)  // anisotropic D with its own Smith G, every F
    for (auto* d : aniso_terms_of(Kind::D))
      for (auto* g : aniso_terms_of(Kind::G))
        for (auto* f : terms_of(Kind::F))
          if (g->fit_for(d->id))
            cases.push_back({fmt::format("BRDF {}/{}/{}", d->id, g->id, f->id), kBrdfAniso, d, g, f,
                             d->ulp_budget + g->ulp_budget + f->ulp_budget + 8,
                             std::max({d->abs_floor, g->abs_floor, f->abs_floor})});
  for (auto& m : models()) {
    Case c{fmt::format("MODEL {}", m.id), kModel, nullptr, nullptr, nullptr, m.ulp_budget, m.abs_floor};
    c.model = &m;
    cases.push_back(c);
  }
  if (!opt.only.empty()) {
    std::vector<Case> kept;
    for (auto& c : cases)
      for (auto& o : opt.only)
        if (c.name.find(o) != std::string::npos) {
          kept.push_back(c);
          break;
        }
    if (kept.empty()) throw Error("--only matches no agreement case (see 'mfv list')");
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
  wi = glm::dvec3(in[0], in[1], in[2]), wo = glm::dvec3(in[3], in[4], in[5]);
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
    double in[6 + kSlots + 1];
    for (int k = 0; k < 6; ++k) in[k] = r[k];
    for (int k = 0; k < kSlots; ++k) in[6 + k] = r[6 + k];
    in[6 + kSlots] = r[14];  // alpha_y of the anisotropic modes; a whole model's p[6] (in + 6 is its p[0..6])
    if (aniso() && bump_index >= 0 && bump_index < 13) in[bump_index] *= 1.0 + bump;
    // inputs 0..3 are the cosines; for the BRDF they are derived from wi, wo
    // below and bumped there (index 11..14), so float rounding inside the
    // kernel's half-vector formation is covered too.
    // A whole model's direction components are bumped by an absolute amount:
    // rounding a unit vector moves each component by ~eps of its length, not
    // of the component (a small z is as uncertain as a large x).
    if (c.mode == kModel && bump_index >= 0 && bump_index < 6) in[bump_index] += bump;
    else if (!aniso() && bump_index >= 0 && bump_index < (c.mode == kModel ? 13 : 11)) in[bump_index] *= 1.0 + bump;
    switch (c.mode) {
      case kDAniso: {
        // The kernels take the recorded h as if unit; both anisotropic D forms
        // (GGX: 1/(π ax ay k²), k = c² + (hx/ax)² + (hy/ay)²; Beckmann:
        // exp(-((hx/ax)² + (hy/ay)²)/c²)/(π ax ay c⁴)) are homogeneous of
        // degree -4 in h, so at the recorded h they are exactly D(ĥ)/|h|⁴:
        // the reference at the kernel's own inputs, not at the rounding of
        // the half vector (issue 19). |h|⁴ differs from 1 by ~4e-7 in float.
        const glm::dvec3 h(in[4], in[5], in[2]);
        const double len2 = glm::dot(h, h);
        return c.d->ref_d_aniso(h, in[6], in[12]) / (len2 * len2);
      }
      case kG1Aniso: return c.g->ref_g1_aniso(glm::dvec3(in[4], in[5], in[1]), in[7], in[12]);
      case kBrdfAniso: {
        // as kernels/agree.cl and the whole models: the record's directions as
        // they are in float32 (made unit in float64 builds), the half vector
        // formed from them (nearly opposite l and v leave it ill-conditioned)
        ref::BrdfSpec s{c.d, c.g, c.f, in[6], in[7], in[8], in[9], in[10]};
        s.pd2 = s.pg2 = in[12];
        glm::dvec3 wi, wo;
        const ref::Shading sh = record_shading(in, fp64, wi, wo);
        if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;
        const glm::dvec3 sum = wi + wo;
        return s.kd / M_PI + ref::eval_d(s, sum / glm::length(sum)) * c.f->ref_f(sh.VoH, s.f0, s.f1) *
                                 ref::eval_g(s, wi, wo, sh) / (4.0 * sh.NoL * sh.NoV);
      }
      case kD: return c.d->ref_d(in[2], in[6]);
      case kG: return c.g->ref_g(in[0], in[1], in[2], in[3], in[7]);
      case kG1: return c.g->ref_g1(in[1], in[7]);
      case kF: return c.f->ref_f(in[3], in[8], in[9]);
      case kModel: {
        // as kernels/agree.cl: the float record's directions as they are in
        // float32 (the model's formula then sees the kernel's own inputs, not
        // unit vectors 1e-7 away), made unit in float64 as the kernel does
        glm::dvec3 wi(in[0], in[1], in[2]), wo(in[3], in[4], in[5]);
        if (fp64) wi = unit_exact(wi), wo = unit_exact(wo);
        return c.model->ref(wi, wo, in + 6);
      }
      case kBrdf: {
        ref::BrdfSpec s{c.d, c.g, c.f, in[6], in[7], in[8], in[9], in[10]};
        glm::dvec3 wi, wo;
        ref::Shading sh = record_shading(in, fp64, wi, wo);  // sin2H < 0: D from NoH alone, so that bumping NoH moves it
        if (wi.z <= 0.0 || wo.z <= 0.0) return 0.0;
        double* cs[4] = {&sh.NoL, &sh.NoV, &sh.NoH, &sh.VoH};
        if (bump_index >= 11 && bump_index < 15) *cs[bump_index - 11] *= 1.0 + bump;
        return ref::brdf(s, sh);
      }
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
  bool aniso() const { return c.mode == kDAniso || c.mode == kG1Aniso || c.mode == kBrdfAniso; }
  int inputs() const { return aniso() ? 13 : c.mode == kBrdf ? 15 : c.mode == kModel ? 13 : 11; }
};

std::string describe(const Case& c, const float* r, double k, double ref) {
  std::string in;
  if (c.mode == kBrdf || c.mode == kModel || c.mode == kBrdfAniso)
    in = fmt::format("wi=({:a}, {:a}, {:a}) wo=({:a}, {:a}, {:a})", r[0], r[1], r[2], r[3], r[4], r[5]);
  else
    in = fmt::format("NoL={:a} NoV={:a} NoH={:a} VoH={:a}", r[0], r[1], r[2], r[3]);
  std::string ps;
  const char* slot[kSlots] = {"pD", "pG", "f0", "f1", "kd", "p5"};
  for (int s = 0; s < kSlots; ++s) ps += fmt::format(" {}={:a}", slot[s], r[6 + s]);
  if (c.mode == kModel && r[14] != 0.0f) ps += fmt::format(" p6={:a}", r[14]);
  if (c.mode == kDAniso || c.mode == kG1Aniso || c.mode == kBrdfAniso)
    ps += fmt::format(" h.x|v.x={:a} h.y|v.y={:a} alpha_y={:a}", r[4], r[5], r[14]);
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
  const double eps = fp64 ? 0x1p-52 : 0x1p-23;
  for (size_t i = begin; i < end; ++i) {
    const float* r = rec + i * kRecord;
    double k = r[12];
    if (std::isfinite(k)) k += r[13];
    Evaluator ev{c, r, fp64};
    double ref = ev.eval(-1, 0.0);
    double diff = std::fabs(k - ref);
    bool same_nonfinite = (std::isinf(k) && k == ref);
    if (same_nonfinite) diff = 0;
    double ulps = diff / ulp_of(ref, fp64);
    double rel = diff / std::max(std::fabs(ref), std::numeric_limits<double>::min());
    if (std::isnan(k) || std::isnan(ref)) ulps = rel = std::numeric_limits<double>::infinity();
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
      const double units = c.mode == kModel ? 4 : 2;
      double dev = 0;
      for (int j = 0; j < ev.inputs(); ++j)
        for (double b : {units * eps, -units * eps}) dev = std::max(dev, std::fabs(ev.eval(j, b) - ref));
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

}  // namespace

double ulp_of(double x, bool fp64) {
  double a = std::fabs(x);
  int mant = fp64 ? 52 : 23;
  double tiny = fp64 ? std::numeric_limits<double>::denorm_min() : std::numeric_limits<float>::denorm_min();
  if (!std::isfinite(a)) return std::numeric_limits<double>::infinity();
  if (a < (fp64 ? std::numeric_limits<double>::min() : std::numeric_limits<float>::min())) return tiny;
  int e;
  std::frexp(a, &e);  // a = m 2^e, m in [0.5, 1)
  return std::ldexp(1.0, e - 1 - mant);
}

namespace {
cl::Program build_agree_program(Runtime& rt, bool fp64);
}

AgreeReport run_agree(Runtime& rt, const AgreeOptions& opt) {
  if (opt.samples == 0) throw Error("--samples must be at least 1");
  if (opt.fp64 && !rt.device().fp64)
    throw Error(fmt::format("device '{}' has no cl_khr_fp64; run without --fp64", rt.device().name));
  auto cases = make_cases(opt);

  AgreeReport rep;
  auto build0 = rt.build_stats().seconds;
  cl::Program prog = build_agree_program(rt, opt.fp64);
  rep.build_seconds = rt.build_stats().seconds - build0;
  cl::Kernel kern(prog, "agree_eval");

  const size_t chunk = static_cast<size_t>(std::min<uint64_t>(opt.samples, 1u << 18));
  // read and written: agree_eval evaluates each record from what it stored
  cl::Buffer rec_buf(rt.context(), CL_MEM_READ_WRITE, chunk * kRecord * sizeof(float));
  cl::Buffer range_buf(rt.context(), CL_MEM_READ_ONLY, 3 * kRangeSlots * sizeof(float));
  std::vector<float> rec(chunk * kRecord);
  unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  const double ftz_floor = !opt.fp64 && !rt.device().fp32_denorms ? std::numeric_limits<float>::min() : 0.0;

  progress::Task task("agree: cases", cases.size());
  for (size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& c = cases[ci];
    std::array<float, 3 * kRangeSlots> ranges{};
    put_range(ranges, 0, param(c.d, 0));
    put_range(ranges, 1, param(c.g, 0));
    put_range(ranges, 2, param(c.f, 0));
    put_range(ranges, 3, param(c.f, 1));
    put_range(ranges, 4, nullptr);  // kd in [0, 1]
    put_range(ranges, 5, nullptr);
    put_range(ranges, 6, nullptr);
    ranges[3 * 6 + 1] = 0.0f;  // p[6]: whole models only
    ranges[3 * 5 + 1] = 0.0f;  // p5: whole models only
    if (c.mode != kBrdf && c.mode != kBrdfAniso) ranges[3 * 4 + 1] = 0.0f;  // no diffuse outside the BRDF
    if (c.model)  // a whole model: its own parameters in every slot, 0 past its count
      for (int k = 0; k < kRangeSlots; ++k) {
        put_range(ranges, k, size_t(k) < c.model->params.size() ? &c.model->params[size_t(k)] : nullptr);
        if (size_t(k) >= c.model->params.size()) ranges[3 * k + 1] = 0.0f;
      }
    rt.queue().enqueueWriteBuffer(range_buf, CL_TRUE, 0, sizeof(ranges), ranges.data());

    Stats total;
    total.rel.reserve(opt.samples);
    for (uint64_t first = 0; first < opt.samples; first += chunk) {
      size_t n = static_cast<size_t>(std::min<uint64_t>(chunk, opt.samples - first));
      // Sentinel: an unwritten record reads as NaN and cannot pass.
      rt.queue().enqueueFillBuffer(rec_buf, std::numeric_limits<float>::quiet_NaN(), 0, n * kRecord * sizeof(float));
      kern.setArg(0, static_cast<cl_ulong>(opt.seed));
      kern.setArg(1, static_cast<cl_uint>(ci));
      kern.setArg(2, static_cast<cl_ulong>(first));
      kern.setArg(3, static_cast<cl_int>(c.mode));
      kern.setArg(4, static_cast<cl_int>(c.model ? int(c.model->number()) : c.d ? term_index(*c.d) : 0));
      kern.setArg(5, static_cast<cl_int>(c.g ? term_index(*c.g) : 0));
      kern.setArg(6, static_cast<cl_int>(c.f ? term_index(*c.f) : 0));
      kern.setArg(7, range_buf);
      kern.setArg(8, rec_buf);
      auto t0 = std::chrono::steady_clock::now();
      rt.queue().enqueueNDRangeKernel(kern, cl::NullRange, cl::NDRange(n));
      rt.queue().enqueueReadBuffer(rec_buf, CL_TRUE, 0, n * kRecord * sizeof(float), rec.data());
      auto t1 = std::chrono::steady_clock::now();
      std::vector<Stats> part(threads);
      std::vector<std::thread> pool;
      for (unsigned t = 0; t < threads; ++t)
        pool.emplace_back([&, t] { check_range(c, rec.data(), n * t / threads, n * (t + 1) / threads, opt.fp64, ftz_floor,
                                               part[t]); });
      for (auto& th : pool) th.join();
      auto t2 = std::chrono::steady_clock::now();
      rep.kernel_seconds += std::chrono::duration<double>(t1 - t0).count();
      rep.reference_seconds += std::chrono::duration<double>(t2 - t1).count();
      for (auto& p : part) {
        total.rel.insert(total.rel.end(), p.rel.begin(), p.rel.end());
        total.max_rel = std::max(total.max_rel, p.max_rel);
        total.max_ulps = std::max(total.max_ulps, p.max_ulps);
        total.failures += p.failures;
        if (p.worst_score > total.worst_score) {
          total.worst_score = p.worst_score;
          total.worst = p.worst;
        }
      }
    }
    AgreeResult r;
    r.name = c.name;
    r.samples = opt.samples;
    r.ulp_budget = c.ulp_budget;
    r.max_rel = total.max_rel;
    r.max_ulps = total.max_ulps;
    r.failures = total.failures;
    r.worst = total.worst;
    auto mid = total.rel.begin() + total.rel.size() / 2;
    std::nth_element(total.rel.begin(), mid, total.rel.end());
    r.median_rel = *mid;
    rep.results.push_back(r);
    rep.samples += opt.samples;
    task.advance(1);
  }
  return rep;
}

namespace {
cl::Program build_agree_program(Runtime& rt, bool fp64) {
  std::vector<std::string> defines;
  if (fp64) defines.push_back("MFV_DOUBLE");
  return rt.build({"common.cl", "rng.cl", "terms_d.cl", "terms_g.cl", "terms_f.cl", "models.cl", "model_gltf.cl", "brdf.cl",
                   "agree.cl"},
                  defines, generate_dispatch(TermSelection::all()), "brdf.cl");
}
}  // namespace

PointResult eval_point(Runtime& rt, const PointSpec& p, bool fp64) {
  if (fp64 && !rt.device().fp64)
    throw Error(fmt::format("device '{}' has no cl_khr_fp64; run without --fp64", rt.device().name));
  cl::Program prog = build_agree_program(rt, fp64);
  cl::Kernel kern(prog, "eval_records");
  std::array<float, kRecord> rec{};
  for (int k = 0; k < 6; ++k) rec[k] = p.inputs[k];
  for (int k = 0; k < kSlots; ++k) rec[6 + k] = p.params[k];
  rec[14] = p.params[6];  // a whole model's p[6] (kernels/agree.cl)
  rec[12] = std::numeric_limits<float>::quiet_NaN();  // sentinel
  cl::Buffer buf(rt.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(rec), rec.data());
  kern.setArg(0, static_cast<cl_int>(p.mode));
  kern.setArg(1, static_cast<cl_int>(p.model ? int(p.model->number()) : p.d ? term_index(*p.d) : 0));
  kern.setArg(2, static_cast<cl_int>(p.g ? term_index(*p.g) : 0));
  kern.setArg(3, static_cast<cl_int>(p.f ? term_index(*p.f) : 0));
  kern.setArg(4, buf);
  rt.queue().enqueueNDRangeKernel(kern, cl::NullRange, cl::NDRange(1));
  rt.queue().enqueueReadBuffer(buf, CL_TRUE, 0, sizeof(rec), rec.data());
  Case c{"point", static_cast<Mode>(p.mode), p.d, p.g, p.f, 0, 0, p.model};
  PointResult r;
  r.kernel = rec[12];
  if (std::isfinite(r.kernel)) r.kernel += rec[13];
  r.reference = Evaluator{c, rec.data(), fp64}.eval(-1, 0.0);
  double diff = r.kernel == r.reference ? 0.0 : std::fabs(r.kernel - r.reference);
  r.ulps = diff / ulp_of(r.reference, fp64);
  r.rel = diff / std::max(std::fabs(r.reference), std::numeric_limits<double>::min());
  return r;
}

}  // namespace mfv
