#pragma once
/// \file live_worker.h
/// The worker thread both live adaptations share (live_adaptation.h: a base-colour history;
/// live_material.h: a layered material): a queue of items the UI feeds, batches for the worker, a
/// settle after kSettleDelay without items (or at once after settle_now()) that gives way to new items,
/// the newest surface for the UI, progress, cancel and the worker's error. The derived class starts
/// thread_ last in its constructor and joins it in its destructor (stop_and_join()).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "adaptex/core/errors.h"
#include "jobs.h"
#include "surface.h"

namespace adaptex::studio {

template <class Item>
class LiveWorker : public JobBase {
 public:
  /// Seconds without a new item before the worker settles (settling costs O(history): it waits for a
  /// pause in the painting).
  static constexpr double kSettleDelay = 2.0;

  /// UI: settle as soon as the fed items are handled (no kSettleDelay).
  void settle_now() {
    {
      std::lock_guard lock(mutex_);
      settle_now_ = true;
    }
    wake_.notify_all();
  }
  /// UI: the newest surface not yet taken, if any. \throw the worker's error (not a cancel)
  std::optional<RebuildResult> take_update() {
    std::lock_guard lock(mutex_);
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
    return std::exchange(update_, std::nullopt);
  }
  /// (phase, fraction) of the running work, or nullopt while waiting.
  std::optional<std::pair<std::string, double>> progress() const {
    std::lock_guard lock(mutex_);
    if (!busy_) return std::nullopt;
    return std::make_pair(phase_, fraction_.load());
  }
  bool ready() const override { return done_; }
  void cancel() override {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
  }

 protected:
  LiveWorker() = default;
  void stop_and_join() {
    cancel();
    if (thread_.joinable()) thread_.join();
  }
  /// UI: appends \p items under the lock, after \p also (more bookkeeping under the same lock).
  template <class F>
  void push(std::vector<Item> items, F also) {
    {
      std::lock_guard lock(mutex_);
      also();
      for (Item& i : items) queue_.push_back(std::move(i));
    }
    wake_.notify_all();
  }
  /// Worker: the progress callback of its work; false when stopped, or a settle should give way.
  bool keep_going(std::string_view phase, double fraction) {
    std::lock_guard lock(mutex_);
    phase_ = phase;
    fraction_ = fraction;
    return !stop_ && !(settling_ && !queue_.empty());
  }
  /// Worker: waits for items, or (not \p settled) the settle time. \return the batch (empty: settle
  /// now); nullopt: stop.
  std::optional<std::vector<Item>> next_batch(bool settled) {
    std::unique_lock lock(mutex_);
    busy_ = false;
    settling_ = false;
    phase_.clear();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(kSettleDelay);
    while (true) {
      if (stop_) return std::nullopt;
      if (!queue_.empty()) {
        busy_ = true;
        return std::exchange(queue_, {});
      }
      if (!settled && (settle_now_ || std::chrono::steady_clock::now() >= deadline)) {
        settle_now_ = false;
        busy_ = settling_ = true;
        return std::vector<Item>{};
      }
      if (settled)
        wake_.wait(lock);
      else
        wake_.wait_until(lock, deadline);
    }
  }
  /// Worker: runs \p work, keeping its error (not a cancel) for take_update(); then done.
  template <class F>
  void run_guarded(F work) {
    try {
      work();
    } catch (const CancelledError&) {
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
    }
    std::lock_guard lock(mutex_);
    busy_ = false;
    done_ = true;
  }

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<Item> queue_;
  bool settle_now_ = false, settling_ = false, busy_ = true;
  std::optional<RebuildResult> update_;
  std::exception_ptr error_;
  std::string phase_;
  std::atomic<double> fraction_{0};
  std::atomic<bool> stop_{false}, done_{false};
  std::thread thread_;  ///< Started last by the derived constructor.
};

}  // namespace adaptex::studio
