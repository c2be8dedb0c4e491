#include "checks/energy.hpp"

#include "catalog/roughness.hpp"
#include "checks/integrate.hpp"
#include "reference/estimators.hpp"
#include "runtime/dispatch.hpp"
#include "stats/normal.hpp"
#include "stats/verdict.hpp"
#include "util/error.hpp"
#include "util/progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

namespace mfv {

std::vector<double> energy_mu_grid(int n) {
  std::vector<double> mu;
  for (int m = 0; m < n; ++m) mu.push_back((m + 0.5) / n);  // cell midpoints of (0, 1]
  return mu;
}

namespace {
// The tables: every D x G of the shared-width grid, and each own lobe (the
// sheen) with its G, whose table is E_sheen (KHR_materials_sheen's albedo scaling).
std::vector<std::pair<const Term*, const Term*>> table_pairs() {
  std::vector<std::pair<const Term*, const Term*>> pairs;
  for (auto* d : terms_of(Kind::D))
    for (auto* g : terms_of(Kind::G)) pairs.push_back({d, g});
  for (auto* d : own_lobe_terms_of(Kind::D))
    for (auto* g : own_lobe_terms_of(Kind::G))
      if (g->fit_for(d->id)) pairs.push_back({d, g});
  return pairs;
}
}  // namespace

std::vector<double> energy_alpha_grid(int n) {
  std::vector<double> a;
  for (int j = 0; j < n; ++j) a.push_back(n == 1 ? 1.0 : std::pow(10.0, -3.0 + 3.0 * j / (n - 1)));
  return a;
}

void validate_energy_options(const EnergyOptions& o) {
  if (o.n_mu < 2 || o.n_mu > 256 || o.n_alpha < 2 || o.n_alpha > 256)
    throw Error(fmt::format("--grid {}x{}: each side must be 2..256", o.n_mu, o.n_alpha));
  if (!(o.target > 0) || !std::isfinite(o.target) || o.target >= 1)
    throw Error(fmt::format("--target {}: must be a standard error in (0, 1)", o.target));
  if (o.replicates < 2 || o.replicates > 256) throw Error(fmt::format("--replicates {}: must be 2..256", o.replicates));
  if (o.min_points < 64 || o.max_points < o.min_points || o.max_points > (uint64_t(1) << 24))
    throw Error(fmt::format("points per replicate {}..{}: need 64 <= min <= max <= 2^24", o.min_points, o.max_points));
  // Every filter must match something, or the user made a typo.
  for (auto& f : o.models) {
    bool hit = false;
    if (o.tables)
      for (auto [d, g] : table_pairs()) hit = hit || (d->id + "/" + g->id).find(f) != std::string::npos;
    if (o.catalog_models)
      for (auto& m : models())
        for (auto& c : m.cases) hit = hit || model_case_name(m, c).find(f) != std::string::npos;
    if (!hit) throw Error(fmt::format("--models '{}' matches no D/G combination or model[case] (see 'mfv list')", f));
  }
  for (auto& mp : o.model_points)
    for (size_t i = 0; i < mp.model->params.size(); ++i) validate_model_param(*mp.model, i, mp.p[i]);
}

namespace {

bool wanted(const std::vector<std::string>& filter, const std::string& name) {
  if (filter.empty()) return true;
  for (auto& f : filter)
    if (name.find(f) != std::string::npos) return true;
  return false;
}

// The whole-model points a run integrates: catalog cases (filtered), then the caller's.
std::vector<ModelPoint> model_points_of(const EnergyOptions& opt) {
  std::vector<ModelPoint> out;
  if (opt.catalog_models)
    for (auto& m : models())
      for (auto& c : m.cases) {
        const std::string name = model_case_name(m, c);
        if (wanted(opt.models, name)) out.push_back({&m, name, c.p, c.energy, c.energy_why});
      }
  out.insert(out.end(), opt.model_points.begin(), opt.model_points.end());
  return out;
}

Cell replicate_stats(const std::vector<double>& v) {
  const double n = double(v.size());
  double s = 0;
  for (double x : v) s += x;
  const double mean = s / n;
  double ss = 0;
  for (double x : v) ss += (x - mean) * (x - mean);
  return {mean, std::sqrt(ss / (n - 1) / n)};
}

// E_avg = 2 ∫ E(mu) mu dmu by the midpoint rule over the mu grid (cells
// E[0..n-1]), with its total uncertainty: the propagated standard error of
// the cells plus the rule's own error. Every third node is the midpoint of a
// cell three times wider, so the same values give the midpoint rule of width
// 3h over the first 3 floor(n/3) cells (the rest keep width h). The midpoint
// rule's error falls as width² (Davis & Rabinowitz 1984, §2.1.4), so
// |Q_3h - I| ~ 9 |Q_h - I| and |Q_3h - Q_h| bounds |Q_h - I| wherever the
// coarse rule is at least twice as wrong as the fine one. The noise-only SE
// left this out and read 9 SE off on the 32-point grid.
Cell eavg_by_midpoints(const std::vector<double>& mu, const Cell* E) {
  const size_t nm = mu.size();
  double s = 0, v = 0;
  for (size_t m = 0; m < nm; ++m) {
    const double w = 2.0 * mu[m] / double(nm);
    s += w * E[m].mean;
    v += w * w * E[m].se * E[m].se;
  }
  double coarse = 0;
  const size_t n3 = nm / 3 * 3;
  for (size_t m = 1; m < n3; m += 3) coarse += 3.0 * 2.0 * mu[m] / double(nm) * E[m].mean;
  for (size_t m = n3; m < nm; ++m) coarse += 2.0 * mu[m] / double(nm) * E[m].mean;
  const double rule_error = n3 > 0 ? std::fabs(coarse - s) : 0.0;
  return {s, stats::total_uncertainty(std::sqrt(v), rule_error)};
}

// Float32 rounding of E (issue 21: E = 1.0000 ± 1.9e-9 read as a gain). Each
// point's value f·cos/pdf is one float32 evaluation of the model, within
// Model::ulp_budget ulps of the double reference (measured by mfv agree),
// times the estimator's weight (cosine, two proposal densities, their MIS
// sum: under 16 operations of <= 1/2 ulp each, so <= 8 ulps; 16 allowed).
// Every value is >= 0 and the sums are in double (kernels/integrate.cl), so
// the mean's relative error is at most the per-point one: |ΔE| <= E (budget + 16) 2^-24.
double float_rounding_of_mean(const Model& m, double e) {
  constexpr double kWeightUlps = 16;
  return std::fabs(e) * (m.ulp_budget + kWeightUlps) * std::ldexp(1.0, -24);
}

// A whole model gains energy where some E(mu) exceeds 1 + its rounding bound
// beyond its noise: one-sided Student t (R - 1 degrees of freedom) per cell,
// Bonferroni over every model cell of the run at family-wise rate
// opt.gain_alpha. A cell whose standard error stayed above target and whose
// upper bound (mean + 3 se, one-sided 99.87 % normal) exceeds 1 + rounding
// is unresolved: neither a gain nor ruled out (issue 21: max E 1.338 ± 0.21).
void judge_model_gains(EnergyReport& rep) {
  size_t cells = 0;
  for (auto& me : rep.models) cells += me.E.size();
  const double threshold = rep.opt.gain_alpha / double(std::max<size_t>(1, cells));
  const double df = rep.opt.replicates - 1;
  for (auto& me : rep.models) {
    me.max_at = 0;
    me.excess_p = 1;
    me.unresolved = false;
    for (size_t m = 0; m < me.E.size(); ++m) {
      const Cell& c = me.E[m];
      if (c.mean > me.E[me.max_at].mean || !std::isfinite(c.mean)) me.max_at = m;
      double p;
      const double one = 1.0 + float_rounding_of_mean(*me.point.model, c.mean);
      if (!std::isfinite(c.mean))
        p = c.mean > 0 || std::isnan(c.mean) ? 0 : 1;
      else if (c.se > 0)
        p = c.mean > one ? 0.5 * stats::student_t_two_sided_p((c.mean - one) / c.se, df) : 1;
      else
        p = c.mean > one ? 0 : 1;
      me.excess_p = std::min(me.excess_p, p);
      if (c.se > rep.opt.target && c.mean + 3.0 * c.se > one) me.unresolved = true;
    }
    me.gains = me.excess_p < threshold;
    me.unresolved = me.unresolved && !me.gains;
  }
}

// One quantity the adaptive loop refines: an E/A/B cell (one integral per
// replicate yields E and, on the same points, B), an E_avg, or a whole
// model's E(mu) or E_avg (E only).
// The table of D x G at every alpha of the grid, its cells not yet run.
EnergyTable empty_table(const Term& d, const Term& g, const std::vector<double>& alpha, size_t nm) {
  EnergyTable t;
  t.d = &d;
  t.g = &g;
  for (double a : alpha) {
    double pd = native_from_alpha(d.roughness, a);
    validate_param(d, 0, pd);
    t.pd.push_back(pd);
    t.pg.push_back(g.params.empty() ? 0.0 : std::min(native_from_alpha(g.roughness, a), g.params[0].hi));
  }
  const size_t na = alpha.size();
  t.E.resize(nm * na);
  t.A = t.B = t.E;
  t.points.assign(nm * na, 0);
  t.eavg.resize(na);
  t.eavg_quad.resize(na);
  return t;
}

struct Unit {
  size_t table, index;  // table (or rep.models) index; cell index, alpha index or mu index
  bool eavg;
  IntegralSpec base;
  uint32_t first_stream;
  bool model = false;  // `table` indexes rep.models
};

// Records a unit's cells from its per-replicate sums over `done` points;
// returns the largest standard error among them.
double record_unit(EnergyReport& rep, const Unit& u, const std::vector<double>& sum, const std::vector<double>& b_sum,
                   uint64_t done) {
  const size_t R = sum.size();
  std::vector<double> e, a, b;
  for (size_t r = 0; r < R; ++r) e.push_back(sum[r] / double(done));
  if (u.model) {
    ModelEnergy& me = rep.models[u.table];
    Cell& c = u.eavg ? me.eavg : me.E[u.index];
    c = replicate_stats(e);
    if (!u.eavg) me.points[u.index] = done;
    return c.se;
  }
  EnergyTable& t = rep.tables[u.table];
  if (u.eavg) {
    t.eavg[u.index] = replicate_stats(e);
    return t.eavg[u.index].se;
  }
  for (size_t r = 0; r < R; ++r) {
    b.push_back(b_sum[r] / double(done));
    a.push_back(e[r] - b[r]);  // same shifted points: A and B share their noise
  }
  t.E[u.index] = replicate_stats(e);
  t.A[u.index] = replicate_stats(a);
  t.B[u.index] = replicate_stats(b);
  t.points[u.index] = done;
  return std::max({t.E[u.index].se, t.A[u.index].se, t.B[u.index].se});
}

// R replicates (randomizations) per unit; an E/A/B cell's kernel integral
// yields E and, on the same points, B (kernels/integrate.cl albedo_rqmc_value).
std::vector<IntegralSpec> specs_of(const Unit& u, size_t R) {
  std::vector<IntegralSpec> v;
  for (size_t r = 0; r < R; ++r) {
    IntegralSpec s = u.base;
    s.stream = u.first_stream + uint32_t(r);
    v.push_back(s);
  }
  return v;
}

// Pilot, then fresh samples: a pilot of min_points / 4 points per
// replicate on streams of its own sizes each unit; the unit's estimate is
// then a fresh run of the power-of-two multiple of min_points its pilot
// error predicts (RQMC error falls as 1/N here: measured N^-1 at normal and
// grazing view), up to max_points. Stopping on the estimate's own standard
// error (the former adaptive passes) keeps the runs whose error happened to
// come out small: 5 of 96 EON cells were beyond 3 SE, worst 5.4. With the
// count fixed before the fresh samples are drawn, mean and replicate SE are
// those of a fixed-size RQMC estimate, so the SE is unbiased.
class PilotThenFresh {
 public:
  PilotThenFresh(EnergyReport& rep, Integrator& in, const std::vector<Unit>& units)
      : rep_(rep), in_(in), units_(units), prog_(units.size()) {}

