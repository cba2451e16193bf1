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
#include "adaptex/paint/strokes.h"
#include "jobs.h"
#include "surface.h"

namespace adaptex::studio {

/// A loaded model with its first (unpainted) surface.
struct LoadResult {
  std::shared_ptr<const Model> model;
  std::unique_ptr<Surface> surface;
  double seconds = 0;
};

/// A canvas rebuilt for one history generation.
struct RebuildResult {
  std::unique_ptr<Surface> surface;
  std::vector<std::pair<std::string, double>> phase_ms;
  std::shared_ptr<const AdaptMaps> maps;  ///< Set when the job re-parameterized.
};

class SurfaceJobs {
 public:
  ~SurfaceJobs();

  /// Starts loading \p path (replaces a running load). \p options: texture size and padding.
  void start_load(const std::string& path, const PaintSessionOptions& options, const Vec3& background);
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
  bool rebuild_adapting() const { return rebuild_ && rebuild_adapting_; }
  std::uint64_t rebuild_generation() const { return rebuild_generation_; }
  std::unique_ptr<Job<RebuildResult>> finished_rebuild();

  /// Starts the fixed-vs-adaptive comparison of \p current (no-op while one runs).
  void start_compare(const Surface& current, StrokeFile history);
  bool comparing() const { return compare_ != nullptr; }
  std::unique_ptr<Job<Comparison>> finished_compare();

  /// Forgets cancelled jobs that have ended.
  void reap();
  bool busy() const { return load_ || rebuild_ || compare_; }
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
  std::vector<std::unique_ptr<JobBase>> retired_;
};

}  // namespace adaptex::studio
