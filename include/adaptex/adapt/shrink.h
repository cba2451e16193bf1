#pragma once
/// \file shrink.h
/// Atlas-preserving shrink of a textured asset: islands of texel-sharing charts get an error-model
/// budget, are repacked with a gutter, and every map is fitted to the original (docs/shrink.md).
#include <cstdint>
#include <string>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/progress.h"

namespace adaptex {

/// What a texture map holds, which decides how its error counts.
enum class MapKind {
  Color,   ///< Colour (base colour, emissive): squared RGB difference, weight 1.
  Normal,  ///< Tangent-space normal map: counted by its effect on Lambert shading (docs/shrink.md).
  Data,    ///< Roughness / metallic / occlusion: squared channel difference, weight 0.25.
};

/// The kind of a map named \p slot: "normal" is Normal; "metallic_roughness", "roughness", "metallic",
/// "occlusion", "bump", "specular" are Data; anything else (base colour, emissive) is Color.
MapKind map_kind_of_slot(const std::string& slot);

/// One map of the material: the texture and what it holds.
struct ShrinkMap {
  std::string slot;  ///< Name of the map ("baseColor", "normal", ...): reports only.
  ImageRGBA8 image;  ///< The original texture on the input layout (any size).
  MapKind kind = MapKind::Color;
};

/// Settings of shrink_textured_mesh(), by stage.
struct ShrinkOptions {
  int size = 256;  ///< Output width = height in texels, in [8, kMaxTextureSize] (default 256).
  // Islands.
  /// Texel overlap (share of the smaller chart's) above which two charts move together (default 0.02).
  double overlap_share = 0.02;
  // Budget.
  bool budget = true;  ///< Per-island texel budget from the error model; false: one scale for all (default on).
  /// Surface samples of the error model, taken from the evaluation's (at most eval_samples; default 100k).
  long long error_samples = 100000;
  /// Largest ratio between an island's texel spacing and the uniform layout's, either way (default 4).
  double max_scale_ratio = 4.0;
  // Packing.
  int gutter = 1;  ///< Texels of dilation around each island (2 = the gap between two islands; default 1).
  bool rotate = true;  ///< Islands may turn by multiples of 90° (orientation is kept; default on).
  // Warp.
  /// Also try the budget layout with every island warped inside itself towards its detail (default on).
  bool island_warp = true;
  /// Island warp: largest texel density ratio along each axis of an island (>= 1; default 4); a gentle
  /// warp (ratio min(1.5, this)) is tried too and the better kept.
  double island_warp_ratio = 4.0;
  /// Island warp: also try cells' areas from their own measured error curves (equal marginal gain, as
  /// the island budget) besides area ∝ (error / area)^(2/3), the edge law; the better is kept (default on).
  bool island_warp_measured = true;
  /// Also try the density-flow warp of the layout when no charts share texels (default on); with
  /// island_warp, that warp refined by every island warped in place too ("warped_islands").
  bool warp = true;
  // Topology.
  /// Largest share of faces a layout may add to the input's (default 0.10); 0 keeps the input's faces
  /// exactly (`--no-refine`). Every candidate keeps the input's faces (none refines), so every
  /// candidate is within any bound (reported as faces_before / faces_after).
  double max_face_growth = 0.10;
  // Candidates.
  long long eval_samples = 200000;  ///< Surface samples of the PSNR that picks the candidate (default 200k).
  std::uint64_t seed = 7;  ///< Seed of the surface samples (default 7).
  /// Output this candidate ("downsized", "artist", "repacked", "budget", "island_warp", "warped",
  /// "warped_islands") when it is valid, whatever its PSNR (experiments; default "": the best).
  std::string force_candidate;
  ProgressCallback progress;  ///< Phases "islands", "error model", "pack", "texels", "evaluate".
};

/// One candidate layout and its measured quality.
struct ShrinkCandidate {
  std::string name;  ///< "downsized", "artist", "repacked", "budget", "island_warp", "warped", "warped_islands".
  /// Surface PSNR of the first map against the original (dB), with draft-fitted texels on a quarter of
  /// the evaluation's samples: what ranks the candidates.
  double psnr = 0;
  double fill = 0;   ///< Repacked: share of the output square's texels the packed islands touch.
  bool valid = true; ///< false: could not be built (e.g. the islands did not fit); psnr unset.
};

/// Geometry and sharing figures of a layout against the input.
struct ShrinkLayoutStats {
  int flipped = 0;     ///< Faces whose UV orientation differs from the input's (0 expected).
  int degenerate = 0;  ///< Faces with a UV area below 1e-6 square texels (of the layout's resolution).
  /// Share of the chart-covered texels covered by two or more charts (texel centres; the input at
  /// its map's size, the output at the output size).
  double shared_fraction = 0;
  /// Share of the surface (3-D area) whose texels other charts share too (the texel under each face's
  /// centroid): unlike shared_fraction, it does not change when islands are scaled.
  double shared_surface = 0;
};

/// Result of shrink_textured_mesh().
struct ShrinkResult {
  Parameterization param;          ///< The output layout (the input mesh's faces; UVs in [0,1]²).
  std::vector<ImageRGBA8> maps;    ///< The output maps, size x size, parallel to the input maps.
  std::string chosen;              ///< Name of the chosen candidate.
  double psnr = 0;                 ///< Surface PSNR of the first map, chosen candidate (dB).
  double psnr_downsized = 0;       ///< Same, plain box downsizing with the artist's UVs.
  std::vector<double> map_psnr, map_psnr_downsized;  ///< Per map, same measure.
  std::vector<ShrinkCandidate> candidates;
  int charts = 0, islands = 0;     ///< UV-connected charts of the input; islands that move together.
  ShrinkLayoutStats before, after; ///< Input layout (at the first map's size) / output layout.
  int faces_before = 0, faces_after = 0;
  /// Degenerate UV faces (after.degenerate's measure) given a tiny area in their input orientation,
  /// so that none remains: the input's, which scaling keeps, and any a layout made.
  int lifted_faces = 0;
  double predicted_gain_db = 0;    ///< Error model: budget over uniform repack at the packed scale.
  double time_total = 0;           ///< Seconds.
};

/// Shrinks \p maps (all on layout \p param of \p mesh) to options.size² texels each on a new layout.
/// UVs outside [0,1] are read with wrapping (repeat): every chart first moves by the integer tile offset
/// that brings its centre into [0,1)², so that even the artist's layout ("downsized", "artist") reads
/// the same texels clamped. A chart wider than one tile keeps crossing the border.
/// \pre param matches mesh (param.uv_faces.size() == mesh.faces.size()); at least one map
/// \throw InvalidInputError empty maps, non-finite UVs, size out of range, inconsistent layout, an
/// unknown options.force_candidate
/// \throw CancelledError options.progress returned false
ShrinkResult shrink_textured_mesh(const TriMesh& mesh, const Parameterization& param,
                                  const std::vector<ShrinkMap>& maps, const ShrinkOptions& options = {});

/// Islands of a layout: UV-connected charts (faces sharing a wedge, or wedges of one vertex at the same
/// UV) grouped by shared texels (coverage overlap, options.overlap_share, wrapped at \p resolution).
struct UvIslands {
  std::vector<int> face_chart;   ///< F: chart of every face.
  std::vector<int> chart_island; ///< C: island of every chart.
  std::vector<Vec2> chart_shift; ///< C: integer UV shift that brings the chart's centre into [0,1)².
  int num_charts = 0, num_islands = 0;
  bool tiling = false;  ///< Some chart spans more than the whole texture (a tiling texture): not repackable.
};
/// \pre param consistent, UVs finite. \p resolution >= 1: raster of the overlap test.
UvIslands find_uv_islands(const Parameterization& param, int resolution, double overlap_share);

/// Layout figures of \p param against \p reference (same faces of \p mesh): flips judged per face
/// against the reference's own orientation, and the texels covered by several charts of \p face_chart
/// at resolution x resolution (texel centres, UVs wrapped).
ShrinkLayoutStats layout_stats(const TriMesh& mesh, const Parameterization& reference, const Parameterization& param,
                               const std::vector<int>& face_chart, int resolution);

}  // namespace adaptex
