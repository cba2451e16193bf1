/// \file unwrap_scan.cpp
/// Scans (ChartMode::Auto on meshes of many components): the top-down segmentation split by each
/// piece's cheap parameterization (probes), the planar candidate, the regrowth of stretched charts,
/// and the choice between the candidates. See docs/charts.md, "Scans".
#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <iterator>
#include <limits>
#include <mutex>
#include <string_view>

#include <tbb/parallel_invoke.h>

#include "adaptex/core/timer.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/lscm.h"
#include "adaptex/param/planar.h"
#include "adaptex/param/stretch.h"

#include "unwrap_internal.h"

namespace adaptex::unwrap_detail {

namespace {

/// out[i] filled by \p fill(i, out[i]) for i in [0, n), in parallel (TBB); the first exception
/// is rethrown once every call has returned. The order of out does not depend on the threads.
template <class Fill>
std::vector<std::vector<Component>> parallel_pieces(size_t n, Fill fill) {
  std::vector<std::vector<Component>> out(n);
  std::mutex mutex;
  std::atomic<bool> failed{false};
  parallel_keep_first_error(static_cast<int>(n), mutex, failed,
                            [&](int i) { fill(static_cast<size_t>(i), out[i]); });
  return out;
}

/// Cheap figures of one piece for the scan segmentation: degenerate + flipped UV triangles and the
/// L2 stretch, at the best rectangle aspect, of its first cheap parameterization (the cut, then
/// Floater + augment_yoshizawa_iterations Yoshizawa iterations, as build_chart() starts).
struct PieceProbe {
  long bad = 0;
  double l2 = 0;
  std::shared_ptr<const std::optional<PolygonLayout>> lscm;  ///< Component::probe_lscm
  std::shared_ptr<const std::optional<PolygonLayout>> projection;  ///< Component::probe_projection
};

PieceProbe probe_piece(const Component& piece, const DiskParamOptions& dopt,
                       const UnwrapOptions& options, const ProgressCallback& progress) {
  const EdgeConnectivity ec = build_edges(piece.mesh);
  const bool disk = piece.mesh.num_vertices() - ec.num_edges() + piece.mesh.num_faces() == 1;
  const std::vector<char> cut =
      disk ? std::vector<char>(ec.num_edges(), 0)
           : initial_cut(piece.mesh, ec, build_edge_graph(piece.mesh, ec));
  const SlicedDisk sd = slice_along_cut(piece.mesh, ec, cut);
  DiskParamOptions cheap = dopt;
  cheap.max_iterations = std::min(dopt.max_iterations, options.augment_yoshizawa_iterations);
  cheap.yoshizawa = cheap.max_iterations > 0;
  cheap.progress = progress;
  const DiskParamResult r = parameterize_disk(sd.disk, sd.boundary_loop, cheap);
  std::vector<double> aspects;
  for (int i = -8; i <= 8; ++i) aspects.push_back(std::pow(4.0, i / 8.0));
  PieceProbe p;
  p.bad = static_cast<long>(r.degenerate) + r.flipped;
  p.l2 = std::numeric_limits<double>::infinity();
  for (double l2 : l2_stretch_of_aspects(sd.disk, r.uv, aspects))
    if (std::isfinite(l2)) p.l2 = std::min(p.l2, l2);
  // The free-boundary layout the chart may get instead (use_free_boundary_if_better()): when it is
  // valid and has the higher share, its stretch is what a split would lower.
  if (options.scan_free_boundary) {
    const double e = options.scan_layout_fill_exponent;
    double share = p.bad > 0 ? 0.0 : 1 / (p.l2 * p.l2);
    auto consider = [&](const TriMesh& m, const std::optional<PolygonLayout>& u) {
      if (!u) return;
      const double l2_u = l2_at_aspect(m, u->uv, u->aspect);
      if (std::isfinite(l2_u) && layout_score(u->fill, l2_u, e) > share) {
        share = layout_score(u->fill, l2_u, e);
        p.bad = 0;
        p.l2 = l2_u;
      }
    };
    if (disk) {
      p.projection =
          std::make_shared<const std::optional<PolygonLayout>>(projection_layout(piece.mesh));
      consider(piece.mesh, *p.projection);
    }
    p.lscm = std::make_shared<const std::optional<PolygonLayout>>(lscm_layout(sd.disk));
    consider(sd.disk, *p.lscm);
  }
  return p;
}

/// The probes of \p pieces, computed in parallel (TBB); the first exception (a cancel) is rethrown
/// after every body has returned. \p progress is called under a mutex.
std::vector<PieceProbe> probe_pieces(const std::vector<Component>& pieces,
                                     const DiskParamOptions& dopt, const UnwrapOptions& options,
                                     double frac) {
  std::vector<PieceProbe> probes(pieces.size());
  std::mutex mutex;
  std::atomic<bool> failed{false};
  const ProgressCallback progress = [&](std::string_view, double) {
    if (failed.load(std::memory_order_relaxed)) return false;
    if (!options.progress) return true;
    const std::lock_guard<std::mutex> lock(mutex);
    return options.progress("segment", frac);
  };
  parallel_keep_first_error(static_cast<int>(pieces.size()), mutex, failed, [&](int i) {
    probes[i] = probe_piece(pieces[i], dopt, options, progress);
  });
  return probes;
}

/// Whether splitting a piece in two pays in effective texel share (coverage / L2²), from its probe:
/// the layout's L2² (the area-weighted mean of the pieces' L2², assemble()) drops by about
/// a (λ² − λ) for a piece of area fraction a and L2 λ (its halves assumed at √λ); the coverage
/// drops by the gutter along the new seam, about 2 · gap · side for a piece whose rectangle has
/// side √(a λ) (in the unit square). Both are taken relative to a typical layout (L2² 1.4,
/// coverage 0.75). Pieces with degenerate or flipped UV triangles: see scan_pieces().
bool split_pays(const PieceProbe& probe, double area_fraction, double gap, double min_l2) {
  const double l2 = probe.l2;
  if (!(l2 > min_l2)) return false;
  const double gain = area_fraction * (l2 * l2 - l2) / 1.4;
  const double loss = 2.0 * gap * std::sqrt(area_fraction * l2) / 0.75;
  return gain > loss;
}

/// Every component of at least 2 faces cut into its planar charts and the connected parts of the
/// rest (planar_charts(), UnwrapOptions::scan_planar_angle); the area threshold is relative to the
/// whole mesh.
std::vector<Component> planar_pieces(const std::vector<Component>& comps, const UnwrapOptions& options) {
  double total_area = 0;
  for (const Component& c : comps) total_area += c.area;
  const std::vector<std::vector<Component>> parts =
      parallel_pieces(comps.size(), [&](size_t i, std::vector<Component>& out) {
        const Component& c = comps[i];
        if (c.mesh.num_faces() < 2 || !(c.area > 0)) return;
        PlanarChartOptions po;
        po.max_normal_angle = options.scan_planar_angle;
        po.min_area_fraction = std::min(1.0, options.scan_planar_min_area * total_area / c.area);
        const PlanarCharts pc = planar_charts(c.mesh, po);
        if (pc.num_charts > 1) append_pieces(c, pc.label, out);
      });
  std::vector<Component> out;
  for (size_t i = 0; i < comps.size(); ++i) {
    if (parts[i].empty()) out.push_back(comps[i]);
    out.insert(out.end(), std::make_move_iterator(parts[i].begin()),
               std::make_move_iterator(parts[i].end()));
  }
  return out;
}

/// Cuts \p piece into planar charts grown bottom-up (planar_charts(): normal cone \p angle, charts
/// of under 1/16 of the piece's area given back), the remaining faces joining the chart they reach
/// first through edges (breadth-first from all charts at once), appended to \p out; returns how
/// many (nothing appended when fewer than 2 planar charts grow).
size_t regrow_piece(const Component& piece, double angle, std::vector<Component>& out) {
  if (!(piece.area > 0)) return 0;
  PlanarChartOptions po;
  po.max_normal_angle = angle;
  po.min_area_fraction = 1.0 / 16;
  PlanarCharts pc = planar_charts(piece.mesh, po);
  if (pc.num_planar < 2) return 0;
  const EdgeConnectivity ec = build_edges(piece.mesh);
  std::vector<int> queue;
  for (int f = 0; f < piece.mesh.num_faces(); ++f)
    if (pc.label[f] < pc.num_planar) queue.push_back(f);
    else pc.label[f] = -1;
  for (size_t i = 0; i < queue.size(); ++i)
    for (int e : ec.face_edges[queue[i]])
      for (int g : ec.edge_faces[e])
        if (pc.label[g] < 0) pc.label[g] = pc.label[queue[i]], queue.push_back(g);
  int next = pc.num_planar;  // faces no chart reaches (none in a piece connected through edges)
  for (int& l : pc.label)
    if (l < 0) l = next++;
  const size_t before = out.size();
  append_pieces(piece, pc.label, out);
  return out.size() - before;
}

/// Segmentation for scans (many components, handles, holes; docs/charts.md, "Scans"): components
/// of more than scan_piece_faces faces are first split into pieces of about that many faces; then,
/// round after round, every piece whose cheap parameterization (probe_piece()) has degenerate or
/// flipped triangles, or an L2 stretch above scan_chart_l2 where split_pays(), is split in two.
/// The chart count thus follows the stretch and the texel budget: small pieces stay whole.
/// \p min_probe_faces: pieces of fewer faces are never split (a stretched piece is split down to
/// twice that). \p halving_weight: the normal penalty of the halvings
/// (ChartSegmentOptions::normal_weight).
std::vector<Component> scan_pieces(const std::vector<Component>& comps, const DiskParamOptions& dopt,
                                   double gutter, const UnwrapOptions& options, double halving_weight,
                                   int min_probe_faces) {
  // Pieces with bad UV triangles are split down to this many faces (zero-area scan faces stay
  // degenerate in any chart, so that rule needs a floor); a stretched piece is split whenever
  // split_pays(): a few large, folded faces of a photogrammetry mesh can hold much of the area.
  constexpr int kMinSplitFaces = 16;
  double total_area = 0;
  for (const Component& c : comps) total_area += c.area;
  std::vector<Component> done, queue, planar;
  const std::vector<Component>& start =
      options.scan_planar_angle > 0 ? (planar = planar_pieces(comps, options)) : comps;
  const std::vector<std::vector<Component>> large =
      parallel_pieces(start.size(), [&](size_t i, std::vector<Component>& out) {
        const long long f = start[i].mesh.num_faces();
        if (f > options.scan_piece_faces)
          split_piece(start[i],
                      static_cast<int>((f + options.scan_piece_faces - 1) / options.scan_piece_faces),
                      options.chart_normal_weight, out);
      });
  for (size_t i = 0; i < start.size(); ++i) {
    const Component& c = start[i];
    const long long f = c.mesh.num_faces();
    if (f > options.scan_piece_faces)
      queue.insert(queue.end(), std::make_move_iterator(large[i].begin()),
                   std::make_move_iterator(large[i].end()));
    else if (f >= min_probe_faces)
      queue.push_back(c);
    else
      done.push_back(c);
  }
  const double gap = std::max(gutter, 1.0 / 4096);
  for (int round = 0; round < options.scan_max_rounds && !queue.empty(); ++round) {
    const double frac = static_cast<double>(round) / options.scan_max_rounds;
    report_progress(options.progress, "segment", frac);
    const std::vector<PieceProbe> probes = probe_pieces(queue, dopt, options, frac);
    // The halves of every piece worth splitting (none: the piece is done), split in parallel.
    std::vector<std::vector<Component>> halves =
        parallel_pieces(queue.size(), [&](size_t i, std::vector<Component>& out) {
          const Component& p = queue[i];
          const PieceProbe& pr = probes[i];
          const int faces = p.mesh.num_faces();
          const bool worth =
              (pr.bad > 0 && faces >= 2 * kMinSplitFaces) ||
              (faces >= 2 * min_probe_faces &&
               split_pays(pr, p.area / std::max(total_area, 1e-300), gap, options.scan_chart_l2));
          if (worth && split_piece(p, 2, halving_weight, out) < 2) out.clear();
        });
    std::vector<Component> next;
    for (size_t i = 0; i < queue.size(); ++i) {
      next.insert(next.end(), std::make_move_iterator(halves[i].begin()),
                  std::make_move_iterator(halves[i].end()));
      if (halves[i].empty()) {
        queue[i].probe_lscm = probes[i].lscm;  // build_chart() starts from the same disk
        queue[i].probe_projection = probes[i].projection;
        done.push_back(std::move(queue[i]));
      }
    }
    queue = std::move(next);
  }
  for (Component& c : queue) done.push_back(std::move(c));
  return done;
}

/// Whether unwrap_scan() keeps a layout of report \p a over one of report \p b. `auto` is
/// conservative (docs/charts.md): one chart per component (\p components charts) that reaches
/// \p min_share wins over any other layout; otherwise the higher effective texel share (a tie
/// keeps \p b).
bool scan_prefers(const UnwrapReport& a, const UnwrapReport& b, size_t components, double min_share) {
  const auto one_each = [&](const UnwrapReport& r) {
    return static_cast<size_t>(r.num_charts) == components && r.effective_texel_share >= min_share;
  };
  if (one_each(a) != one_each(b)) return one_each(a);
  return a.effective_texel_share > b.effective_texel_share;
}

}  // namespace

void keep_better_layout(const TriMesh& mesh, const std::vector<Component>& pieces,
                        const DiskParamOptions& dopt, double gutter, Clock::time_point t_start,
                        const UnwrapOptions& options, PieceLayouts layouts, UnwrapResult& result,
                        bool shapes, size_t components) {
  UnwrapReport& rep = result.report;
  UnwrapResult candidate;
  candidate.report = rep;
  if (unwrap_pieces(mesh, pieces, dopt, gutter, t_start, options, candidate, layouts, 0, {}, shapes) &&
      (result.param.uv_faces.empty() ||
       (components > 0 ? scan_prefers(candidate.report, rep, components, options.min_texel_share)
                       : candidate.report.effective_texel_share > rep.effective_texel_share)))
    result = std::move(candidate);
  else
    copy_phase_times(candidate.report, rep);
}

namespace {

/// Small meshes also try the split down to 32 faces: split_pays()'s estimate is rough for so few
/// faces (kFineProbeFaces, in unwrap_internal.h, is the default floor).
constexpr int kCoarseProbeFaces = 16;

/// The own L2 stretch of every piece of \p pieces in the layout \p param of \p mesh (as
/// StretchStats::l2 over the piece's faces: scaled to the piece's own UV / 3-D area ratio).
std::vector<double> piece_l2(const TriMesh& mesh, const Parameterization& param,
                             const std::vector<Component>& pieces) {
  const std::vector<double> face = face_l2_stretch(mesh, param);
  double a3 = 0, a2 = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) a3 += face_area(mesh, f), a2 += uv_signed_area(param, f);
  std::vector<double> out(pieces.size(), 0.0);
  for (size_t i = 0; i < pieces.size(); ++i) {
    double c3 = 0, c2 = 0, sum = 0;
    for (int f : pieces[i].faces) {
      const double a = face_area(mesh, f);
      c3 += a, c2 += uv_signed_area(param, f);
      if (a > 0) sum += a * face[f] * face[f];
    }
    out[i] = c3 > 0 && c2 > 0 && a2 > 0 ? std::sqrt(sum / c3) * std::sqrt((c2 / c3) / (a2 / a3)) : 0.0;
  }
  return out;
}

/// The layout of \p built (packed in \p result) with every chart whose own L2 is above
/// scan_regrow_l2 cut by regrow_piece() (normal cone scan_regrow_angle), or halved (normal penalty
/// \p halving_weight) when that gives fewer than 2, and rebuilt; the other charts are kept as they
/// are. Kept in \p result when its share is higher (phase times add up either way).
void regrow_stretched(const TriMesh& mesh, BuiltPieces built, const DiskParamOptions& dopt,
                      double gutter, Clock::time_point t_start, const UnwrapOptions& options,
                      double halving_weight, PieceLayouts layouts, bool shapes,
                      UnwrapResult& result) {
  const auto t0 = Clock::now();
  const std::vector<double> l2 = piece_l2(mesh, result.param, built.pieces);
  const std::vector<std::vector<Component>> parts =
      parallel_pieces(built.pieces.size(), [&](size_t i, std::vector<Component>& out) {
        const Component& p = built.pieces[i];
        if (!(l2[i] > options.scan_regrow_l2) || p.mesh.num_faces() < 2) return;
        if (regrow_piece(p, options.scan_regrow_angle, out) >= 2) return;
        if (split_piece(p, 2, halving_weight, out) < 2) out.clear();
      });
  std::vector<Component> pieces, fresh;
  std::vector<Chart> charts;
  for (size_t i = 0; i < built.pieces.size(); ++i) {
    if (!parts[i].empty()) {
      fresh.insert(fresh.end(), parts[i].begin(), parts[i].end());
      continue;
    }
    pieces.push_back(std::move(built.pieces[i]));
    charts.push_back(std::move(built.charts[i]));
  }
  result.report.time_segment += seconds_since(t0);
  if (fresh.empty()) return;
  UnwrapResult candidate;
  candidate.report = result.report;
  // The regrown charts are near-planar patches: no cut augmentation (its budget is not spent).
  UnwrapOptions no_augment = options;
  no_augment.max_augmentations = 0;
  std::vector<Chart> more = build_charts(fresh, dopt, t_start, no_augment, candidate.report, layouts);
  for (size_t i = 0; i < fresh.size(); ++i) {
    pieces.push_back(std::move(fresh[i]));
    charts.push_back(std::move(more[i]));
  }
  pack_valid(mesh, pieces, std::move(charts), dopt, gutter, t_start, options, candidate, layouts,
             shapes, nullptr);
  if (candidate.report.effective_texel_share > result.report.effective_texel_share)
    result = std::move(candidate);
  else
    copy_phase_times(candidate.report, result.report);
}

}  // namespace

