#pragma once
// A fork–join of two threads (see ForkJoin). The machines this project targets have two cores.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace rbla::conic::detail {

/// One helper thread that runs a task while the calling thread runs another (a fork–join of
/// two), for the solver's two-thread parts: the split normal matrix (SplitCholesky), the
/// products with A and M, the cone operations and the assembly. Kept for the object's lifetime:
/// a thread per call would cost more than the call at small sizes. Either side spins briefly
/// before it sleeps on a condition variable: waking a sleeping thread took about 0.15 ms on
/// this project's virtual machines, half of a whole triangular solve at 1920 blocks.
class ForkJoin {
 public:
  ForkJoin() : thread_([this] { loop(); }) {}
  ~ForkJoin() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stop_.store(true);
    }
    wake_.notify_one();
    thread_.join();
  }
  ForkJoin(const ForkJoin&) = delete;
  ForkJoin& operator=(const ForkJoin&) = delete;

  /// Runs there() on the helper thread and here() on this one; returns when both have
  /// finished, rethrowing an exception of either.
  void run(const std::function<void()>& here, const std::function<void()>& there) {
    error_ = nullptr;
    done_.store(false, std::memory_order_relaxed);
    {
      // Published under the mutex, so that a helper about to sleep sees it (no lost wake-up).
      const std::lock_guard<std::mutex> lock(mutex_);
      task_.store(&there, std::memory_order_release);
    }
    wake_.notify_one();
    std::exception_ptr here_error;
    try {
      here();
    } catch (...) {
      here_error = std::current_exception();
    }
    if (!spin_until([this] { return done_.load(std::memory_order_acquire); })) {
      std::unique_lock<std::mutex> lock(mutex_);
      finished_.wait(lock, [this] { return done_.load(std::memory_order_acquire); });
    }
    if (here_error) std::rethrow_exception(here_error);
    if (error_) std::rethrow_exception(error_);
  }

 private:
  /// Polls ready() for up to 0.2 ms; true once it holds.
  template <class Ready>
  static bool spin_until(Ready ready) {
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::microseconds(200);
    for (int k = 1;; ++k) {
      if (ready()) return true;
      if (k % 64 == 0 && std::chrono::steady_clock::now() > give_up) return false;
      cpu_relax();
    }
  }
  static void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }

  void loop() {
    for (;;) {
      auto has_work = [this] {
        return task_.load(std::memory_order_acquire) != nullptr || stop_.load();
      };
      if (!spin_until(has_work)) {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, has_work);
      }
      const std::function<void()>* task = task_.exchange(nullptr, std::memory_order_acq_rel);
      if (task == nullptr) return;  // stop_ with nothing left to do
      try {
        (*task)();
      } catch (...) {
        error_ = std::current_exception();
      }
      {
        const std::lock_guard<std::mutex> lock(mutex_);
        done_.store(true, std::memory_order_release);
      }
      finished_.notify_one();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  std::atomic<const std::function<void()>*> task_{nullptr};
  std::atomic<bool> done_{true}, stop_{false};
  std::exception_ptr error_;  // written by the helper before done_, read by run() after it
  std::thread thread_;        // last: started once the members above exist
};

}  // namespace rbla::conic::detail
