// The rough dielectric BSDFs (catalog/bsdfs.hpp, issue 29) as a point source
// of the registry (kSourceBsdf): every kind that takes them gets each BSDF at
// the widths, indices, sides and view cosines below, with the catalog's
// expectation (CheckKind::expect) and, for the flux (Shape::BsdfFlux),
// the facet-space truth of checks/transmission_truth.hpp as the expected value.
#include "abi/bsdf.h"
#include "catalog/roughness.hpp"
#include "checks/integrate.hpp"
#include "checks/profile.hpp"
#include "checks/registry.hpp"
#include "checks/suite.hpp"
#include "checks/suite_bsdf.hpp"
#include "checks/transmission_truth.hpp"
#include "util/parallel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <tuple>

namespace mfv {
namespace {

// Widths: the smooth limit (alpha = 1e-4: E_R = F(mu), E_T = 1 - F(mu) where
// masking is 1), a sharp, a medium and a rough lobe; each D keeps those in
// its range. Indices: glass and a dense medium, each entered (side above)
// and left (side below: relative index 1/eta, total internal reflection).
const std::vector<double> kBsdfAlphas = {1e-4, 0.05, 0.3, 0.8};
const std::vector<double> kBsdfEtas = {1.5, 3.0};

// The index-matched limit (issue 29): at eta = 1 F = 0 at every facet, so
// bsdf_furnace's E_R = 0, two-sided, at every width and view (one side: at
// eta = 1 the two are one). E_T there is a Dirac at o = -i, which no BTDF
// value carries (h_t is 0/0; docs/transmission.md), so only E_R is a point.
// The kernel's F = 1 - T_dielectric(c, 1) is 0 only to T's rounding: there
// g2 = fl(c c) (eta - 1 = 0 exactly), g = sqrt(g2) within 6.5u (OpenCL's
// 3-ulp sqrt), c + g and eta^2 c + g within 4.25u, their squares 9.5u, the
// two quotients (2.5-ulp division) 14.5u, their sum 15.5u, 2 c g (sum) 24u:
// |F| <= 24u (u = 2^-24), and E_R <= 24u times the F = 1 albedo, itself <= 1.
constexpr double kIndexMatched = 1.0;
constexpr double kIndexMatchedRounding = 24.0 * 0x1p-24;

// View cosines from 0.01 (0.6 degrees above the surface) to the normal,
// dense towards grazing. Not below: light leaving a dense medium (eta = 3)
// at mu < 0.01 is transmitted only through facets within a degree of the
// horizon (refraction sends the rest back to its side), an event so rare
// under any proposal around the refracted direction that the integral's
// standard error is no measure of its error (measured: no sample of 4096
// landing there, against E_T = 7.4e-4 by quadrature at alpha = 0.8, mu =
// 0.004). mfv stability sweeps the BTDF at grazing cosines down to 2^-149.
std::vector<double> bsdf_views(int n) {
  std::vector<double> c;
  for (int i = 0; i < n; ++i) c.push_back(std::pow(10.0, -2.0 * double(n - 1 - i) / double(n - 1)));
  return c;
}

// The truth's two product rules (numeric/hemisphere_quadrature.hpp): their
// difference bounds the finer one's error, which the point's test adds.
const ProductRule kTruthFine{12, 3, 8, 1e-10}, kTruthCoarse{8, 2, 4, 1e-10};

// The correct entry of b's D and form: the truth of a known-bad entry is the
// physics of its D (its own Smith G1, F at the facet, eq. 21 as printed).
const Bsdf& truth_entry(const Bsdf& b) {
  for (const Bsdf& c : bsdfs())
    if (c.known_bad.empty() && c.d == b.d && c.form == b.form) return c;
  return b;
}

struct Truth {
  double reflected = 0, transmitted = 0, error = 0;
};

using TruthKey = std::tuple<const Bsdf*, double, double, int, double>;  // entry, alpha, eta, side, cos_i

// The truths of a process, computed once each (the tests run many seeds).
std::mutex truth_lock;
std::map<TruthKey, Truth> truth_cache;

void compute_truths(const std::vector<TruthKey>& keys) {
  // Each key once: the known-bad entries share their correct entry's truths.
  std::set<TruthKey> todo;
  {
    std::lock_guard<std::mutex> g(truth_lock);
    for (const TruthKey& k : keys)
      if (!truth_cache.count(k)) todo.insert(k);
  }
  const std::vector<TruthKey> items(todo.begin(), todo.end());  // sorted: one BSDF and width after another
  // One quadrature (nodes and D) per BSDF and width, shared by its indices,
  // sides and views: a truth then costs its view's sweep alone.
  std::vector<std::pair<const Bsdf*, double>> widths;
  for (const TruthKey& k : items)
    if (widths.empty() || widths.back() != std::make_pair(std::get<0>(k), std::get<1>(k)))
      widths.emplace_back(std::get<0>(k), std::get<1>(k));
  std::vector<std::unique_ptr<const BsdfFluxQuadrature>> fine(widths.size()), coarse(widths.size());
  parallel_for(widths.size(), host_threads(), [&](size_t j) {
    const auto& [b, alpha] = widths[j];
    const ref::BtdfSpec s{b->d, b->g, b->form, MFV_BTDF_OK, native_from_alpha(b->d->roughness, alpha),
                          native_from_alpha(b->g->roughness, alpha)};
    fine[j] = std::make_unique<const BsdfFluxQuadrature>(s, kTruthFine);
    coarse[j] = std::make_unique<const BsdfFluxQuadrature>(s, kTruthCoarse);
  });
  std::vector<Truth> out(items.size());
  parallel_for(items.size(), host_threads(), [&](size_t j) {
    const auto& [b, alpha, eta, side, cos_i] = items[j];
    const size_t w = std::lower_bound(widths.begin(), widths.end(), std::make_pair(b, alpha)) - widths.begin();
    const BsdfFlux f = fine[w]->flux(cos_i, side == MFV_SIDE_BELOW, eta);
    const BsdfFlux c = coarse[w]->flux(cos_i, side == MFV_SIDE_BELOW, eta);
    out[j] = {f.reflected, f.transmitted, std::max(std::fabs(f.reflected - c.reflected), std::fabs(f.transmitted - c.transmitted))};
  });
  std::lock_guard<std::mutex> g(truth_lock);
  for (size_t j = 0; j < items.size(); ++j) truth_cache.emplace(items[j], out[j]);
}

Truth truth_of(const TruthKey& k) {
  std::lock_guard<std::mutex> g(truth_lock);
  return truth_cache.at(k);
}

bool in_range(const Term& t, double alpha) {
  const double v = native_from_alpha(t.roughness, alpha);
  return t.params.empty() || (v >= t.params[0].lo && v <= t.params[0].hi);
}

// only: one BSDF at the widths and indices given (a scene's refracting
// material, bsdf_points); else every wanted BSDF at kBsdfAlphas x kBsdfEtas.
Plan bsdf_plan(const CheckKind& kind, const SuiteOptions& opt, const Bsdf* only = nullptr,
               const std::vector<double>& alphas = kBsdfAlphas, const std::vector<double>& etas = kBsdfEtas) {
  Plan p = new_plan(kind.check, kind.base_samples, opt.scale);
  const bool flux = shape_of(kind) == Shape::BsdfFlux;
  const bool avg = shape_of(kind) == Shape::BsdfAvg;  // one integral a width and index: both sides, mu drawn
  const std::vector<uint32_t> lobes =
      flux ? std::vector<uint32_t>{MFV_LOBE_REFLECT, MFV_LOBE_TRANSMIT} : std::vector<uint32_t>{MFV_LOBE_ALL};
  const std::vector<double> views = avg ? std::vector<double>{1.0} : bsdf_views(kind.n_view * opt.density);
  std::vector<TruthKey> keys;
  for (const Bsdf& b : bsdfs()) {
    if (only ? &b != only : !suite_model_wanted(opt.models, b.id)) continue;
    bool used = false;
    for (double alpha : densify(alphas, opt.density)) {
      if (!in_range(*b.d, alpha) || !in_range(*b.g, alpha)) continue;
      used = true;
      const Expectation e = kind.expect ? kind.expect({b.d, b.g, alpha, 0, 0, &b}) : Expectation{};
      // the flux from both sides at each index (the averages take both in one
      // integral); transmission masking reads no eta (o below)
      // bsdf_furnace over the catalog: the index-matched limit besides (not a scene's material at its ior)
      std::vector<double> flux_etas = etas;
      if (flux && !only) flux_etas.push_back(kIndexMatched);
      for (double eta : flux ? flux_etas : avg ? etas : std::vector<double>{1.0})
        for (int side : flux && eta == kIndexMatched ? std::vector<int>{MFV_SIDE_ABOVE}
                        : flux                       ? std::vector<int>{MFV_SIDE_ABOVE, MFV_SIDE_BELOW}
                        : avg                        ? std::vector<int>{MFV_SIDE_ABOVE}
                                                     : std::vector<int>{MFV_SIDE_BELOW})
          for (double co : views) {
            const TruthKey key{&truth_entry(b), alpha, eta, side, co};
            if (flux) keys.push_back(key);
            for (uint32_t lobe : lobes) {
              if (flux && eta == kIndexMatched && lobe != MFV_LOBE_REFLECT) continue;  // E_T: the Dirac
              MicrofacetIntegral m;
              m.kind = kind.kind;
              m.d = b.d;
              m.g = b.g;
              m.pd = native_from_alpha(b.d->roughness, alpha);
              m.pg = native_from_alpha(b.g->roughness, alpha);
              m.width = alpha;
              m.cos_o = co;
              IntegralSpec s = spec_of(m);
              s.eta = float(eta);
              s.side = side;
              s.bsdf = b.code();
              s.lobe = lobe;
              p.specs.push_back(s);
              PointResult r;
              r.check = kind.check;
              r.model = b.id;
              r.params = {{"alpha", alpha}};
              if (!avg) r.params["side"] = side, r.params[flux ? "cos_i" : "cos_o"] = co;
              if (flux || avg) r.params["eta"] = eta;
              if (lobe != MFV_LOBE_ALL) r.params["lobe"] = lobe;
              r.expected = kind.expected;  // the flux: its truth, below
              r.upper_only = kind.upper_only;
              r.take(e);
              if (flux && eta == kIndexMatched) r.rounding_bound = kIndexMatchedRounding;
              p.points.push_back(r);
            }
          }
    }
    if (!used) continue;
    if (std::find(p.terms.d.begin(), p.terms.d.end(), b.d) == p.terms.d.end()) p.terms.d.push_back(b.d);
    if (std::find(p.terms.g.begin(), p.terms.g.end(), b.g) == p.terms.g.end()) p.terms.g.push_back(b.g);
  }
  // The same-sample comparison with the reference takes the correct entries:
  // a known-bad entry plants its bug in the kernel and the reference alike
  // (mfv agree compares those), and a planted ill-conditioned formula (the
  // Jacobian's (i.h + o.h)^2, which cancels at o = -i) would fail that
  // comparison rather than the physics this kind tests.
  // The index-matched points neither: the comparison's bound is relative to
  // the samples' values, and F's rounding at F = 0 is absolute (their
  // rounding_bound above).
  std::vector<size_t> pick;
  for (size_t i = 0; i < p.points.size(); ++i)
    if (p.points[i].expect == Expect::Hold && !(flux && p.specs[i].eta == float(kIndexMatched))) pick.push_back(i);
  p.reference_pick = pick;
  if (flux) {
    compute_truths(keys);
    for (size_t i = 0; i < p.points.size(); ++i) {
      PointResult& r = p.points[i];
      const IntegralSpec& s = p.specs[i];
      const Truth t = truth_of({&truth_entry(*try_find_bsdf(r.model)), r.params.at("alpha"), r.params.at("eta"),
                                s.side, r.params.at("cos_i")});
      r.expected = s.lobe == MFV_LOBE_REFLECT ? t.reflected : t.transmitted;
      // the truth's error, as a relative tolerance of the expected value (the judge's bias)
      if (r.expected > 0) r.tolerance += t.error / r.expected;
      // Leaving the medium beyond the critical angle the macro-surface
      // reflects totally: E_T comes from the few facets tilted past it,
      // weighted by (i.m)/(i.n), a rare event for every proposal at grazing
      // view (measured: 2 facets of 10^6 drawn from D at alpha = 0.05, mu =
      // 0.025, eta = 1.5, against E_T = 9.2e-4 by quadrature), so the
      // sample's standard error does not measure its error: there the
      // estimate is only bounded above by the truth (an estimate that misses
      // the tail lies below it).
      const double eta_seen = s.side == MFV_SIDE_BELOW ? 1.0 / r.params.at("eta") : r.params.at("eta");
      if (s.lobe == MFV_LOBE_TRANSMIT && eta_seen < 1.0 && r.params.at("cos_i") < std::sqrt(1.0 - eta_seen * eta_seen))
        r.upper_only = true;
    }
  }
  return p;
}

}  // namespace

PointSource bsdf_source(const SuiteOptions& opt) {
  return {kSourceBsdf, "the rough dielectric BSDFs", [&opt](const CheckKind& k, std::vector<Plan>& plans) {
            const Shape shape = shape_of(k);
            if (shape != Shape::BsdfFlux && shape != Shape::MaskingT && shape != Shape::BsdfAvg) return false;
            Plan p = bsdf_plan(k, opt);
            if (!p.specs.empty()) plans.push_back(std::move(p));
            return true;
          }};
}

Plan bsdf_points(const CheckKind& k, const SuiteOptions& opt, const Bsdf& b, const std::vector<double>& alphas,
                 const std::vector<double>& etas) {
  return bsdf_plan(k, opt, &b, alphas, etas);
}

std::vector<BsdfCheck> bsdf_checks(const Bsdf& b) {
  std::vector<BsdfCheck> out;
  for (const CheckKind& k : check_kinds()) {
    if (!(k.sources & kSourceBsdf)) continue;
    BsdfCheck c{&k, Expect::Hold, ""};
    for (double alpha : kBsdfAlphas) {  // the group's verdict: its worst point's (a Fail anywhere fails it)
      if (!in_range(*b.d, alpha) || !in_range(*b.g, alpha) || !k.expect) continue;
      const Expectation e = k.expect({b.d, b.g, alpha, 0, 0, &b});
      if (e.expect != Expect::Hold && c.expect != Expect::Fail) c.expect = e.expect, c.reason = e.reason;
    }
    out.push_back(c);
  }
  return out;
}

std::vector<std::string> bsdf_model_names() {
  std::vector<std::string> out;
  for (const Bsdf& b : bsdfs()) out.push_back(b.id);
  return out;
}

}  // namespace mfv