std::vector<Component> timed_scan_pieces(const std::vector<Component>& comps,
                                         const DiskParamOptions& dopt, double gutter,
                                         const UnwrapOptions& options, double halving_weight,
                                         UnwrapReport& rep, int min_probe_faces) {
  const auto t0 = Clock::now();
  std::vector<Component> pieces =
      scan_pieces(comps, dopt, gutter, options, halving_weight, min_probe_faces);
  rep.time_segment += seconds_since(t0);
  return pieces;
}

namespace {

/// The planar candidate of unwrap_scan() into \p result: the charts of scan_pieces() with planar
/// charts and free-boundary layouts, their regrowth and, short of min_texel_share on meshes of up
/// to scan_regrow_max_faces faces, its second build with scan_slim_second_exponent. Returns the
/// number of pieces of its segmentation.
size_t planar_scan_candidate(const TriMesh& mesh, const std::vector<Component>& comps,
                           const DiskParamOptions& dopt, double gutter, Clock::time_point t_start,
                           const UnwrapOptions& options, UnwrapResult& result) {
  const PieceLayouts scan_layouts =
      options.scan_free_boundary ? PieceLayouts::Free : PieceLayouts::Unfold;
  const bool shapes = options.scan_pack_shapes;
  // The planar candidate's halvings take scan_planar_normal_weight, the top-down ones
  // chart_normal_weight (docs/decisions.md, "Scans: a normal penalty ...").
  const bool planar = options.scan_planar_angle > 0;
  const double weight = planar ? options.scan_planar_normal_weight : options.chart_normal_weight;
  std::vector<Component> pieces =
      timed_scan_pieces(comps, dopt, gutter, options, weight, result.report);
  const bool small = mesh.num_faces() <= options.scan_regrow_max_faces;
  const bool regrow = planar && options.scan_regrow_l2 > 0 && small;
  // The planar candidate and its regrowth, built with \p o into \p into.
  const auto planar_candidate = [&](const UnwrapOptions& o, UnwrapResult& into) {
    BuiltPieces built;
    const bool ok = unwrap_pieces(mesh, pieces, dopt, gutter, t_start, o, into, scan_layouts, 0, {},
                                  shapes, regrow ? &built : nullptr);
    if (ok && regrow)
      regrow_stretched(mesh, std::move(built), dopt, gutter, t_start, o, weight, scan_layouts, shapes, into);
    return ok;
  };
  planar_candidate(options, result);
  // Only a layout short of min_texel_share buys the extra seams (auto is conservative: charts.md).
  if (small && result.report.effective_texel_share < options.min_texel_share &&
      options.scan_free_boundary && options.scan_slim_iterations > 0 &&
      options.scan_slim_second_exponent >= 0 &&
      options.scan_slim_second_exponent != options.scan_slim_fill_exponent) {
    UnwrapOptions second = options;
    second.scan_slim_fill_exponent = options.scan_slim_second_exponent;
    UnwrapResult candidate;
    candidate.report = result.report;
    if (planar_candidate(second, candidate) &&
        candidate.report.effective_texel_share > result.report.effective_texel_share)
      result = std::move(candidate);
    else
      copy_phase_times(candidate.report, result.report);
  }
  return pieces.size();
}

}  // namespace

