/// \file unwrap_pack.cpp
/// Packing the charts of one layout into [0,1]² (pack.h: rectangles, and shapes where the charts leave
/// much of their rectangles empty), the layout's figures, and the rounds that split charts until no
/// UV triangle is flipped, degenerate or overlapping; then the repacks with the charts' kept
/// alternative layouts. See docs/charts.md.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "adaptex/core/errors.h"
#include "adaptex/core/timer.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/pack.h"
#include "adaptex/param/stretch.h"

#include "unwrap_internal.h"

namespace adaptex::unwrap_detail {

double seam_length(const TriMesh& mesh, const Parameterization& param) {
  const EdgeConnectivity ec = build_edges(mesh);
  double seams = 0;
  for (int e = 0; e < ec.num_edges(); ++e) {
    if (ec.edge_faces[e].size() != 2) continue;
    auto uv_of = [&](int f, int v) {
      const Face& t = mesh.faces[f];
      return param.uv_faces[f][t[0] == v ? 0 : t[1] == v ? 1 : 2];
    };
    const int f1 = ec.edge_faces[e][0], f2 = ec.edge_faces[e][1];
    const int a = ec.edges[e][0], b = ec.edges[e][1];
    if (uv_of(f1, a) != uv_of(f2, a) || uv_of(f1, b) != uv_of(f2, b))
      seams += (mesh.positions[a] - mesh.positions[b]).norm();
  }
  return seams;
}

namespace {

/// Writes the layout of \p charts into \p result, chart c's wedge at place(c, its uv in the chart's
/// frame), and the layout figures (charts, cut length of the pieces, augmentations, stretch,
/// coverage, effective texel share). \p k[c]: the linear scale of chart c's frame in the square
/// (for the combined Floater figures).
template <class Place>
void write_layout(const TriMesh& mesh, const std::vector<Component>& pieces,
                  const std::vector<Chart>& charts, const Place& place, const std::vector<double>& k,
                  UnwrapResult& result) {
  UnwrapReport& rep = result.report;
  const int nc = static_cast<int>(pieces.size());
  Parameterization& param = result.param;
  param = Parameterization{};
  param.num_charts = nc;
  param.uv_faces.resize(mesh.faces.size());
  param.face_chart.resize(mesh.faces.size());
  rep.cut_length = 0;
  rep.augmentations = 0;
  rep.yoshizawa_iterations = 0;
  for (int c = 0; c < nc; ++c) {
    const Chart& chart = charts[c];
    const Component& comp = pieces[c];
    const int offset = param.num_wedges();
    for (size_t w = 0; w < chart.state.param.uv.size(); ++w) {
      param.uv.push_back(place(c, chart.state.param.uv[w]).cwiseMax(0.0).cwiseMin(1.0));
      param.wedge_vertex.push_back(comp.vertices[chart.state.disk.wedge_vertex[w]]);
    }
    for (size_t lf = 0; lf < comp.faces.size(); ++lf) {
      const Face& t = chart.state.disk.disk.faces[lf];
      param.uv_faces[comp.faces[lf]] = {offset + t[0], offset + t[1], offset + t[2]};
      param.face_chart[comp.faces[lf]] = c;
    }
    rep.cut_length += chart.cut_length;
    rep.augmentations += chart.augmentations;
    rep.yoshizawa_iterations += chart.state.param.iterations;
  }
  rep.num_charts = nc;
  // Several charts: cut_length becomes the seam length (seam_length()), measured once on the
  // layout unwrap() returns.

  // Mesh-level stretch. The final figures are measured on the packed layout; the Floater figures
  // are combined from the per-chart ones (the chart's L2 and L∞ are normalized in its own frame
  // of UV area A2_c and 3-D area A3_c; scaling a chart by k divides its stretch by k; for a
  // rectangle k is the geometric mean of its sides, so the combined Floater figure is approximate).
  const StretchStats final_stats = measure_stretch(mesh, param);
  rep.final_l2 = final_stats.l2;
  rep.final_linf = final_stats.linf;
  if (nc == 1) {
    rep.floater_l2 = charts[0].state.param.floater_l2;
    rep.floater_linf = charts[0].state.param.floater_linf;
  } else {
    double a3 = 0, sum_r = 0, sum_a2 = 0, max_gamma = 0;
    for (int c = 0; c < nc; ++c) {
      const double A3 = std::max(pieces[c].area, 1e-300);
      const double A2 = charts[c].domain_area;
      const DiskParamResult& r = charts[c].state.param;
      a3 += A3;
      sum_r += r.floater_l2 * r.floater_l2 * A3 * A3 / (A2 * k[c] * k[c]);
      sum_a2 += k[c] * k[c] * A2;
      max_gamma = std::max(max_gamma, r.floater_linf * std::sqrt(A3 / A2) / k[c]);
    }
    rep.floater_l2 = std::sqrt(sum_r / a3) * std::sqrt(sum_a2 / a3);
    rep.floater_linf = max_gamma * std::sqrt(sum_a2 / a3);
  }
  double coverage = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) coverage += std::max(0.0, uv_signed_area(param, f));
  rep.coverage = std::min(1.0, coverage);
  rep.effective_texel_share =
      std::isfinite(rep.final_l2) && rep.final_l2 > 0 ? rep.coverage / (rep.final_l2 * rep.final_l2)
                                                      : 0.0;
}

/// assemble() packs the charts by their shapes too only when they cover less than this part of
/// their rectangles.
constexpr double kShapePackingMaxFill = 0.9;

/// Packs the charts of \p pieces with gap \p padding (their rectangles, pack_rectangles(); with
/// \p shapes also their shapes, pack_shapes(), where they fill less than kShapePackingMaxFill of
/// their rectangles, keeping the packing of the higher effective texel share) and writes the
/// layout and its figures into \p result (write_layout()); unwrap() replaces the cut length of
/// several charts by their seam length.
void assemble(const TriMesh& mesh, const std::vector<Component>& pieces,
              const std::vector<Chart>& charts, double padding, const UnwrapOptions& options,
              UnwrapResult& result, bool shapes = false) {
  const int nc = static_cast<int>(pieces.size());
  // Rectangles of the chart's best aspect ratio and of area proportional to A3_c * L2_c (3-D area
  // times the chart's own L2 stretch): of all allocations of the square to the charts this one
  // gives the lowest layout L2 (it becomes the area-weighted mean of the L2_c instead of their
  // root mean square; docs/charts.md). The packer may turn a rectangle by 90° (a rotation keeps
  // the UV orientation).
  std::vector<Vec2> sizes(nc);
  for (int c = 0; c < nc; ++c) {
    const auto [a, l2] = nc > 1 ? best_aspect(charts[c]) : std::pair<double, double>(1.0, 1.0);
    const double area = std::max(pieces[c].area, 1e-300) * (std::isfinite(l2) && l2 > 0 ? l2 : 1.0);
    sizes[c] = Vec2(std::sqrt(area * a), std::sqrt(area / a));
  }
  // No chart is smaller than the gap (tiny components keep a usable number of texels).
  RectPackOptions po;
  po.padding = padding;
  po.min_side = options.min_chart_side_of_gap * padding;
  po.may_turn = true;
  po.progress = options.progress;
  std::vector<char> turned;
  double gap = padding;
  const std::vector<RectPlacement> place = pack_rectangles(sizes, po, &turned, &gap);
  std::vector<double> k(nc);
  for (int c = 0; c < nc; ++c) k[c] = std::sqrt(place[c].size.x() * place[c].size.y());
  write_layout(mesh, pieces, charts,
               [&](int c, const Vec2& t) {
                 return Vec2(place[c].offset +
                             place[c].size.cwiseProduct(turned[c] ? Vec2(1 - t.y(), t.x()) : t));
               },
               k, result);
  result.report.gutter = gap;
  result.report.requested_gutter = padding;
  // Shapes can only pay where the charts leave much of their rectangles empty (on the meshes of
  // the share table they fill 0.94-0.999 of them and the shapes never won; docs/bench_unwrap.md).
  double rect_area = 0;
  for (const RectPlacement& r : place) rect_area += r.size.prod();
  if (!shapes || nc < 2 || !(result.report.coverage < kShapePackingMaxFill * rect_area)) return;
  // The shapes: each chart's UVs at the aspect of its rectangle, its UV area (not its
  // rectangle's) proportional to A3_c * L2_c.
  std::vector<ChartShape> shape(nc);
  std::vector<Vec2> stretch(nc);
  for (int c = 0; c < nc; ++c) {
    stretch[c] = sizes[c] / std::sqrt(std::max(charts[c].domain_area, 1e-12));
    for (const Vec2& t : charts[c].state.param.uv) shape[c].uv.push_back(t.cwiseProduct(stretch[c]));
    shape[c].faces = charts[c].state.disk.disk.faces;
  }
  ShapePackOptions so;
  // The gap (and minimum side) the rectangles kept: both packings are compared at one gap.
  so.padding = gap;
  so.min_side = padding > 0 ? po.min_side * gap / padding : 0.0;
  so.progress = options.progress;
  double shape_gap = gap;
  const std::vector<ShapePlacement> sp = pack_shapes(shape, so, &shape_gap);
  for (int c = 0; c < nc; ++c) k[c] = sp[c].scale * std::sqrt(stretch[c].x() * stretch[c].y());
  UnwrapResult alt;
  alt.report = result.report;
  write_layout(mesh, pieces, charts,
               [&](int c, const Vec2& t) { return sp[c].apply(t.cwiseProduct(stretch[c])); }, k, alt);
  alt.report.gutter = shape_gap;
  if (alt.report.effective_texel_share > result.report.effective_texel_share) result = std::move(alt);
}

/// invalid_uv_faces() of the packed layout of \p charts. Overlaps are looked for only in the charts
/// of a fixed aspect (free-boundary, projected, unfolded layouts): a disk parameterization maps its
/// boundary onto a convex curve, so with no flipped or degenerate triangle it is a bijection onto
/// its rectangle, and the packed rectangles are disjoint (packed by their shapes, the triangles
/// of two charts are disjoint: pack_shapes()).
std::vector<int> invalid_layout_faces(const Parameterization& param, const std::vector<Chart>& charts) {
  std::vector<char> free(param.uv_faces.size(), 0);
  for (size_t f = 0; f < free.size(); ++f) free[f] = charts[param.face_chart[f]].aspect > 0;
  return invalid_uv_faces(param, &free);
}

/// Rounds of splitting invalid charts in unwrap_pieces() before it gives up (each round halves
/// them; pieces of at most kFaceSplitFaces faces are split into single faces).
constexpr int kMaxValidityRounds = 24, kFaceSplitFaces = 8;

/// Replaces every piece \p bad marks (its chart's UV triangles are flipped, degenerate or overlap)
/// by its two halves (split_piece()), or by its single faces when it has at most kFaceSplitFaces
/// faces or does not split, and builds their charts: \p pieces and \p charts stay parallel.
/// \throw SolverError a marked piece of one face (a triangle's own layout is valid; nothing left)
void split_invalid_charts(std::vector<Component>& pieces, std::vector<Chart>& charts,
                          const std::vector<char>& bad, const DiskParamOptions& dopt,
                          Clock::time_point t_start, const UnwrapOptions& options,
                          UnwrapReport& rep, PieceLayouts layouts) {
  std::vector<Component> kept, halves;
  std::vector<Chart> kept_charts;
  for (size_t c = 0; c < pieces.size(); ++c) {
    if (!bad[c]) {
      kept.push_back(std::move(pieces[c]));
      kept_charts.push_back(std::move(charts[c]));
      continue;
    }
    const Component& p = pieces[c];
    const int nf = p.mesh.num_faces();
    if (nf < 2)
      throw SolverError("unwrap: no valid layout found for a face of the mesh (its UV triangle is "
                        "flipped, degenerate or overlaps)");
    if (nf > kFaceSplitFaces) {
      const size_t n = split_piece(p, 2, options.chart_normal_weight, halves);
      if (n >= 2) continue;
      halves.resize(halves.size() - n);
    }
    std::vector<int> single(nf);
    std::iota(single.begin(), single.end(), 0);
    append_pieces(p, single, halves);
  }
  std::vector<Chart> built = build_charts(halves, dopt, t_start, options, rep, layouts);
  for (size_t i = 0; i < halves.size(); ++i) {
    kept.push_back(std::move(halves[i]));
    kept_charts.push_back(std::move(built[i]));
  }
  pieces = std::move(kept);
  charts = std::move(kept_charts);
}

/// Boundary contact, relative to a chart's extent, below which boundary_near_contact() calls its
/// layout fragile: packed at 1e-4 of the square, a double's rounding moves a UV by ~1e-12 of it.
constexpr double kContactTolerance = 1e-9;

/// Whether \p chart is of a fixed aspect and its own layout has overlapping UV triangles (in the
/// chart's frame), or is valid only up to rounding at its boundary (boundary_near_contact(): a
/// zipped cut); invalid_layout_faces() would find the first in any packing and the second in some.
bool fragile_chart(const Chart& chart) {
  if (!(chart.aspect > 0)) return false;
  Parameterization local;
  local.uv = chart.state.param.uv;
  local.uv_faces = chart.state.disk.disk.faces;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec2& p : local.uv) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double extent = local.uv.empty() ? 0.0 : (hi - lo).maxCoeff();
  return boundary_near_contact(local.uv, local.uv_faces, kContactTolerance * extent) ||
         count_overlapping_triangles(local, 1) > 0;
}

