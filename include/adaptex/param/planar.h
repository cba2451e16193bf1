#pragma once
/// \file planar.h
/// Bottom-up planar charts for scans, in the spirit of the chart growth of xatlas and of D-Charts
/// (Julius, Kraevoy, Sheffer 2005): faces join a chart while their normal stays within a cone
/// around the chart's mean normal. The walls, floors and ceilings of a room scan become charts
/// whose projection onto their plane is nearly isometric (L2 near 1); the rest of the surface is
/// left to the top-down scan segmentation (unwrap.h, docs/charts.md "Scans").
#include <optional>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/param/unfold.h"  // PolygonLayout

namespace adaptex {

/// Settings of planar_charts().
struct PlanarChartOptions {
  /// A face joins a chart when the angle between its normal and the chart's area-weighted mean
  /// normal is at most this (degrees, in (0, 90)); 20 keeps the projection's L2 of one face
  /// <= 1.03 (UnwrapOptions::scan_planar_angle).
  double max_normal_angle = 20.0;
  /// Rounds of smoothing of the face normals that decide the growth (each averages a face's normal
  /// with its edge neighbours', area-weighted) for noisy scans. 0 (default): none; 3 gave lower
  /// shares on two of four Matterport scans (docs/bench_unwrap.md).
  int normal_smoothing = 0;
  /// Planar charts of less than this fraction of the mesh's area are given back to the rest.
  double min_area_fraction = 0.001;
};

/// Result of planar_charts().
struct PlanarCharts {
  std::vector<int> label;  ///< F labels in [0, num_charts): each chart is connected through edges.
  int num_planar = 0;      ///< Labels [0, num_planar) are planar charts, the rest the connected
                           ///< parts of the remaining faces.
  int num_charts = 0;
};

/// Grows planar charts over the dual graph: seeds in order of decreasing face area, breadth-first
/// growth through shared edges while a face's normal is within max_normal_angle of the chart's
/// mean normal (updated as faces join), both normals smoothed (normal_smoothing), and the face's own
/// normal makes an angle below 90° with it. Zero-area faces never seed and join no planar chart.
/// \pre mesh has manifold edges
/// \throw InvalidInputError max_normal_angle outside (0, 90), min_area_fraction outside [0, 1] or
///        normal_smoothing < 0
PlanarCharts planar_charts(const TriMesh& mesh, const PlanarChartOptions& options = {});

/// Orthogonal projection of \p piece onto the plane of its area-weighted mean normal, turned into
/// its smallest bounding rectangle and scaled into [0,1]² (fit_to_rectangle()).
/// \return the layout, or std::nullopt when a projected triangle is flipped or degenerate or two
///         overlap, or the piece has no area
std::optional<PolygonLayout> projection_layout(const TriMesh& piece);

}  // namespace adaptex
