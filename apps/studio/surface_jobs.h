#pragma once
/// \file surface_jobs.h
/// The studio's background work on surfaces: loading + unwrapping a mesh, rebuilding the canvas
/// for a history (replay on the current layout, or a re-parameterization from the initial layout),
/// and the fixed-vs-adaptive comparison. The UI thread starts jobs and polls for finished ones; it
/// never waits for a job (cancelled jobs are retired and joined once they end).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "adaptex/adapt/session.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/strokes.h"
#include "jobs.h"
#include "live_adaptation.h"
#include "live_material.h"
#include "surface.h"

namespace adaptex::studio {

/// How a model is opened.
struct LoadRequest {
  /// A fresh unwrap even when the model has its own UV atlas and base-colour texture.
  bool unwrap = false;
  /// Keeping the atlas: the texture size becomes the artist texture's (its larger side), not the
  /// options' (a model opened afresh; a project or a new texture size keeps the options').
  bool size_from_texture = false;
};

/// A loaded model with its first (unpainted) surface.
struct LoadResult {
  std::shared_ptr<const Model> model;
  std::unique_ptr<Surface> surface;
  double seconds = 0;
};

class SurfaceJobs {
 public:
  ~SurfaceJobs();

  /// Starts loading \p path (replaces a running load). \p options: texture size and padding.
  void start_load(const std::string& path, const PaintSessionOptions& options, const Vec3& background,
                  LoadRequest request);
  void cancel_load();
  bool loading() const { return load_ != nullptr; }
  const std::string& loading_path() const { return loading_path_; }
  /// The finished load job (take() it: rethrows its error), or null while running / none.
  std::unique_ptr<Job<LoadResult>> finished_load();

  /// Starts rebuilding the canvas for \p history (generation \p generation), replacing a running
  /// rebuild. adapt = false: replay on \p current's layout; true: paint_history() from the model's
  /// initial layout with \p options (the layout then depends on the history only).
  void start_rebuild(const Surface& current, std::uint64_t generation, StrokeFile history,
                     const PaintSessionOptions& options, bool adapt);
  bool rebuilding() const { return rebuild_ != nullptr; }
  /// Cancels the running rebuild (retired: never waited for).
  void cancel_rebuild() {
    if (rebuild_) retire(std::move(rebuild_));
  }
  bool rebuild_adapting() const { return rebuild_ && rebuild_adapting_; }
  std::uint64_t rebuild_generation() const { return rebuild_generation_; }
  std::unique_ptr<Job<RebuildResult>> finished_rebuild();

  /// Live adaptation (schedule each-stroke): feeds the strokes of the history (\p strokes) not yet fed to the live
  /// session for \p model, generation \p generation and \p options; starts a new one with the whole
  /// history when there is none for them (a replaced one is retired).
  /// The UI thread copies only the new strokes (the whole history when a session starts).
  void feed_live(const std::shared_ptr<const Model>& model, std::uint64_t generation, const std::vector<Stroke>& strokes,
                 const Vec3& background, const PaintSessionOptions& options);
  /// Drops the live session (the history was rewritten, or adaptation is off).
  void stop_live();
  /// The live session's newest surface, if any. \throw its error (the session is then dropped)
  std::optional<RebuildResult> finished_live();
  /// No live session, or it has adapted every fed stroke, settled and handed over its last surface.
  bool live_caught_up() const { return !live_ || live_->caught_up(); }
  /// Settle the live session as soon as it has adapted the fed strokes (scripts, wait_idle()).
  void settle_live_now();
  const LiveAdaptation* live() const { return live_.get(); }

  /// Layered material (live_material.h): starts a session for \p model's document \p file (generation
  /// \p generation) with \p options, replacing (retiring) the running one.
  void start_material(const std::shared_ptr<const Model>& model, std::uint64_t generation, MaterialStrokeFile file,
                      const PaintSessionOptions& options);
  /// Feeds \p stroke, appended to the document of generation stroke.generation - 1, to the material
  /// session. \return false (nothing fed) when none serves \p model, \p options and that generation
  bool feed_material(const Model* model, const PaintSessionOptions& options, MaterialFeed stroke);
  /// The material session serves \p model, \p options and document generation \p generation.
  bool material_serves(const Model* model, const PaintSessionOptions& options, std::uint64_t generation) const;
  void stop_material();
  /// The material session's newest surface, if any. \throw its error (the session is then dropped)
  std::optional<RebuildResult> finished_material();
  const LiveMaterial* live_material() const { return material_.get(); }
  /// Material sessions started so far (a stroke is fed to the running one; tests).
  int material_starts() const { return material_starts_; }

  /// Starts the fixed-vs-adaptive comparison of \p current (no-op while one runs).
  void start_compare(const Surface& current, StrokeFile history);
  bool comparing() const { return compare_ != nullptr; }
  std::unique_ptr<Job<Comparison>> finished_compare();

  /// Forgets cancelled jobs that have ended.
  void reap();
  bool busy() const {
    return load_ || rebuild_ || compare_ || !live_caught_up() || (material_ && !material_->caught_up());
  }
  /// Work in progress: (label, fraction) or nullopt.
  std::optional<std::pair<std::string, double>> progress() const;

 private:
  void retire(std::unique_ptr<JobBase> job);

  std::unique_ptr<Job<LoadResult>> load_;
  std::string loading_path_;
  std::unique_ptr<Job<RebuildResult>> rebuild_;
  std::uint64_t rebuild_generation_ = 0;
  bool rebuild_adapting_ = false;
  std::unique_ptr<Job<Comparison>> compare_;
  std::unique_ptr<LiveAdaptation> live_;
  std::unique_ptr<LiveMaterial> material_;
  int material_starts_ = 0;
  std::vector<std::unique_ptr<JobBase>> retired_;
};

}  // namespace adaptex::studio
