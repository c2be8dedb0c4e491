#include "checks/energy_plan.hpp"

#include "checks/check_table.hpp"
#include "checks/integrate.hpp"
#include "checks/suite.hpp"
#include "abi/bsdf.h"
#include "catalog/bsdfs.hpp"
#include "catalog/roughness.hpp"
#include "util/error.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mfv {

std::vector<double> energy_mu_grid(int n) {
  std::vector<double> mu;
  for (int m = 0; m < n; ++m) mu.push_back((m + 0.5) / n);  // cell midpoints of (0, 1]
  return mu;
}

std::vector<double> energy_alpha_grid(int n) {
  std::vector<double> a;
  for (int j = 0; j < n; ++j) a.push_back(n == 1 ? 1.0 : std::pow(10.0, -3.0 + 3.0 * j / (n - 1)));
  return a;
}

double energy_min_alpha(const Term& d) {
  if (d.params.empty()) return 0;
  const Param& p = d.params[0];
  const double lo = alpha_from_native(d.roughness, p.lo), hi = alpha_from_native(d.roughness, p.hi);
  return std::min(lo, hi) > 0 ? std::min(lo, hi) : std::max(lo, hi);
}

std::string EnergyTable::name() const { return bsdf ? bsdf->id : d->id + "/" + g->id; }

double energy_eval_mu(double mu) { return std::max(mu, kEnergyMuFloor); }

double energy_eval_alpha(const Term& d, double alpha) { return std::max(alpha, energy_min_alpha(d)); }

std::vector<CellAt> EnergyReport::cells() const {
  std::vector<CellAt> out;
  if (paired)
    for (size_t i = 0; i < alpha.size(); ++i) out.push_back({i, i, i});
  else
    for (size_t a = 0; a < alpha.size(); ++a)
      for (size_t m = 0; m < mu.size(); ++m) out.push_back({a, m, a * mu.size() + m});
  return out;
}

void validate_energy_options(const EnergyOptions& o) {
  if (o.mu_axis.empty() != o.alpha_axis.empty()) throw Error("give both axes (--mu and --alpha), or neither");
  if (o.mu_axis.empty() && (o.n_mu < 2 || o.n_mu > 256 || o.n_alpha < 2 || o.n_alpha > 256))
    throw Error(fmt::format("--grid {}x{}: each side must be 2..256", o.n_mu, o.n_alpha));
  if (o.paired && o.mu_axis.size() != o.alpha_axis.size()) throw Error("points: as many mu as alpha values");
  if (!o.paired && o.mu_axis.size() * o.alpha_axis.size() > 65536)
    throw Error(fmt::format("{} x {} cells: at most 65536", o.mu_axis.size(), o.alpha_axis.size()));
  for (double m : o.mu_axis)
    if (!(m >= 0 && m <= 1)) throw Error(fmt::format("mu = {}: a view cosine must be in [0, 1]", m));
  for (double a : o.alpha_axis)
    if (!(a >= 0 && a <= 10)) throw Error(fmt::format("alpha = {}: must be in [0, 10]", a));
  if (!(o.target > 0) || !std::isfinite(o.target) || o.target >= 1)
    throw Error(fmt::format("--target {}: must be a standard error in (0, 1)", o.target));
  if (o.replicates < 2 || o.replicates > 256) throw Error(fmt::format("--replicates {}: must be 2..256", o.replicates));
  if (o.min_points < 64 || o.max_points < o.min_points || o.max_points > (uint64_t(1) << 24))
    throw Error(fmt::format("points per replicate {}..{}: need 64 <= min <= max <= 2^24", o.min_points, o.max_points));
  // Every filter must match something, or the user made a typo.
  for (auto& f : o.models) {
    bool hit = false;
    if (o.tables && !o.eta.empty())
      for (const Bsdf& b : bsdfs()) hit = hit || b.id.find(f) != std::string::npos;
    else if (o.tables)
      for (auto [d, g] : energy_table_pairs()) hit = hit || (d->id + "/" + g->id).find(f) != std::string::npos;
    if (o.catalog_models)
      for (auto& m : models())
        for (auto& c : m.cases) hit = hit || model_case_name(m, c).find(f) != std::string::npos;
    if (!hit)
      throw Error(fmt::format("--models '{}' matches no {} (see 'mfv list')", f,
                              o.eta.empty() ? "D/G combination or model[case]" : "rough dielectric BSDF"));
  }
  if (!o.eta.empty() && o.eta.size() != o.alpha_axis.size()) throw Error("internal: one eta per width");
  const Param& eta_range = bsdfs().front().eta;  // every BSDF declares the same range
  for (double e : o.eta)
    if (!(e >= eta_range.lo && e <= eta_range.hi) || e == 1)
      throw Error(fmt::format("eta = {}: a relative index in [{:g}, {:g}] (the BSDFs' declared range), not 1", e,
                              eta_range.lo, eta_range.hi));
  for (auto& mp : o.model_points)
    for (size_t i = 0; i < mp.model->params.size(); ++i) validate_model_param(*mp.model, i, mp.p[i]);
}

