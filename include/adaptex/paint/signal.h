#pragma once
/// \file signal.h
/// The exact painted signal C(p) of a stroke file at surface points (the ground truth of every
/// quality measurement; contract: shared/docs/strokes.md). Brush dabs are found through a
/// multi-level uniform grid hash (one level per power-of-two radius class), so evaluating 10^6
/// points against 10^5 dabs costs about the number of dabs that actually reach each point.
#include <memory>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/strokes.h"

namespace adaptex {

/// A point on a mesh face: barycentric (b0, b1, 1-b0-b1) on the corners of face `face`.
struct SurfacePoint {
  int face = -1;
  double b0 = 1.0 / 3, b1 = 1.0 / 3;
};

/// Evaluates C(p) for all strokes of a file, in file order, over the file's background.
/// Build once, query from any number of threads.
class StrokeSignal {
 public:
  /// \pre \p mesh and \p strokes stay alive while the signal is used (decals need the mesh for
  ///      visibility); strokes are as read_strokes() returns them
  /// \throw InvalidInputError a stroke violates the contract's rules (validate_stroke)
  StrokeSignal(const TriMesh& mesh, const StrokeFile& strokes);
  ~StrokeSignal();
  StrokeSignal(StrokeSignal&&) noexcept;
  StrokeSignal& operator=(StrokeSignal&&) noexcept;

  /// C at the 3-D point \p p of face \p face (the face is only used by decal strokes; -1 is allowed
  /// when the file has no decal). RGB in [0,1].
  Vec3 evaluate(const Vec3& p, int face = -1) const;
  /// C at a surface point of the mesh. \pre 0 <= sp.face < F
  Vec3 evaluate(const SurfacePoint& sp) const;
  /// C at many surface points, in parallel (TBB). Result k belongs to points[k].
  std::vector<Vec3> evaluate(const std::vector<SurfacePoint>& points) const;

  /// True if some stroke is a decal (those need a face with every point).
  bool has_decals() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The exact signal C at a fixed set of surface points, kept up to date stroke by stroke: each
/// add_stroke() composites one stroke over the stored colours (the contract composites strokes in
/// order, C <- C (1 - a) + colour a), touching only the points inside the stroke's bounding box (a
/// brush stroke; a decal is evaluated at every point). The cost of a stroke is one box test per point
/// plus O(points in its box x its dabs), independent of how many strokes came before; values() equals StrokeSignal(mesh,
/// history).evaluate(points()) up to rounding (the same arithmetic in the same order; tested).
/// Used by PaintSession's safeguard (adapt/session.h) instead of evaluating the whole history again
/// after every stroke.
class PointSignalCache {
 public:
  /// \param mesh the surface of \p points (kept by reference: must outlive the cache)
  /// \param points surface points, shape [P]
  /// \param background colour of unpainted surface, RGB in [0,1]
  /// \pre 0 <= points[k].face < mesh.num_faces()
  /// \throw InvalidInputError a face index out of range
  PointSignalCache(const TriMesh& mesh, std::vector<SurfacePoint> points, const Vec3& background);
  ~PointSignalCache();
  PointSignalCache(PointSignalCache&&) noexcept;
  PointSignalCache& operator=(PointSignalCache&&) noexcept;

  /// Composites \p stroke over the stored colours.
  /// \throw InvalidInputError the stroke breaks the contract's rules (validate_stroke)
  void add_stroke(const Stroke& stroke);
  /// Brings the cache up to date with \p history: adds strokes [strokes(), history.strokes.size()).
  /// \pre the first strokes() strokes of \p history are the ones added so far, same background
  /// \throw InvalidInputError as add_stroke
  void update(const StrokeFile& history);

  const std::vector<SurfacePoint>& points() const;  ///< The points, shape [P].
  const std::vector<Vec3>& values() const;          ///< C at points()[k], shape [P].
  int strokes() const;                              ///< Strokes composited so far.
  bool has_decals() const;                          ///< Some composited stroke was a decal.

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Brute-force C(p) straight from the contract (every dab of every brush stroke; decals are not
/// supported and throw InvalidInputError). For tests of the fast paths.
Vec3 evaluate_strokes_reference(const StrokeFile& strokes, const Vec3& p);

}  // namespace adaptex
