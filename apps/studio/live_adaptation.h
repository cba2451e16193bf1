#pragma once
/// \file live_adaptation.h
/// The studio's adaptation while painting (schedule each-stroke): one background LiveSession kept
/// across strokes. The UI feeds it every finished stroke; it paints them and runs one each-stroke
/// cycle per batch (a cycle's cost does not grow with the history: the surface cache, the min-gain
/// gate), and publishes a new surface whenever the layout changes. Once no stroke has come
/// for settle_delay (or at once after settle_now()), it settles on end mode's layout and texture for
/// the history (PaintSession::finish), so the layout still depends on the history alone; a stroke
/// arriving meanwhile cancels that and is adapted to first.
///
/// A history rewrite (undo), other options, another model or texture size need a new LiveAdaptation.
/// Like a Job, it is never waited for on the UI thread: SurfaceJobs retires a replaced one.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "adaptex/adapt/session.h"
#include "adaptex/paint/strokes.h"
#include "jobs.h"
#include "surface.h"

namespace adaptex::studio {

class LiveAdaptation : public JobBase {
 public:
  /// Seconds without a new stroke before the session settles on end mode's layout.
  /// Settling replays the history exactly (O(history)), so it waits for a pause in the painting.
  static constexpr double kSettleDelay = 2.0;

  /// Starts the worker on \p model's initial layout with \p history (its strokes are the first
  /// batch) for history generation \p generation.
  LiveAdaptation(std::shared_ptr<const Model> model, std::uint64_t generation, const PaintSessionOptions& options,
                 StrokeFile history);
  /// Cancels and joins (SurfaceJobs retires running ones instead of destroying them).
  ~LiveAdaptation() override;
  LiveAdaptation(const LiveAdaptation&) = delete;
  LiveAdaptation& operator=(const LiveAdaptation&) = delete;

  /// Whether this session adapts \p history generation \p generation of \p model with \p options.
  bool serves(const Model* model, std::uint64_t generation, const std::string& options_key) const;
  /// UI: the next finished strokes of the history (appended in order).
  void feed(std::vector<Stroke> strokes);
  /// Strokes fed so far (the first batch included).
  size_t fed() const;
  /// UI: settle as soon as the fed strokes are adapted (no settle_delay).
  void settle_now();
  /// UI: the newest surface not yet taken, if any. \throw the worker's error (not a cancel)
  std::optional<RebuildResult> take_update();
  /// Every fed stroke is adapted, the session settled and its last surface taken.
  bool caught_up() const;
  /// (phase, fraction) of the running cycle, or nullopt while waiting.
  std::optional<std::pair<std::string, double>> progress() const;
  /// Cycles run so far (batches and settles), for tests.
  int cycles() const { return cycles_; }
  /// Strokes the last finished cycle adapted to (benchmarks: the adaptation's lag behind the feed).
  size_t adapted() const { return adapted_; }
  /// The session is settled on end mode's layout for every fed stroke (its surface may still be
  /// waiting in take_update()).
  bool settled() const;

  bool ready() const override { return done_; }
  void cancel() override;

 private:
  void run(std::shared_ptr<const Model> model, PaintSessionOptions options, Vec3 background);
  /// Waits for strokes or the settle time. \return the batch (empty: settle now); nullopt: stop.
  std::optional<std::vector<Stroke>> next_batch(bool settled);
  /// After a cycle: the new surface if the layout changed, and the counters, in one step.
  void publish(const std::shared_ptr<const Model>& model, LiveSession& session);
  bool keep_going(std::string_view phase, double fraction);

  const Model* model_;
  const std::uint64_t generation_;
  const std::string options_key_;
  const int size_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<Stroke> queue_;
  size_t fed_ = 0;
  bool settle_now_ = false, settling_ = false, busy_ = true, settled_ = false;
  std::optional<RebuildResult> update_;
  std::exception_ptr error_;
  std::string phase_;
  std::atomic<double> fraction_{0};
  std::atomic<bool> stop_{false}, done_{false};
  std::atomic<int> cycles_{0};
  std::atomic<size_t> adapted_{0};  ///< Written under mutex_ (read alone by adapted()).
  std::thread thread_;  ///< Last: started once everything above exists.
};

}  // namespace adaptex::studio
