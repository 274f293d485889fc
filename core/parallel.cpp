#include "core/parallel.h"

#include <unistd.h>

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace patchwork::detail {
namespace {

// This thread is a pool thread, or is running a call on the pool: a call from here must not
// wait for the pool (std::mutex::try_lock by its owner is undefined, and a pool thread waiting
// for the pool would wait for itself).
thread_local bool on_pool = false;

// Threads that wait for work between calls. A call publishes its work as a new generation; each
// thread runs each generation at most once, if its index is below the generation's count.
// The pool is never destroyed (pool()): its threads wait until the process ends, so a loop run
// while static objects are destroyed, or by another thread while the process exits, finds it
// whole. A process forked from this one has none of its threads: there, calls make their own.
class Pool {
 public:
  Pool() = default;
  Pool(const Pool&) = delete;
  Pool& operator=(const Pool&) = delete;

  bool run(std::size_t workers, void (*work)(void*), void* context) noexcept {
    // getpid() is not cached by glibc: a forked child sees its own pid, and must not wait for
    // threads it does not have (nor touch mutexes another thread may have held at the fork).
    if (on_pool || ::getpid() != owner_) return false;
    std::unique_lock<std::mutex> dispatch(dispatch_, std::try_to_lock);
    if (!dispatch.owns_lock()) return false;
    std::size_t helpers = workers - 1;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      try {
        while (threads_.size() < helpers) {
          threads_.reserve(helpers);
          const std::size_t index = threads_.size();
          threads_.emplace_back([this, index, seen = generation_] { loop(index, seen); });
        }
      } catch (const std::exception&) {
        // No more threads (std::system_error, std::bad_alloc): those made do the work.
        helpers = threads_.size();
        if (helpers == 0) return false;
      }
      work_ = work;
      context_ = context;
      wanted_ = helpers;
      running_ = helpers;
      ++generation_;
    }
    wake_.notify_all();
    on_pool = true;
    work(context);
    on_pool = false;
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return running_ == 0; });
    work_ = nullptr;
    context_ = nullptr;
    return true;
  }

 private:
  // A pool thread: waits for each generation it is wanted for, runs it, and never returns.
  [[noreturn]] void loop(std::size_t index, std::uint64_t seen) {
    on_pool = true;
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      wake_.wait(lock, [&] { return generation_ != seen && index < wanted_; });
      seen = generation_;
      void (*const work)(void*) = work_;
      void* const context = context_;
      lock.unlock();
      work(context);
      lock.lock();
      if (--running_ == 0) done_.notify_one();
    }
  }

  std::mutex dispatch_;  // held by the call running on the pool
  std::mutex mutex_;     // guards everything below
  std::condition_variable wake_;
  std::condition_variable done_;
  std::vector<std::thread> threads_;
  void (*work_)(void*) = nullptr;
  void* context_ = nullptr;
  std::size_t wanted_ = 0;   // threads that run the current generation
  std::size_t running_ = 0;  // of those, still running it
  std::uint64_t generation_ = 0;
  const pid_t owner_ = ::getpid();
};

Pool& pool() {
  static Pool* const instance = new Pool;  // never deleted (see Pool)
  return *instance;
}

}  // namespace

bool run_on_pool(std::size_t workers, void (*work)(void*), void* context) noexcept {
  if (workers <= 1) {
    work(context);
    return true;
  }
  return pool().run(workers, work, context);
}

}  // namespace patchwork::detail
