/// \file unwrap.cpp
/// The initial parameterization pipeline (thesis §3.2 + §3.3): per connected component, one chart
/// (unwrap_chart.cpp), packed into the square (unwrap_pack.cpp); with ChartMode::Auto, segmented
/// layouts of growing chart counts until one reaches min_texel_share, and the scan pipeline
/// (unwrap_scan.cpp) on meshes of many components. See docs/surgery.md.
#include "adaptex/param/unwrap.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <string>
#include <string_view>

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/orientation.h"
#include "adaptex/core/pinched.h"
#include "adaptex/core/timer.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/charts.h"
#include "adaptex/param/stretch.h"

#include "unwrap_internal.h"

namespace adaptex {

namespace unwrap_detail {

namespace {

std::vector<Component> split_components(const TriMesh& mesh, const MeshTopology& topo) {
  const int nc = topo.num_components;
  std::vector<Component> comps(nc);
  std::vector<int> local(mesh.num_vertices(), -1);
  for (int f = 0; f < mesh.num_faces(); ++f) comps[topo.face_component[f]].faces.push_back(f);
  for (Component& c : comps) {
    c.mesh.faces.reserve(c.faces.size());
    for (int f : c.faces) {
      Face t;
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.faces[f][k];
        if (local[v] < 0) {
          local[v] = static_cast<int>(c.vertices.size());
          c.vertices.push_back(v);
          c.mesh.positions.push_back(mesh.positions[v]);
        }
        t[k] = local[v];
      }
      c.mesh.faces.push_back(t);
    }
    for (int v : c.vertices) local[v] = -1;
    c.area = surface_area(c.mesh);
  }
  return comps;
}

}  // namespace

void append_pieces(const Component& comp, const std::vector<int>& label,
                   std::vector<Component>& pieces) {
  const int k = *std::max_element(label.begin(), label.end()) + 1;
  for (ChartMesh& cm : extract_charts(comp.mesh, label, k)) {
    if (cm.faces.empty()) continue;
    Component piece;
    piece.mesh = std::move(cm.mesh);
    for (int f : cm.faces) piece.faces.push_back(comp.faces[f]);
    for (int v : cm.vertices) piece.vertices.push_back(comp.vertices[v]);
    piece.area = surface_area(piece.mesh);
    pieces.push_back(std::move(piece));
  }
}

namespace {

/// Splits every component into about \p total_charts charts in proportion to its area (at least
/// one each) and returns the pieces with input face/vertex ids. \p segmenters: one slot per
/// component, filled on first use and kept across the chart counts of one unwrap() (charts.h).
std::vector<Component> segment_components(const std::vector<Component>& comps, int total_charts,
                                          const UnwrapOptions& options,
                                          std::vector<std::optional<ChartSegmenter>>& segmenters) {
  double total_area = 0;
  for (const Component& c : comps) total_area += c.area;
  std::vector<Component> pieces;
  for (size_t c = 0; c < comps.size(); ++c) {
    const Component& comp = comps[c];
    ChartSegmentOptions so;
    so.num_charts = std::max(
        1, static_cast<int>(std::lround(total_charts * comp.area / std::max(total_area, 1e-300))));
    so.normal_weight = options.chart_normal_weight;
    if (so.num_charts == 1 || comp.mesh.num_faces() < 2 * static_cast<long long>(so.num_charts)) {
      pieces.push_back(comp);
      continue;
    }
    if (!segmenters[c]) segmenters[c].emplace(comp.mesh);
    append_pieces(comp, segmenters[c]->segment(so), pieces);
  }
  return pieces;
}

}  // namespace

size_t split_piece(const Component& piece, int k, double normal_weight, std::vector<Component>& out) {
  ChartSegmentOptions so;
  so.num_charts = k;
  so.normal_weight = normal_weight;
  const size_t before = out.size();
  append_pieces(piece, ChartSegmenter(piece.mesh).segment(so), out);
  return out.size() - before;
}

void copy_phase_times(const UnwrapReport& from, UnwrapReport& to) {
  to.time_cut = from.time_cut;
  to.time_segment = from.time_segment;
  to.time_floater = from.time_floater;
  to.time_yoshizawa = from.time_yoshizawa;
  to.time_augment = from.time_augment;
  to.time_layouts = from.time_layouts;
  to.time_pack = from.time_pack;
}

namespace {

/// The chart counts that ChartMode::Auto tries, in order (docs/charts.md): max(4, 2 × components),
/// then steps of 1.5 and 4/3 (4, 6, 8, 12, 16, 24, 32, 48, 64, ...) up to \p max_charts. \p first > 0:
/// the counts >= \p first come first (in increasing order), then the smaller ones.
std::vector<long long> auto_chart_counts(int num_components, int max_charts, int first) {
  std::vector<long long> counts;
  // 64-bit counts: with max_charts near INT_MAX the next count would overflow an int.
  for (long long k = std::max(4, 2 * num_components); k <= max_charts;
       k = k % 3 == 0 ? k / 3 * 4 : k / 2 * 3)
    counts.push_back(k);
  if (first > 0)
    std::stable_partition(counts.begin(), counts.end(), [&](long long k) { return k >= first; });
  return counts;
}

}  // namespace

void add_phase_times(const UnwrapReport& from, UnwrapReport& to) {
  to.time_cut += from.time_cut;
  to.time_segment += from.time_segment;
  to.time_floater += from.time_floater;
  to.time_yoshizawa += from.time_yoshizawa;
  to.time_augment += from.time_augment;
  to.time_layouts += from.time_layouts;
  to.time_pack += from.time_pack;
}

namespace {

/// One chart count of segment_until_good(): its pieces and the layout built from them in a TBB
/// task, possibly before the earlier counts are decided (speculatively).
struct Attempt {
  std::vector<Component> pieces;
  bool launched = false;         ///< A task builds the layout (else the count is skipped).
  UnwrapResult result;           ///< Valid after wait() when error is empty.
  std::exception_ptr error;      ///< What the task threw (CancelledError after cancel).
  std::atomic<bool> cancel{false};  ///< Set: the task stops at its next progress call.
  std::atomic<bool> tail{false};    ///< Its last chart has started (build_charts()).
  /// The attempt's own arena: a thread waiting for it runs only its tasks (a thread waiting in a
  /// shared arena could pick up a chart of a later, speculative attempt and finish it first).
  tbb::task_arena arena;
  tbb::task_group group;
  /// Waits for the task (in the attempt's arena).
  void wait() {
    arena.execute([this] { group.wait(); });
  }
};

/// The chart counts of segment_until_good() in their order: segmented in the calling thread (the
/// segmenters keep their state across counts), their layouts built by TBB tasks. The count being
/// decided (the head) always runs; with UnwrapOptions::speculative_attempts = S > 1, each of the
/// next S - 1 counts starts once the count before it has started its last chart, on the threads
/// that count no longer needs, and the next count is segmented while the head is built. Each
/// layout depends only on its pieces and the options (build_charts()), so which counts ran
/// speculatively does not change any layout. The destructor stops the launches and cancels and
/// waits for every task (the tasks refer to the pipeline).
class CountPipeline {
 public:
  CountPipeline(const TriMesh& mesh, const std::vector<Component>& comps,
                const DiskParamOptions& dopt, double gutter, Clock::time_point t_start,
                const UnwrapOptions& options, bool reordered, const UnwrapReport& base)
      : mesh_(mesh), comps_(comps), dopt_(dopt), gutter_(gutter), t_start_(t_start),
        options_(options), reordered_(reordered), base_(base),
        counts_(auto_chart_counts(static_cast<int>(comps.size()), options.max_charts,
                                  reordered ? options.probe_first_charts : 0)),
        segmenters_(comps.size()), attempts_(counts_.size()) {
    base_.time_cut = base_.time_floater = base_.time_yoshizawa = base_.time_augment =
        base_.time_layouts = base_.time_pack = 0;  // each attempt reports its own phase times
  }
  CountPipeline(const CountPipeline&) = delete;
  CountPipeline& operator=(const CountPipeline&) = delete;
  ~CountPipeline() {
    {
      const std::lock_guard<std::mutex> lock(launch_mutex_);
      stopped_ = true;
    }
    for (auto& a : attempts_)
      if (a && a->launched) a->cancel = true;
    for (auto& a : attempts_)
      if (a && a->launched) a->wait();  // the tasks catch everything: wait() does not throw
  }

