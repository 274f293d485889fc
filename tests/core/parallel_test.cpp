// parallel_for: every index once whatever the threads, the first error rethrown after the others
// stop, loops nested in bodies and loops run from several threads at once complete, and loop
// after loop runs on the same pool threads.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/parallel.h"

namespace parallel_test {
namespace {

using patchwork::parallel_for;

TEST(ParallelFor, EveryIndexOnceOnAnyNumberOfThreads) {
  for (const int threads : {0, 1, 2, 3, 7}) {
    for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{1000}}) {
      std::vector<std::atomic<int>> seen(count);
      parallel_for(count, threads, [&](std::size_t i) { ++seen[i]; });
      for (std::size_t i = 0; i < count; ++i) EXPECT_EQ(seen[i].load(), 1) << "index " << i << ", " << threads << " threads";
    }
  }
}

TEST(ParallelFor, RethrowsTheErrorAfterEveryThreadStopped) {
  std::atomic<int> running{0}, finished{0};
  EXPECT_THROW(parallel_for(200, 3,
                            [&](std::size_t i) {
                              ++running;
                              std::this_thread::sleep_for(std::chrono::microseconds(50));
                              if (i == 17) throw std::runtime_error("index 17");
                              ++finished;
                              --running;
                            }),
               std::runtime_error);
  // The throwing body left `running` at 1; every other body had finished when the call returned.
  EXPECT_EQ(running.load(), 1);
  EXPECT_LT(finished.load(), 200);
  // The next call runs as usual.
  std::atomic<int> after{0};
  parallel_for(100, 3, [&](std::size_t) { ++after; });
  EXPECT_EQ(after.load(), 100);
}

TEST(ParallelFor, NestedLoopsAndConcurrentCallersComplete) {
  std::atomic<long> total{0};
  std::vector<std::thread> callers;
  for (int c = 0; c < 4; ++c) {
    callers.emplace_back([&] {
      for (int round = 0; round < 20; ++round) {
        parallel_for(8, 2, [&](std::size_t) { parallel_for(16, 3, [&](std::size_t j) { total += static_cast<long>(j); }); });
      }
    });
  }
  for (std::thread& t : callers) t.join();
  EXPECT_EQ(total.load(), 4L * 20 * 8 * (15 * 16 / 2));
}

// The pool's threads live from loop to loop: a thread_local counter on a helper thread keeps
// counting across loops (a thread made for one loop would start again from zero every loop).
TEST(ParallelFor, LoopAfterLoopRunsOnThePoolsThreads) {
  thread_local int bodies_on_this_thread = 0;
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> most{0};
  constexpr int loops = 30;
  constexpr int count = 16;
  for (int loop = 0; loop < loops; ++loop) {
    parallel_for(count, 2, [&](std::size_t) {
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      if (std::this_thread::get_id() == caller) return;
      const int seen = ++bodies_on_this_thread;
      int previous = most.load();
      while (seen > previous && !most.compare_exchange_weak(previous, seen)) {
      }
    });
  }
  EXPECT_GT(most.load(), count) << "a helper thread ran no more than one loop's bodies";
}

}  // namespace
}  // namespace parallel_test
