#pragma once
/// \file live_material.h
/// The studio's adaptation of a layered material while painting: one background MaterialLiveSession
/// (backend.h) kept across strokes, as LiveAdaptation is for a single base-colour layer. The UI feeds
/// it every stroke appended to the document; it composites them incrementally, runs one gated
/// each-stroke cycle per batch and publishes the composite. Once no stroke has come for kSettleDelay
/// (or at once after settle_now()), it settles on paint_material_history() for the document: the
/// layout and textures `adaptex paint` gives for it (what an export writes); a stroke arriving
/// meanwhile cancels that and is adapted to first.
///
/// An edit other than a stroke appended (a layer edit, undo, redo), other options or another model
/// need a new LiveMaterial. Never waited for on the UI thread: SurfaceJobs retires a replaced one.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "adaptex/adapt/session.h"
#include "live_worker.h"
#include "surface.h"

namespace adaptex::studio {

/// A stroke appended to a layer of the document (or to its mask), making document generation \p generation.
struct MaterialFeed {
  int layer = 0;
  bool mask = false;
  MaterialStroke stroke;
  std::uint64_t generation = 0;
};

class LiveMaterial : public LiveWorker<MaterialFeed> {
 public:
  /// Starts the worker on \p model's initial layout with the document \p file of generation
  /// \p generation: its composite is published first, then it settles at once.
  LiveMaterial(std::shared_ptr<const Model> model, std::uint64_t generation, const PaintSessionOptions& options,
               MaterialStrokeFile file);
  /// Cancels and joins (SurfaceJobs retires running ones instead of destroying them).
  ~LiveMaterial() override;
  LiveMaterial(const LiveMaterial&) = delete;
  LiveMaterial& operator=(const LiveMaterial&) = delete;

  /// Whether this session works for \p model with \p options (and has not failed).
  bool serves(const Model* model, const std::string& options_key) const;
  /// The document generation of the last stroke fed (the first: the constructor's).
  std::uint64_t generation() const;
  /// UI: a stroke was appended to the document.
  void feed(MaterialFeed stroke);
  /// Every fed stroke is composited, the session settled and its last surface taken (surfaces:
  /// take_update(); surface->generation is the document generation shown, surface->settled whether
  /// it is paint_material_history()'s).
  bool caught_up() const;
  /// Composites published so far (strokes, settles and the first), for tests.
  int cycles() const { return cycles_; }
  /// Settles run so far (tests: a stroke is not a settle).
  int settles() const { return settles_; }

 private:
  void run(std::shared_ptr<const Model> model, PaintSessionOptions options, MaterialStrokeFile file);
  /// Adds \p batch to \p session, consecutive strokes of one layer (or mask) in one cycle.
  static void add_batch(MaterialLiveSession& session, const std::vector<MaterialFeed>& batch);

  const Model* model_;
  const std::string options_key_;
  const int size_;
  std::uint64_t fed_generation_ = 0;   ///< Of the last stroke fed (under mutex_).
  std::uint64_t done_generation_ = 0;  ///< Of the last composite published (under mutex_).
  bool settled_ = false;               ///< The last composite published is the settled one (under mutex_).
  std::atomic<int> cycles_{0}, settles_{0};
};

}  // namespace adaptex::studio
