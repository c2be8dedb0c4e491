#include "checks/furnace_truth.hpp"

#include "checks/furnace_views.hpp"
#include "checks/integrate.hpp"
#include "checks/registry.hpp"

#include "numeric/hemisphere_quadrature.hpp"
#include "reference/brdf.hpp"
#include "runtime/program_cache.hpp"
#include "runtime/provenance.hpp"
#include "util/error.hpp"
#include "util/parallel.hpp"

#include <fmt/format.h>
#include <gnu/libc-version.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>

namespace mfv {
namespace {

// Three rules: order 12, 1 panel a decade in t = 1 - cos of the half
// vector's angle down to 1e-7 (the smallest width checked, alpha = 0.01,
// puts the lobe at t ~ alpha²/2 = 5e-5), 8 phi panels; the coarse ones order
// 10 and 8, 2 panels a decade, 4 phi panels. The error estimate is the larger
// of the fine rule's differences from the two: one difference alone can
// vanish by chance where the other does not. The phi panels are even: at
// grazing view the horizon cut t_c(phi) jumps at phi = pi/2, which must be a
// panel edge (3 panels read 3e-3 of error there at every width; 2 and 4 read
// below 2e-4). Against a rule of order 24, 4 panels a decade, 12 phi panels,
// over every 8th of ggx/smith_ggx_correlated's 384 default furnace integrals:
// mean estimate 3.61e-6, mean actual error 2.42e-7 (beckmann/smith_beckmann:
// 3.21e-6, 4.74e-7); the pooled test adds the mean estimate to its bias
// bound. The error lies in phi, not in t: with 2 panels a decade the fine
// rule read 3.59e-6 and 2.0e-7 (beckmann 3.02e-6, 8.3e-8) with 34560 nodes a
// view against 18432 (the three rules 54240 against 38112; issue 30: the
// truth is a cold run's host CPU). The former pair (order 8
// and 6, 2 and 4 phi panels) read 3.94e-5 against 3.58e-6
// (tests/test_furnace_truth.cpp).
const ProductRule kFine{12, 1, 8, 1e-7}, kCoarse{10, 2, 4, 1e-7}, kCoarser{8, 2, 4, 1e-7};

glm::dvec3 view_of(double cos_o) { return {std::sqrt((1.0 - cos_o) * (1.0 + cos_o)), 0.0, cos_o}; }

KnownValue known_from(double fine, double coarse, double coarser) {
  return {fine, std::max(std::fabs(fine - coarse), std::fabs(fine - coarser))};
}

// The specs the shared-node path takes: isotropic D x G x F, the view above the horizon.
bool shares_nodes(const ref::IntegralRef& r) {
  return !r.brdf.model && !r.brdf.aniso() && r.brdf.d && r.brdf.g && r.brdf.f && r.cos_o > 0 && r.phi_o == 0;
}

// The integrals `which` of `specs`, all at one view, into their slots of out.
void albedos_at_view(const std::vector<IntegralSpec>& specs, const std::vector<size_t>& which,
                     std::vector<KnownValue>& out) {
  const glm::dvec3 o = view_of(reference_of(specs[which.front()]).cos_o);
  std::vector<ref::BrdfSpec> brdfs;
  for (size_t i : which) brdfs.push_back(reference_of(specs[i]).brdf);
  const std::vector<double> fine = albedos_at_view(o, kFine, brdfs), coarse = albedos_at_view(o, kCoarse, brdfs),
                            coarser = albedos_at_view(o, kCoarser, brdfs);
  for (size_t q = 0; q < which.size(); ++q) out[which[q]] = known_from(fine[q], coarse[q], coarser[q]);
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

namespace {

// The work of albedos_by_quadrature: one unit per view (sharing its nodes),
// one per other spec; each unit writes its own slots of `out`, so the values
// do not depend on which thread runs which unit.
struct Quadratures {
  explicit Quadratures(const std::vector<IntegralSpec>& s) : specs(s), out(s.size()) {
    std::map<double, std::vector<size_t>> by_view;
    std::vector<size_t> alone;
    for (size_t i = 0; i < specs.size(); ++i) {
      const ref::IntegralRef r = reference_of(specs[i]);
      if (shares_nodes(r))
        by_view[r.cos_o].push_back(i);
      else
        alone.push_back(i);
    }
    for (auto& [cos_o, which] : by_view) units.push_back(which);
    for (size_t i : alone) units.push_back({i});
  }
  void run(size_t u) {
    if (units[u].size() == 1 && !shares_nodes(reference_of(specs[units[u][0]])))
      out[units[u][0]] = albedo_by_quadrature(specs[units[u][0]]);
    else
      albedos_at_view(specs, units[u], out);
  }
  // Runs the units no one has taken, until none is left or `stop` is set;
  // true where this call ran the last one to end.
  bool take_until(const std::atomic<bool>& stop) {
    bool last = false;
    for (size_t u; !stop && (u = next++) < units.size();) {
      run(u);
      last = ++done == units.size();
    }
    return last;
  }

  const std::vector<IntegralSpec> specs;
  std::vector<std::vector<size_t>> units;
  std::vector<KnownValue> out;
  std::atomic<size_t> next{0}, done{0};
};

}  // namespace

std::vector<KnownValue> albedos_by_quadrature(const std::vector<IntegralSpec>& specs, unsigned threads) {
  Quadratures q(specs);
  parallel_for(q.units.size(), threads, [&](size_t u) { q.run(u); });
  return std::move(q.out);
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

namespace {

// The truths of `specs` from `dir` where its entry checks out ("": none);
// `key` is set to the entry's key ("" where none is kept).
std::optional<std::vector<KnownValue>> load_truths(const std::vector<IntegralSpec>& specs, const std::string& dir,
                                                   std::string& key) {
  const ProgramCache disk(dir);
  key = disk.enabled() && !specs.empty() ? truth_cache_key(specs) : "";
  const size_t size = specs.size() * sizeof(KnownValue);
  if (!key.empty())
    if (const auto bytes = disk.load(key); bytes && bytes->size() == size) {
      std::vector<KnownValue> out(specs.size());
      std::memcpy(out.data(), bytes->data(), size);
      return out;
    }
  return std::nullopt;
}

void store_truths(const std::vector<KnownValue>& values, const std::string& dir, const std::string& key) {
  if (key.empty()) return;
  const auto* p = reinterpret_cast<const unsigned char*>(values.data());
  ProgramCache(dir).store(key, std::vector<unsigned char>(p, p + values.size() * sizeof(KnownValue)));
}

}  // namespace

std::vector<KnownValue> stored_albedos_by_quadrature(const std::vector<IntegralSpec>& specs, unsigned threads,
                                                     const std::string& dir) {
  std::string key;
  if (auto loaded = load_truths(specs, dir, key)) return std::move(*loaded);
  std::vector<KnownValue> out = albedos_by_quadrature(specs, threads);
  store_truths(out, dir, key);
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

namespace {

// The points attach_furnace_truth gives a truth: isotropic, that must hold.
bool takes_truth(const PointResult& p, const IntegralSpec& s) {
  return p.expect == Expect::Hold && !(s.pd2 > 0) && s.phi_o == 0;
}

// The specs of `n` points that take a truth the process does not know yet,
// nor `also_known` (cache_lock held): as attach_furnace_truth has always
// listed them, so that the disk key (truth_cache_key) is the same.
std::vector<IntegralSpec> unknown_specs(const IntegralSpec* specs, const PointResult* points, size_t n,
                                        const std::set<std::string>& also_known = {}) {
  std::vector<IntegralSpec> out;
  for (size_t i = 0; i < n; ++i)
    if (takes_truth(points[i], specs[i]) && !cache.count(cache_key(specs[i])) && !also_known.count(cache_key(specs[i])))
      out.push_back(specs[i]);
  return out;
}

// FurnaceTruthAhead's computation: one at a time in a process. The thread
// loads or computes the plans' truths in order; a plan's quadratures are
// published in `job` while they run, so that attach_furnace_truth, arriving
// before they end, takes the units left beside the thread.
struct Background {
  std::vector<std::vector<IntegralSpec>> specs;  // per truth plan, in plan order
  std::vector<std::vector<KnownValue>> values;
  std::string dir;
  std::mutex lock;
  std::condition_variable changed;  // job or finished set, a job's last unit done, stop set
  std::shared_ptr<Quadratures> job;
  bool finished = false;
  std::atomic<bool> stop{false};
  std::exception_ptr error;
  std::thread thread;

  void notify() {
    std::lock_guard<std::mutex> g(lock);
    changed.notify_all();
  }
  // The thread's work.
  void compute() {
    try {
      for (const std::vector<IntegralSpec>& s : specs) {
        std::string key;
        if (auto loaded = load_truths(s, dir, key)) {
          values.push_back(std::move(*loaded));
          continue;
        }
        auto q = std::make_shared<Quadratures>(s);
        {
          std::lock_guard<std::mutex> g(lock);
          job = q;
          changed.notify_all();
        }
        if (q->take_until(stop)) notify();
        {
          std::unique_lock<std::mutex> g(lock);
          changed.wait(g, [&] { return stop || q->done == q->units.size(); });
          job.reset();
        }
        if (stop) return finish();
        store_truths(q->out, dir, key);
        values.push_back(std::move(q->out));
      }
    } catch (...) {
      error = std::current_exception();
      stop = true;  // a helping attach_furnace_truth stops too
    }
    finish();
  }
  void finish() {
    std::lock_guard<std::mutex> g(lock);
    finished = true;
    changed.notify_all();
  }
  // attach_furnace_truth's part: the units left, until the thread finishes.
  void help() {
    for (;;) {
      std::shared_ptr<Quadratures> q;
      {
        std::unique_lock<std::mutex> g(lock);
        changed.wait(g, [&] { return finished || (job && job->next < job->units.size()); });
        if (finished) return;
        q = job;
      }
      try {
        if (q->take_until(stop)) notify();
      } catch (...) {
        stop = true;
        notify();
        throw;
      }
    }
  }
};
std::mutex background_lock;
std::unique_ptr<Background> background;  // guarded by background_lock

// Waits for the background computation, if any (helping it), and puts its
// values in the process's cache; rethrows its error.
void join_background() {
  std::unique_ptr<Background> b;
  {
    std::lock_guard<std::mutex> g(background_lock);
    b = std::move(background);
  }
  if (!b) return;
  try {
    b->help();
  } catch (...) {
    b->thread.join();
    throw;
  }
  b->thread.join();
  if (b->error) std::rethrow_exception(b->error);
  std::lock_guard<std::mutex> g(cache_lock);
  for (size_t k = 0; k < b->specs.size(); ++k)
    for (size_t i = 0; i < b->specs[k].size(); ++i) cache.emplace(cache_key(b->specs[k][i]), b->values[k][i]);
}

}  // namespace

FurnaceTruthAhead::FurnaceTruthAhead(const std::vector<Plan>& plans) {
  auto b = std::make_unique<Background>();
  bool any = false;
  {
    std::lock_guard<std::mutex> g(cache_lock);
    std::set<std::string> earlier;  // attach_furnace_truth finds an earlier plan's in the cache
    for (const Plan& p : plans)
      if (check_kind(p.check).truth && !p.specs.empty()) {
        any = true;
        b->specs.push_back(unknown_specs(p.specs.data(), p.points.data(), p.specs.size(), earlier));
        for (const IntegralSpec& s : b->specs.back()) earlier.insert(cache_key(s));
      }
  }
  if (!any) return;
  b->dir = truth_cache_dir();  // its error (MFV_TRUTH_CACHE) here, before the thread
  std::lock_guard<std::mutex> g(background_lock);
  if (background) return;  // another's, which attach_furnace_truth joins
  // one thread: the device's (PoCL's) threads need the other cores
  Background* w = b.get();
  w->thread = std::thread([w] { w->compute(); });
  background = std::move(b);
  started_ = true;
}

FurnaceTruthAhead::~FurnaceTruthAhead() {
  if (!started_) return;
  std::unique_ptr<Background> b;
  {
    std::lock_guard<std::mutex> g(background_lock);
    b = std::move(background);  // null where attach_furnace_truth joined it
  }
  if (!b) return;
  b->stop = true;  // at the next view: a run that ends early waits no longer than one
  b->notify();
  b->thread.join();
}

void attach_furnace_truth(const std::vector<IntegralSpec>& specs, PointResult* points) {
  join_background();
  constexpr double kMaxTruthError = 1e-3;
  // Every isotropic point that must hold, less those the process knows.
  std::vector<IntegralSpec> missing;
  {
    std::lock_guard<std::mutex> g(cache_lock);
    missing = unknown_specs(specs.data(), points, specs.size());
  }
  // across runs from disk: the default run's 15151 integrals take ~3.1 s of one core (docs/performance.md)
  const std::vector<KnownValue> computed = stored_albedos_by_quadrature(missing, host_threads(), truth_cache_dir());
  std::lock_guard<std::mutex> g(cache_lock);
  for (size_t k = 0; k < missing.size(); ++k) cache.emplace(cache_key(missing[k]), computed[k]);
  for (size_t i = 0; i < specs.size(); ++i) {
    if (!takes_truth(points[i], specs[i])) continue;
    const KnownValue& v = cache.at(cache_key(specs[i]));
    PointResult& p = points[i];
    // A value known to worse than kMaxTruthError adds more bias bound to
    // the pool than information (an integral's SE is ~1.7e-2 at default
    // samples): such points stay out of it (none in the catalog today:
    // the worst estimate is 2e-4).
    p.known = std::isfinite(v.value) && v.error <= kMaxTruthError;
    p.known_value = v.value;
    p.known_error = v.error;
  }
}

void attach_furnace_truth(Plan& plan) { attach_furnace_truth(plan.specs, plan.points.data()); }

}  // namespace mfv
