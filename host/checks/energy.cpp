// mfv energy (checks/energy.hpp), a caller of its plan: the tables and
// models and their integrals (energy_plan.hpp, from the check table's
// energy rows), run pilot-then-fresh here, judged in energy_judge.hpp, and a
// sample compared with the double reference.
#include "checks/energy.hpp"

#include "checks/energy_judge.hpp"
#include "checks/energy_plan.hpp"
#include "checks/integrate.hpp"
#include "reference/estimators.hpp"
#include "runtime/dispatch.hpp"
#include "stats/normal.hpp"
#include "util/error.hpp"
#include "util/progress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

namespace mfv {

namespace {

Cell replicate_stats(const std::vector<double>& v) {
  const double n = double(v.size());
  double s = 0;
  for (double x : v) s += x;
  const double mean = s / n;
  double ss = 0;
  for (double x : v) ss += (x - mean) * (x - mean);
  return {mean, std::sqrt(ss / (n - 1) / n)};
}

// Records a unit's cells from its per-replicate sums over `done` points;
// returns the largest standard error among them.
double record_unit(EnergyReport& rep, const EnergyUnit& u, const std::vector<double>& sum,
                   const std::vector<double>& b_sum, uint64_t done) {
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
    // a glass cell: E_R and E_T integrated apart (glass_units), E their sum on each replicate
    if (u.has_second) a[r] = e[r], e[r] += b[r];
  }
  t.E[u.index] = replicate_stats(e);
  t.A[u.index] = replicate_stats(a);
  t.B[u.index] = replicate_stats(b);
  t.points[u.index] = done;
  return std::max({t.E[u.index].se, t.A[u.index].se, t.B[u.index].se});
}

// Pilot, then fresh samples. Each unit's estimate is a fresh run of a
// power-of-two multiple of min_points fixed before its samples are drawn, up
// to max_points. Stopping on the estimate's own standard error (the former
// adaptive passes) keeps the runs whose error happened to come out small: 5
// of 96 EON cells were beyond 3 SE, worst 5.4. With the count fixed first,
// mean and replicate SE are those of a fixed-size RQMC estimate, so the SE
// is unbiased.
// The count comes from pilots on streams of their own: one of P0 =
// max(64, min_points / 4) points per replicate and, where that predicts more
// than 64 P0 points, a second at 1/16 of the prediction, P1 >= 4 P0. The
// error's rate N^-b is measured between the two pilots (b = log(se0/se1) /
// log(P1/P0), clamped to [1/2, 1]: RQMC's N^-1 on smooth integrands, Monte
// Carlo's N^-1/2 at worst) and extrapolates the second pilot's error to
// target / m, m = sqrt(chi²_{R-1}(1 - 0.05/U) / (R-1)) over U units: the
// replicate SE scatters about the true one as a chi with R - 1 degrees of
// freedom, so where every unit's true SE is target / m, all U report at
// most the target with probability 0.95 (Bonferroni; m = 1.79 at R = 8 and
// U = 24, 1.37 at R = 32). With one pilot at 256 points and b = 1 assumed,
// 6 of 48 values of the 12-point --fp64 query at 2e-6 ended above it
// (worst 5.2e-6, E_avg at alpha = 0.16: 256 points predicted its error at
// 65536 points 3x low); docs/performance.md.
class PilotThenFresh {
 public:
  // `family`: the units of the whole plan (a shard runs some of them)
  PilotThenFresh(EnergyReport& rep, Integrator& in, const std::vector<EnergyUnit>& units, size_t family)
      : rep_(rep), in_(in), units_(units), family_(family), prog_(units.size()) {}

  // Each unit's reported run.
  std::vector<EnergyUnitResult> results() const {
    std::vector<EnergyUnitResult> v;
    for (auto& p : prog_) v.push_back({p.sum, p.b_sum, p.done});
    return v;
  }

