// parallel_for: every index once whatever the threads, the first error rethrown after the others
// stop, loops nested in bodies and loops run from several threads at once complete, and loop
// after loop runs on the same pool threads.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

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

// The pool's threads live from loop to loop: a thread_local counter on the helper thread keeps
// counting across loops (a thread made for one loop would start again from zero every loop).
// Each loop has two indices whose bodies wait for each other, so the helper takes one every loop.
TEST(ParallelFor, LoopAfterLoopRunsOnThePoolsThreads) {
  thread_local int bodies_on_this_thread = 0;
  const std::thread::id caller = std::this_thread::get_id();
  int most = 0;
  constexpr int loops = 20;
  for (int loop = 0; loop < loops; ++loop) {
    std::atomic<int> started{0};
    parallel_for(2, 2, [&](std::size_t) {
      ++started;
      // Both bodies at once (a second of patience, not a hang, if that cannot happen).
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(1);
      while (started.load() < 2 && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
      if (std::this_thread::get_id() != caller) most = ++bodies_on_this_thread;
    });
  }
  EXPECT_EQ(most, loops) << "the helper thread of the last loop ran " << most << " of the " << loops << " loops";
}

// A process forked after loops have run has none of the pool's threads: its loops make their own
// and complete (with the pool's threads it would wait for them forever).
TEST(ParallelFor, ForkedChildRunsItsLoops) {
  std::atomic<int> warm{0};
  parallel_for(64, 2, [&](std::size_t) { ++warm; });
  ASSERT_EQ(warm.load(), 64);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::atomic<int> seen{0};
    parallel_for(1000, 2, [&](std::size_t) { ++seen; });
    ::_exit(seen.load() == 1000 ? 0 : 1);
  }
  int status = 0;
  pid_t done = 0;
  for (int wait = 0; wait < 1000 && done == 0; ++wait) {
    done = ::waitpid(child, &status, WNOHANG);
    if (done == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (done == 0) {
    ::kill(child, SIGKILL);
    ::waitpid(child, &status, 0);
    FAIL() << "the forked child's loop did not finish in 10 s";
  }
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace parallel_test