  // The pilot on streams past every unit's own (from `free_stream` on), then
  // the fresh run on the units' own streams.
  void run(uint32_t free_stream) {
    const EnergyOptions& opt = rep_.opt;
    const uint64_t pilot = std::max<uint64_t>(64, opt.min_points / 4);
    for (auto& p : prog_) p.want = pilot;
    const std::vector<double> pilot_se = run_units(free_stream);
    for (size_t ui = 0; ui < units_.size(); ++ui) {
      Progress& p = prog_[ui];
      const double need = std::isfinite(pilot_se[ui]) ? 1.25 * double(p.done) * pilot_se[ui] / opt.target : 0.0;
      uint64_t want = opt.min_points;
      while (want < opt.max_points && double(want) < need) want *= 2;
      p.want = std::min<uint64_t>(want, opt.max_points);
    }
    run_units(0);
  }

 private:
  struct Progress {
    uint64_t done = 0, want = 0;
    std::vector<double> sum, b_sum;  // per replicate: sums of the E (or E_avg) and B values
  };

  // Runs every unit at its `want` points on streams first_stream + shift + r
  // and records its cells; returns each unit's largest standard error.
  std::vector<double> run_units(uint32_t shift) {
    const size_t R = size_t(rep_.opt.replicates);
    std::vector<double> worst(units_.size(), 0.0);
    std::map<uint64_t, std::vector<size_t>> passes;  // one pass per point count
    for (size_t ui = 0; ui < units_.size(); ++ui) passes[prog_[ui].want].push_back(ui);
    for (auto& [want, group] : passes) {
      std::vector<IntegralSpec> specs;
      std::vector<size_t> offset;
      for (size_t ui : group) {
        offset.push_back(specs.size());
        for (auto& s : specs_of(units_[ui], R)) {
          s.stream += shift;
          specs.push_back(s);
        }
      }
      std::vector<Estimate> est = in_.run(specs, want, rep_.opt.seed);
      const uint64_t used = in_.samples_used(want);
      rep_.samples += used * specs.size();
      for (size_t k = 0; k < group.size(); ++k) {
        Progress& p = prog_[group[k]];
        p.sum.assign(R, 0.0);
        p.b_sum.assign(R, 0.0);
        for (size_t r = 0; r < R; ++r) {
          p.sum[r] = est[offset[k] + r].mean * double(used);
          p.b_sum[r] = est[offset[k] + r].b_mean * double(used);
        }
        p.done = used;
        worst[group[k]] = record_unit(rep_, units_[group[k]], p.sum, p.b_sum, p.done);
      }
    }
    return worst;
  }

