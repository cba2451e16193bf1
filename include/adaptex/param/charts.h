#pragma once
/// \file charts.h
/// Segmentation of a surface into a few charts for a multi-chart layout (docs/charts.md).
/// Charts are grown from seeds over the dual graph with a cost that adds normal deviation to
/// geodesic distance, in the spirit of the Lloyd-style region growing of Sander et al. 2003
/// ("Multi-chart geometry images") and Julius, Kraevoy, Sheffer 2005 ("D-Charts": developable,
/// compact charts), then re-seeded at their centres a few times. Each chart is then cut to a disk
/// and parameterized like a component (unwrap.h).
#include <memory>
#include <vector>

#include "adaptex/core/mesh.h"

namespace adaptex {

/// Settings of segment_charts().
struct ChartSegmentOptions {
  /// Number of charts (seeds). Fewer come out only if the mesh has fewer faces.
  int num_charts = 8;
  /// Lloyd iterations: after growing, every seed moves to the centre of its chart (the face
  /// farthest from the chart's border) and the charts are grown again.
  int lloyd_iterations = 3;
  /// Normal penalty of a dual step f -> g of length d: cost d * (1 + normal_weight * (1 - n_g·n_c)),
  /// n_c = the area-weighted mean normal of the chart (the seed's normal before the first
  /// iteration). 0 gives plain geodesic Voronoi cells (compact charts: the highest texel share
  /// measured, docs/charts.md); higher values follow creases.
  double normal_weight = 0.0;
};

/// Splits \p mesh into connected charts (through shared edges).
/// Seeds: farthest-point sampling on the dual graph (step length = distance between face
/// centroids), starting from the face farthest from face 0. Growth: multi-source Dijkstra with the
/// cost of ChartSegmentOptions::normal_weight. Then ear removal (a face alone at a vertex of its
/// chart moves to the chart with most faces there; greedy, it does not always converge), and every
/// chart with more than four ears left is halved until none has (a disk with more than four ears
/// cannot go onto the square without flattening them, docs/charts.md).
/// \pre mesh has manifold edges (at most two faces per edge) and is connected (one component)
/// \return F labels in [0, C), C about min(num_charts, F) (more where charts were halved or split
///         into parts); every label is used and each chart is connected through edges
/// \throw InvalidInputError num_charts < 1, lloyd_iterations < 0, normal_weight < 0 or not finite, no faces
std::vector<int> segment_charts(const TriMesh& mesh, const ChartSegmentOptions& options = {});

/// segment_charts() for one mesh at several chart counts: keeps the dual graph, the vertex-face
/// incidences and the farthest-point seed sequence (the seeds of k charts are the first k of any
/// longer sequence) between calls. segment(o) returns exactly segment_charts(mesh, o).
/// --charts auto segments each component at 4, 6, 8, 12, ... charts (unwrap.h).
class ChartSegmenter {
 public:
  /// \pre \p mesh outlives the segmenter and is not changed; the preconditions of segment_charts()
  /// \throw InvalidInputError the mesh has no faces
  explicit ChartSegmenter(const TriMesh& mesh);
  ~ChartSegmenter();
  ChartSegmenter(ChartSegmenter&&) noexcept;
  ChartSegmenter& operator=(ChartSegmenter&&) noexcept;

  /// segment_charts(mesh, options).
  /// \throw InvalidInputError as segment_charts()
  std::vector<int> segment(const ChartSegmentOptions& options);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One chart cut out of a mesh: its own vertices (a vertex where the chart's faces meet in several
/// separate fans gets one vertex per fan, so every chart is edge- and vertex-manifold).
struct ChartMesh {
  TriMesh mesh;               ///< The chart's faces, in input order, with local vertex ids.
  std::vector<int> faces;     ///< Local face -> input face.
  std::vector<int> vertices;  ///< Local vertex -> input vertex.
};

/// Cuts \p mesh into the charts given by \p face_chart (F labels in [0, num_charts)).
/// \pre mesh has manifold edges
/// \return num_charts charts (a label no face uses gives an empty chart)
/// \throw InvalidInputError face_chart has the wrong size or a label outside [0, num_charts)
std::vector<ChartMesh> extract_charts(const TriMesh& mesh, const std::vector<int>& face_chart,
                                      int num_charts);

}  // namespace adaptex
