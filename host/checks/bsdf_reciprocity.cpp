// bsdf_reciprocity (checks/registry.cpp; docs/transmission.md): the generalized
// reciprocity of the rough dielectric BTDF in the radiance form,
// f_t(i,o)/η_o² = f_t(o,i)/η_i² (Walter et al. 2007 eq. 21 carries η_o²; the
// identity: Veach 1997 §5.2, generalized reciprocity), over random, grazing,
// near-critical and near-refraction pairs, at each BSDF's widths and
// indices, both sides.
// Two points a (BSDF, alpha, eta): the float kernel (kernels/btdf.cl through
// mfv agree's eval_records) and the double reference twin
// (reference/btdf.cpp), each a count of pairs beyond its derived bound.
#include "abi/bsdf.h"
#include "catalog/roughness.hpp"
#include "checks/agree.hpp"
#include "checks/pointwise.hpp"
#include "checks/registry.hpp"
#include "checks/streams.hpp"
#include "checks/suite.hpp"
#include "checks/suite_bsdf.hpp"
#include "reference/btdf.hpp"
#include "rng/philox.hpp"
#include "runtime/dispatch.hpp"
#include "util/parallel.hpp"

#include <glm/geometric.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace mfv {

namespace {

using namespace pw;

// Widths within each D's and G's range; relative indices glass and a dense
// medium, each entered (i above) and left (i below: 1/eta, total internal
// reflection) by half the pairs.
const std::vector<double> kRecipAlphas = {0.05, 0.3, 1.0};
const std::vector<double> kRecipEtas = {1.5, 3.0};

// The double reference's own rounding of the identity: the Snell form of
// 1 - F from the other side cancels in η² - 1 + c² where that side's facet
// cosine c is small, to 64 ε / min(|i·h|, |o·h|)² relative
// (tests/test_btdf.cpp measures it over the same kinds of pairs).
double twin_bound(const glm::dvec3& i, const glm::dvec3& o, double eta) {
  const glm::dvec3 h = ref::half_vector_t(i, o, eta);
  const double c = std::min(std::fabs(glm::dot(i, h)), std::fabs(glm::dot(o, h)));
  return 64 * 0x1p-52 / (c * c);
}

glm::dvec3 polar(double c, double phi) {
  const double s = std::sqrt(std::max(0.0, (1 - c) * (1 + c)));
  return {s * std::cos(phi), s * std::sin(phi), c};
}

// The k-th pair: i above for even k, below for odd k; one pair in four with
// o uniform on the other side, one grazing (n·i below 10^-3), one
// near-critical (i below at 1 + 10^-u of the critical cosine, through the
// normal facet: o grazes the surface), the rest refracted through a facet of
// tilt up to 2 alpha (the lobe; eq. 40).
void pair_at(uint64_t seed, uint64_t stream, uint64_t k, double alpha, double eta, glm::dvec3& i, glm::dvec3& o) {
  const auto r = philox(seed, uint32_t(stream), uint32_t(stream >> 32), k);
  const double u0 = u01_open(r[0]), u1 = u01_open(r[1]), u2 = u01_open(r[2]), u3 = u01_open(r[3]);
  const double up = k % 2 == 0 ? 1.0 : -1.0;
  const int kind = int((k / 2) % 4);
  const double crit = std::sqrt(1 - 1 / (eta * eta));  // the critical cosine leaving (i below)
  double ci = kind == 1 ? 1e-3 * u0 : u0;
  if (kind == 2) ci = std::min(1.0, crit * (1 + std::pow(10.0, -1 - 6 * u0)));
  i = polar(ci, 2 * M_PI * u1);
  i.z *= kind == 2 ? -1.0 : up;
  const double eta_i = i.z > 0 ? 1.0 : eta, eta_o = i.z > 0 ? eta : 1.0;
  glm::dvec3 m(0, 0, 1);
  if (kind == 3) m = polar(std::cos(std::min(1.5, 2 * alpha * u2)), 2 * M_PI * u3);
  if (glm::dot(i, m) < 0) m = -m;
  if (kind == 0 || !ref::refract(i, m, eta_i / eta_o, o) || o.z * i.z >= 0) {
    o = polar(u2, 2 * M_PI * u3);  // uniform in cos on the other side (also under total internal reflection)
    o.z *= i.z > 0 ? -1.0 : 1.0;
  }
}

FloatRecord record_of(const glm::dvec3& i, const glm::dvec3& o, float pd, float pg, float eta) {
  FloatRecord r{};
  const glm::dvec3 dirs[2] = {i, o};
  for (int k = 0; k < 6; ++k) r[size_t(k)] = float(dirs[k / 3][k % 3]);
  r[PW_PD] = pd, r[PW_PG] = pg, r[PW_F0] = eta;
  r[PW_VALUE] = std::numeric_limits<float>::quiet_NaN();  // sentinel: an unwritten record fails
  return r;
}

glm::dvec3 dir_of(const FloatRecord& r, int first) {
  const glm::dvec3 w(r[size_t(first)], r[size_t(first + 1)], r[size_t(first + 2)]);
  return w / glm::length(w);
}

struct Tally {
  uint64_t failures = 0;
  double worst = -1;  // asymmetry over its bound
  std::string at;
  void add(double asym, double bound, const FloatRecord& r, double a, double b) {
    const bool fail = !(asym <= bound);
    failures += fail;
    const double ratio = fail && !(asym == asym) ? std::numeric_limits<double>::infinity() : asym / bound;
    if (ratio > worst || (fail && worst < 1)) {
      worst = ratio;
      at = fmt::format("i=({:a}, {:a}, {:a}) o=({:a}, {:a}, {:a}): f(i,o)/eta_o^2 = {:.9g}, f(o,i)/eta_i^2 = {:.9g}",
                       r[0], r[1], r[2], r[3], r[4], r[5], a, b);
    }
  }
};

}  // namespace

