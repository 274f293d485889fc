#pragma once
// A parallel loop over indices for work whose results go to per-index slots: the outcome does
// not depend on the number of threads or on which thread ran which index.
//
// The loops run on a pool of threads made once per process (core/parallel.cpp) and kept
// waiting between loops: a tessellation runs some twenty loops, and making and joining threads
// for each cost more than the small ones' work (the teapot from the command line ran no faster
// on 2 threads than on 1), and lost the threads' thread_local buffers every time. One loop uses
// the pool at a time; a loop that finds it taken (another thread's loop, or a loop inside a
// loop's body), or that runs in a process forked from the pool's, makes its own threads, as
// every loop did before. The pool is never destroyed: it is whole for loops run at exit.

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

namespace detail {

/// Calls work(context) on the calling thread and at the same time on workers - 1 threads of the
/// process's pool (made on first use, kept for later calls), and returns once every call has
/// returned. `work` must not throw. Returns false, having called nothing, when the pool is in
/// use (by another thread's call, or by a call this thread is inside of), this process was
/// forked from the one that made the pool, or no pool thread can be made.
bool run_on_pool(std::size_t workers, void (*work)(void*), void* context) noexcept;

}  // namespace detail

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
  const auto run = [](void* context) { (*static_cast<decltype(work)*>(context))(); };
  if (!detail::run_on_pool(workers, run, const_cast<void*>(static_cast<const void*>(&work)))) {
    std::vector<std::thread> threads;
    threads.reserve(workers - 1);
    for (std::size_t t = 1; t < workers; ++t) threads.emplace_back(work);
    work();
    for (std::thread& thread : threads) thread.join();
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace patchwork
