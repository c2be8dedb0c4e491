// The shared-node quadrature of the furnace truth (furnace_truth.hpp,
// albedos_by_quadrature): every isotropic D x G x F at one view by one rule.
#include "checks/furnace_views.hpp"

#include "reference/brdf.hpp"
#include "reference/d_log_cos.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

namespace mfv {
namespace {

// One rule at one view: the nodes that add to its sum and the BRDF's shading
// at them, which every isotropic D x G x F at that view shares (ref::brdf
// forms the same Shading from the same i and o), and the terms' values there
// by (term, params).
//
// The same bits as integrate_reflected of ref::brdf(s, i, o) * i.z, with the
// sum_reflected's order kept per integral: phi node by phi node, each inner
// sum over its t nodes in order (hemisphere_quadrature.cpp). A node whose
// brdf_of_terms is 0 (dead, or n·l or n·v <= 0: it returns 0 before reading
// its terms) adds w (0 · 4 (o·h)) = +0 there, which leaves any sum but -0
// unchanged, and an inner sum that starts at +0 never is -0: such nodes are
// left out. Several integrals are summed side by side (kBatch chains of adds
// instead of one: the adds' latency, not their count, bounds one chain), each
// in its own order.
class ViewRule {
 public:
  ViewRule(const glm::dvec3& o, const ProductRule& rule) {
    const ReflectedNodes n = reflected_nodes(o, rule);
    for (size_t j = 0, k = 0; j < n.phi_weight.size(); ++j) {
      for (const size_t end = k + n.per_phi; k < end; ++k) {
        if (!n.live[k]) continue;
        const ref::Shading c = ref::shading_from(n.i[k], o);
        if (c.NoL <= 0.0 || c.NoV <= 0.0) continue;  // brdf_of_terms's 0
        shading_.push_back(c);
        weight_.push_back(n.weight[k]);
        oh_.push_back(n.oh[k]);
        iz_.push_back(n.i[k].z);
        den_.push_back(4.0 * c.NoL * c.NoV);  // brdf_of_terms's denominator
      }
      group_end_.push_back(shading_.size());
      phi_weight_.push_back(n.phi_weight[j]);
    }
  }

  // ∫ f(i, o) (n·i) di of each spec by the rule, into out[0..]: per node
  // brdf_of_terms(s, c, D, F, G) * i.z = (kd/π + D·F·G / (4 n·l n·v)) i.z,
  // then sum_reflected's w (f · 4 (o·h)), each as written there.
  void albedos(const std::vector<ref::BrdfSpec>& specs, double* out) {
    const size_t n = specs.size();
    std::vector<const double*> df(n), g(n);
    std::vector<double> kd_pi(n);
    for (size_t q = 0; q < n; ++q) {
      const ref::BrdfSpec& s = specs[q];
      df[q] = d_times_f(s).data();
      g[q] = g_values(s).data();
      kd_pi[q] = s.kd / M_PI;
    }
    std::fill(out, out + n, 0.0);
    for (size_t j = 0, k0 = 0; j < group_end_.size(); k0 = group_end_[j++])
      for (size_t b = 0; b < n; b += kBatch) {
        double inner[kBatch] = {};
        const double* dfb[kBatch];
        const double* gb[kBatch];
        double kdb[kBatch];
        for (size_t q = 0; q < kBatch; ++q) {  // a short batch repeats its last integral
          const size_t i = std::min(b + q, n - 1);
          dfb[q] = df[i], gb[q] = g[i], kdb[q] = kd_pi[i];
        }
        for (size_t k = k0; k < group_end_[j]; ++k)
          for (size_t q = 0; q < kBatch; ++q) {
            const double f = (kdb[q] + dfb[q][k] * gb[q][k] / den_[k]) * iz_[k];
            inner[q] += weight_[k] * (f * 4.0 * oh_[k]);
          }
        for (size_t q = 0; q < kBatch && b + q < n; ++q) out[b + q] += phi_weight_[j] * inner[q];
      }
  }

 private:
  static constexpr size_t kBatch = 8;
  using Key = std::tuple<const ref::TermTwins*, double, double>;
  using Cache = std::map<Key, std::vector<double>>;

