// camdyn (private) — the worker pool of run_batch, simulate_batch and run_sweep: `threads`
// workers (the calling thread is one) take indices 0 … count−1 from an atomic counter.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace camdyn {
namespace detail {

/// Worker count for `requested` threads (≤ 0: hardware_concurrency) and `count` jobs:
/// at least 1, at most max(1, count).
inline int worker_count(int requested, std::size_t count) {
  std::size_t n = requested > 0 ? static_cast<std::size_t>(requested)
                                : std::max(1u, std::thread::hardware_concurrency());
  return static_cast<int>(std::min(n, std::max<std::size_t>(1, count)));
}

/// Calls job(i) for every i in [0, count) on `threads` workers (worker_count) from a
/// dynamic queue; a worker takes no new index once `stop` (may be null) is set or its
/// job returned false. Exceptions must not escape `job`. Returns when every worker has.
/// @throws std::system_error if a thread cannot be started (the started ones are joined).
template <class Job>
void parallel_for(std::size_t count, int threads, const std::atomic<bool>* stop, Job&& job) {
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (;;) {
      if (stop && stop->load()) return;
      const std::size_t i = next.fetch_add(1);
      if (i >= count) return;
      if (!job(i)) return;
    }
  };
  std::vector<std::thread> pool;
  const int n = worker_count(threads, count);
  try {
    for (int t = 1; t < n; ++t) pool.emplace_back(worker);
  } catch (...) {
    for (auto& t : pool) t.join();
    throw;
  }
  worker();
  for (auto& t : pool) t.join();
}

}  // namespace detail
}  // namespace camdyn