/// fragile_chart() of every chart, in parallel.
std::vector<char> fragile_charts(const std::vector<Chart>& charts) {
  std::vector<char> bad(charts.size(), 0);
  tbb::parallel_for(size_t{0}, charts.size(), [&](size_t c) { bad[c] = fragile_chart(charts[c]); });
  return bad;
}

/// A chart's layout before it took its Chart::alternative.
struct KeptLayout {
  size_t chart = 0;
  DiskParamResult param;
  double domain_area = 1, aspect = 0;
};

/// The repacking step of pack_alternatives() and pack_unfolded(): the charts \p swapped of
/// \p charts have just been given other layouts; \p swap_back(i) gives chart swapped[i] its
/// layout back. Fragile ones get theirs back at once; the rest are packed (assemble()) and that
/// layout replaces \p result when it is valid and its effective texel share is higher, otherwise
/// they get theirs back too. \p kept_new (if not null; resized): kept_new[i] when chart swapped[i]
/// keeps its new layout.
void repack_swapped(const TriMesh& mesh, const std::vector<Component>& pieces,
                    std::vector<Chart>& charts, const std::vector<size_t>& swapped,
                    const std::function<void(size_t)>& swap_back, double padding,
                    const UnwrapOptions& options, UnwrapResult& result, bool shapes,
                    std::vector<char>* kept_new = nullptr) {
  std::vector<char> fragile(swapped.size(), 0);
  tbb::parallel_for(size_t{0}, swapped.size(),
                    [&](size_t i) { fragile[i] = fragile_chart(charts[swapped[i]]); });
  for (size_t i = 0; i < swapped.size(); ++i)
    if (fragile[i]) swap_back(i);
  if (kept_new) kept_new->assign(swapped.size(), 0);
  if (std::find(fragile.begin(), fragile.end(), 0) == fragile.end()) return;
  UnwrapResult alt;
  alt.report = result.report;
  assemble(mesh, pieces, charts, padding, options, alt, shapes);
  const bool wins = alt.report.effective_texel_share > result.report.effective_texel_share &&
                    invalid_layout_faces(alt.param, charts).empty();
  if (wins) result = std::move(alt);
  for (size_t i = 0; i < swapped.size(); ++i)
    if (!fragile[i]) {
      if (!wins) swap_back(i);
      else if (kept_new) (*kept_new)[i] = 1;
    }
}

/// Gives every chart of \p charts (parallel to \p pieces) its Chart::alternative (a SLIM layout
/// its own score rejected: near-isometric but filling less of its rectangle, which packed by
/// shape may still nest) and keeps that packing when it wins (repack_swapped()). The
/// alternatives are used up either way (docs/decisions.md, "Scans: the rejected SLIM layouts are
/// packed too"). \p shapes as in assemble().
void pack_alternatives(const TriMesh& mesh, const std::vector<Component>& pieces,
                       std::vector<Chart>& charts, double padding, const UnwrapOptions& options,
                       UnwrapResult& result, bool shapes) {
  std::vector<KeptLayout> kept;
  std::vector<size_t> swapped;
  for (size_t c = 0; c < charts.size(); ++c) {
    if (!charts[c].alternative) continue;
    PolygonLayout u = std::move(*charts[c].alternative);
    charts[c].alternative.reset();
    kept.push_back({c, charts[c].state.param, charts[c].domain_area, charts[c].aspect});
    swapped.push_back(c);
    adopt_disk_layout(charts[c], std::move(u));
  }
  const auto restore = [&](size_t i) {
    const KeptLayout& k = kept[i];
    charts[k.chart].state.param = k.param;
    charts[k.chart].domain_area = k.domain_area;
    charts[k.chart].aspect = k.aspect;
  };
  repack_swapped(mesh, pieces, charts, swapped, restore, padding, options, result, shapes);
}

/// Gives every chart of \p charts (parallel to \p pieces) with a Chart::unfolded layout that
/// layout and keeps that packing when it wins (repack_swapped(); those charts then drop their
/// Chart::alternative, a layout of the other disk). Runs before pack_alternatives(), so that the
/// free layouts are weighed against the unfolded ones alone (docs/decisions.md, "Scans:
/// free-boundary layouts for the top-down candidate"). The unfolded layouts are used up either
/// way. \p shapes as in assemble().
void pack_unfolded(const TriMesh& mesh, const std::vector<Component>& pieces, std::vector<Chart>& charts,
                   double padding, const UnwrapOptions& options, UnwrapResult& result, bool shapes) {
  std::vector<size_t> swapped;
  for (size_t c = 0; c < charts.size(); ++c)
    if (charts[c].unfolded) swap_unfolded(charts[c]), swapped.push_back(c);
  std::vector<char> kept_new;
  repack_swapped(mesh, pieces, charts, swapped, [&](size_t i) { swap_unfolded(charts[swapped[i]]); },
                 padding, options, result, shapes, &kept_new);
  for (size_t i = 0; i < swapped.size(); ++i)
    if (kept_new[i]) charts[swapped[i]].alternative.reset();
  for (Chart& chart : charts) chart.unfolded.reset();  // used up either way
}

}  // namespace

