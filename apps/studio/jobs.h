#pragma once
/// \file jobs.h
/// A background job: one worker thread computing one result, with progress, cancel and an
/// exception channel. The UI thread polls ready() every frame and take()s the result: it never waits.
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace adaptex::studio {

/// Type-erased view of a job (for cancelled jobs that are left to finish on their own).
class JobBase {
 public:
  virtual ~JobBase() = default;
  virtual bool ready() const = 0;
  virtual void cancel() = 0;
};

template <class R>
class Job : public JobBase {
 public:
  /// Starts \p work(job) on a new thread; work reports through progress() and checks cancelled().
  explicit Job(std::function<R(Job&)> work) {
    thread_ = std::thread([this, w = std::move(work)]() mutable {
      try {
        R r = w(*this);
        std::lock_guard lock(mutex_);
        result_.emplace(std::move(r));
      } catch (...) {
        std::lock_guard lock(mutex_);
        error_ = std::current_exception();
      }
      done_ = true;
    });
  }
  ~Job() override {
    cancel_ = true;
    if (thread_.joinable()) thread_.join();
  }
  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;

  /// Worker side: records progress; \return false when cancelled (a ProgressCallback).
  bool progress(std::string_view phase, double fraction) {
    {
      std::lock_guard lock(mutex_);
      phase_ = phase;
    }
    fraction_ = fraction;
    return !cancel_;
  }
  bool cancelled() const { return cancel_; }
  void cancel() override { cancel_ = true; }

  /// UI side.
  bool ready() const override { return done_; }
  double fraction() const { return fraction_; }
  std::string phase() const {
    std::lock_guard lock(mutex_);
    return phase_;
  }
  /// \pre ready(). Rethrows the worker's exception.
  R take() {
    if (thread_.joinable()) thread_.join();
    std::lock_guard lock(mutex_);
    if (error_) std::rethrow_exception(error_);
    return std::move(*result_);
  }

 private:
  std::thread thread_;
  mutable std::mutex mutex_;
  std::string phase_;
  std::optional<R> result_;
  std::exception_ptr error_;
  std::atomic<bool> cancel_{false}, done_{false};
  std::atomic<double> fraction_{0.0};
};

}  // namespace adaptex::studio
