#pragma once
/// \file material_surface_cache.h
/// The surface cache of a layered material: the version 2 analogue of SurfaceSignalCache
/// (surface_cache.h), on the same per-face sample lattice, holding at every sample each layer's own
/// state per channel and its mask (a MaterialPointCache at the lattice's samples, material_point_cache.h).
/// A stroke costs the samples its dabs reach, whatever the strokes before; the material at the chart
/// texels of any layout of the same surface (or of a refinement of it) is then interpolated from the
/// composited samples in O(texels), instead of replaying every stroke of every layer there.
///
/// Error: exact at the samples (within the point cache's 1e-5); between them the linear
/// interpolation of the composite, as SurfaceSignalCache's (tests/adapt/test_material_session.cpp
/// states the PSNR against exact replay). Memory: about 150 bytes per sample with one layer, 48 more
/// per further layer (docs/adaptive.md, "Material sessions").
#include <memory>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

class MaterialSurfaceCache {
 public:
  /// Adds every stroke of \p file.
  /// \param mesh the surface (kept by reference: must outlive the cache)
  /// \param spacing target distance between neighbouring samples (world units)
  /// \param max_samples refuse a lattice larger than this
  /// \throw InvalidInputError spacing <= 0 or not finite, or more than max_samples samples
  MaterialSurfaceCache(const TriMesh& mesh, double spacing, const MaterialStrokeFile& file,
                       long long max_samples = 20'000'000);
  ~MaterialSurfaceCache();
  MaterialSurfaceCache(MaterialSurfaceCache&&) noexcept;
  MaterialSurfaceCache& operator=(MaterialSurfaceCache&&) noexcept;

  /// Adds the strokes appended to any layer or mask of \p file since the last call (as
  /// MaterialPointCache::update()). \throw InvalidInputError fewer layers or strokes than added
  void update(const MaterialStrokeFile& file);

  /// The composited material of \p file at the chart texels of \p map (a texel map of a layout of
  /// \p map_mesh), shape [map.inside.size()], interpolated from the samples, in parallel (TBB).
  /// \p parent_face: as SurfaceSignalCache::texel_colours(). \pre update(file) was called
  /// \throw InvalidInputError a map face out of range of map_mesh or parent_face
  std::vector<MaterialValue> texel_values(const MaterialStrokeFile& file, const TexelMap& map, const TriMesh& map_mesh,
                                          const std::vector<int>* parent_face = nullptr);
  /// As above, into \p out (resized; its storage reused: a fresh vector of tens of MB costs a page
  /// fault per 4 KB, which on a loaded machine costs more than the interpolation).
  void texel_values(const MaterialStrokeFile& file, const TexelMap& map, const TriMesh& map_mesh,
                    const std::vector<int>* parent_face, std::vector<MaterialValue>& out);

  /// The samples a cache of \p mesh at \p spacing would have (O(faces), nothing allocated).
  /// \throw InvalidInputError spacing <= 0 or not finite
  static long long count_samples(const TriMesh& mesh, double spacing);

  long long num_samples() const;  ///< Samples of the lattice.
  long long strokes() const;      ///< Layer and mask strokes added so far.

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex
