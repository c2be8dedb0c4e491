#include "checks/furnace_truth.hpp"

#include "checks/integrate.hpp"

#include "numeric/hemisphere_quadrature.hpp"
#include "reference/brdf.hpp"
#include "runtime/program_cache.hpp"
#include "runtime/provenance.hpp"
#include "util/error.hpp"
#include "util/parallel.hpp"

#include <fmt/format.h>
#include <gnu/libc-version.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <string>
#include <tuple>

namespace mfv {
namespace {

// Three rules: order 12, 2 panels a decade in t = 1 - cos of the half
// vector's angle down to 1e-7 (the smallest width checked, alpha = 0.01,
// puts the lobe at t ~ alpha²/2 = 5e-5), 8 phi panels; the coarse ones order
// 10 and 8, 2 panels a decade, 4 phi panels. The error estimate is the larger
// of the fine rule's differences from the two: one difference alone can
// vanish by chance where the other does not. The phi panels are even: at
// grazing view the horizon cut t_c(phi) jumps at phi = pi/2, which must be a
// panel edge (3 panels read 3e-3 of error there at every width; 2 and 4 read
// below 2e-4). Against a rule of order 24, 4 panels a decade, 12 phi panels,
// over the 384 integrals of ggx/smith_ggx_correlated's default furnace: mean
// estimate 3.44e-6, mean actual error 1.71e-7 (the pooled test adds the mean
// estimate to its bias bound); the former pair (order 8 and 6, 2 and 4 phi
// panels) read 3.94e-5 against 3.58e-6 (tests/test_furnace_truth.cpp).
const ProductRule kFine{12, 2, 8, 1e-7}, kCoarse{10, 2, 4, 1e-7}, kCoarser{8, 2, 4, 1e-7};

glm::dvec3 view_of(double cos_o) { return {std::sqrt((1.0 - cos_o) * (1.0 + cos_o)), 0.0, cos_o}; }

KnownValue known_from(double fine, double coarse, double coarser) {
  return {fine, std::max(std::fabs(fine - coarse), std::fabs(fine - coarser))};
}

// One rule at one view: its nodes and the BRDF's shading at them, which every
// isotropic D x G x F at that view shares (ref::brdf forms the same Shading
// from the same i and o), and the terms' values at the nodes by (term, params).
class ViewRule {
 public:
  ViewRule(const glm::dvec3& o, const ProductRule& rule) : nodes_(reflected_nodes(o, rule)) {
    shading_.resize(nodes_.i.size());
    for (size_t k = 0; k < shading_.size(); ++k)
      if (nodes_.live[k]) shading_[k] = ref::shading_from(nodes_.i[k], o);
  }

  // ∫ f(i, o) (n·i) di by the rule: the same bits as integrate_reflected of
  // ref::brdf(s, i, o) * i.z (brdf.hpp: brdf_of_terms is brdf's own assembly).
  double albedo(const ref::BrdfSpec& s) {
    const std::vector<double>& D =
        values(d_, {s.d, s.pd, 0}, [&](const ref::Shading& c) { return ref::eval_d_iso(s, c); });
    const std::vector<double>& G =
        values(g_, {s.g, s.pg, 0}, [&](const ref::Shading& c) { return ref::eval_g_iso(s, c); });
    const std::vector<double>& F =
        values(f_, {s.f, s.f0, s.f1}, [&](const ref::Shading& c) { return s.f->ref_f(c.VoH, s.f0, s.f1); });
    std::vector<double> f(shading_.size(), 0.0);
    for (size_t k = 0; k < f.size(); ++k)
      if (nodes_.live[k]) f[k] = ref::brdf_of_terms(s, shading_[k], D[k], F[k], G[k]) * nodes_.i[k].z;
    return sum_reflected(nodes_, f);
  }

 private:
  using Key = std::tuple<const ref::TermTwins*, double, double>;
  using Cache = std::map<Key, std::vector<double>>;

  template <class Term>
  const std::vector<double>& values(Cache& cache, const Key& key, const Term& term) {
    auto it = cache.find(key);
    if (it != cache.end()) return it->second;
    std::vector<double> v(shading_.size(), 0.0);
    for (size_t k = 0; k < v.size(); ++k)
      if (nodes_.live[k]) v[k] = term(shading_[k]);
    return cache.emplace(key, std::move(v)).first->second;
  }

  ReflectedNodes nodes_;
  std::vector<ref::Shading> shading_;
  Cache d_, g_, f_;
};

// The specs the shared-node path takes: isotropic D x G x F, the view above the horizon.
bool shares_nodes(const ref::IntegralRef& r) {
  return !r.brdf.model && !r.brdf.aniso() && r.brdf.d && r.brdf.g && r.brdf.f && r.cos_o > 0 && r.phi_o == 0;
}

// The integrals `which` of `specs`, all at one view, into their slots of out.
void albedos_at_view(const std::vector<IntegralSpec>& specs, const std::vector<size_t>& which,
                     std::vector<KnownValue>& out) {
  const glm::dvec3 o = view_of(reference_of(specs[which.front()]).cos_o);
  ViewRule fine(o, kFine), coarse(o, kCoarse), coarser(o, kCoarser);
  for (size_t i : which) {
    const ref::IntegralRef r = reference_of(specs[i]);
    out[i] = known_from(fine.albedo(r.brdf), coarse.albedo(r.brdf), coarser.albedo(r.brdf));
  }
}

}  // namespace

KnownValue albedo_by_rules(const IntegralSpec& s, const RuleSet& rules) {
  const ref::IntegralRef r = reference_of(s);
  const glm::dvec3 o = view_of(r.cos_o);
  auto f = [&](const glm::dvec3& i) { return ref::brdf(r.brdf, i, o) * i.z; };
  return known_from(integrate_reflected(f, o, rules.fine).value, integrate_reflected(f, o, rules.coarse).value,
                    integrate_reflected(f, o, rules.coarser).value);
}

const RuleSet& furnace_rules() {
  static const RuleSet rules{kFine, kCoarse, kCoarser};
  return rules;
}

KnownValue albedo_by_quadrature(const IntegralSpec& s) { return albedo_by_rules(s, furnace_rules()); }

std::vector<KnownValue> albedos_by_quadrature(const std::vector<IntegralSpec>& specs, unsigned threads) {
  std::vector<KnownValue> out(specs.size());
  // the work: one unit per view (sharing its nodes), one per other spec
  std::map<double, std::vector<size_t>> by_view;
  std::vector<size_t> alone;
  for (size_t i = 0; i < specs.size(); ++i) {
    const ref::IntegralRef r = reference_of(specs[i]);
    if (shares_nodes(r))
      by_view[r.cos_o].push_back(i);
    else
      alone.push_back(i);
  }
  std::vector<std::vector<size_t>> units;
  for (auto& [cos_o, which] : by_view) units.push_back(which);
  for (size_t i : alone) units.push_back({i});
  // each unit writes its own slots: the values do not depend on the thread count
  parallel_for(units.size(), threads, [&](size_t u) {
    if (units[u].size() == 1 && !shares_nodes(reference_of(specs[units[u][0]])))
      out[units[u][0]] = albedo_by_quadrature(specs[units[u][0]]);
    else
      albedos_at_view(specs, units[u], out);
  });
  return out;
}

namespace {

// The running executable's SHA-256 ("" where /proc/self/exe cannot be read).
const std::string& executable_digest() {
  static const std::string digest = [] {
    std::ifstream in("/proc/self/exe", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return in.bad() || bytes.empty() ? std::string() : sha256_hex(bytes);
  }();
  return digest;
}

std::string rule_text(const ProductRule& r) {
  return fmt::format("{} {} {} {:a}", r.order, r.per_decade, r.phi_panels, r.t_min);
}

static_assert(sizeof(KnownValue) == 2 * sizeof(double), "KnownValue: stored as its bytes");

}  // namespace

std::string truth_cache_key(const std::vector<IntegralSpec>& specs) {
  // a test's plant (plant_reference_term) changes the values but not the executable
  if (executable_digest().empty() || reference_planted()) return "";
  const RuleSet& r = furnace_rules();
  std::string bytes;
  for (IntegralSpec s : specs) {
    s.stream = s.stream_hi = 0;  // the stream draws samples; the truth does not read it
    bytes.append(reinterpret_cast<const char*>(&s), sizeof s);
  }
  // Length-prefixed fields, so no two different keys concatenate alike (as ProgramCache::key).
  std::string k;
  for (const std::string& f :
       {std::string("mfv-furnace-truth-1"), executable_digest(), std::string(gnu_get_libc_version()), rule_text(r.fine),
        rule_text(r.coarse), rule_text(r.coarser), bytes})
    k += std::to_string(f.size()) + ":" + f + ";";
  return sha256_hex(k);
}

std::string truth_cache_dir() {
  const char* v = std::getenv("MFV_TRUTH_CACHE");
  const std::string on = v ? v : "";
  if (!on.empty() && on != "0" && on != "1")
    throw Error(fmt::format("MFV_TRUTH_CACHE={}: expected 0 (off) or 1 (on, the default)", on));
  const std::string folder = ProgramCache::cache_folder();
  return on == "0" || folder.empty() ? "" : folder + "/furnace-truth";
}

std::vector<KnownValue> stored_albedos_by_quadrature(const std::vector<IntegralSpec>& specs, unsigned threads,
                                                     const std::string& dir) {
  const ProgramCache disk(dir);
  const std::string key = disk.enabled() && !specs.empty() ? truth_cache_key(specs) : "";
  const size_t size = specs.size() * sizeof(KnownValue);
  if (!key.empty())
    if (const auto bytes = disk.load(key); bytes && bytes->size() == size) {
      std::vector<KnownValue> out(specs.size());
      std::memcpy(out.data(), bytes->data(), size);
      return out;
    }
  std::vector<KnownValue> out = albedos_by_quadrature(specs, threads);
  if (!key.empty()) {
    const auto* p = reinterpret_cast<const unsigned char*>(out.data());
    disk.store(key, std::vector<unsigned char>(p, p + size));
  }
  return out;
}

namespace {

// The quadratures of a process, by the spec's bytes less its stream: a
// process that runs the suite under many seeds (the tests) computes each once.
std::mutex cache_lock;
std::map<std::string, KnownValue> cache;

std::string cache_key(IntegralSpec s) {
  s.stream = 0;
  return std::string(reinterpret_cast<const char*>(&s), sizeof s);
}

}  // namespace

KnownValue cached_albedo_by_quadrature(const IntegralSpec& s) {
  {
    std::lock_guard<std::mutex> g(cache_lock);
    auto it = cache.find(cache_key(s));
    if (it != cache.end()) return it->second;
  }
  const KnownValue v = albedo_by_quadrature(s);
  std::lock_guard<std::mutex> g(cache_lock);
  return cache.emplace(cache_key(s), v).first->second;
}

void attach_furnace_truth(Plan& plan) {
  constexpr double kMaxTruthError = 1e-3;
  // Every isotropic point that must hold, less those the process knows.
  std::vector<size_t> todo, missing;
  std::vector<IntegralSpec> specs;
  {
    std::lock_guard<std::mutex> g(cache_lock);
    for (size_t i = 0; i < plan.points.size(); ++i)
      if (plan.points[i].expect == Expect::Hold && !(plan.specs[i].pd2 > 0) && plan.specs[i].phi_o == 0) {
        todo.push_back(i);
        if (!cache.count(cache_key(plan.specs[i]))) missing.push_back(i), specs.push_back(plan.specs[i]);
      }
  }
  // across runs from disk: the default run's 15151 integrals take ~10 s of one core (docs/performance.md)
  const std::vector<KnownValue> computed = stored_albedos_by_quadrature(specs, host_threads(), truth_cache_dir());
  std::lock_guard<std::mutex> g(cache_lock);
  for (size_t k = 0; k < missing.size(); ++k) cache.emplace(cache_key(plan.specs[missing[k]]), computed[k]);
  for (size_t i : todo) {
    const KnownValue& v = cache.at(cache_key(plan.specs[i]));
    PointResult& p = plan.points[i];
    // A value known to worse than kMaxTruthError adds more bias bound to
    // the pool than information (an integral's SE is ~1.7e-2 at default
    // samples): such points stay out of it (none in the catalog today:
    // the worst estimate is 2e-4).
    p.known = std::isfinite(v.value) && v.error <= kMaxTruthError;
    p.known_value = v.value;
    p.known_error = v.error;
  }
}

}  // namespace mfv
