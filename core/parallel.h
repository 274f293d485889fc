#pragma once
// A parallel loop over indices for work whose results go to per-index slots: the outcome does
// not depend on the number of threads or on which thread ran which index.

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace patchwork {

/// The number of threads `requested` stands for: itself if positive, else the number of cores.
inline int thread_count(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

/// Calls body(i) for i in [0, count) on up to `threads` threads (0: all cores), taking indices
/// in order from a shared counter. The first exception thrown by a body is rethrown after all
/// threads have stopped; indices not started by then are skipped.
template <class Body>
void parallel_for(std::size_t count, int threads, const Body& body) {
  const std::size_t workers = std::min<std::size_t>(static_cast<std::size_t>(thread_count(threads)), count);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&] {
    for (std::size_t i = next++; i < count && !failed; i = next++) {
      try {
        body(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace patchwork