void run_bsdf_reciprocity_pass(Runtime& rt, const SuiteOptions& opt, SuiteReport& rep) {
  const auto t0 = std::chrono::steady_clock::now();
  const CheckKind& kind = check_kind("bsdf_reciprocity");
  const uint64_t pairs = scaled_samples(kind.base_samples, opt.scale);
  const double ftz_floor = !rt.device().fp32_denorms ? std::numeric_limits<float>::min() : 0.0;
  const double b0 = rt.build_stats().seconds;
  cl::Program prog = build_pointwise_program(rt, false);
  rep.build_seconds += rt.build_stats().seconds - b0;
  cl::Kernel kern(prog, "eval_records");
  size_t n_points = 0;
  for (const Bsdf& b : bsdfs()) {
    if (!suite_model_wanted(opt.models, b.id)) continue;
    for (double alpha : kRecipAlphas)
      for (double eta : kRecipEtas) {
        const double pd = native_from_alpha(b.d->roughness, alpha), pg = native_from_alpha(b.g->roughness, alpha);
        if (pd < b.d->params[0].lo || pd > b.d->params[0].hi || pg < b.g->params[0].lo || pg > b.g->params[0].hi)
          continue;
        // the pairs in float records, (i, o) then (o, i), from a Philox stream
        // keyed by the BSDF, width and index (checks/streams.hpp: never by place)
        const uint64_t stream = stream_of_key(fmt::format("check={} bsdf={} alpha={:a} eta={:a}", kind.check, b.id, alpha, eta));
        std::vector<FloatRecord> rec(2 * pairs);
        for (uint64_t k = 0; k < pairs; ++k) {
          glm::dvec3 i, o;
          pair_at(opt.seed, stream, k, alpha, eta, i, o);
          rec[2 * k] = record_of(i, o, float(pd), float(pg), float(eta));
          rec[2 * k + 1] = record_of(o, i, float(pd), float(pg), float(eta));
        }
        cl::Buffer buf(rt.context(), CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, rec.size() * sizeof(FloatRecord),
                       rec.data());
        kern.setArg(0, static_cast<cl_int>(PW_BTDF));
        kern.setArg(1, static_cast<cl_int>(term_index(*b.d)));
        kern.setArg(2, static_cast<cl_int>(term_index(*b.g)));
        kern.setArg(3, static_cast<cl_int>(b.code()));
        kern.setArg(4, buf);
        rt.queue().enqueueNDRangeKernel(kern, cl::NullRange, cl::NDRange(rec.size()));
        rt.queue().enqueueReadBuffer(buf, CL_TRUE, 0, rec.size() * sizeof(FloatRecord), rec.data());
        const ref::BtdfSpec spec{b.d, b.g, b.form, b.variant, double(float(pd)), double(float(pg)), double(float(eta))};
        // each pair's asymmetries and bounds on the host's threads (each writes its own slot), then tallied in order
        struct PairCheck {
          double au = 0, bu = 0, rb = 0, ak = 0, bk = 0, bound = 0;
          bool twin = false;
        };
        std::vector<PairCheck> pc(pairs);
        parallel_for(pairs, host_threads(), [&](size_t k) {
          const FloatRecord &ro = rec[2 * k], &rs = rec[2 * k + 1];
          const glm::dvec3 i = dir_of(ro, 0), o = dir_of(ro, 3);  // the recorded directions made unit
          const double ei = i.z > 0 ? 1.0 : spec.eta, eo = o.z > 0 ? 1.0 : spec.eta;
          PairCheck& c = pc[k];
          // the twin: the reference at the unit directions, within its own rounding
          c.au = ref::btdf(spec, i, o) / (eo * eo), c.bu = ref::btdf(spec, o, i) / (ei * ei);
          c.rb = twin_bound(i, o, spec.eta) * std::max(c.au, c.bu);
          c.twin = std::max(c.au, c.bu) >= std::numeric_limits<double>::min();  // a subnormal tail has no relative digits
          // the kernel: each value within mfv agree's allowance of the reference at
          // its own (float) record, which is the unit-direction reference moved by
          // the directions' rounding: the identity holds to the sum of these
          c.ak = record_value(ro.data()) / (eo * eo), c.bk = record_value(rs.data()) / (ei * ei);
          for (bool conditioned : {false, true}) {
            const RecordAllowance xa = btdf_record_allowance(b, ro.data(), false, ftz_floor, conditioned);
            const RecordAllowance xb = btdf_record_allowance(b, rs.data(), false, ftz_floor, conditioned);
            c.bound = (xa.allowed + std::fabs(xa.reference - c.au * eo * eo)) / (eo * eo) +
                      (xb.allowed + std::fabs(xb.reference - c.bu * ei * ei)) / (ei * ei) + c.rb;
            if (std::fabs(c.ak - c.bk) <= c.bound) break;  // the conditioning allowance only where the budget falls short
          }
        });
        Tally kernel_t, twin_t;
        for (uint64_t k = 0; k < pairs; ++k) {
          const PairCheck& c = pc[k];
          if (c.twin) twin_t.add(std::fabs(c.au - c.bu), c.rb, rec[2 * k], c.au, c.bu);
          kernel_t.add(std::fabs(c.ak - c.bk), c.bound, rec[2 * k], c.ak, c.bk);
        }
        for (const Tally* t : {&kernel_t, &twin_t}) {
          const bool twin = t == &twin_t;
          PointResult p;
          p.check = kind.check;
          p.model = b.id;
          p.params = {{"alpha", alpha}, {"eta", eta}, {"twin", twin ? 1.0 : 0.0}};
          p.bounded = true;
          p.estimate = double(t->failures);
          p.bound = 0;
          p.samples = pairs;
          p.measure = twin ? "pairs beyond the double reference's rounding (64 eps / min(|i.h|, |o.h|)^2)"
                           : "pairs beyond the float kernel's agree allowance plus the reference's rounding";
          p.detail = fmt::format("{}: worst {:.3g} of its bound at {}", twin ? "double twin" : "float kernel", t->worst,
                                 t->at);
          const Expectation e = kind.expect ? kind.expect({b.d, b.g, alpha, 0, 0, &b}) : Expectation{};
          p.expect = e.expect;
          p.reason = e.reason;
          rep.points.push_back(p);
          ++n_points;
        }
      }
  }
  rep.stats.push_back({kind.check, n_points, n_points * pairs,
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()});
}

}  // namespace mfv
