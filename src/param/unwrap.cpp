/// \file unwrap.cpp
/// The initial parameterization pipeline (thesis §3.2 + §3.3): per connected component, the initial
/// cut and slicing (cut.h), the disk parameterization (disk_param.h: Floater + Yoshizawa), the
/// Gu–Gortler–Hoppe cut augmentation, then chart packing (pack.h). See docs/surgery.md.
#include "adaptex/param/unwrap.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <iterator>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <string>
#include <string_view>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/orientation.h"
#include "adaptex/core/pinched.h"
#include "adaptex/core/timer.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/charts.h"
#include "adaptex/param/cut.h"
#include "adaptex/param/disk_param.h"
#include "adaptex/param/lscm.h"
#include "adaptex/param/pack.h"
#include "adaptex/param/planar.h"
#include "adaptex/param/slim.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unfold.h"
#include "adaptex/param/yoshizawa.h"

namespace adaptex {

namespace {

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

/// Swaps the layout of \p chart with its Chart::unfolded one.
void swap_unfolded(Chart& chart) {
  ChartLayout& u = *chart.unfolded;
  if (u.own_disk) std::swap(chart.state.cut, u.cut), std::swap(chart.state.disk, u.disk);
  std::swap(chart.state.param, u.param);
  std::swap(chart.domain_area, u.domain_area);
  std::swap(chart.aspect, u.aspect);
  std::swap(chart.cut_length, u.cut_length);
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

/// Which layouts a piece may get besides its disk parameterization.
enum class PieceLayouts {
  Disk,    ///< the disk parameterization only
  Unfold,  ///< also the isometric unfolding of a piece without interior vertices (unfold.h)
  Free,    ///< also that, and a free-boundary (LSCM) layout (lscm.h; UnwrapOptions::scan_free_boundary)
  /// as Free, and the layout as Unfold leaves it is kept too (Chart::unfolded, pack_unfolded()):
  /// the top-down candidate of unwrap_scan() (UnwrapOptions::scan_top_down_free_layouts)
  FreeKeepUnfolded,
};

/// Whether \p l gives the pieces free-boundary layouts (Free or FreeKeepUnfolded).
bool free_layouts(PieceLayouts l) {
  return l == PieceLayouts::Free || l == PieceLayouts::FreeKeepUnfolded;
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

/// L2 stretch of the per-vertex map \p uv of \p disk scaled by (sqrt(a), 1 / sqrt(a)) (measured).
double l2_at_aspect(const TriMesh& disk, const std::vector<Vec2>& uv, double a) {
  const double sx = std::sqrt(a);
  std::vector<Vec2> scaled(uv.size());
  for (size_t w = 0; w < uv.size(); ++w) scaled[w] = Vec2(uv[w].x() * sx, uv[w].y() / sx);
  return measure_stretch(disk, scaled).l2;
}

/// Width / height ratio a of the rectangle that gives the chart the lowest L2 stretch when its
/// square parameterization is scaled by (sqrt(a), 1 / sqrt(a)): Chart::aspect when fixed, else the
/// best of 17 values from 1/4 to 4 (log-spaced). Multi-chart layouts only; a single chart keeps the
/// square. Returns (a, that L2).
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

/// A layout's own texel share as the chart choice scores it: fill^e / L2²
/// (UnwrapOptions::scan_layout_fill_exponent; e = 1: the share of its bounding rectangle).
double layout_score(double fill, double l2, double e) { return std::pow(fill, e) / (l2 * l2); }

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

/// Gives \p chart the layout \p u of its own disk (cut and disk unchanged).
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

/// Total 3-D length of the seams of \p param: input edges whose two faces do not share both UV
/// corners.
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
/// their rectangles, keeping the packing of the higher effective texel share) and writes the layout and its figures into \p result (write_layout()); unwrap()
/// replaces the cut length of several charts by their seam length.
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

/// Appends the charts of \p comp given by \p label (F labels, charts.h) to \p pieces, with input
/// face/vertex ids.
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

/// The chart of every piece (build_chart()), phase times added to \p rep. The charts share the
/// augmentation face budget in piece order; when even the largest use of every chart
/// ((1 + max_augmentations) cheap evaluations) fits in it, the budget cannot run out, the charts do
/// not depend on each other, and they are built in parallel (TBB) with the same result. The
/// progress callback is then called under a mutex with a non-decreasing fraction. \p unfold: a
/// piece without interior vertices may be unfolded (ChartContext::unfold_polygons).
/// \p on_last_started (if set) is called once, when the last chart starts (segment_until_good()
/// then starts the next chart count on the threads this attempt no longer needs).
std::vector<Chart> build_charts(const std::vector<Component>& pieces, const DiskParamOptions& dopt,
                                Clock::time_point t_start, const UnwrapOptions& options,
                                UnwrapReport& rep, PieceLayouts layouts, double give_up_l2 = 0,
                                const std::function<void()>& on_last_started = {}) {
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

/// Splits \p piece into \p k charts (segment_charts()) appended to \p out; returns how many.
size_t split_piece(const Component& piece, int k, double normal_weight, std::vector<Component>& out) {
  ChartSegmentOptions so;
  so.num_charts = k;
  so.normal_weight = normal_weight;
  const size_t before = out.size();
  append_pieces(piece, ChartSegmenter(piece.mesh).segment(so), out);
  return out.size() - before;
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

/// The pieces and charts of a valid packed layout, kept so that some charts can be rebuilt.
struct BuiltPieces {
  std::vector<Component> pieces;
  std::vector<Chart> charts;
};

/// Packs \p charts (parallel to \p pieces) into \p result; while UV triangles are invalid, splits
/// their charts (split_invalid_charts()) and packs again. \p built (if set) receives the final
/// pieces and charts.
/// \throw SolverError still invalid after kMaxValidityRounds rounds
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

/// Builds the chart of every piece and packs them into \p result (one unwrap() attempt).
/// \p unfold and \p on_last_started as in build_charts(); \p give_up_l2 as
/// ChartContext::give_up_l2; \p shapes as in assemble(); \p built as in pack_valid(). Returns
/// false, and leaves the layout of \p result alone (only its phase times grow), when a chart was
/// abandoned.
bool unwrap_pieces(const TriMesh& mesh, const std::vector<Component>& pieces,
                   const DiskParamOptions& dopt, double padding, Clock::time_point t_start,
                   const UnwrapOptions& options, UnwrapResult& result, PieceLayouts layouts,
                   double give_up_l2 = 0, const std::function<void()>& on_last_started = {},
                   bool shapes = false, BuiltPieces* built = nullptr) {
  std::vector<Chart> charts = build_charts(pieces, dopt, t_start, options, result.report, layouts,
                                           give_up_l2, on_last_started);
  for (const Chart& c : charts)
    if (c.abandoned) return false;
  pack_valid(mesh, pieces, std::move(charts), dopt, padding, t_start, options, result, layouts,
             shapes, built);
  return true;
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

/// Copies the phase times of \p from (they add up over the attempts of one unwrap()) into \p to.
void copy_phase_times(const UnwrapReport& from, UnwrapReport& to) {
  to.time_cut = from.time_cut;
  to.time_segment = from.time_segment;
  to.time_floater = from.time_floater;
  to.time_yoshizawa = from.time_yoshizawa;
  to.time_augment = from.time_augment;
  to.time_layouts = from.time_layouts;
  to.time_pack = from.time_pack;
}

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

/// Adds the phase times of \p from to \p to.
void add_phase_times(const UnwrapReport& from, UnwrapReport& to) {
  to.time_cut += from.time_cut;
  to.time_segment += from.time_segment;
  to.time_floater += from.time_floater;
  to.time_yoshizawa += from.time_yoshizawa;
  to.time_augment += from.time_augment;
  to.time_layouts += from.time_layouts;
  to.time_pack += from.time_pack;
}

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

/// Builds the layout of \p pieces as a candidate and keeps it in \p result when its effective
/// texel share is higher, or when \p result has no layout yet (the phase times add up either way).
/// \p shapes as in assemble(). \p components > 0: compared by scan_prefers() instead.
void keep_better_layout(const TriMesh& mesh, const std::vector<Component>& pieces,
                        const DiskParamOptions& dopt, double gutter, Clock::time_point t_start,
                        const UnwrapOptions& options, PieceLayouts layouts, UnwrapResult& result,
                        bool shapes = false, size_t components = 0) {
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

/// Pieces of a few large folded faces are split down to 8 faces when split_pays() says so; its
/// estimate is rough for so few faces, so small meshes also try the split down to 32 faces.
constexpr int kFineProbeFaces = 4, kCoarseProbeFaces = 16;

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

/// scan_pieces(), its time added to \p rep.time_segment.
std::vector<Component> timed_scan_pieces(const std::vector<Component>& comps,
                                         const DiskParamOptions& dopt, double gutter,
                                         const UnwrapOptions& options, double halving_weight,
                                         UnwrapReport& rep, int min_probe_faces = kFineProbeFaces) {
  const auto t0 = Clock::now();
  std::vector<Component> pieces =
      scan_pieces(comps, dopt, gutter, options, halving_weight, min_probe_faces);
  rep.time_segment += seconds_since(t0);
  return pieces;
}

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

/// ChartMode::Auto on a mesh with more components than max_charts / 2: the charts of
/// scan_pieces() with planar charts and free-boundary layouts (scan_planar_angle,
/// scan_free_boundary), and, when either is on, also those of the top-down segmentation alone (with
/// the free-boundary layouts when scan_top_down_free_layouts); on meshes of at most
/// scan_single_max_faces faces also its split down to 32 faces and one chart per component. The
/// layout kept is the first by scan_prefers(): one chart per component when that reaches
/// min_texel_share, otherwise the highest effective texel share.
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