  EnergyReport& rep_;
  Integrator& in_;
  const std::vector<Unit>& units_;
  std::vector<Progress> prog_;
};

// E_avg by the midpoint rule over the mu grid, as a cross-check of the
// dedicated integral (its error is the quadrature's O(1/n^2) plus noise).
void add_quadrature_cross_check(EnergyReport& rep) {
  const size_t nm = rep.mu.size();
  for (auto& t : rep.tables)
    for (size_t a = 0; a < rep.alpha.size(); ++a) t.eavg_quad[a] = eavg_by_midpoints(rep.mu, &t.E[a * nm]);
  for (auto& me : rep.models) me.eavg_quad = eavg_by_midpoints(rep.mu, me.E.data());
}

// The cells above the target standard error, and the largest error and where.
void track_largest_error(EnergyReport& rep) {
  auto consider = [&](const Cell& c, const std::string& where) {
    if (!(c.se <= rep.opt.target)) rep.above_target++;
    if (!(c.se <= rep.max_se)) {
      if (!std::isfinite(c.se) || c.se > rep.max_se) rep.max_se_at = where;
      rep.max_se = std::isfinite(c.se) ? c.se : std::numeric_limits<double>::infinity();
    }
  };
  const size_t nm = rep.mu.size();
  for (auto& t : rep.tables)
    for (size_t a = 0; a < rep.alpha.size(); ++a) {
      for (size_t m = 0; m < nm; ++m) {
        const size_t c = a * nm + m;
        const std::string w = fmt::format("{} alpha={:.4g} mu={:.4g}", t.name(), rep.alpha[a], rep.mu[m]);
        consider(t.E[c], "E " + w);
        consider(t.A[c], "A " + w);
        consider(t.B[c], "B " + w);
      }
      consider(t.eavg[a], fmt::format("E_avg {} alpha={:.4g}", t.name(), rep.alpha[a]));
    }
  for (auto& me : rep.models) {
    for (size_t m = 0; m < nm; ++m) consider(me.E[m], fmt::format("E {} mu_l={:.4g}", me.point.name, rep.mu[m]));
    consider(me.eavg, "E_avg " + me.point.name);
  }
}

// "D/G/F" or "model ID": what an integral integrates, for messages.
std::string subject_of(const IntegralSpec& s) {
  if (const Model* m = model_by_number(s.model)) return "model " + m->id;
  const auto& c = catalog();
  return c[size_t(s.d)].id + "/" + c[size_t(s.g)].id + "/" + c[size_t(s.f)].id;
}

// The double reference on the identical first samples of every k-th integral.
void compare_sample_with_reference(EnergyReport& rep, Integrator& in, const std::vector<Unit>& units) {
  const EnergyOptions& opt = rep.opt;
  std::vector<IntegralSpec> subset;
  size_t k = 0;
  for (auto& u : units)
    for (auto& s : specs_of(u, size_t(opt.replicates)))
      if (k++ % size_t(std::max(1, opt.reference_every)) == 0) {
        subset.push_back(s);
        if (s.check == static_cast<int32_t>(IntegralKind::AlbedoRqmc) && s.model == 0) {
          s.check = static_cast<int32_t>(IntegralKind::AlbedoRqmcB);  // and its B channel
          subset.push_back(s);
        }
      }
  in.stratify(subset, opt.min_points);  // E_avg's view cosines are spaced by the point count
  auto agree = compare_with_reference(in, subset, opt.reference_samples, opt.seed);
  for (size_t j = 0; j < agree.size(); ++j) {
    rep.reference_compared++;
    if (agree[j].disagreement <= rep.reference_worst) continue;
    rep.reference_worst = agree[j].disagreement;
    const ref::IntegralRef r = reference_of(subset[j]);
    rep.reference_worst_at = fmt::format("{} kind={} width={:g} cos_o={:g} stream={} (kernel {:.9g}, reference {:.9g})",
                                         subject_of(subset[j]), subset[j].check, r.width, r.cos_o, r.stream,
                                         agree[j].kernel_mean, agree[j].reference_mean);
  }
}

}  // namespace

EnergyReport run_energy(Runtime& rt, const EnergyOptions& opt) {
  validate_energy_options(opt);
  const auto t0 = std::chrono::steady_clock::now();
  EnergyReport rep;
  rep.opt = opt;
  rep.device = rt.device().name;
  rep.mu = energy_mu_grid(opt.n_mu);
  rep.alpha = energy_alpha_grid(opt.n_alpha);
  const size_t nm = size_t(opt.n_mu), na = size_t(opt.n_alpha), R = size_t(opt.replicates);
  const Term& none = find_term("none");

  TermSelection sel;
  for (auto [d, g] : table_pairs()) {
    if (!opt.tables || !wanted(opt.models, d->id + "/" + g->id)) continue;
    rep.tables.push_back(empty_table(*d, *g, rep.alpha, nm));
    if (std::find(sel.d.begin(), sel.d.end(), d) == sel.d.end()) sel.d.push_back(d);
    if (std::find(sel.g.begin(), sel.g.end(), g) == sel.g.end()) sel.g.push_back(g);
  }
  for (auto& mp : model_points_of(opt)) {
    ModelEnergy me;
    me.point = mp;
    me.E.resize(nm);
    me.points.assign(nm, 0);
    rep.models.push_back(me);
    if (std::find(sel.models.begin(), sel.models.end(), mp.model) == sel.models.end()) sel.models.push_back(mp.model);
  }
  if (rep.tables.empty() && rep.models.empty()) throw Error("no D/G combination or whole model selected");
  sel.f = {&none};

  const double b0 = rt.build_stats().seconds;
  Integrator in(rt, sel);
  rep.build_seconds = rt.build_stats().seconds - b0;

  // Units and their Philox streams (fixed across passes, so a pass with more
  // points extends the same shifted point sets).
  std::vector<Unit> units;
  uint32_t stream = 0;
  for (size_t ti = 0; ti < rep.tables.size(); ++ti) {
    const EnergyTable& t = rep.tables[ti];
    auto spec = [&](IntegralKind k, size_t a, double mu) {
      IntegralSpec s;
      s.check = static_cast<int32_t>(k);
      s.d = term_index(*t.d);
      s.g = term_index(*t.g);
      s.f = term_index(none);
      s.pd = float(t.pd[a]);
      s.pg = float(t.pg[a]);
      s.width = float(proposal_width(*t.d, rep.alpha[a]));
      s.cos_o = float(mu);
      return s;
    };
    for (size_t a = 0; a < na; ++a) {
      for (size_t m = 0; m < nm; ++m) {
        units.push_back({ti, a * nm + m, false, spec(IntegralKind::AlbedoRqmc, a, rep.mu[m]), stream});
        stream += uint32_t(R);
      }
      units.push_back({ti, a, true, spec(IntegralKind::EavgRqmc, a, 1.0), stream});
      stream += uint32_t(R);
    }
  }
  for (size_t mi = 0; mi < rep.models.size(); ++mi) {
    const ModelPoint& mp = rep.models[mi].point;
    for (size_t m = 0; m < nm; ++m) {
      units.push_back({mi, m, false, model_spec(IntegralKind::AlbedoRqmc, *mp.model, mp.p, rep.mu[m]), stream, true});
      stream += uint32_t(R);
    }
    units.push_back({mi, 0, true, model_spec(IntegralKind::EavgRqmc, *mp.model, mp.p, 1.0), stream, true});
    stream += uint32_t(R);
  }
  PilotThenFresh(rep, in, units).run(stream);

  add_quadrature_cross_check(rep);
  track_largest_error(rep);
  judge_model_gains(rep);
  if (opt.reference_samples > 0) compare_sample_with_reference(rep, in, units);

  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double run_s = std::max(1e-9, rep.seconds - rep.build_seconds);
  rep.samples_per_second = double(rep.samples) / run_s;
  return rep;
}

}  // namespace mfv