std::vector<std::pair<const Term*, const Term*>> energy_table_pairs() {
  std::vector<std::pair<const Term*, const Term*>> pairs;
  for (auto* d : terms_of(Kind::D))
    for (auto* g : terms_of(Kind::G)) pairs.push_back({d, g});
  for (auto* d : own_lobe_terms_of(Kind::D))
    for (auto* g : own_lobe_terms_of(Kind::G))
      if (g->fit_for(d->id)) pairs.push_back({d, g});
  return pairs;
}

namespace {

// The whole-model points a run integrates: catalog cases (filtered), then the caller's.
std::vector<ModelPoint> model_points_of(const EnergyOptions& opt) {
  std::vector<ModelPoint> out;
  if (opt.catalog_models)
    for (auto& m : models())
      for (auto& c : m.cases) {
        const std::string name = model_case_name(m, c);
        if (suite_model_wanted(opt.models, name)) out.push_back({&m, name, c.p, c.energy, c.energy_why});
      }
  out.insert(out.end(), opt.model_points.begin(), opt.model_points.end());
  return out;
}

// The table of D x G at every alpha of the grid, its cells not yet run.
EnergyTable empty_table(const Term& d, const Term& g, const std::vector<double>& alpha, size_t cells) {
  EnergyTable t;
  t.d = &d;
  t.g = &g;
  for (double a : alpha) {
    const NativeWidths w = native_widths(d, g, energy_eval_alpha(d, a));
    validate_param(d, 0, w.pd);
    t.pd.push_back(w.pd);
    t.pg.push_back(w.pg);
  }
  const size_t na = alpha.size();
  t.E.resize(cells);
  t.A = t.B = t.E;
  t.points.assign(cells, 0);
  t.eavg.resize(na);
  t.eavg_quad.resize(na);
  return t;
}

template <class T>
void add_once(std::vector<T>& v, T x) {
  if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
}

// The view cosines of a row: every mu of the grid (energy_mu), or the normal (energy_avg).
std::vector<double> row_views(const CheckRow& row, const std::vector<double>& mu) {
  return row.n_view > 0 ? mu : std::vector<double>{1.0};
}

// Appends a row's units of one table width or one model point, R streams each.
template <class SpecAt>
void add_row_units(std::vector<EnergyUnit>& units, const CheckRow& row, const std::vector<double>& mu, size_t table,
                   size_t first_index, bool model, size_t R, uint32_t& stream, SpecAt spec_at) {
  const bool eavg = row.kind == IntegralKind::EavgRqmc;
  const std::vector<double> views = row_views(row, mu);
  for (size_t m = 0; m < views.size(); ++m) {
    units.push_back(
        {table, eavg ? first_index : first_index + m, eavg, spec_at(row.kind, energy_eval_mu(views[m])), stream, model});
    stream += uint32_t(R);
  }
}

// A glass table's cells (rep.opt.eta per width): bsdf_furnace's integrand
// (IntegralKind::BsdfFlux, kernels/transmission.cl, as host/checks/suite_bsdf.cpp
// builds it) at each (eta, roughness, mu): E_R (MFV_LOBE_REFLECT) and E_T
// (MFV_LOBE_TRANSMIT) on the same streams, E = E_R + E_T on each replicate
// (energy.cpp record_unit): each lobe's integrand is smooth in the point set,
// where one over the whole sphere picks its side by a third coordinate (30x
// the replicate spread, measured at alpha = 0.39, eta = 2.17, mu = 0.375).
// eta < 1 is the light leaving: the fixed direction below, relative index 1/eta.
void glass_units(std::vector<EnergyUnit>& units, const EnergyReport& rep, size_t ti, size_t R, uint32_t& stream) {
  const EnergyTable& t = rep.tables[ti];
  const size_t nm = rep.mu.size();
  for (size_t a = 0; a < rep.alpha.size(); ++a) {
    const double eta = rep.opt.eta[a];
    for (size_t m = 0; m < nm; ++m) {
      MicrofacetIntegral mi;
      mi.kind = IntegralKind::BsdfFlux;
      mi.d = t.d, mi.g = t.g;
      mi.pd = t.pd[a], mi.pg = t.pg[a];
      mi.width = energy_eval_alpha(*t.d, rep.alpha[a]);
      mi.cos_o = energy_eval_mu(rep.mu[m]);
      IntegralSpec s = spec_of(mi);
      s.eta = float(eta > 1 ? eta : 1.0 / eta);
      s.side = eta > 1 ? MFV_SIDE_ABOVE : MFV_SIDE_BELOW;
      s.bsdf = t.bsdf->code();
      s.lobe = MFV_LOBE_REFLECT;
      EnergyUnit u{ti, a * nm + m, false, s, stream, false};
      u.has_second = true;
      u.second = s;
      u.second.lobe = MFV_LOBE_TRANSMIT;
      units.push_back(u);
      stream += uint32_t(R);
    }
  }
}

}  // namespace