  // The pilots on streams past every unit's own (from `free_stream` and
  // 2 `free_stream` on), then the fresh run on the units' own streams.
  void run(uint32_t free_stream) {
    const EnergyOptions& opt = rep_.opt;
    const double dof = double(opt.replicates - 1);
    const double tail = 0.05 / double(std::max<size_t>(1, family_));  // every unit at once
    const double margin = std::sqrt(stats::chi_squared_upper_quantile(tail, dof) / dof);
    const uint64_t p0 = std::max<uint64_t>(64, opt.min_points / 4);
    rate_.assign(units_.size(), 1.0);
    for (auto& p : prog_) p.want = p0;
    const std::vector<double> se0 = run_units(free_stream);
    std::vector<uint64_t> done0(units_.size());
    for (size_t ui = 0; ui < units_.size(); ++ui) {
      Progress& p = prog_[ui];
      done0[ui] = p.done;
      const double need = points_for(double(p.done), se0[ui], 1.0, margin);
      uint64_t p1 = p0;
      while (double(p1) * 16 < need && p1 * 32 <= opt.max_points) p1 *= 2;
      p.want = p1 >= 4 * p0 ? p1 : 0;  // 0: no second pilot
    }
    const std::vector<double> se1 = run_units(2 * free_stream);
    for (size_t ui = 0; ui < units_.size(); ++ui) {
      Progress& p = prog_[ui];
      double base = double(done0[ui]), se = se0[ui], rate = 1.0;
      if (p.want > 0) {
        rate = std::log(se0[ui] / se1[ui]) / std::log(double(p.done) / base);
        rate = std::isnan(rate) ? 1.0 : std::clamp(rate, 0.5, 1.0);
        base = double(p.done), se = se1[ui];
      }
      rate_[ui] = rate;
      const double need = points_for(base, se, rate, margin);
      uint64_t want = opt.min_points;
      while (want < opt.max_points && double(want) < need) want *= 2;
      p.want = std::min<uint64_t>(want, opt.max_points);
    }
    const std::vector<double> se2 = run_units(0);
    // The top-up: a unit whose fresh run still ended above the target (the
    // margin aims at none with probability 0.95) is run once more, fresh, on
    // streams of its own (3 free_stream on) at a count sized from that run's
    // error (at least twice its count), and that run replaces it. Not pooled:
    // the reported run's count is fixed before its samples are drawn, so its
    // mean and replicate SE are a fixed-size RQMC estimate's. A kept run was
    // selected on its SE only through the event SE <= target, of probability
    // 1 - p >= 1 - 0.05/U per unit, so any tail probability of its deviation
    // over SE rises by at most the factor 1/(1 - p) (1.00005 at U = 1024).
    for (size_t ui = 0; ui < units_.size(); ++ui) {
      Progress& p = prog_[ui];
      uint64_t want = 0;
      if (se2[ui] > opt.target && p.want < opt.max_points) {
        const double need = points_for(double(p.done), se2[ui], rate_[ui], margin);
        want = 2 * p.want;
        while (want < opt.max_points && double(want) < need * double(p.want) / double(p.done)) want *= 2;
        want = std::min<uint64_t>(want, opt.max_points);
        ++rep_.topped_up;
      }
      p.want = want;
    }
    run_units(3 * free_stream);
  }

 private:
  struct Progress {
    uint64_t done = 0, want = 0;
    std::vector<double> sum, b_sum;  // per replicate: sums of the E (or E_avg) and B values
  };

  // The points per replicate that bring an error `se` at `base` points,
  // falling as N^-rate, to target / margin (0 where se is 0 or not finite).
  double points_for(double base, double se, double rate, double margin) const {
    if (!(se > 0) || !std::isfinite(se)) return 0.0;
    return base * std::pow(margin * se / rep_.opt.target, 1.0 / rate);
  }

  // Runs every unit at its `want` points (none where want is 0) on streams
  // first_stream + shift + r and records its cells; returns each unit's
  // largest standard error.
  std::vector<double> run_units(uint32_t shift) {
    const size_t R = size_t(rep_.opt.replicates);
    std::vector<double> worst(units_.size(), 0.0);
    std::map<uint64_t, std::vector<size_t>> passes;  // one pass per point count
    for (size_t ui = 0; ui < units_.size(); ++ui)
      if (prog_[ui].want > 0) passes[prog_[ui].want].push_back(ui);
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
      // the points each replicate took (a BsdfFlux replicate: 5·2^k of them, Integrator::mis_points)
      const uint64_t used = specs.empty() || est.empty() ? in_.samples_used(want) : est.front().samples;
      rep_.samples += used * specs.size();
      for (size_t k = 0; k < group.size(); ++k) {
        Progress& p = prog_[group[k]];
        p.sum.assign(R, 0.0);
        p.b_sum.assign(R, 0.0);
        for (size_t r = 0; r < R; ++r) {
          p.sum[r] = est[offset[k] + r].mean * double(used);
          // B: the albedo's second channel, or a glass cell's E_T (its second integral)
          p.b_sum[r] = (units_[group[k]].has_second ? est[offset[k] + R + r].mean : est[offset[k] + r].b_mean) *
                       double(used);
        }
        p.done = used;
        worst[group[k]] = record_unit(rep_, units_[group[k]], p.sum, p.b_sum, p.done);
      }
    }
    return worst;
  }