  size_t size() const { return counts_.size(); }

  /// Makes count \p i (called with 0, 1, 2, ...) the one being decided: segments and launches
  /// it. Returns nullptr when it is skipped (no more pieces than components; reordered: a number
  /// of pieces tried already), else the attempt (wait() for its layout).
  Attempt* decide(size_t i) {
    segment_until(i + 1);
    {
      const std::lock_guard<std::mutex> lock(launch_mutex_);
      head_ = i;
      launch_ready();
    }
    if (options_.speculative_attempts > 1) {
      segment_until(i + 2);  // wasted only after the count that is kept
      const std::lock_guard<std::mutex> lock(launch_mutex_);
      launch_ready();
    }
    return attempts_[i]->launched ? attempts_[i].get() : nullptr;
  }

 private:
  /// Segments counts_[segmented_, end).
  void segment_until(size_t end) {
    while (segmented_ < std::min(end, counts_.size())) {
      auto a = std::make_unique<Attempt>();
      a->pieces = segment_components(comps_, static_cast<int>(counts_[segmented_]), options_,
                                     segmenters_);
      const std::lock_guard<std::mutex> lock(launch_mutex_);
      attempts_[segmented_++] = std::move(a);
    }
  }

  /// Under launch_mutex_: launches (or skips) the segmented counts that may run now, in order.
  void launch_ready() {
    const size_t window = static_cast<size_t>(std::max(1, options_.speculative_attempts));
    for (; !stopped_ && next_ < segmented_ && next_ < head_.load() + window; ++next_) {
      Attempt& a = *attempts_[next_];
      if (a.pieces.size() <= comps_.size() ||
          (reordered_ && std::find(tried_.begin(), tried_.end(), a.pieces.size()) != tried_.end()))
        continue;
      if (next_ > head_.load() && last_launched_ >= 0 && !attempts_[last_launched_]->tail) break;
      tried_.push_back(a.pieces.size());
      a.launched = true;
      last_launched_ = static_cast<long>(next_);
      a.result.report = base_;
      a.arena.execute([this, i = next_] { attempts_[i]->group.run([this, i] { build(i); }); });
    }
  }