TermSelection add_energy_subjects(EnergyReport& rep) {
  const EnergyOptions& opt = rep.opt;
  const size_t nm = rep.mu.size();
  TermSelection sel;
  if (!opt.eta.empty()) {  // a glass layout: the rough dielectric BSDFs, nothing else
    for (const Bsdf& b : bsdfs()) {
      if (!opt.tables || !suite_model_wanted(opt.models, b.id)) continue;
      rep.tables.push_back(empty_table(*b.d, *b.g, rep.alpha, rep.n_cells()));
      rep.tables.back().bsdf = &b;
      add_once(sel.d, b.d);
      add_once(sel.g, b.g);
    }
    if (rep.tables.empty()) throw Error("no rough dielectric BSDF selected");
    sel.f = {&find_term("none")};
    return sel;
  }
  for (auto [d, g] : energy_table_pairs()) {
    if (!opt.tables || !suite_model_wanted(opt.models, d->id + "/" + g->id)) continue;
    rep.tables.push_back(empty_table(*d, *g, rep.alpha, rep.n_cells()));
    add_once(sel.d, d);
    add_once(sel.g, g);
    sel.specialized.push_back({term_index(*d), term_index(*g)});  // its kernels per term pair (runtime/specialize.hpp)
  }
  for (auto& mp : model_points_of(opt)) {
    ModelEnergy me;
    me.point = mp;
    me.E.resize(nm);
    me.points.assign(nm, 0);
    rep.models.push_back(me);
    add_once(sel.models, mp.model);
  }
  if (rep.tables.empty() && rep.models.empty()) throw Error("no D/G combination or whole model selected");
  sel.f = {&find_term("none")};
  return sel;
}

std::vector<EnergyUnit> energy_units(const EnergyReport& rep, uint32_t& next_stream) {
  // Streams are fixed per unit, so a run with more points extends the same shifted point sets.
  const size_t nm = rep.mu.size(), R = size_t(rep.opt.replicates);
  const Term& none = find_term("none");
  std::vector<EnergyUnit> units;
  uint32_t stream = 0;
  for (size_t ti = 0; ti < rep.tables.size(); ++ti) {
    const EnergyTable& t = rep.tables[ti];
    if (t.bsdf) {
      glass_units(units, rep, ti, R, stream);
      continue;
    }
    for (size_t a = 0; a < rep.alpha.size(); ++a) {
      auto spec_at = [&](IntegralKind kind, double cos_o) {
        MicrofacetIntegral m;
        m.kind = kind;
        m.d = t.d, m.g = t.g, m.f = &none;
        m.pd = t.pd[a], m.pg = t.pg[a];
        m.width = proposal_width(*t.d, energy_eval_alpha(*t.d, rep.alpha[a]));
        m.cos_o = cos_o;
        return spec_of(m);
      };
      // a grid: every mu at this width; paired points: this point's mu
      const std::vector<double> mus = rep.paired ? std::vector<double>{rep.mu[a]} : rep.mu;
      for (const CheckRow& row : energy_check_rows())
        add_row_units(units, row, mus, ti, row.n_view > 0 && !rep.paired ? a * nm : a, false, R, stream, spec_at);
    }
  }
  for (size_t mi = 0; mi < rep.models.size(); ++mi) {
    const ModelPoint& mp = rep.models[mi].point;
    auto spec_at = [&](IntegralKind kind, double cos_o) { return model_spec(kind, *mp.model, mp.p, cos_o); };
    for (const CheckRow& row : energy_check_rows()) add_row_units(units, row, rep.mu, mi, 0, true, R, stream, spec_at);
  }
  next_stream = stream;
  return units;
}

std::vector<IntegralSpec> specs_of(const EnergyUnit& u, size_t R) {
  std::vector<IntegralSpec> v;
  for (const IntegralSpec* base : {&u.base, &u.second}) {
    if (base == &u.second && !u.has_second) break;
    for (size_t r = 0; r < R; ++r) {
      IntegralSpec s = *base;
      s.stream = u.first_stream + uint32_t(r);
      v.push_back(s);
    }
  }
  return v;
}

}  // namespace mfv
