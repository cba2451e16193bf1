#pragma once
/// \file surface_cache.h
/// A surface-space cache of the painted signal, finer than the texture, updated per stroke, from
/// which the texture of any layout of the same surface is resampled in O(texels) — instead of
/// replaying every dab of the history on it. Per-face samples on a regular barycentric
/// lattice, as Mesh Colors (Yuksel, Keyser, House: "Mesh Colors", Tech. Rep. TAMU 2010): face f of
/// longest edge e carries n_f = ceil(e / spacing) subdivisions, i.e. (n_f+1)(n_f+2)/2 samples at
/// barycentrics (1 - i/n - j/n, i/n, j/n), 0 <= i + j <= n (edge and corner samples are stored once
/// per face). Each sample holds the exact signal at its point (stroke-file contract, as the Painter
/// does at texel centres, to 16-bit fixed point: 8 bytes per sample with the stroke's coverage); a
/// query interpolates linearly in the lattice triangle around the point. A dab finds the faces it may
/// reach through an index of the face centroids (faces binned by size), and in each face only the
/// lattice rows and columns under the ball: the index costs O(faces), not O(samples).
///
/// Error: exact at the samples; between them the linear interpolation of the signal, so an error of
/// at most spacing² |∇²C| / 8 where C is smooth (soft brushes) and up to the full contrast within one
/// spacing of a hard brush edge. With the spacing a third of the texel spacing, the texture resampled
/// from the cache is within a fraction of a dB of exact replay (tests/paint/test_surface_cache.cpp).
#include <memory>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

class SurfaceSignalCache {
 public:
  /// \param mesh the surface (kept by reference: must outlive the cache)
  /// \param spacing target distance between neighbouring samples (world units)
  /// \param background colour of unpainted surface, RGB in [0,1]
  /// \param max_samples refuse a lattice larger than this
  /// \throw InvalidInputError spacing <= 0 or not finite, background outside [0,1], or more than
  ///        max_samples samples
  SurfaceSignalCache(const TriMesh& mesh, double spacing, const Vec3& background,
                     long long max_samples = 50'000'000);
  ~SurfaceSignalCache();
  SurfaceSignalCache(SurfaceSignalCache&&) noexcept;
  SurfaceSignalCache& operator=(SurfaceSignalCache&&) noexcept;

  /// Composites one stroke over the samples: brush dabs through the index of the faces (cost ~ the
  /// samples the dabs reach, independent of the strokes before), decals at every sample.
  /// \throw InvalidInputError the stroke breaks the contract's rules (validate_stroke)
  void add_stroke(const Stroke& stroke);
  /// Adds strokes [strokes(), history.strokes.size()) of \p history.
  /// \pre the first strokes() strokes of \p history are the ones added so far
  void update(const StrokeFile& history);

  /// The interpolated signal at barycentrics (b0, b1) of face \p face. \pre 0 <= face < F
  Vec3f colour(int face, double b0, double b1) const;
  /// The colours of the chart texels of \p map (a texel map of a layout of \p map_mesh), shape
  /// [map.inside.size()], in parallel (TBB). \p parent_face: if not null, \p map_mesh is a
  /// refinement of the cache's mesh and parent_face[c] the cache face that face c lies on (the texel's
  /// 3-D point is located in that face); else \p map_mesh has the cache mesh's faces.
  /// \throw InvalidInputError a map face out of range of map_mesh or parent_face
  std::vector<Vec3f> texel_colours(const TexelMap& map, const TriMesh& map_mesh,
                                   const std::vector<int>* parent_face = nullptr) const;

  /// The samples a cache of \p mesh at \p spacing would have (O(faces), nothing allocated).
  /// \pre spacing > 0 \throw InvalidInputError spacing <= 0 or not finite
  static long long count_samples(const TriMesh& mesh, double spacing);

  int strokes() const;             ///< Strokes composited so far.
  long long num_samples() const;   ///< Samples of the lattice.

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex
