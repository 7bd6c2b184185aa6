#include "linear_algebra/run_tasks.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "linear_algebra/parallel.h"

namespace polycube {
namespace {

thread_local bool in_task = false;

// Workers that wait on a condition variable for the next batch of tasks and
// take its tasks one at a time, the calling thread with them.
class Pool {
 public:
  explicit Pool(int workers) {
    for (int i = 0; i < workers; ++i) threads_.emplace_back([this] { work(); });
  }
  int workers() const { return static_cast<int>(threads_.size()); }

  // False, running nothing, when another thread's batch is running.
  bool run(int count, const std::function<void(int)>& task) {
    std::unique_lock<std::mutex> batch(batch_, std::try_to_lock);
    if (!batch.owns_lock()) return false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      task_ = &task;
      count_ = count;
      next_ = 0;
      unfinished_ = count;
      published_.store(++generation_, std::memory_order_release);
    }
    for (int k = 1; k < count && k <= workers(); ++k) wake_.notify_one();
    take_tasks();
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return unfinished_ == 0; });
    task_ = nullptr;
    return true;
  }

 private:
  void take_tasks() {
    for (;;) {
      const std::function<void(int)>* task;
      int i;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!task_ || next_ >= count_) return;
        task = task_;
        i = next_++;
      }
      in_task = true;
      (*task)(i);  // does not throw: run_tasks() wraps it
      in_task = false;
      std::lock_guard<std::mutex> lock(mutex_);
      if (--unfinished_ == 0) done_.notify_one();
    }
  }

  void work() {
    long seen = 0;
    for (;;) {
      // A little while awake first: batches often come in quick succession
      // (a solve, then a pair of trials), and a sleeping thread is slow to
      // start again.
      const auto until = std::chrono::steady_clock::now() + kAwake;
      while (published_.load(std::memory_order_acquire) == seen && std::chrono::steady_clock::now() < until)
        std::this_thread::yield();
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return generation_ != seen; });
        seen = generation_;
      }
      take_tasks();
    }
  }

  std::vector<std::thread> threads_;
  std::mutex batch_;  // one batch at a time
  std::mutex mutex_;  // the fields below
  std::condition_variable wake_, done_;
  const std::function<void(int)>* task_ = nullptr;
  int count_ = 0, next_ = 0, unfinished_ = 0;
  long generation_ = 0;
  std::atomic<long> published_{0};  // generation_, read without the lock
  static constexpr std::chrono::microseconds kAwake{1000};
};

// Started on first use and never stopped: its threads sleep until the
// process ends, which no destructor then has to wait for.
Pool& pool() {
  static Pool* const instance = new Pool(task_threads(1 << 30) - 1);
  return *instance;
}

}  // namespace

void run_tasks(int count, const std::function<void(int)>& task) {
  std::vector<std::exception_ptr> failures(count > 0 ? count : 0);
  const std::function<void(int)> guarded = [&](int i) {
    try {
      task(i);
    } catch (...) {
      failures[i] = std::current_exception();
    }
  };
  if (count > 1 && !in_task && task_threads(count) > 1 && pool().workers() > 0 && pool().run(count, guarded)) {
  } else {
    for (int i = 0; i < count; ++i) guarded(i);
  }
  for (const std::exception_ptr& failure : failures)
    if (failure) std::rethrow_exception(failure);
}

}  // namespace polycube
