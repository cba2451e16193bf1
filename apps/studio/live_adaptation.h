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
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adaptex/adapt/session.h"
#include "adaptex/paint/strokes.h"
#include "live_worker.h"
#include "surface.h"

namespace adaptex::studio {

class LiveAdaptation : public LiveWorker<Stroke> {
 public:
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
  /// Every fed stroke is adapted, the session settled and its last surface taken.
  bool caught_up() const;
  /// Cycles run so far (batches and settles), for tests.
  int cycles() const { return cycles_; }
  /// Strokes the last finished cycle adapted to (benchmarks: the adaptation's lag behind the feed).
  size_t adapted() const { return adapted_; }
  /// The session is settled on end mode's layout for every fed stroke (its surface may still be
  /// waiting in take_update()).
  bool settled() const;

 private:
  void run(std::shared_ptr<const Model> model, PaintSessionOptions options, Vec3 background);
  /// After a cycle: the new surface if the layout changed, and the counters, in one step.
  void publish(const std::shared_ptr<const Model>& model, LiveSession& session);

  const Model* model_;
  const std::uint64_t generation_;
  const std::string options_key_;
  const int size_;
  size_t fed_ = 0;        ///< Under mutex_.
  bool settled_ = false;  ///< Under mutex_.
  std::atomic<int> cycles_{0};
  std::atomic<size_t> adapted_{0};  ///< Written under mutex_ (read alone by adapted()).
};

}  // namespace adaptex::studio
