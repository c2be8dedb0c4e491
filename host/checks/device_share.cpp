#include "checks/device_share.hpp"

#include "util/error.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>

namespace mfv {

PendingIntegrators integrators_beside(const std::vector<Runtime*>& more, const TermSelection& terms) {
  PendingIntegrators p;
  for (Runtime* rt : more)
    p.builds.push_back(std::async(std::launch::async, [rt, terms] { return std::make_unique<Integrator>(*rt, terms); }));
  return p;
}

std::vector<std::unique_ptr<Integrator>> integrators_ready(PendingIntegrators& pending, const Runtime& first,
                                                           const std::vector<Runtime*>& more,
                                                           std::vector<DeviceShare>& shares) {
  std::vector<std::unique_ptr<Integrator>> out;
  for (auto& f : pending.builds) out.push_back(f.get());
  if (out.empty()) return out;
  shares.clear();
  auto row = [](const Runtime& rt) {
    return DeviceShare{rt.device().name, rt.device().platform, rt.device().index, 0, 0};
  };
  shares.push_back(row(first));
  for (Runtime* rt : more) shares.push_back(row(*rt));
  return out;
}

size_t share_chunk(size_t integrals, size_t devices) {
  const size_t per = (integrals + 8 * devices - 1) / std::max<size_t>(1, 8 * devices);
  return std::max<size_t>(1, std::min(integrals, std::max<size_t>(16, per)));
}

std::vector<Estimate> run_shared(const std::vector<Integrator*>& integrators, const std::vector<IntegralSpec>& specs,
                                 uint64_t samples, uint64_t seed, std::vector<DeviceShare>& shares) {
  if (integrators.empty() || shares.size() != integrators.size())
    throw Error("internal: run_shared needs one share per integrator");
  std::vector<Integrator*> able;  // the devices that take this plan's samples as the first does
  std::vector<size_t> share_of;
  for (size_t d = 0; d < integrators.size(); ++d)
    if (integrators[d]->samples_used(samples) == integrators[0]->samples_used(samples) &&
        integrators[d]->mis_points(samples) == integrators[0]->mis_points(samples)) {
      able.push_back(integrators[d]);
      share_of.push_back(d);
    }
  std::vector<Estimate> out(specs.size());
  const size_t chunk = share_chunk(specs.size(), able.size());
  const size_t chunks = specs.empty() ? 0 : (specs.size() + chunk - 1) / chunk;
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_lock;
  auto work = [&](size_t a) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      for (size_t c; !failed && (c = next++) < chunks;) {
        const size_t lo = c * chunk, hi = std::min(specs.size(), lo + chunk);
        std::vector<IntegralSpec> part(specs.begin() + long(lo), specs.begin() + long(hi));
        std::vector<Estimate> est = able[a]->run(part, samples, seed);
        std::copy(est.begin(), est.end(), out.begin() + long(lo));
        shares[share_of[a]].integrals += hi - lo;  // one thread per share
      }
    } catch (...) {
      std::lock_guard<std::mutex> g(error_lock);
      if (!error) error = std::current_exception();
      failed = true;
    }
    shares[share_of[a]].seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::vector<std::thread> threads;
  for (size_t a = 1; a < able.size(); ++a) threads.emplace_back(work, a);
  work(0);
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);
  return out;
}

}  // namespace mfv