void unwrap_scan(const TriMesh& mesh, const std::vector<Component>& comps,
                 const DiskParamOptions& dopt, double gutter, Clock::time_point t_start,
                 const UnwrapOptions& options, UnwrapResult& result) {
  const bool shapes = options.scan_pack_shapes;
  UnwrapOptions plain = options;
  plain.scan_planar_angle = 0;
  plain.scan_free_boundary = false;
  const double top_down = options.chart_normal_weight;
  const bool new_ways = options.scan_planar_angle > 0 || options.scan_free_boundary;
  // The top-down candidate's charts take the free-boundary layouts too (its segmentation does not).
  const PieceLayouts top_down_layouts =
      options.scan_free_boundary && options.scan_top_down_free_layouts ? PieceLayouts::FreeKeepUnfolded
                                                                       : PieceLayouts::Unfold;
  // The top-down candidate does not depend on the planar one, so it is segmented and built beside
  // it (either leaves a core idle much of the time). The callback is called under a mutex; once it
  // returned false or a branch failed, it is not called again and both branches are cancelled.
  std::mutex progress_mutex;
  std::atomic<bool> stop{false};
  const auto serialized = [&](UnwrapOptions o) {
    o.progress = [&progress_mutex, &stop, inner = o.progress](std::string_view phase, double f) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      if (stop.load()) return false;
      if (inner && !inner(phase, f)) stop = true;
      return !stop.load();
    };
    return o;
  };
  // The top-down candidate: its report starts with no phase time (added to the kept one's below).
  UnwrapResult top_down_result;
  top_down_result.report = result.report;
  copy_phase_times(UnwrapReport{}, top_down_result.report);
  bool top_down_built = false;
  std::vector<Component> pieces;
  size_t num_planar_pieces = 0;
  // Each branch keeps its own exception: one escaping into parallel_invoke would cancel the other
  // branch's nested TBB loops, which then return early, their work half done. The first one is
  // rethrown (the other branch's is then the cancel it caused).
  std::exception_ptr first_error;
  std::mutex error_mutex;
  const auto keep_error = [&] {
    const std::lock_guard<std::mutex> lock(error_mutex);
    if (!first_error) first_error = std::current_exception();
    stop = true;
  };
  tbb::parallel_invoke(
      [&] {
        try {
          num_planar_pieces =
              planar_scan_candidate(mesh, comps, dopt, gutter, t_start, serialized(options), result);
        } catch (...) {
          keep_error();
        }
      },
      [&] {
        if (!new_ways) return;
        try {
          const UnwrapOptions o = serialized(plain);
          pieces = timed_scan_pieces(comps, dopt, gutter, o, top_down, top_down_result.report);
          top_down_built = unwrap_pieces(mesh, pieces, dopt, gutter, t_start, o, top_down_result,
                                         top_down_layouts, 0, {}, shapes);
        } catch (...) {
          keep_error();
        }
      });
  if (first_error) std::rethrow_exception(first_error);
  if (new_ways) {  // as keep_better_layout(): the planar candidate wins ties
    if (top_down_built &&
        (scan_prefers(top_down_result.report, result.report, comps.size(), options.min_texel_share) ||
         result.param.uv_faces.empty())) {
      add_phase_times(result.report, top_down_result.report);
      result = std::move(top_down_result);
    } else {
      add_phase_times(top_down_result.report, result.report);
    }
  }
  if (mesh.num_faces() > options.scan_single_max_faces) return;
  const std::vector<Component> coarse =
      timed_scan_pieces(comps, dopt, gutter, plain, top_down, result.report, kCoarseProbeFaces);
  if (coarse.size() != (new_ways ? pieces.size() : num_planar_pieces))
    keep_better_layout(mesh, coarse, dopt, gutter, t_start, plain, PieceLayouts::Unfold, result,
                       shapes, comps.size());
  keep_better_layout(mesh, comps, dopt, gutter, t_start, plain, PieceLayouts::Unfold, result, shapes,
                     comps.size());
}

}  // namespace adaptex::unwrap_detail