  /// The task of attempt \p i: its layout, or the exception in Attempt::error.
  void build(size_t i) {
    Attempt& a = *attempts_[i];
    UnwrapOptions o = options_;
    o.progress = [this, &a, i](std::string_view phase, double f) {
      if (a.cancel.load(std::memory_order_relaxed)) return false;
      if (!options_.progress || head_.load() != i) return true;  // only the head reports
      const std::lock_guard<std::mutex> lock(progress_mutex_);
      return options_.progress(phase, f);
    };
    const std::function<void()> on_last_started = [this, &a] {
      const std::lock_guard<std::mutex> lock(launch_mutex_);
      a.tail = true;
      launch_ready();
    };
    try {
      unwrap_pieces(mesh_, a.pieces, dopt_, gutter_, t_start_, o, a.result, PieceLayouts::Disk, 0,
                    on_last_started);
    } catch (...) {
      a.error = std::current_exception();
    }
  }

  const TriMesh& mesh_;
  const std::vector<Component>& comps_;
  const DiskParamOptions& dopt_;
  const double gutter_;
  const Clock::time_point t_start_;
  const UnwrapOptions& options_;
  const bool reordered_;
  UnwrapReport base_;  ///< The figures of the mesh, phase times zero.
  const std::vector<long long> counts_;
  std::vector<std::optional<ChartSegmenter>> segmenters_;  ///< One per component.
  std::vector<std::unique_ptr<Attempt>> attempts_;  ///< [0, segmented_) are set.
  std::atomic<size_t> head_{0};  ///< The count being decided.
  std::mutex progress_mutex_;
  std::mutex launch_mutex_;      ///< Guards the members below and Attempt::launched.
  size_t segmented_ = 0;         ///< Written by the calling thread under launch_mutex_.
  size_t next_ = 0;              ///< attempts_[0, next_) are launched or skipped.
  long last_launched_ = -1;
  std::vector<size_t> tried_;    ///< Piece counts launched.
  bool stopped_ = false;         ///< No more launches (destructor).
};

/// ChartMode::Auto after the layout of one chart per component: segments the components into the
/// counts of auto_chart_counts() until a layout reaches min_texel_share; \p result keeps the layout
/// with the highest share (its phase times add up over the attempts). \p reordered: the single
/// layout was abandoned (\p result holds no layout): the counts from probe_first_charts on are
/// tried first, and a segmentation is skipped when its number of pieces was tried already;
/// otherwise when it has no more pieces than the best layout so far. The counts are decided one
/// after the other with this rule, whatever CountPipeline built ahead (speculative_attempts), so
/// the result is that of building them one after the other, bit for bit.
void segment_until_good(const TriMesh& mesh, const std::vector<Component>& comps,
                        const DiskParamOptions& dopt, double gutter, Clock::time_point t_start,
                        const UnwrapOptions& options, bool reordered, UnwrapResult& result) {
  UnwrapReport& rep = result.report;
  CountPipeline pipeline(mesh, comps, dopt, gutter, t_start, options, reordered, rep);
  for (size_t i = 0; i < pipeline.size(); ++i) {
    if (rep.effective_texel_share >= options.min_texel_share) break;
    Attempt* a = pipeline.decide(i);
    if (!a) continue;
    if (!reordered && static_cast<int>(a->pieces.size()) <= rep.num_charts) {
      a->cancel = true;  // the sequential rule skips it
      continue;
    }
    a->wait();
    if (a->error) std::rethrow_exception(a->error);  // a cancel by the callback, a solver error
    add_phase_times(a->result.report, rep);  // times add up over all attempts
    if (a->result.report.effective_texel_share > rep.effective_texel_share) {
      const UnwrapReport times = rep;
      result.param = std::move(a->result.param);
      rep = a->result.report;
      copy_phase_times(times, rep);
    }
  }
}

/// Throws InvalidInputError (TopologyError for a mesh without faces) when \p options are out of
/// range, before any work.
void check_unwrap_input(const TriMesh& mesh, const UnwrapOptions& options) {
  if (mesh.faces.empty()) throw TopologyError("unwrap: the mesh has no faces");
  if (!(options.chart_padding >= 0 && options.chart_padding < 0.25))
    throw InvalidInputError("unwrap: chart_padding " + std::to_string(options.chart_padding) +
                            " is outside [0, 0.25)");
  if (options.max_augmentations < 0 || options.yoshizawa_max_iterations < 0 ||
      options.augment_yoshizawa_iterations < 0 || options.max_charts < 1 ||
      options.probe_first_charts < 0 || !(options.single_probe_l2 >= 0) ||
      options.speculative_attempts < 1)
    throw InvalidInputError("unwrap: iteration, augmentation and chart counts and single_probe_l2 "
                            "must be >= 0 (>= 1 for max_charts and speculative_attempts)");
  if (!(options.gutter_texels >= 0) || options.gutter_texture_size < 1 ||
      !(options.gutter_texels / options.gutter_texture_size < 0.25))
    throw InvalidInputError("unwrap: gutter of " + std::to_string(options.gutter_texels) +
                            " texels at " + std::to_string(options.gutter_texture_size) +
                            " is out of range");
  if (options.scan_piece_faces < 64 || options.scan_max_rounds < 0 || !(options.scan_chart_l2 >= 1))
    throw InvalidInputError("unwrap: scan_piece_faces must be >= 64, scan_max_rounds >= 0 and "
                            "scan_chart_l2 >= 1");
  if (!(options.scan_planar_angle >= 0 && options.scan_planar_angle < 90) ||
      !(options.scan_planar_min_area >= 0 && options.scan_planar_min_area <= 1) ||
      !(options.scan_planar_normal_weight >= 0) || !std::isfinite(options.scan_planar_normal_weight) ||
      !(options.scan_regrow_l2 == 0 || (options.scan_regrow_l2 >= 1 && std::isfinite(options.scan_regrow_l2))) ||
      !(options.scan_regrow_angle > 0 && options.scan_regrow_angle < 90) || options.scan_regrow_max_faces < 0 ||
      !(options.chart_normal_weight >= 0) || !std::isfinite(options.chart_normal_weight))
    throw InvalidInputError("unwrap: scan_planar_angle must be in [0, 90), scan_planar_min_area "
                            "in [0, 1], scan_planar_normal_weight and chart_normal_weight finite and >= 0, "
                            "scan_regrow_l2 0 or finite and >= 1, scan_regrow_angle in (0, 90), scan_regrow_max_faces >= 0");
  if (options.scan_slim_iterations < 0 ||
      !(options.scan_slim_fill_exponent >= 0 && options.scan_slim_fill_exponent <= 1) ||
      !(options.scan_slim_second_exponent <= 1) || !std::isfinite(options.scan_slim_second_exponent))
    throw InvalidInputError("unwrap: scan_slim_iterations must be >= 0, scan_slim_fill_exponent in [0, 1] "
                            "and scan_slim_second_exponent finite and <= 1");
  if (std::isnan(options.augment_time_budget))
    throw InvalidInputError("unwrap: augment_time_budget is NaN (<= 0: no time budget)");
  if (!(options.scan_layout_fill_exponent >= 0 && options.scan_layout_fill_exponent <= 1))
    throw InvalidInputError("unwrap: scan_layout_fill_exponent " +
                            std::to_string(options.scan_layout_fill_exponent) + " is outside [0, 1]");
  if (!(options.min_chart_side_of_gap >= 0 && options.min_chart_side_of_gap <= 4))
    throw InvalidInputError("unwrap: min_chart_side_of_gap " +
                            std::to_string(options.min_chart_side_of_gap) + " is outside [0, 4]");
}

/// Throws TopologyError for a mesh without a layout (non-manifold edges, a non-orientable
/// component). Returns true when it must be split first (pinched vertices, mixed winding).
bool needs_split(const MeshTopology& topo) {
  if (!topo.nonmanifold_edges.empty())
    throw TopologyError("unwrap: the mesh is not manifold (" +
                        std::to_string(topo.nonmanifold_edges.size()) +
                        " non-manifold edges); repair it first");
  bool mixed_winding = false;
  for (const ComponentTopology& c : topo.components) {
    if (!c.orientable)
      throw TopologyError("unwrap: a component of " + std::to_string(c.faces) +
                          " faces is not orientable (a Moebius band or similar); it has no layout");
    mixed_winding = mixed_winding || !c.consistently_oriented;
  }
  return !topo.nonmanifold_vertices.empty() || mixed_winding;
}

/// Pinched vertices (core/pinched.h) and mixed winding (core/orientation.h): unwraps the split,
/// consistently wound surface; its wedges and face corners map back to the input \p mesh.
UnwrapResult unwrap_split(const TriMesh& mesh, const UnwrapOptions& options) {
  PinchedSplit split = split_pinched_vertices(mesh);
  const FaceOrientation orientation = orient_faces(split.mesh);
  apply_orientation(split.mesh, orientation);
  UnwrapResult r = unwrap(split.mesh, options);
  for (int& v : r.param.wedge_vertex) v = split.vertex_source[v];
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    if (orientation.flip[f]) std::swap(r.param.uv_faces[f][1], r.param.uv_faces[f][2]);
  return r;
}

/// Disk-parameterization settings of \p options for \p mesh (mean-value weights only up to
/// mean_value_max_faces faces).
DiskParamOptions disk_param_options(const TriMesh& mesh, const UnwrapOptions& options) {
  DiskParamOptions dopt;
  dopt.weights = options.weights == EmbeddingWeights::MeanValue &&
                         mesh.num_faces() > options.mean_value_max_faces
                     ? EmbeddingWeights::ShapePreserving
                     : options.weights;
  dopt.eta = options.yoshizawa_eta;
  dopt.max_iterations = options.yoshizawa_max_iterations;
  dopt.yoshizawa = options.yoshizawa_max_iterations > 0;
  return dopt;
}

/// ChartMode::Auto when the layout of one chart per component (\p single_built: not abandoned)
/// is below min_texel_share: segmented layouts, then the single chart, then the scan charts, each
/// kept in \p result if better.
void improve_low_share(const TriMesh& mesh, const std::vector<Component>& comps,
                       const DiskParamOptions& dopt, double gutter, Clock::time_point t_start,
                       const UnwrapOptions& options, bool single_built, UnwrapResult& result) {
  const UnwrapReport& rep = result.report;
  segment_until_good(mesh, comps, dopt, gutter, t_start, options, !single_built, result);
  // No segmentation reached the share: the single chart after all (never below it).
  if (!single_built && rep.effective_texel_share < options.min_texel_share)
    keep_better_layout(mesh, comps, dopt, gutter, t_start, options, PieceLayouts::Disk, result);
  // Still below: the charts of the scan segmentation, split by each piece's own stretch rather
  // than a count over the whole mesh (a large smooth part no longer draws the charts that rough
  // parts need), built too and kept if better.
  // (The top-down segmentation alone: planar charts and free boundaries are for scans.)
  UnwrapOptions plain = options;
  plain.scan_planar_angle = 0;
  plain.scan_free_boundary = false;
  if (rep.effective_texel_share < options.min_texel_share)
    keep_better_layout(mesh, timed_scan_pieces(comps, dopt, gutter, plain,
                                               options.chart_normal_weight, result.report), dopt,
                       gutter, t_start, plain, PieceLayouts::Unfold, result);
}

/// Last report figures of a finished layout: the seam length of a multi-chart one, the total time.
void finish_report(const TriMesh& mesh, Clock::time_point t_start, UnwrapResult& result) {
  UnwrapReport& rep = result.report;
  if (rep.num_charts > 1) rep.cut_length = seam_length(mesh, result.param);
  rep.time_total = seconds_since(t_start);
}

}  // namespace

}  // namespace unwrap_detail

