#pragma once
/// \file texel_map.h
/// The texel -> surface map: for every texel centre inside a UV triangle, the face and barycentric
/// coordinates of the surface point it stands for, and that 3-D point. Built by rasterizing the UV
/// triangles; the CPU equivalent of the thesis' UV-swap rendering (§3.4).
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// A texel that one more UV triangle covers than the one TexelMap::face names: overlapping charts
/// (e.g. a mirrored half) share it, so it also stands for this surface point.
struct TexelAlias {
  int texel = 0;                ///< j*W+i.
  int face = 0;                 ///< The other triangle.
  Eigen::Vector2f bary;         ///< Barycentric (b0, b1) on that face.
  Vec3f position;               ///< 3-D point at the texel centre on that face.
};

struct TexelMap {
  int width = 0, height = 0;
  std::vector<int> face;        ///< W*H: face id at the texel centre, -1 outside every chart.
  std::vector<Eigen::Vector2f> bary;  ///< W*H: barycentric (b0, b1) on that face (b2 = 1-b0-b1).
  std::vector<Vec3f> position;  ///< W*H: 3-D point at the texel centre (undefined where face = -1).
  std::vector<int> inside;      ///< Indices (j*W+i) of the texels with face >= 0, row by row.
  /// Every further triangle over a texel of `inside` (shared texels), row by row; empty without
  /// overlap, and unless build_texel_map() was asked for them.
  std::vector<TexelAlias> aliases;

  int index(int i, int j) const { return j * width + i; }
};

/// Rasterizes \p param at width x height (texel centres at ((i+0.5)/W, (j+0.5)/H), v = 0 bottom).
/// Where UV triangles overlap, the last one in face order is the texel's `face`; the others are
/// listed in `aliases` when \p with_aliases (the painter; other readers of a texel need one point
/// of it and skip the list). Parallel over rows. \pre width, height > 0
TexelMap build_texel_map(const TriMesh& mesh, const Parameterization& param, int width, int height,
                         bool with_aliases = false);

}  // namespace adaptex