  template <class Term>
  const std::vector<double>& values(Cache& cache, const Key& key, const Term& term) {
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    std::vector<double> v;  // not zeroed first: 135 keys x 38112 nodes a view (the three rules)
    v.reserve(shading_.size());
    for (const ref::Shading& c : shading_) v.push_back(term(c));
    return cache.emplace(key, std::move(v)).first->second;
  }
  // G at the nodes; a separable one (TermTwins::g_separable) as G1(n·l) G1(n·v),
  // a height-correlated one as 1 / (1 + Λ(n·l) + Λ(n·v)) (g_correlated_lambda),
  // G1(n·v) or Λ(n·v) taken once: n·v is the view's (the same bits at every node).
  const std::vector<double>& g_values(const ref::BrdfSpec& s) {
    const ref::TermTwins& t = *s.g;
    const Key key{s.g, s.pg, 0};
    double nov = NAN, of_v = NAN;  // G1 or Λ at n·v
    auto at_v = [&](ref::RefG1 fn, double NoV) {
      if (!(NoV == nov)) nov = NoV, of_v = fn(NoV, s.pg);
      return of_v;
    };
    auto visible = [](const ref::Shading& c) { return c.NoL > 0.0 && c.NoV > 0.0 && c.VoH > 0.0; };
    if (t.g_separable)
      return values(g_, key, [&](const ref::Shading& c) {
        return visible(c) ? t.ref_g1(c.NoL, s.pg) * at_v(t.ref_g1, c.NoV) : 0.0;
      });
    if (t.g_correlated_lambda)
      return values(g_, key, [&](const ref::Shading& c) {
        return visible(c) ? 1.0 / (1.0 + t.g_correlated_lambda(c.NoL, s.pg) + at_v(t.g_correlated_lambda, c.NoV))
                          : 0.0;
      });
    return values(g_, key, [&](const ref::Shading& c) { return ref::eval_g_iso(s, c); });
  }
  // D at the nodes; one of Phong's forms (ref::d_of_log_cos) from log cos θ_h,
  // taken once a node for every width, as eval_d_iso takes its _cs form.
  const std::vector<double>& d_values(const ref::BrdfSpec& s, const Key& key) {
    const ref::RefDlc lc = s.d->ref_d_cs ? ref::d_of_log_cos(s.d->ref_d_cs) : nullptr;
    if (!lc) return values(d_, key, [&](const ref::Shading& c) { return ref::eval_d_iso(s, c); });
    if (log_cos_.empty())
      for (const ref::Shading& c : shading_) {
        const double cos2 = c.NoH * c.NoH;
        log_cos_.push_back(cos2 > 0.0 ? ref::log_cos_cs(std::min(cos2, 1.0), c.sin2H) : 0.0);
      }
    size_t k = 0;
    return values(d_, key, [&](const ref::Shading& c) {
      const double log_cos = log_cos_[k++];
      if (!(c.sin2H >= 0.0 && c.NoH > 0.0)) return ref::eval_d_iso(s, c);  // not the _cs form
      return c.NoH * c.NoH > 0.0 ? lc(log_cos, s.pd) : 0.0;                // D_*_cs's χ+
    });
  }
  // D·F at the nodes (brdf_of_terms's D * F * G is (D * F) * G), by (D's key, F's key).
  const std::vector<double>& d_times_f(const ref::BrdfSpec& s) {
    const Key dk{s.d, s.pd, 0}, fk{s.f, s.f0, s.f1};
    auto it = df_.find({dk, fk});
    if (it != df_.end()) return it->second;
    const std::vector<double>& D = d_values(s, dk);
    const std::vector<double>& F =
        values(f_, fk, [&](const ref::Shading& c) { return s.f->ref_f(c.VoH, s.f0, s.f1); });
    std::vector<double> v;
    v.reserve(D.size());
    for (size_t k = 0; k < D.size(); ++k) v.push_back(D[k] * F[k]);
    return df_.emplace(std::make_pair(dk, fk), std::move(v)).first->second;
  }

  std::vector<ref::Shading> shading_;
  std::vector<double> weight_, oh_, iz_, den_;  // per node that adds
  std::vector<double> log_cos_;                 // log cos θ_h per node, where a D takes it
  std::vector<size_t> group_end_;               // per φ node: the end of its t nodes
  std::vector<double> phi_weight_;
  Cache d_, g_, f_;
  std::map<std::pair<Key, Key>, std::vector<double>> df_;
};

}  // namespace

std::vector<double> albedos_at_view(const glm::dvec3& o, const ProductRule& rule,
                                    const std::vector<ref::BrdfSpec>& brdfs) {
  std::vector<double> out(brdfs.size());
  ViewRule(o, rule).albedos(brdfs, out.data());
  return out;
}

}  // namespace mfv
