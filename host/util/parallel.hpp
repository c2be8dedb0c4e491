// Independent work items on the machine's hardware threads. Each item writes
// only its own result slot, so what a caller computes does not depend on the
// number of threads or on which thread ran an item.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace mfv {

// The threads host-side work may use: the hardware's, at most 8.
inline unsigned host_threads() { return std::max(1u, std::min(8u, std::thread::hardware_concurrency())); }

// item(i) for every i in [0, n), on `threads` threads (the caller's among
// them), each taking the next unstarted item.
template <class Item>
void parallel_for(size_t n, unsigned threads, const Item& item) {
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t i; (i = next++) < n;) item(i);
  };
  std::vector<std::thread> pool;
  for (unsigned w = 1; w < std::min<size_t>(std::max(1u, threads), std::max<size_t>(1, n)); ++w)
    pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
}

}  // namespace mfv