  EnergyReport& rep_;
  Integrator& in_;
  const std::vector<EnergyUnit>& units_;
  size_t family_;
  std::vector<Progress> prog_;
  std::vector<double> rate_;  // per unit: the error's measured rate b in N^-b
};

// The integration program in double (MFV_DOUBLE, mfv energy --fp64): every
// point's value in float64, summed in double. Integrator(rt, program) without
// the fast paths, whose value buffers are float: the general `integrate`
// kernel computes and sums each value in `real`.
cl::Program build_energy_fp64_program(Runtime& rt, const TermSelection& sel) {
  return rt.build(integrate_sources(), {"MFV_DOUBLE", "MFV_ACC_DOUBLE"}, generate_dispatch(sel), kDispatchBefore);
}

// "D/G/F" or "model ID": what an integral integrates, for messages.
std::string subject_of(const IntegralSpec& s) {
  if (const Model* m = model_by_number(s.model)) return "model " + m->id;
  const auto& c = catalog();
  return c[size_t(s.d)].id + "/" + c[size_t(s.g)].id + "/" + c[size_t(s.f)].id;
}

// The double reference on the identical first samples of every k-th integral.
// Picked over the whole plan's units; a part compares those of its units [lo, hi).
void compare_sample_with_reference(EnergyReport& rep, Integrator& in, const std::vector<EnergyUnit>& units,
                                   bool fp64, size_t lo, size_t hi) {
  const EnergyOptions& opt = rep.opt;
  std::vector<IntegralSpec> subset;
  size_t k = 0;
  for (size_t ui = 0; ui < units.size(); ++ui)
    for (auto& s : specs_of(units[ui], size_t(opt.replicates)))
      if (k++ % size_t(std::max(1, opt.reference_every)) == 0 && ui >= lo && ui < hi) {
        subset.push_back(s);
        if (s.check == static_cast<int32_t>(IntegralKind::AlbedoRqmc) && s.model == 0) {
          s.check = static_cast<int32_t>(IntegralKind::AlbedoRqmcB);  // and its B channel
          subset.push_back(s);
        }
      }
  in.stratify(subset, opt.min_points);  // E_avg's view cosines are spaced by the point count
  auto agree =
      fp64 ? agreement_with_reference(
                 subset, program_sample_values<double>(in.runtime(), in.program(), subset, opt.reference_samples, opt.seed),
                 opt.reference_samples, opt.seed)
           : compare_with_reference(in, subset, opt.reference_samples, opt.seed);
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


// rep's axes, tables and models as opt selects them (cells not yet run).
TermSelection init_report(EnergyReport& rep, const EnergyOptions& opt) {
  validate_energy_options(opt);
  rep.opt = opt;
  rep.mu = opt.mu_axis.empty() ? energy_mu_grid(opt.n_mu) : opt.mu_axis;
  rep.alpha = opt.alpha_axis.empty() ? energy_alpha_grid(opt.n_alpha) : opt.alpha_axis;
  rep.paired = opt.paired;
  rep.midpoint_mu = !rep.paired && rep.mu == energy_mu_grid(int(rep.mu.size()));
  return add_energy_subjects(rep);
}

// What follows the cells' runs: cross-checks, largest error, model gains.
void finish_cells(EnergyReport& rep) {
  if (rep.midpoint_mu) add_quadrature_cross_check(rep);
  // a glass table's E_avg: the midpoint rule over its mu cells, with the rule's error (energy_judge.hpp)
  for (EnergyTable& t : rep.tables)
    if (t.bsdf) t.eavg = t.eavg_quad;
  track_largest_error(rep);
  judge_model_gains(rep);
}

}  // namespace

EnergyPlanSummary energy_plan_summary(const EnergyOptions& opt) {
  EnergyReport rep;
  init_report(rep, opt);
  uint32_t free_stream = 0;
  const std::vector<EnergyUnit> units = energy_units(rep, free_stream);
  EnergyPlanSummary s;
  PlanDigest d;
  const size_t R = size_t(opt.replicates);
  for (auto& u : units) {
    const std::vector<IntegralSpec> specs = specs_of(u, R);
    s.cost.push_back(specs.size());
    for (auto& sp : specs) d.bytes(&sp, sizeof sp);
    d.value(u.table), d.value(u.index), d.value(u.eavg), d.value(u.model);
  }
  for (auto& t : rep.tables) d.text(t.name());
  for (auto& m : rep.models) d.text(m.point.name);
  d.doubles(rep.mu), d.doubles(rep.alpha), d.doubles(opt.eta), d.doubles(opt.roughness);
  d.value(free_stream), d.value(opt.paired), d.value(opt.fp64), d.value(opt.target), d.value(opt.gain_alpha);
  d.value(opt.replicates), d.value(opt.min_points), d.value(opt.max_points);
  d.value(opt.reference_samples), d.value(opt.reference_every);
  d.text(opt.layout);
  s.hash = d.hex();
  return s;
}