void pack_valid(const TriMesh& mesh, const std::vector<Component>& pieces, std::vector<Chart> charts,
                const DiskParamOptions& dopt, double padding, Clock::time_point t_start,
                const UnwrapOptions& options, UnwrapResult& result, PieceLayouts layouts,
                bool shapes, BuiltPieces* built) {
  std::vector<Component> split;  // the pieces once an invalid chart was split
  int round = 0;
  // Fragile charts are split before the first packing: a packing costs far more than the check,
  // and the rounds below would find them one packing at a time (docs/decisions.md).
  for (std::vector<char> bad; round < kMaxValidityRounds; ++round) {
    const auto t0 = Clock::now();
    bad = fragile_charts(charts);
    result.report.time_pack += seconds_since(t0);
    if (std::find(bad.begin(), bad.end(), 1) == bad.end()) break;
    std::vector<Component> next = round == 0 ? pieces : std::move(split);
    split_invalid_charts(next, charts, bad, dopt, t_start, options, result.report, layouts);
    split = std::move(next);
  }
  for (;; ++round) {
    const std::vector<Component>& current = round == 0 ? pieces : split;
    const auto t0 = Clock::now();
    report_progress(options.progress, "pack", 0.0);
    assemble(mesh, current, charts, padding, options, result, shapes);
    report_progress(options.progress, "pack", 1.0);
    result.report.time_pack += seconds_since(t0);
    const std::vector<int> bad = invalid_layout_faces(result.param, charts);
    if (bad.empty()) {
      const auto t1 = Clock::now();
      pack_unfolded(mesh, current, charts, padding, options, result, shapes);
      pack_alternatives(mesh, current, charts, padding, options, result, shapes);
      result.report.time_pack += seconds_since(t1);
      if (built) *built = BuiltPieces{round == 0 ? pieces : std::move(split), std::move(charts)};
      return;
    }
    if (round == kMaxValidityRounds)
      throw SolverError("unwrap: no valid layout found (" + std::to_string(bad.size()) +
                        " flipped, degenerate or overlapping UV triangles remain)");
    std::vector<char> bad_chart(current.size(), 0);
    for (int f : bad) bad_chart[result.param.face_chart[f]] = 1;
    std::vector<Component> next = round == 0 ? pieces : std::move(split);
    split_invalid_charts(next, charts, bad_chart, dopt, t_start, options, result.report, layouts);
    split = std::move(next);
  }
}

bool unwrap_pieces(const TriMesh& mesh, const std::vector<Component>& pieces,
                   const DiskParamOptions& dopt, double padding, Clock::time_point t_start,
                   const UnwrapOptions& options, UnwrapResult& result, PieceLayouts layouts,
                   double give_up_l2, const std::function<void()>& on_last_started,
                   bool shapes, BuiltPieces* built) {
  std::vector<Chart> charts = build_charts(pieces, dopt, t_start, options, result.report, layouts,
                                           give_up_l2, on_last_started);
  for (const Chart& c : charts)
    if (c.abandoned) return false;
  pack_valid(mesh, pieces, std::move(charts), dopt, padding, t_start, options, result, layouts,
             shapes, built);
  return true;
}

}  // namespace adaptex::unwrap_detail
