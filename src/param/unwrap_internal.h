/// \file unwrap_internal.h
/// Private to src/param: what the files of the unwrap() pipeline share (docs/surgery.md, "Source
/// files of unwrap()"). unwrap_chart.cpp builds one chart per piece (cut, augmentation, layouts),
/// unwrap_pack.cpp packs the charts and keeps the layout valid, unwrap_scan.cpp segments and lays
/// out scans, unwrap.cpp runs the pipeline and the chart counts of ChartMode::Auto.
#pragma once

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/param/cut.h"
#include "adaptex/param/disk_param.h"
#include "adaptex/param/unfold.h"
#include "adaptex/param/unwrap.h"

namespace adaptex::unwrap_detail {

using Clock = std::chrono::steady_clock;

/// One connected component, extracted with compact vertex ids.
struct Component {
  TriMesh mesh;
  std::vector<int> faces;     ///< Local face -> input face.
  std::vector<int> vertices;  ///< Local vertex -> input vertex.
  double area = 0;            ///< 3-D surface area.
  /// The free-boundary layout (lscm_layout()) of the disk of the piece's initial cut, as its last
  /// probe computed it (probe_piece()); null when no probe computed it.
  std::shared_ptr<const std::optional<PolygonLayout>> probe_lscm;
  /// Its projection layout (projection_layout(), pieces that are disks), as its last probe
  /// computed it; null when no probe computed it.
  std::shared_ptr<const std::optional<PolygonLayout>> probe_projection;
};

/// A cut of one component with its disk and parameterization.
struct CutState {
  std::vector<char> cut;
  SlicedDisk disk;
  DiskParamResult param;
  DiskParamStatePtr solve_state;  ///< Where the cheap parameterization stopped (continued by the full one).
};

/// One layout of a chart: its parameterization with the figures packing reads, and its cut and
/// disk when they differ from the chart's (own_disk).
struct ChartLayout {
  bool own_disk = false;
  std::vector<char> cut;
  SlicedDisk disk;
  DiskParamResult param;
  double domain_area = 1;
  double aspect = 0;
  double cut_length = 0;
};

/// The chart of one component after the surgery and augmentation.
struct Chart {
  CutState state;
  double cut_length = 0;
  int augmentations = 0;
  double domain_area = 1;  ///< UV area of the chart in its own [0,1]^2 frame.
  /// > 0: the width / height of the chart's rectangle is fixed (an unfolded polygon, unfold.h);
  /// 0: best_aspect() chooses it.
  double aspect = 0;
  /// The chart was given up after its first cheap parameterization (ChartContext::give_up_l2):
  /// only `state.param` (that parameterization) is meaningful.
  bool abandoned = false;
  /// A valid SLIM layout of the chart's disk that its own score rejected and the alternative
  /// exponent accepts (use_slim_if_better()); pack_valid() packs the charts with these too.
  std::optional<PolygonLayout> alternative;
  /// The layout its disk parameterization and unfolding gave (not flipped or degenerate), kept
  /// when the free-boundary layouts replaced it on a segmentation that did not judge the pieces
  /// by them (the top-down candidate of unwrap_scan()); pack_valid() packs the charts with these
  /// too.
  std::unique_ptr<ChartLayout> unfolded;
};

/// Which layouts a piece may get besides its disk parameterization.
enum class PieceLayouts {
  Disk,    ///< the disk parameterization only
  Unfold,  ///< also the isometric unfolding of a piece without interior vertices (unfold.h)
  Free,    ///< also that, and a free-boundary (LSCM) layout (lscm.h; UnwrapOptions::scan_free_boundary)
  /// as Free, and the layout as Unfold leaves it is kept too (Chart::unfolded, pack_unfolded()):
  /// the top-down candidate of unwrap_scan() (UnwrapOptions::scan_top_down_free_layouts)
  FreeKeepUnfolded,
};

/// Runs \p body(i) for i in [0, n) in parallel (TBB, one index per task). An exception must not
/// leave a body: TBB would cancel the task group, and nested parallel algorithms still running
/// would return with part of their work undone. The first exception is kept, \p failed is set
/// (bodies poll it through their progress callbacks and stop) and it is rethrown once every body
/// has returned. \p mutex guards the first exception (and the callers' progress reports).
template <class Body>
void parallel_keep_first_error(int n, std::mutex& mutex, std::atomic<bool>& failed, Body body) {
  std::exception_ptr first_error;
  tbb::parallel_for(
      0, n,
      [&](int i) {
        try {
          body(i);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(mutex);
          if (!first_error) first_error = std::current_exception();
          failed = true;
        }
      },
      tbb::simple_partitioner{});
  if (first_error) std::rethrow_exception(first_error);
}

/// The pieces and charts of a valid packed layout, kept so that some charts can be rebuilt.
struct BuiltPieces {
  std::vector<Component> pieces;
  std::vector<Chart> charts;
};

/// Pieces of a few large folded faces are split down to 8 faces when split_pays() says so
/// (timed_scan_pieces()'s default min_probe_faces).
constexpr int kFineProbeFaces = 4;

// unwrap_chart.cpp: one chart per piece.

/// Swaps the layout of \p chart with its Chart::unfolded one.
void swap_unfolded(Chart& chart);

/// L2 stretch of the per-vertex map \p uv of \p disk scaled by (sqrt(a), 1 / sqrt(a)) (measured).
double l2_at_aspect(const TriMesh& disk, const std::vector<Vec2>& uv, double a);

/// Width / height ratio a of the rectangle that gives the chart the lowest L2 stretch when its
/// square parameterization is scaled by (sqrt(a), 1 / sqrt(a)): Chart::aspect when fixed, else the
/// best of 17 values from 1/4 to 4 (log-spaced). Multi-chart layouts only; a single chart keeps the
/// square. Returns (a, that L2).
std::pair<double, double> best_aspect(const Chart& chart);

/// A layout's own texel share as the chart choice scores it: fill^e / L2²
/// (UnwrapOptions::scan_layout_fill_exponent; e = 1: the share of its bounding rectangle).
inline double layout_score(double fill, double l2, double e) { return std::pow(fill, e) / (l2 * l2); }

/// Gives \p chart the layout \p u of its own disk (cut and disk unchanged).
void adopt_disk_layout(Chart& chart, PolygonLayout&& u);

/// The chart of every piece (build_chart()), phase times added to \p rep. The charts share the
/// augmentation face budget in piece order; when even the largest use of every chart
/// ((1 + max_augmentations) cheap evaluations) fits in it, the budget cannot run out, the charts do
/// not depend on each other, and they are built in parallel (TBB) with the same result. The
/// progress callback is then called under a mutex with a non-decreasing fraction. \p layouts: the
/// layouts a piece may take besides its disk parameterization; \p give_up_l2 as
/// ChartContext::give_up_l2.
/// \p on_last_started (if set) is called once, when the last chart starts (segment_until_good()
/// then starts the next chart count on the threads this attempt no longer needs).
std::vector<Chart> build_charts(const std::vector<Component>& pieces, const DiskParamOptions& dopt,
                                Clock::time_point t_start, const UnwrapOptions& options,
                                UnwrapReport& rep, PieceLayouts layouts, double give_up_l2 = 0,
                                const std::function<void()>& on_last_started = {});

// unwrap_pack.cpp: packing the charts into the square.

/// Total 3-D length of the seams of \p param: input edges whose two faces do not share both UV
/// corners.
double seam_length(const TriMesh& mesh, const Parameterization& param);

/// Packs \p charts (parallel to \p pieces) into \p result; while UV triangles are invalid, splits
/// their charts (split_invalid_charts()) and packs again. \p built (if set) receives the final
/// pieces and charts.
/// \throw SolverError still invalid after kMaxValidityRounds rounds
void pack_valid(const TriMesh& mesh, const std::vector<Component>& pieces, std::vector<Chart> charts,
                const DiskParamOptions& dopt, double padding, Clock::time_point t_start,
                const UnwrapOptions& options, UnwrapResult& result, PieceLayouts layouts,
                bool shapes, BuiltPieces* built);

/// Builds the chart of every piece and packs them into \p result (one unwrap() attempt).
/// \p layouts, \p give_up_l2 and \p on_last_started as in build_charts(); \p shapes as in assemble(); \p built as in pack_valid(). Returns
/// false, and leaves the layout of \p result alone (only its phase times grow), when a chart was
/// abandoned.
bool unwrap_pieces(const TriMesh& mesh, const std::vector<Component>& pieces,
                   const DiskParamOptions& dopt, double padding, Clock::time_point t_start,
                   const UnwrapOptions& options, UnwrapResult& result, PieceLayouts layouts,
                   double give_up_l2 = 0, const std::function<void()>& on_last_started = {},
                   bool shapes = false, BuiltPieces* built = nullptr);

// unwrap_scan.cpp: scans.

/// Builds the layout of \p pieces as a candidate and keeps it in \p result when its effective
/// texel share is higher, or when \p result has no layout yet (the phase times add up either way).
/// \p shapes as in assemble(). \p components > 0: compared by scan_prefers() instead.
void keep_better_layout(const TriMesh& mesh, const std::vector<Component>& pieces,
                        const DiskParamOptions& dopt, double gutter, Clock::time_point t_start,
                        const UnwrapOptions& options, PieceLayouts layouts, UnwrapResult& result,
                        bool shapes = false, size_t components = 0);

/// scan_pieces(), its time added to \p rep.time_segment.
std::vector<Component> timed_scan_pieces(const std::vector<Component>& comps,
                                         const DiskParamOptions& dopt, double gutter,
                                         const UnwrapOptions& options, double halving_weight,
                                         UnwrapReport& rep, int min_probe_faces = kFineProbeFaces);

/// ChartMode::Auto on a mesh with more components than max_charts / 2: the charts of
/// scan_pieces() with planar charts and free-boundary layouts (scan_planar_angle,
/// scan_free_boundary), and, when either is on, also those of the top-down segmentation alone (with
/// the free-boundary layouts when scan_top_down_free_layouts); on meshes of at most
/// scan_single_max_faces faces also its split down to 32 faces and one chart per component. The
/// layout kept is the first by scan_prefers(): one chart per component when that reaches
/// min_texel_share, otherwise the highest effective texel share.
void unwrap_scan(const TriMesh& mesh, const std::vector<Component>& comps,
                 const DiskParamOptions& dopt, double gutter, Clock::time_point t_start,
                 const UnwrapOptions& options, UnwrapResult& result);

// unwrap.cpp: pieces and phase times.

/// Appends the charts of \p comp given by \p label (F labels, charts.h) to \p pieces, with input
/// face/vertex ids.
void append_pieces(const Component& comp, const std::vector<int>& label,
                   std::vector<Component>& pieces);

/// Splits \p piece into \p k charts (segment_charts()) appended to \p out; returns how many.
size_t split_piece(const Component& piece, int k, double normal_weight, std::vector<Component>& out);

/// Copies the phase times of \p from (they add up over the attempts of one unwrap()) into \p to.
void copy_phase_times(const UnwrapReport& from, UnwrapReport& to);

/// Adds the phase times of \p from to \p to.
void add_phase_times(const UnwrapReport& from, UnwrapReport& to);

}  // namespace adaptex::unwrap_detail