EnergyReport merge_energy(const EnergyOptions& opt, const std::string& device, const std::vector<EnergyPart>& parts) {
  EnergyReport rep;
  init_report(rep, opt);
  rep.device = device;
  uint32_t free_stream = 0;
  const std::vector<EnergyUnit> units = energy_units(rep, free_stream);
  size_t next = 0;
  for (size_t k = 0; k < parts.size(); ++k) {
    const EnergyPart& p = parts[k];
    if (p.lo != next || p.hi < p.lo || p.hi > units.size() || p.results.size() != p.hi - p.lo)
      throw Error(fmt::format("part {} holds units [{}, {}) with {} results; the plan's next unit is {} of {}", k + 1,
                              p.lo, p.hi, p.results.size(), next, units.size()));
    for (size_t i = 0; i < p.results.size(); ++i) {
      const EnergyUnitResult& r = p.results[i];
      if (r.sum.size() != size_t(opt.replicates) || r.b_sum.size() != r.sum.size() || r.done == 0)
        throw Error(fmt::format("part {}: unit {} has {} replicates, the plan {}", k + 1, p.lo + i, r.sum.size(),
                                opt.replicates));
      record_unit(rep, units[p.lo + i], r.sum, r.b_sum, r.done);
    }
    next = p.hi;
    rep.samples += p.samples;
    rep.topped_up += p.topped_up;
    rep.reference_compared += p.reference_compared;
    if (p.reference_worst > rep.reference_worst) {  // the first of the largest, as the whole run keeps it
      rep.reference_worst = p.reference_worst;
      rep.reference_worst_at = p.reference_worst_at;
    }
    rep.seconds += p.seconds;
    rep.build_seconds += p.build_seconds;
  }
  if (next != units.size())
    throw Error(fmt::format("the parts hold units [0, {}) of the plan's {}", next, units.size()));
  finish_cells(rep);
  rep.samples_per_second = double(rep.samples) / std::max(1e-9, rep.seconds - rep.build_seconds);
  return rep;
}

EnergyReport run_energy(Runtime& rt, const EnergyOptions& opt, EnergyPart* part) {
  const auto t0 = std::chrono::steady_clock::now();
  EnergyReport rep;
  const TermSelection sel = init_report(rep, opt);
  rep.device = rt.device().name;
  if (opt.fp64 && !rt.device().fp64)
    throw Error(fmt::format("--fp64: device '{}' has no cl_khr_fp64; run without --fp64 (float32 kernels) or pick "
                            "a device with it (mfv list-devices)",
                            rt.device().name));
  const double b0 = rt.build_stats().seconds;
  Integrator in = opt.fp64 ? Integrator(rt, build_energy_fp64_program(rt, sel)) : Integrator(rt, sel);
  in.set_mis_replicates(1);  // a glass cell's BsdfFlux: each of the R streams one RQMC replicate
  rep.build_seconds = rt.build_stats().seconds - b0;

  uint32_t stream = 0;
  const std::vector<EnergyUnit> units = energy_units(rep, stream);
  const size_t lo = part ? std::min(part->lo, units.size()) : 0;
  const size_t hi = part ? std::min(std::max(part->hi, lo), units.size()) : units.size();
  const std::vector<EnergyUnit> mine(units.begin() + long(lo), units.begin() + long(hi));
  PilotThenFresh run(rep, in, mine, units.size());
  run.run(stream);

  if (!part) finish_cells(rep);
  if (opt.reference_samples > 0) compare_sample_with_reference(rep, in, units, opt.fp64, lo, hi);

  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double run_s = std::max(1e-9, rep.seconds - rep.build_seconds);
  rep.samples_per_second = double(rep.samples) / run_s;
  if (part) {
    part->results = run.results();
    part->samples = rep.samples;
    part->topped_up = rep.topped_up;
    part->reference_compared = rep.reference_compared;
    part->reference_worst = rep.reference_worst;
    part->reference_worst_at = rep.reference_worst_at;
    part->seconds = rep.seconds;
    part->build_seconds = rep.build_seconds;
  }
  return rep;
}

}  // namespace mfv