using namespace unwrap_detail;

UnwrapResult unwrap(const TriMesh& mesh, const UnwrapOptions& options) {
  const auto t_start = Clock::now();
  UnwrapResult result;
  UnwrapReport& rep = result.report;
  check_unwrap_input(mesh, options);

  const auto t0 = Clock::now();
  report_progress(options.progress, "cut", 0.0);
  const MeshTopology topo = analyze_topology(mesh);
  if (needs_split(topo)) return unwrap_split(mesh, options);
  rep.num_components = topo.num_components;
  rep.genus = topo.total_genus();
  rep.boundary_loops = topo.total_loops();
  const std::vector<Component> comps = split_components(mesh, topo);
  rep.time_cut += seconds_since(t0);

  const DiskParamOptions dopt = disk_param_options(mesh, options);
  // One chart per component (thesis §3.2). Every layout of several charts keeps the gutter.
  const double gutter =
      std::max(options.chart_padding, options.gutter_texels / options.gutter_texture_size);
  // Components without interior vertices (strips, single triangles) are unfolded when several
  // charts share the square; segmented charts are not (their layouts stay those measured in
  // docs/history/benchmarks.md).
  // Auto on one component: the single chart is given up after its first cheap parameterization
  // when that predicts it cannot reach min_texel_share (UnwrapOptions::single_probe_l2).
  const bool probe =
      options.charts == ChartMode::Auto && comps.size() == 1 && options.single_probe_l2 > 0;
  if (options.charts == ChartMode::Auto && 2 * comps.size() > static_cast<size_t>(options.max_charts)) {
    unwrap_scan(mesh, comps, dopt, gutter, t_start, options, result);
    finish_report(mesh, t_start, result);
    return result;
  }
  const bool single_built = unwrap_pieces(mesh, comps, dopt, gutter, t_start, options, result,
                                          comps.size() > 1 ? PieceLayouts::Unfold : PieceLayouts::Disk,
                                          probe ? options.single_probe_l2 : 0);
  if (options.charts == ChartMode::Auto && rep.effective_texel_share < options.min_texel_share)
    improve_low_share(mesh, comps, dopt, gutter, t_start, options, single_built, result);
  finish_report(mesh, t_start, result);
  return result;
}

UnwrapOptions unwrap_options_for_texture(int texture_size, int padding, UnwrapOptions base) {
  if (texture_size < 1 || texture_size > kMaxTextureSize || padding < 0)
    throw InvalidInputError("unwrap options: texture size must be in [1, " +
                            std::to_string(kMaxTextureSize) + "] and padding >= 0, got " +
                            std::to_string(texture_size) + " and " + std::to_string(padding));
  base.gutter_texture_size = texture_size;
  base.gutter_texels = std::min(std::max(2.0, static_cast<double>(padding)), 0.2 * texture_size);
  return base;
}

template <>
std::span<const EnumName<ChartMode>> enum_names<ChartMode>() {
  static constexpr EnumName<ChartMode> names[] = {{ChartMode::Auto, "auto"}, {ChartMode::Single, "single"}};
  return names;
}

}  // namespace adaptex
