/// \file unwrap_chart.cpp
/// One chart per piece (thesis §3.2): the initial cut and slicing (cut.h), the Gu–Gortler–Hoppe cut
/// augmentation compared on a cheap parameterization, the disk parameterization (disk_param.h:
/// Floater + Yoshizawa), then the other layouts a piece may take (unfolding, projection, LSCM, SLIM)
/// when their own texel share is higher. See docs/surgery.md and docs/charts.md.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string_view>

#include "adaptex/core/timer.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/lscm.h"
#include "adaptex/param/planar.h"
#include "adaptex/param/slim.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/yoshizawa.h"

#include "unwrap_internal.h"

namespace adaptex::unwrap_detail {

void swap_unfolded(Chart& chart) {
  ChartLayout& u = *chart.unfolded;
  if (u.own_disk) std::swap(chart.state.cut, u.cut), std::swap(chart.state.disk, u.disk);
  std::swap(chart.state.param, u.param);
  std::swap(chart.domain_area, u.domain_area);
  std::swap(chart.aspect, u.aspect);
  std::swap(chart.cut_length, u.cut_length);
}

namespace {

/// Whether \p l gives the pieces free-boundary layouts (Free or FreeKeepUnfolded).
bool free_layouts(PieceLayouts l) {
  return l == PieceLayouts::Free || l == PieceLayouts::FreeKeepUnfolded;
}

/// Input vertex (of the component) with the largest stretch that is not on the cut yet: the
/// per-wedge stretch σ (yoshizawa.h: area-weighted face L2 around the wedge), maximum over wedges.
/// Vertices next to a degenerate UV triangle (σ = inf: an extremity squeezed to nothing by the
/// Tutte embedding) come first, the one farthest from the cut (the tip of the extremity) first.
int worst_vertex(const Component& comp, const EdgeGraph& graph, CutState& s,
                 const std::vector<char>& on_cut) {
  const std::vector<double> sigma = s.solve_state
                                        ? result_vertex_stretch(s.disk.disk, *s.solve_state, s.param)
                                        : vertex_stretch(s.disk.disk, s.param.uv);
  const int nv = comp.mesh.num_vertices();
  std::vector<double> per_vertex(nv, 0.0);
  bool any_inf = false;
  for (size_t w = 0; w < sigma.size(); ++w) {
    double& x = per_vertex[s.disk.wedge_vertex[w]];
    x = std::max(x, std::isfinite(sigma[w]) ? sigma[w] : std::numeric_limits<double>::infinity());
    any_inf |= !std::isfinite(sigma[w]) && !on_cut[s.disk.wedge_vertex[w]];
  }
  if (any_inf) {
    const std::vector<double> dist = distance_to_cut(graph, on_cut);
    for (int v = 0; v < nv; ++v)
      per_vertex[v] = std::isfinite(per_vertex[v]) ? 0.0 : 1.0 + dist[v];
  }
  int best = -1;
  for (int v = 0; v < nv; ++v)
    if (!on_cut[v] && (best < 0 || per_vertex[v] > per_vertex[best])) best = v;
  return best;
}

/// How good a cut is, from its (cheap) parameterization: fewer degenerate/flipped UV triangles
/// first, then lower L2 stretch.
struct CutScore {
  long bad = 0;
  double l2 = 0;
};
CutScore score(const CutState& s) {
  // parameterize_disk() measured its result with measure_stretch() already.
  const DiskParamResult& p = s.param;
  return {static_cast<long>(p.degenerate) + p.flipped, std::isfinite(p.final_l2) ? p.final_l2 : 0.0};
}
bool better(const CutScore& a, const CutScore& b, double min_improvement) {
  if (a.bad != b.bad) return a.bad < b.bad;
  return a.l2 < b.l2 * (1.0 - min_improvement);
}

/// What every chart of one unwrap() attempt shares: the options, the disk-parameterization
/// settings, the augmentation budgets and the report being filled.
struct ChartContext {
  const UnwrapOptions& options;
  DiskParamOptions dopt;
  long augment_faces_left = 0;
  Clock::time_point augment_deadline;
  UnwrapReport& rep;
  /// Unfold: a piece without interior vertices may be unfolded (whole components of a layout of
  /// several components); Free: the pieces of the scan segmentation may also get an LSCM layout.
  PieceLayouts layouts;
  /// > 0: a chart whose first cheap parameterization (Floater + augment_yoshizawa_iterations
  /// Yoshizawa iterations, before any augmentation) has degenerate or flipped UV triangles or an
  /// L2 above this is abandoned there (Chart::abandoned; UnwrapOptions::single_probe_l2).
  double give_up_l2 = 0;
};

/// Budget units (face-solves, UnwrapOptions::augment_face_budget) of one cheap parameterization of
/// a chart of \p faces faces: the Floater solve and the cheap Yoshizawa iterations.
long augment_eval_cost(long faces, const DiskParamOptions& dopt, const UnwrapOptions& options) {
  return faces * (1 + std::max(0, std::min(dopt.max_iterations, options.augment_yoshizawa_iterations)));
}

}  // namespace

double l2_at_aspect(const TriMesh& disk, const std::vector<Vec2>& uv, double a) {
  const double sx = std::sqrt(a);
  std::vector<Vec2> scaled(uv.size());
  for (size_t w = 0; w < uv.size(); ++w) scaled[w] = Vec2(uv[w].x() * sx, uv[w].y() / sx);
  return measure_stretch(disk, scaled).l2;
}

std::pair<double, double> best_aspect(const Chart& chart) {
  const TriMesh& disk = chart.state.disk.disk;
  const std::vector<Vec2>& uv = chart.state.param.uv;
  if (chart.aspect > 0) return {chart.aspect, l2_at_aspect(disk, uv, chart.aspect)};
  // The aspect is chosen on the closed form of the L2 of all 17 aspects (one pass over the faces,
  // stretch.h); the L2 returned is measured (measure_stretch(), as parameterize_disk() measured the
  // chart's own L2 for a = 1), so the rectangle sizes do not change by rounding: the packing
  // reacts to the last bit of a size.
  std::vector<double> aspects;
  for (int i = -8; i <= 8; ++i) aspects.push_back(std::pow(4.0, i / 8.0));
  const std::vector<double> l2 = l2_stretch_of_aspects(disk, uv, aspects);
  size_t best = 8;  // a = 1
  for (size_t i = 0; i < aspects.size(); ++i)
    if (i != 8 && l2[i] < l2[best]) best = i;
  if (best == 8) return {1.0, chart.state.param.final_l2};
  return {aspects[best], l2_at_aspect(disk, uv, aspects[best])};
}

namespace {

/// Replaces \p chart by \p u, a layout of its whole piece (no cut: an unfolding, a projection),
/// when its own texel share, UV fill of its rectangle / L2² at its aspect, is higher than the
/// chart's at its best aspect.
void use_layout_if_better(const Component& comp, Chart& chart, std::optional<PolygonLayout> u,
                          double e = 1.0) {
  if (!u) return;
  const double l2_u = l2_at_aspect(comp.mesh, u->uv, u->aspect);
  const double l2_c = best_aspect(chart).second;
  if (!(std::isfinite(l2_u) && layout_score(u->fill, l2_u, e) > layout_score(chart.domain_area, l2_c, e)))
    return;
  CutState& s = chart.state;
  s.cut.assign(s.cut.size(), 0);
  s.disk.disk = comp.mesh;
  s.disk.wedge_vertex.resize(comp.mesh.num_vertices());
  std::iota(s.disk.wedge_vertex.begin(), s.disk.wedge_vertex.end(), 0);
  s.disk.boundary_loop.clear();
  s.solve_state.reset();
  const StretchStats st = measure_stretch(comp.mesh, u->uv);  // in the chart's own square frame
  s.param.uv = std::move(u->uv);
  s.param.floater_l2 = s.param.final_l2 = st.l2;
  s.param.floater_linf = s.param.final_linf = st.linf;
  s.param.iterations = 0;
  s.param.flipped = s.param.degenerate = 0;
  s.param.on_square = false;
  chart.cut_length = 0;
  chart.augmentations = 0;
  chart.domain_area = u->fill;
  chart.aspect = u->aspect;
}

/// Replaces \p chart by the isometric unfolding of its piece (unfold.h) when the piece is a
/// triangulated polygon (every vertex on the boundary: the disk parameterization can only map
/// them onto the square) and the unfolding's own texel share, UV fill of its rectangle / L2² at
/// its aspect, is higher than the chart's at its best aspect (tiny_components(200): its 10-face
/// strips go from L2 1.5 at fill 1 to L2 1 at fill 0.91, its slivers from L2 250 to 1; strips of
/// two faces keep the square, L2 1.06 at fill 1 against fill 0.71).
void use_unfolding_if_better(const Component& comp, Chart& chart, double e) {
  use_layout_if_better(comp, chart, unfold_polygon(comp.mesh), e);
}

}  // namespace

void adopt_disk_layout(Chart& chart, PolygonLayout&& u) {
  CutState& s = chart.state;
  s.solve_state.reset();
  const StretchStats st = measure_stretch(s.disk.disk, u.uv);
  s.param.uv = std::move(u.uv);
  s.param.floater_l2 = s.param.final_l2 = st.l2;
  s.param.floater_linf = s.param.final_linf = st.linf;
  s.param.flipped = s.param.degenerate = 0;
  s.param.on_square = false;
  chart.domain_area = u.fill;
  chart.aspect = u.aspect;
}

namespace {

/// Replaces the layout of \p chart by a free-boundary conformal layout of its disk (lscm.h) when
/// that is valid and its own texel share, UV fill of its rectangle / L2² at its aspect, is higher
/// than the chart's at its best aspect (the cut, hence the disk and its wedges, stay).
/// \p first: the cut and disk before the augmentation, tried too (LSCM of a disk may overlap
/// where that of a shorter cut does not); \p first_lscm (if not null): its layout, computed already.
void use_free_boundary_if_better(Chart& chart, CutState first,
                                 const std::optional<PolygonLayout>* first_lscm, double e) {
  CutState& s = chart.state;
  const auto lscm_of_first = [&] { return first_lscm ? *first_lscm : lscm_layout(first.disk.disk); };
  // The cut was not augmented: the same disk, whose layout would only tie with u.
  const bool same_disk = first.disk.wedge_vertex == s.disk.wedge_vertex &&
                         first.disk.disk.faces == s.disk.disk.faces &&
                         first.disk.disk.positions == s.disk.disk.positions;
  std::optional<PolygonLayout> u = same_disk ? lscm_of_first() : lscm_layout(s.disk.disk);
  double l2_u = u ? l2_at_aspect(s.disk.disk, u->uv, u->aspect) : 0.0;
  if (std::optional<PolygonLayout> f = same_disk ? std::nullopt : lscm_of_first()) {
    const double l2_f = l2_at_aspect(first.disk.disk, f->uv, f->aspect);
    if (std::isfinite(l2_f) && (!u || layout_score(f->fill, l2_f, e) > layout_score(u->fill, l2_u, e))) {
      const double l2_c = best_aspect(chart).second;
      if (!(layout_score(f->fill, l2_f, e) > layout_score(chart.domain_area, l2_c, e))) return;
      s.cut = std::move(first.cut);
      s.disk = std::move(first.disk);
      chart.augmentations = 0;
      u = std::move(f);
      l2_u = l2_f;
    }
  }
  if (!u) return;
  const double l2_c = best_aspect(chart).second;
  if (!(std::isfinite(l2_u) && layout_score(u->fill, l2_u, e) > layout_score(chart.domain_area, l2_c, e)))
    return;
  adopt_disk_layout(chart, std::move(*u));
}

/// Replaces the layout of \p chart (own L2 above 1.05) by a free-boundary SLIM layout of its disk
/// (slim.h) started from its own layout at its best aspect, when that has a higher own texel share
/// (fill of its rectangle / L2²). A layout whose free boundary runs into itself is tried again with
/// half the iterations, down to one. \p iterations: SlimOptions::max_iterations
/// (UnwrapOptions::scan_slim_iterations; 0: none). A layout rejected under \p e but better under
/// \p e_alt (when 0 <= e_alt < e) is kept as Chart::alternative.
void use_slim_if_better(Chart& chart, double e, int iterations, double e_alt) {
  const CutState& s = chart.state;
  if (iterations <= 0 || s.param.flipped > 0 || s.param.degenerate > 0) return;
  const auto [a, l2_c] = best_aspect(chart);
  // A chart within 5 % of an isometry has little to gain, and re-laying it out only churns the
  // packing (docs/decisions.md, "Scans: a free-boundary SLIM layout for every stretched chart").
  if (!(std::isfinite(l2_c) && l2_c > 1.05)) return;
  const double sx = std::sqrt(a);
  std::vector<Vec2> start(s.param.uv.size());
  for (size_t w = 0; w < start.size(); ++w) start[w] = Vec2(s.param.uv[w].x() * sx, s.param.uv[w].y() / sx);
  SlimOptions sopt;
  sopt.max_iterations = iterations;
  std::optional<PolygonLayout> u = slim_layout_halving(s.disk.disk, start, sopt);
  if (!u) return;
  const double l2_u = l2_at_aspect(s.disk.disk, u->uv, u->aspect);
  if (!std::isfinite(l2_u)) return;
  if (layout_score(u->fill, l2_u, e) > layout_score(chart.domain_area, l2_c, e))
    adopt_disk_layout(chart, std::move(*u));
  else if (e_alt >= 0 && e_alt < e &&
           layout_score(u->fill, l2_u, e_alt) > layout_score(chart.domain_area, l2_c, e_alt))
    chart.alternative = std::move(*u);
}

/// One piece's cut augmentation in build_chart(): the piece and its edges, the cheap
/// parameterization the candidate cuts are compared with, its budget cost and progress range.
struct Augmentation {
  const Component& comp;
  const EdgeConnectivity& ec;
  const EdgeGraph& graph;
  DiskParamOptions cheap;
  long eval_cost = 0;
  double frac0 = 0, frac1 = 0;
  /// Input vertex -> its wedge in the first evaluated disk when it has only one (-2 when several).
  std::vector<int> pattern_wedge;
};

/// Settings of the cheap parameterization that compares candidate cuts (Floater + at most
/// augment_yoshizawa_iterations Yoshizawa iterations); progress is reported as "augment" at \p frac0.
DiskParamOptions cheap_param_options(const DiskParamOptions& dopt, const UnwrapOptions& options,
                                     double frac0) {
  DiskParamOptions cheap = dopt;
  cheap.max_iterations = std::min(dopt.max_iterations, options.augment_yoshizawa_iterations);
  cheap.yoshizawa = cheap.max_iterations > 0;
  cheap.progress = [&options, frac0](std::string_view, double) {
    return !options.progress || options.progress("augment", frac0);
  };
  return cheap;
}

/// The cut of \p cur extended by the shortest path from vertex \p from to it (\p on_cut), sliced
/// and given its cheap parameterization. Solved with the pattern of the first evaluated disk when
/// there is one: the candidate is the same surface cut along a larger cut.
CutState augment_candidate(const Augmentation& aug, const CutState& cur,
                           const std::vector<char>& on_cut, int from) {
  CutState cand;
  cand.cut = cur.cut;
  for (int e : shortest_path_to_cut(aug.graph, on_cut, from)) cand.cut[e] = 1;
  cand.disk = slice_along_cut(aug.comp.mesh, aug.ec, cand.cut);
  if (cur.solve_state && !aug.pattern_wedge.empty()) {
    // Its Tutte systems are solved with the pattern (ordering, pivots) of the first evaluated disk.
    std::vector<int> to_pattern(cand.disk.wedge_vertex.size());
    for (size_t w = 0; w < to_pattern.size(); ++w)
      to_pattern[w] = aug.pattern_wedge[cand.disk.wedge_vertex[w]];
    cand.param = parameterize_subdisk(cand.disk.disk, cand.disk.boundary_loop, to_pattern,
                                      *cur.solve_state, aug.cheap, &cand.solve_state);
  } else {
    cand.param =
        parameterize_disk(cand.disk.disk, cand.disk.boundary_loop, aug.cheap, &cand.solve_state);
  }
  return cand;
}

/// Cut augmentation (GGH 2002 §3.2): adds the path from the worst vertex to the cut of \p cur while
/// the score improves, counting them in \p augmentations. The budgets apply while the current
/// parameterization is valid; one with degenerate UV triangles (squeezed extremities) is augmented
/// regardless of them, up to max_augmentations. Returns true if the cut changed.
bool augment_cut(const Augmentation& aug, ChartContext& ctx, CutState& cur, CutScore cur_score,
                 int& augmentations) {
  const UnwrapOptions& options = ctx.options;
  const auto ta = Clock::now();
  bool changed = false;
  for (int a = 0; a < options.max_augmentations; ++a) {
    if (cur_score.bad == 0 &&
        (ctx.augment_faces_left < aug.eval_cost || Clock::now() >= ctx.augment_deadline))
      break;
    report_progress(options.progress, "augment",
                    aug.frac0 + (aug.frac1 - aug.frac0) * a / options.max_augmentations);
    const std::vector<char> on_cut = cut_vertices(aug.comp.mesh, aug.ec, cur.cut);
    const int from = worst_vertex(aug.comp, aug.graph, cur, on_cut);
    if (from < 0) break;
    CutState cand = augment_candidate(aug, cur, on_cut, from);
    ctx.augment_faces_left -= aug.eval_cost;
    const CutScore cand_score = score(cand);
    if (!better(cand_score, cur_score, options.augment_min_improvement)) break;
    cur = std::move(cand);
    cur_score = cand_score;
    ++augmentations;
    changed = true;
  }
  ctx.rep.time_augment += seconds_since(ta);
  return changed;
}

/// The first cheap parameterization of the initial cut \p cur, whose solve pattern the candidates
/// reuse (sets Augmentation::pattern_wedge); charged to the augmentation budget and time.
void evaluate_initial_cut(Augmentation& aug, ChartContext& ctx, CutState& cur) {
  const auto t0 = Clock::now();
  report_progress(ctx.options.progress, "augment", aug.frac0);
  cur.param = parameterize_disk(cur.disk.disk, cur.disk.boundary_loop, aug.cheap, &cur.solve_state);
  aug.pattern_wedge.assign(aug.comp.mesh.num_vertices(), -1);
  for (size_t w = 0; w < cur.disk.wedge_vertex.size(); ++w) {
    int& p = aug.pattern_wedge[cur.disk.wedge_vertex[w]];
    p = p == -1 ? static_cast<int>(w) : -2;
  }
  ctx.augment_faces_left -= aug.eval_cost;
  ctx.rep.time_augment += seconds_since(t0);
}

/// The full parameterization of the chosen cut (Floater, then Yoshizawa with \p full), its
/// times added to \p rep; drops the solver state.
void solve_full(CutState& cur, const DiskParamOptions& full, UnwrapReport& rep) {
  if (cur.solve_state) {
    // The chosen cut's cheap parameterization is the start of its full one (same Floater solve,
    // same first Yoshizawa iterations): continue it.
    const double t_before = cur.param.time_yoshizawa;
    cur.param = continue_disk_param(cur.disk.disk, *cur.solve_state, cur.param, full);
    rep.time_yoshizawa += cur.param.time_yoshizawa - t_before;
  } else {
    cur.param = parameterize_disk(cur.disk.disk, cur.disk.boundary_loop, full);
    rep.time_floater += cur.param.time_floater;
    rep.time_yoshizawa += cur.param.time_yoshizawa;
  }
  cur.solve_state.reset();
}

/// Signed UV area of the parameterized disk of \p s (Chart::domain_area), 1 when not positive.
double uv_domain_area(const CutState& s) {
  double area2 = 0;
  for (const Face& t : s.disk.disk.faces) {
    const Vec2 e1 = s.param.uv[t[1]] - s.param.uv[t[0]];
    const Vec2 e2 = s.param.uv[t[2]] - s.param.uv[t[0]];
    area2 += 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
  }
  return area2 > 0 ? area2 : 1.0;
}

/// Replaces the disk layout of \p chart by one of the other layouts \p layouts allows when that has
/// a higher texel share: the unfolding, the projection (only for a piece that is a \p disk: charts
/// are disks), the free-boundary layout of the final or the \p initial cut; then the SLIM layout
/// (scored with \p slim_exponent; \p slim_alt_exponent as in use_slim_if_better()).
void use_other_layouts_if_better(const Component& comp, Chart& chart, PieceLayouts layouts,
                                  bool disk, CutState initial, double fill_exponent,
                                  int slim_iterations, double slim_exponent,
                                  double slim_alt_exponent = -1) {
  // The fill exponent applies to the scan charts (Free) only.
  const double e = free_layouts(layouts) ? fill_exponent : 1.0;
  if (layouts != PieceLayouts::Disk) use_unfolding_if_better(comp, chart, e);
  if (!free_layouts(layouts)) return;
  // A projection keeps the piece's own boundaries: only a disk may take it (charts are disks).
  if (disk)
    use_layout_if_better(comp, chart,
                         comp.probe_projection ? *comp.probe_projection
                                               : projection_layout(comp.mesh),
                         e);
  use_free_boundary_if_better(chart, std::move(initial), comp.probe_lscm.get(), e);
  use_slim_if_better(chart, slim_exponent, slim_iterations, slim_alt_exponent);
}

/// Gives \p chart (its disk parameterization done) the unfolding if better, as the Unfold layouts
/// do, and returns a copy of that layout, or null when it has flipped or degenerate triangles.
std::unique_ptr<ChartLayout> unfolded_layout(const Component& comp, Chart& chart, bool disk) {
  use_other_layouts_if_better(comp, chart, PieceLayouts::Unfold, disk, {}, 1.0, 0, 1.0);
  if (score(chart.state).bad > 0) return nullptr;
  auto u = std::make_unique<ChartLayout>();
  u->cut = chart.state.cut;
  u->disk = chart.state.disk;
  u->param = chart.state.param;
  u->domain_area = chart.domain_area;
  u->aspect = chart.aspect;
  return u;
}

/// Keeps \p u (unfolded_layout()) as \p chart's Chart::unfolded when the chart's final layout
/// differs from it; its cut and disk only when they differ too (memory). \p graph: the piece's.
void keep_unfolded(Chart& chart, std::unique_ptr<ChartLayout> u, const EdgeGraph& graph) {
  if (u->param.uv == chart.state.param.uv && u->cut == chart.state.cut) return;
  u->cut_length = cut_length(graph, u->cut);
  const SlicedDisk& d = chart.state.disk;
  u->own_disk = u->cut != chart.state.cut || u->disk.disk.faces != d.disk.faces ||
                u->disk.wedge_vertex != d.wedge_vertex || u->disk.boundary_loop != d.boundary_loop;
  if (!u->own_disk) std::vector<char>().swap(u->cut), u->disk = SlicedDisk();
  chart.unfolded = std::move(u);
}

/// Cuts one piece (a component, or a chart of a component) to a disk, augments the cut (GGH 2002
/// §3.2) and parameterizes the disk (Floater + Yoshizawa). Progress fractions [frac0, frac1].
Chart build_chart(const Component& comp, ChartContext& ctx, double frac0, double frac1) {
  const UnwrapOptions& options = ctx.options;
  const DiskParamOptions& dopt = ctx.dopt;
  UnwrapReport& rep = ctx.rep;
  Chart chart;
  // Initial cut and slicing.
  const auto t0 = Clock::now();
  report_progress(options.progress, "cut", frac0);
  const EdgeConnectivity ec = build_edges(comp.mesh);
  const EdgeGraph graph = build_edge_graph(comp.mesh, ec);
  CutState cur;
  // A connected piece with Euler characteristic 1 is a disk (one boundary loop, genus 0): its
  // initial cut is empty (test Cut.ADiskNeedsNoCut), so initial_cut() is skipped.
  const bool disk = comp.mesh.num_vertices() - ec.num_edges() + comp.mesh.num_faces() == 1;
  cur.cut = disk ? std::vector<char>(ec.num_edges(), 0) : initial_cut(comp.mesh, ec, graph);
  cur.disk = slice_along_cut(comp.mesh, ec, cur.cut);
  rep.time_cut += seconds_since(t0);
  CutState initial;  // the initial cut, for the free-boundary layout
  if (free_layouts(ctx.layouts)) initial.cut = cur.cut, initial.disk = cur.disk;

  // Cut augmentation: as in the thesis, the candidates are compared with a cheaper
  // parameterization; the full Yoshizawa solve runs once, on the chosen cut.
  Augmentation aug{comp, ec, graph, cheap_param_options(dopt, options, frac0),
                   augment_eval_cost(comp.mesh.num_faces(), dopt, options), frac0, frac1, {}};
  bool evaluated = false;
  if (options.max_augmentations > 0 && ctx.augment_faces_left >= 2 * aug.eval_cost &&
      Clock::now() < ctx.augment_deadline) {
    evaluate_initial_cut(aug, ctx, cur);
    evaluated = true;
    const CutScore first = score(cur);
    if (ctx.give_up_l2 > 0 && (first.bad > 0 || first.l2 > ctx.give_up_l2)) {
      chart.abandoned = true;
      chart.state = std::move(cur);
      return chart;
    }
    augment_cut(aug, ctx, cur, first, chart.augmentations);
  }

  // The parameterization of the disk (Floater, then Yoshizawa).
  DiskParamOptions full = dopt;
  full.progress = [&](std::string_view phase, double f) {
    return !options.progress || options.progress(phase, frac0 + f * (frac1 - frac0));
  };
  solve_full(cur, full, rep);
  // Rescue: a chart over the budgets whose result has degenerate triangles is augmented anyway.
  if (options.max_augmentations > 0 && !evaluated) {
    const CutScore s = score(cur);
    if (s.bad > 0 && augment_cut(aug, ctx, cur, s, chart.augmentations)) solve_full(cur, full, rep);
  }
  chart.state = std::move(cur);
  chart.domain_area = uv_domain_area(chart.state);
  const auto tl = Clock::now();
  // The top-down candidate: the chart as the Unfold layouts leave it is kept too (Chart::unfolded),
  // packed in its place if that wins.
  std::unique_ptr<ChartLayout> unfolded;
  if (ctx.layouts == PieceLayouts::FreeKeepUnfolded)
    unfolded = unfolded_layout(comp, chart, disk);
  use_other_layouts_if_better(comp, chart, ctx.layouts, disk, std::move(initial),
                              options.scan_layout_fill_exponent, options.scan_slim_iterations,
                              options.scan_slim_fill_exponent, options.scan_slim_second_exponent);
  rep.time_layouts += seconds_since(tl);
  // Still flipped or degenerate UV triangles (no augmentation allowed or none helped): a valid
  // layout of the other kinds, whatever its share (unwrap_pieces() splits the piece otherwise).
  if (!free_layouts(ctx.layouts) && score(chart.state).bad > 0) {
    CutState same;  // the free-boundary layout of the chart's own disk
    same.cut = chart.state.cut, same.disk = chart.state.disk;
    use_other_layouts_if_better(comp, chart, PieceLayouts::Free, disk, std::move(same), 1.0, 0, 1.0);
  }
  chart.cut_length = cut_length(graph, chart.state.cut);
  if (unfolded) keep_unfolded(chart, std::move(unfolded), graph);
  return chart;
}

}  // namespace

std::vector<Chart> build_charts(const std::vector<Component>& pieces, const DiskParamOptions& dopt,
                                Clock::time_point t_start, const UnwrapOptions& options,
                                UnwrapReport& rep, PieceLayouts layouts, double give_up_l2,
                                const std::function<void()>& on_last_started) {
  const Clock::time_point deadline =
      t_start + std::chrono::duration_cast<Clock::duration>(
                    std::chrono::duration<double>(std::max(0.0, options.augment_time_budget)));
  const int nc = static_cast<int>(pieces.size());
  long largest_use = 0;
  for (const Component& p : pieces)
    largest_use += (1L + options.max_augmentations) * augment_eval_cost(p.mesh.num_faces(), dopt, options);
  std::vector<Chart> charts(nc);
  if (nc < 2 || largest_use > options.augment_face_budget) {
    ChartContext ctx{options, dopt, options.augment_face_budget, deadline, rep, layouts, give_up_l2};
    for (int c = 0; c < nc; ++c) {
      if (c == nc - 1 && on_last_started) on_last_started();
      charts[c] = build_chart(pieces[c], ctx, static_cast<double>(c) / nc,
                              static_cast<double>(c + 1) / nc);
    }
    return charts;
  }
  // Exceptions: parallel_keep_first_error() (the other charts stop at their next progress report).
  std::mutex mutex;
  double reported = 0;
  std::atomic<bool> failed{false};
  UnwrapOptions shared = options;
  shared.progress = [&](std::string_view phase, double f) {
    if (failed.load(std::memory_order_relaxed)) return false;  // another chart failed
    if (!options.progress) return true;
    const std::lock_guard<std::mutex> lock(mutex);
    reported = std::max(reported, f);
    return options.progress(phase, reported);
  };
  std::vector<UnwrapReport> reps(nc);
  // Largest pieces first, each taken by the next free thread: the longest chart does not start
  // last (a chart's result does not depend on the order).
  std::vector<int> order(nc);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return pieces[a].mesh.num_faces() > pieces[b].mesh.num_faces();
  });
  std::atomic<int> started{0};
  parallel_keep_first_error(nc, mutex, failed, [&](int i) {
    if (++started == nc && on_last_started) on_last_started();
    const int c = order[i];
    ChartContext ctx{shared, dopt, largest_use, deadline, reps[c], layouts, give_up_l2};  // cannot run out
    charts[c] = build_chart(pieces[c], ctx, static_cast<double>(c) / nc,
                            static_cast<double>(c + 1) / nc);
  });
  for (const UnwrapReport& r : reps) {
    rep.time_cut += r.time_cut;
    rep.time_floater += r.time_floater;
    rep.time_yoshizawa += r.time_yoshizawa;
    rep.time_augment += r.time_augment;
    rep.time_layouts += r.time_layouts;
  }
  return charts;
}

}  // namespace adaptex::unwrap_detail
