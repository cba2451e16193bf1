#pragma once
/// \file material_point_cache.h
/// A layered material's exact value at fixed surface points, kept up to date stroke by stroke: each
/// layer's own state per point (its value L, coverage a per channel and mask M; docs/strokes.md,
/// "Layer state"), composited over the background on demand. A new stroke costs one box test per
/// point plus the work of its dabs, independent of the strokes before it; the composite equals
/// evaluate_material() up to the single precision of the stored state (tested within 1e-5). The
/// version 2 analogue of PointSignalCache (signal.h), used by MaterialPaintSession.
#include <functional>
#include <memory>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/signal.h"

namespace adaptex {

class MaterialPointCache {
 public:
  /// Adds every stroke of \p file (update()).
  /// \param mesh the surface of \p points (kept by reference: must outlive the cache)
  /// \param points surface points, shape [P]
  /// \pre 0 <= points[k].face < mesh.num_faces()
  /// \throw InvalidInputError a face index out of range
  MaterialPointCache(const TriMesh& mesh, std::vector<SurfacePoint> points, const MaterialStrokeFile& file);
  /// The cache of other points (of another mesh) with \p file's strokes, as if constructed anew,
  /// reusing this one's storage (a session replays the history onto each candidate layout).
  /// \throw as the constructor
  void reset(const TriMesh& mesh, std::vector<SurfacePoint> points, const MaterialStrokeFile& file);
  ~MaterialPointCache();
  MaterialPointCache(MaterialPointCache&&) noexcept;
  MaterialPointCache& operator=(MaterialPointCache&&) noexcept;

  /// Adds the strokes appended to any layer or mask of \p file since the last call (layers may be
  /// appended too). Layer visibility, opacity and blend mode are read by values() only.
  /// \pre the strokes added so far are still the first ones of their layer / mask, in order
  /// \throw InvalidInputError fewer layers or strokes than already added
  void update(const MaterialStrokeFile& file);
  /// The composited material of \p file at every point, shape [P] (\pre update(file) was called).
  /// Recomputed only where strokes reached since the last call, unless the layers' blending changed;
  /// valid until the next call.
  const std::vector<MaterialValue>& values(const MaterialStrokeFile& file);
  /// As values(), calling \p changed(k, value) for every point k recomputed (from several threads).
  const std::vector<MaterialValue>& values(const MaterialStrokeFile& file,
                                           const std::function<void(size_t, const MaterialValue&)>& changed);

  const std::vector<SurfacePoint>& points() const;  ///< The points, shape [P].
  long long strokes() const;                        ///< Layer and mask strokes added so far.

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex
