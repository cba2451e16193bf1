#pragma once
/// \file unwrap.h
/// The whole initial parameterization pipeline: cut every component to a disk (§3.2), Floater
/// parameterization onto the square (§2.2), Yoshizawa–Belyaev–Seidel stretch minimization (§3.3),
/// cut augmentation, and chart packing into [0,1]^2.
#include <string>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/progress.h"
#include "adaptex/param/disk_param.h"  // EmbeddingWeights

namespace adaptex {

/// How unwrap() divides the surface into charts (docs/charts.md).
enum class ChartMode {
  /// One chart per connected component (thesis §3.2): no seams beyond the cut.
  Single,
  /// One chart per component when that layout reaches UnwrapOptions::min_texel_share; otherwise
  /// the components are segmented into 4, 6, 8, 12, 16, ... charts (up to max_charts) until a layout
  /// reaches it, and the layout with the highest effective texel share is kept; when none reaches
  /// it, the charts of the scan segmentation (scan_* options) are built too. On one component,
  /// a single chart predicted to fail (UnwrapOptions::single_probe_l2) is skipped and the counts
  /// from probe_first_charts on are tried first.
  Auto,
};
/// "auto", "single".
template <>
std::span<const EnumName<ChartMode>> enum_names<ChartMode>();

/// Settings of unwrap().
struct UnwrapOptions {
  /// Weights of the initial embedding. Mean-value by default: on the shared meshes it gives lower
  /// final L2 than shape-preserving on 7 of 10 and solves faster (docs/parameterization.md).
  EmbeddingWeights weights = EmbeddingWeights::MeanValue;
  /// Meshes with more faces than this use shape-preserving weights even when `weights` is
  /// MeanValue: the multigrid solver converges about twice as fast on them (1M-face torus: 15 s vs
  /// 28 s for the whole unwrap on 2 cores) at a slightly higher L2 (1.69 vs 1.66). docs/parameterization.md.
  int mean_value_max_faces = 300000;
  /// Yoshizawa exponent η: weights are divided by σ^η. 1.0 as in the paper.
  double yoshizawa_eta = 1.0;
  /// Maximum Yoshizawa re-weighting iterations (stops earlier when L2 stops improving).
  int yoshizawa_max_iterations = 30;
  /// Maximum number of cut augmentations (Gu et al. 2002) per chart; 0 disables augmentation.
  int max_augmentations = 8;
  /// Yoshizawa iterations of the cheaper parameterization that compares the augmentation candidates
  /// (the thesis §3.2 uses Yoshizawa instead of full stretch minimization here for speed).
  int augment_yoshizawa_iterations = 1;
  /// Augmentation budget in face-solves: one candidate costs (1 + augment_yoshizawa_iterations)
  /// sparse solves of its chart's size. A chart is augmented only if its first two evaluations fit
  /// in what is left of the budget (over all charts); augmentation stops when the next would not
  /// fit. Deterministic; bounds the cost on large meshes. Exception: a chart whose cheap
  /// parameterization still has degenerate UV triangles (an extremity squeezed by the Tutte
  /// embedding) is augmented regardless of both budgets, up to max_augmentations. docs/surgery.md.
  long augment_face_budget = 2000000;
  /// Augmentation budget in seconds of wall time from the start of unwrap(); no new augmentation
  /// step starts after it (<= 0: none, except as above; NaN is refused). A safety bound for very
  /// slow machines, set high enough that the (deterministic) face budget decides on ordinary ones,
  /// even loaded (docs/surgery.md).
  double augment_time_budget = 600.0;
  /// An augmentation is kept only if it lowers the chart's L2 stretch by this relative amount;
  /// the first one that does not stops the augmentation of that chart.
  double augment_min_improvement = 0.005;
  /// Smallest gap between packed charts, as a fraction of the unit square; the gap is the larger of
  /// this and the gutter (gutter_texels / gutter_texture_size), for whole components as for
  /// segmented charts. A single chart fills the square.
  double chart_padding = 0;
  /// Single: one chart per component; Auto (default): segment into several charts only when one
  /// chart per component wastes too many texels (docs/charts.md).
  ChartMode charts = ChartMode::Auto;
  /// Auto keeps one chart per component when its effective texel share (coverage / L2², see
  /// UnwrapReport) is at least this; 0.5 = half of the texture's texels do useful work.
  double min_texel_share = 0.5;
  /// Auto: the largest number of charts tried (over the whole mesh, plus the components).
  int max_charts = 64;
  /// Auto, meshes of one component: when the first cheap parameterization of the single chart
  /// (Floater + augment_yoshizawa_iterations Yoshizawa iterations, before the cut augmentation)
  /// has degenerate or flipped UV triangles or an L2 stretch above this, the single chart is not
  /// finished (no augmentation, no full Yoshizawa solve) and the segmentation starts at
  /// probe_first_charts charts; it is built after all only if no segmentation reaches
  /// min_texel_share. 3: every shared and code-built mesh whose single chart reaches a share of
  /// 0.5 starts at an L2 of at most 2.47 (venus); docs/charts.md. 0 disables the probe.
  double single_probe_l2 = 3.0;
  /// Auto, after the probe above gave up the single chart: the chart counts >= this are tried
  /// first (12: 12, 16, 24, ..., then 4, 6, 8). 4 keeps the order 4, 6, 8, ...: the probe then only
  /// skips the single chart, and the fewest charts that reach the share are kept. 12 (the default)
  /// builds one layout where 4 first builds three or four: triceratops 52 -> 24 ms, dino
  /// 103 -> 34 ms. An earlier default of 4 was kept because triceratops' 12
  /// charts adapted badly (texel saving ~1.7x); the cause was the safe remap (a 3-D sliver whose
  /// neighbours overlapped, SafeRemapOptions::damp_overlaps), not the layout. With it fixed, 12
  /// first gains 0.5 dB on lines, dots and mixed on the meshes whose layout changes, and its seams
  /// cost smooth paint up to 5 dB at 128² (about 1 dB at 256², above 60 dB; docs/charts.md, "What
  /// auto does").
  int probe_first_charts = 12;
  /// Auto: how many chart counts may be built at the same time (TBB tasks). With S > 1, each of the
  /// next S - 1 counts starts on the threads the count before it no longer needs (once that one has
  /// started its last chart) and is cancelled and discarded if an earlier count is kept. The counts
  /// are decided in their order with the same rule, so the layout does not depend on S or on the
  /// number of threads (test Unwrap.SpeculativeAttemptsGiveTheSequentialLayout). 1 (default): one
  /// count after the other, the least CPU time; on 2 cores 2 gave no wall-time gain that stood out
  /// of the noise and up to 20 % more CPU time (docs/history/benchmarks.md).
  int speculative_attempts = 1;
  /// Auto: normal penalty of the chart growth (ChartSegmentOptions::normal_weight). 0 (compact
  /// geodesic charts) gave the highest texel share on every mesh measured (docs/charts.md). Finite, >= 0.
  double chart_normal_weight = 0.0;
  /// Gutter between packed charts (components or segmented charts) in texels of a
  /// gutter_texture_size² texture: the gap is gutter_texels / gutter_texture_size of the unit
  /// square. 8 texels at 1024 leave room for the 4-texel seam padding of both neighbouring charts
  /// (paint/padding.h); `adaptex paint --size N` sets gutter_texture_size = N.
  double gutter_texels = 8;
  /// See gutter_texels.
  int gutter_texture_size = 1024;
  /// Layouts of several charts: no chart's rectangle has a side shorter than this times the gap
  /// between charts (a minimum texel floor for tiny components and slivers; 1: no chart smaller
  /// than its gutter). 0 disables the floor. In [0, 4].
  double min_chart_side_of_gap = 1.0;
  // Auto on scans: meshes with more components than max_charts / 2 (docs/charts.md, "Scans").
  /// Scans: components of more faces than this are first split into pieces of about this many
  /// faces (bounds the size of the probing solves). >= 64.
  int scan_piece_faces = 50000;
  /// Scans: a piece whose cheap parameterization has an L2 stretch above this (at its best
  /// rectangle aspect) is split in two when the predicted gain in texel share (lower L2) exceeds
  /// the predicted loss (the gutter along the new seam), down to pieces of 8 faces; a piece of
  /// 32 faces or more with degenerate or flipped UV triangles is split regardless
  /// (docs/charts.md, "Scans"). >= 1.
  double scan_chart_l2 = 1.1;
  /// Scans: every chart of the scan segmentation also tries a free-boundary conformal layout
  /// (LSCM, lscm.h) of its disk and keeps it when valid and its texel share (fill of its
  /// rectangle / L2²) is higher; the probes that decide the splits do the same (docs/charts.md,
  /// "Scans"). true (default); false: the disk parameterization (and unfolding) only.
  bool scan_free_boundary = true;
  /// Scans, with scan_free_boundary: the top-down candidate (unwrap_scan()) also gives its charts
  /// those layouts and the SLIM tries; its segmentation stays that of the disk layouts
  /// (docs/decisions.md, "Scans: free-boundary layouts for the top-down candidate"). true
  /// (default); false: its charts keep the disk layouts and unfoldings.
  bool scan_top_down_free_layouts = true;
  /// Scans, with scan_free_boundary: every chart also tries a free-boundary, locally injective
  /// layout of low symmetric Dirichlet energy (SLIM, slim.h) started from its chosen one, with at
  /// most this many iterations, kept when its texel share is higher (docs/charts.md, "Scans").
  /// 12 (default); 0: none. >= 0.
  int scan_slim_iterations = 12;
  /// Scans: the SLIM try is kept when its fill^this / L2² beats the chart's (the other layouts are
  /// scored with scan_layout_fill_exponent). 1 (default). In [0, 1].
  double scan_slim_fill_exponent = 1.0;
  /// Scans: near-isometric SLIM charts that fill little of their rectangle nest when packed by
  /// shape, but not on every mesh (docs/decisions.md). (1) Every layout of the planar candidate is
  /// also packed with the SLIM tries that fill^this / L2² takes and fill^scan_slim_fill_exponent
  /// rejects, kept if its share is higher (same charts, no new seams). (2) On meshes of up to
  /// scan_regrow_max_faces faces whose planar candidate (and its regrowth) is short of
  /// min_texel_share, the candidate is built a second time with scan_slim_fill_exponent = this,
  /// kept if its share is higher. 0.5 (default); negative: neither. At most 1.
  double scan_slim_second_exponent = 0.5;
  /// Scans: components are first cut into planar charts (planar.h: faces whose normal is within
  /// this many degrees of the chart's mean normal) and the connected parts of the rest, before the
  /// top-down splitting (docs/charts.md, "Scans"). 20 (default); 0 disables it. In [0, 90).
  double scan_planar_angle = 20.0;
  /// Scans: planar charts of less than this fraction of the mesh's area are given back to the rest.
  double scan_planar_min_area = 0.001;
  /// Scans, with scan_planar_angle > 0: normal penalty of the chart growth
  /// (ChartSegmentOptions::normal_weight) in the halvings of the planar candidate's pieces; the
  /// top-down candidate and the first split of large components keep chart_normal_weight
  /// (docs/charts.md, "Scans"). 1 (default); 0: as chart_normal_weight = 0. Finite, >= 0.
  double scan_planar_normal_weight = 1.0;
  /// Scans, with scan_planar_angle > 0: the planar candidate's charts whose own L2 stretch is above
  /// this are cut by a bottom-up planar growth (normal cone scan_regrow_angle) and that layout is
  /// built too, kept if its share is higher (docs/decisions.md, "Scans: regrowing stretched
  /// charts"). 2 (default); 0: never. 0 or finite and >= 1.
  double scan_regrow_l2 = 2.0;
  /// Scans: the normal cone of that growth, degrees in (0, 90). 30 (default).
  double scan_regrow_angle = 30.0;
  /// Scans: meshes of more faces skip that regrowth (it adds a third layout to build and pack:
  /// +34 % CPU on a 1.09M-face scan for +0.002 share; docs/decisions.md). 500000 (default); >= 0.
  int scan_regrow_max_faces = 500000;
  /// Scans: rounds of splitting (each round at most doubles the pieces). >= 0.
  int scan_max_rounds = 12;
  /// Scans: meshes of at most this many faces also build one chart per component, and the
  /// layout with the higher effective texel share is kept.
  int scan_single_max_faces = 100000;
  /// Scans: every layout is also packed by the charts' shapes (pack_shapes(), pack.h: irregular
  /// charts nest) besides their rectangles, and the packing with the higher effective texel share
  /// is kept (docs/charts.md, "Scans"). true (default).
  bool scan_pack_shapes = true;
  /// Scans, with scan_free_boundary: a chart takes the layout (square, free boundary, unfolding,
  /// projection) of the highest fill^e / L2², where fill is the part of its bounding rectangle the
  /// layout covers: 1 scores rectangles (what the rectangle packer places), 0 the stretch alone
  /// (what a shape packer places). 1 (default); 0.5 gains 0.003-0.008 of share on the Matterport
  /// scans but gives tiny_components(200) 410 charts instead of one per component
  /// (docs/bench_unwrap.md, "Shape packing"). In [0, 1].
  double scan_layout_fill_exponent = 1.0;
  /// Progress / cancel callback (phases "cut", "segment", "floater", "yoshizawa", "augment",
  /// "pack").
  ProgressCallback progress;
};

/// Figures about one unwrap() run (everything the `unwrap --report` JSON needs).
struct UnwrapReport {
  int num_components = 0;
  int num_charts = 0;            ///< Charts of the layout (>= num_components).
  int genus = 0;                 ///< Total genus over the components.
  int boundary_loops = 0;        ///< Boundary loops of the input.
  int augmentations = 0;         ///< Cut paths added by augmentation, over all charts.
  double cut_length = 0;         ///< Total 3-D length of the cut edges and chart seams (original
                                 ///< boundary excluded).
  double floater_l2 = 0;         ///< Mesh L2 stretch of the Floater embedding (before Yoshizawa).
  double floater_linf = 0;
  double final_l2 = 0;           ///< Mesh L2 stretch of the result.
  double final_linf = 0;
  double coverage = 0;           ///< Fraction of [0,1]^2 covered by UV triangles.
  double effective_texel_share = 0;  ///< coverage / final_l2²: the share of texels doing useful
                                     ///< work at the sampling rate of an ideal map.
  /// Gap between packed charts (and, with several charts, to the border), as a fraction of the
  /// unit square: the requested one, halved while the charts did not fit. A single chart fills the
  /// square and reports the requested gap.
  double gutter = 0;
  /// The requested gap (the larger of UnwrapOptions::chart_padding and the gutter); gutter <
  /// requested_gutter: the paint of neighbouring charts may bleed into each other at that size.
  double requested_gutter = 0;
  int yoshizawa_iterations = 0;  ///< Re-weighting iterations performed (summed over charts).
  /// Phase times in s, summed over charts and attempts (the charts of an attempt may be built in
  /// parallel, so the sum can exceed time_total).
  double time_cut = 0, time_floater = 0, time_yoshizawa = 0, time_augment = 0, time_pack = 0;
  double time_segment = 0;       ///< s, the scan segmentation (scan_pieces: probes and splits).
  double time_layouts = 0;       ///< s, the scan charts' other layouts (unfolding, projection, LSCM, SLIM).
  double time_total = 0;         ///< s
};

/// Result of unwrap().
struct UnwrapResult {
  Parameterization param;
  UnwrapReport report;
};

/// Parameterizes every connected component as one chart, or (ChartMode::Auto, when that wastes
/// texels) as several charts, packed into [0,1]^2 without overlap. Whatever the options, the
/// layout has no flipped, degenerate or overlapping UV triangle (invalid_uv_faces() is empty): a
/// chart that would have one is given another layout or split (even in ChartMode::Single).
/// Pinched vertices (several separate fans of faces at one vertex, core/pinched.h) are split and a
/// mixed face winding is made consistent (core/orientation.h) first: the charts are those of the
/// split, consistently wound surface; wedges refer to the input vertices and uv_faces to the input
/// corners (so a face wound against its neighbours has a UV triangle of negative signed area).
/// \pre mesh has manifold edges, valid indices and no degenerate faces (as read_mesh() returns it)
/// \throw TopologyError non-manifold edges, a non-orientable component
/// \throw InvalidInputError an option out of range (chart_padding outside [0, 0.25), negative
///        counts, max_charts < 1, a gutter of a quarter of the square or more, a scan_* option or
///        min_chart_side_of_gap out of its range)
/// \throw SolverError the sparse solve failed, or no valid layout was found (never happens on the
///        meshes measured: a chart with a flipped, degenerate or overlapping UV triangle gets another
///        layout or is split, down to single faces; docs/surgery.md, "Validity")
/// Memory: O(F). On scans the peak resident set grows by about 0.65 KB per face during the unwrap
/// (bound 1 KB per face, test UnwrapMemory); no chart of a scan is solved whole above
/// scan_piece_faces faces.
/// \throw CancelledError the progress callback returned false
UnwrapResult unwrap(const TriMesh& mesh, const UnwrapOptions& options = {});

/// \p base with the gutter of a layout that will hold a \p texture_size² texture painted with
/// \p padding texels of seam padding: the gutter is the padding, at least 2 texels (the bilinear
/// footprint of both neighbours), at most a fifth of the square. At least the padding is
/// required; measured with `adaptex paint` + `adaptex eval` (docs/history/quality.md, "Gutter of a paint run"),
/// 2 texels beat 4 by a median 0.25 dB and 8 by 0.71 dB, so a wider gutter only costs texels. Used by
/// `adaptex paint --size N --padding P` and by the studio, so both lay a mesh out the same way.
/// \pre 1 <= texture_size <= kMaxTextureSize (core/limits.h), padding >= 0
/// \throw InvalidInputError texture_size outside [1, kMaxTextureSize] or padding < 0
UnwrapOptions unwrap_options_for_texture(int texture_size, int padding, UnwrapOptions base = {});

}  // namespace adaptex
