// density-flow on multi-chart layouts (atlas_flow.h): re-packing by density, one flow per chart
// rectangle, and the end-to-end gain on a many-chart layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <string_view>
#include <vector>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/atlas_flow.h"
#include "adaptex/adapt/session.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"

namespace adaptex {
namespace {

/// Four boxes in the quadrants; the density is `hot` in the first box and 1 elsewhere.
struct FourBoxes {
  std::vector<UvRect> boxes{{Vec2(0.05, 0.05), Vec2(0.45, 0.35)},
                            {Vec2(0.55, 0.05), Vec2(0.95, 0.45)},
                            {Vec2(0.05, 0.55), Vec2(0.30, 0.95)},
                            {Vec2(0.55, 0.55), Vec2(0.95, 0.95)}};
  ImageF density;
  explicit FourBoxes(float hot, int L = 64) : density(L, L, 1.0f) {
    for (int j = 0; j < L; ++j)
      for (int i = 0; i < L; ++i) {
        const double u = (i + 0.5) / L, v = (j + 0.5) / L;
        if (u > 0.02 && u < 0.48 && v > 0.02 && v < 0.38) density.at(i, j) = hot;
      }
  }
};

TEST(AtlasFlow, BoxesAndGapsOfALayout) {
  const FourBoxes f(1.0f);
  EXPECT_NEAR(smallest_box_gap(f.boxes), 0.1, 1e-12);
  std::vector<UvRect> overlapping = f.boxes;
  overlapping[1].lo.x() = 0.40;  // now overlaps box 0 on both axes
  EXPECT_LT(smallest_box_gap(overlapping), 0.0);

  const TriMesh mesh = shapes::two_components();
  const Parameterization p = unwrap(mesh).param;
  ASSERT_GE(p.num_charts, 2);
  const std::vector<UvRect> boxes = chart_boxes(p);
  ASSERT_EQ(static_cast<int>(boxes.size()), p.num_charts);
  for (size_t k = 0; k < p.uv_faces.size(); ++k)
    for (int w : p.uv_faces[k]) {
      const UvRect& b = boxes[p.face_chart[k]];
      EXPECT_TRUE(p.uv[w].x() >= b.lo.x() && p.uv[w].x() <= b.hi.x() && p.uv[w].y() >= b.lo.y() && p.uv[w].y() <= b.hi.y());
    }
  EXPECT_GT(smallest_box_gap(boxes), 0.0);
}

TEST(AtlasFlow, RepackSizesChartsByTheirShareOfTheDensity) {
  for (float hot : {1.0f, 9.0f}) {
    const FourBoxes f(hot);
    ChartRepackOptions o;
    o.padding = 0.01;
    const std::vector<ChartMove> m = repack_charts_by_density(f.boxes, f.density, o);
    ASSERT_EQ(m.size(), 4u);
    for (size_t c = 0; c < m.size(); ++c) {
      const UvRect d = m[c].dst();
      EXPECT_GE(d.lo.minCoeff(), o.padding - 1e-12);
      EXPECT_LE(d.hi.maxCoeff(), 1 - o.padding + 1e-12);
      // Aspect kept: a similarity.
      EXPECT_NEAR(d.size().x() / d.size().y(), f.boxes[c].size().x() / f.boxes[c].size().y(), 1e-9);
      for (size_t e = c + 1; e < m.size(); ++e)
        EXPECT_GE(smallest_box_gap({d, m[e].dst()}), o.padding - 1e-12) << c << " " << e;
    }
    // New area ∝ ∫ρ: box 0 holds `hot` times the density of the others per unit area.
    const double ratio = (m[0].dst().area() / f.boxes[0].area()) / (m[1].dst().area() / f.boxes[1].area());
    EXPECT_NEAR(ratio, hot, 0.1 * hot) << "hot " << hot;
  }
}

// allocate_charts_by_error(): the candidate with the least predicted error wins, and it is a valid
// packing. Paint only in the hot box: its chart must grow relative to the others (its cells' error
// falls as its scale rises). Paint evenly in all boxes: resizing buys nothing and loses packing
// area, so no candidate beats keeping the charts where they are by a resize toward one chart.
TEST(AtlasFlow, ErrorModelChoosesHowStronglyChartsAreResized) {
  const FourBoxes f(9.0f);
  const int L = f.density.width;
  ChartRepackOptions o;
  o.padding = 0.01;
  ImageF error(L, L, 0.0f), exponent(L, L, 0.0f), even(L, L, 1e-3f), ones(L, L, 1.0f);
  for (int j = 0; j < L; ++j)
    for (int i = 0; i < L; ++i)
      if (f.density.at(i, j) > 1) error.at(i, j) = 1e-3f, exponent.at(i, j) = 1.0f;
  double gamma = -2;
  const std::vector<ChartMove> m = allocate_charts_by_error(f.boxes, f.density, error, exponent, o, &gamma);
  ASSERT_EQ(m.size(), 4u);
  // One of the candidates, and a resize toward the painted chart (γ > 0), not "stay" (−1) or γ = 0.
  EXPECT_TRUE(gamma == 1.0 || gamma == 0.75 || gamma == 0.5 || gamma == 0.25) << gamma;
  for (size_t c = 0; c < m.size(); ++c) {
    const UvRect d = m[c].dst();
    EXPECT_GE(d.lo.minCoeff(), o.padding - 1e-12);
    EXPECT_LE(d.hi.maxCoeff(), 1 - o.padding + 1e-12);
    for (size_t e = c + 1; e < m.size(); ++e) EXPECT_GE(smallest_box_gap({d, m[e].dst()}), o.padding - 1e-12);
  }
  const double chosen = predicted_chart_error(m, f.density, error, exponent, o);
  const double full = predicted_chart_error(repack_charts_by_density(f.boxes, f.density, o), f.density, error, exponent, o);
  std::vector<ChartMove> stay(4);
  for (size_t c = 0; c < 4; ++c) stay[c].src = f.boxes[c], stay[c].dst_lo = f.boxes[c].lo;
  const double kept = predicted_chart_error(stay, f.density, error, exponent, o);
  EXPECT_LE(chosen, full);
  EXPECT_LE(chosen, kept);
  EXPECT_LT(chosen, kept * 0.9);  // the hot chart's error falls by growing it
  EXPECT_GT(m[0].scale, 1.2 * m[1].scale);
  // The same error everywhere (density 1): the full share is the identity of sizes, and the
  // winner's predicted error is no worse than the charts left in place.
  double g2 = -2;
  const std::vector<ChartMove> m2 = allocate_charts_by_error(f.boxes, ones, even, ones, o, &g2);
  std::vector<ChartMove> stay2 = stay;
  EXPECT_LE(predicted_chart_error(m2, ones, even, ones, o), predicted_chart_error(stay2, ones, even, ones, o));
  EXPECT_THROW(allocate_charts_by_error(f.boxes, f.density, ImageF(L / 2, L / 2, 0.0f), exponent, o), InvalidInputError);
  // A padding wider than the boxes' own gaps (0.1) and side margins (0.05): leaving the charts in
  // place would break it, so whatever wins is a re-packing with that padding.
  ChartRepackOptions wide = o;
  wide.padding = 0.12;
  double g3 = -2;
  const std::vector<ChartMove> m3 = allocate_charts_by_error(f.boxes, ones, even, ones, wide, &g3);
  EXPECT_GE(g3, 0.0);
  for (size_t c = 0; c < m3.size(); ++c) {
    EXPECT_GE(m3[c].dst().lo.minCoeff(), wide.padding - 1e-12);
    EXPECT_LE(m3[c].dst().hi.maxCoeff(), 1 - wide.padding + 1e-12);
    for (size_t e = c + 1; e < m3.size(); ++e) EXPECT_GE(smallest_box_gap({m3[c].dst(), m3[e].dst()}), wide.padding - 1e-12);
  }
}

TEST(AtlasFlow, ChartMovesAndRectangleWarpsKeepEveryChartInItsRectangle) {
  const FourBoxes f(9.0f);
  const std::vector<ChartMove> m = repack_charts_by_density(f.boxes, f.density);
  // The locator finds the chart of a point by position and moves it like the chart's move.
  const ChartMoveLocator loc(m);
  for (size_t c = 0; c < m.size(); ++c) {
    const Vec2 p = 0.3 * f.boxes[c].lo + 0.7 * f.boxes[c].hi;
    EXPECT_LT((loc.apply(p) - m[c].apply(p)).norm(), 1e-12);
  }
  EXPECT_EQ(loc.apply(Vec2(0.5, 0.5)), Vec2(0.5, 0.5));  // in no box: unchanged

  // A non-uniform density inside the hot chart: its warp is not the identity, maps its rectangle
  // onto itself (sides slide, corners stay) and leaves every point outside it alone.
  ImageF d(64, 64, 1.0f);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 16; ++i) d.at(i, j) = 12.0f;
  DensityFlowOptions fo;
  fo.cells = 64;
  DensityFlowStats st;
  const std::vector<GridWarp> w = chart_flow_warps(m, d, fo, 8, &st);
  ASSERT_EQ(w.size(), m.size());
  EXPECT_EQ(st.inverted_cells, 0);
  const UvRect r = m[0].dst();
  EXPECT_LT((w[0].lo - r.lo).norm() + (w[0].hi - r.hi).norm(), 1e-15);
  EXPECT_GT(w[0].max_displacement(), 0.01 * r.size().minCoeff());
  for (const Vec2& corner : {r.lo, r.hi, Vec2(r.lo.x(), r.hi.y()), Vec2(r.hi.x(), r.lo.y())})
    EXPECT_LT((w[0].apply(corner) - corner).norm(), 1e-9);
  for (int k = 0; k <= 20; ++k) {
    const double t = k / 20.0;
    const Vec2 bottom = w[0].apply(Vec2(r.lo.x() + t * r.size().x(), r.lo.y()));
    EXPECT_NEAR(bottom.y(), r.lo.y(), 1e-9);
    for (int l = 0; l <= 20; ++l) {
      const Vec2 q = w[0].apply(r.lo + Vec2(t * r.size().x(), l / 20.0 * r.size().y()));
      EXPECT_TRUE(q.x() >= r.lo.x() - 1e-12 && q.x() <= r.hi.x() + 1e-12 && q.y() >= r.lo.y() - 1e-12 &&
                  q.y() <= r.hi.y() + 1e-12);
    }
  }
  const Vec2 outside = m[1].dst().lo + 0.5 * m[1].dst().size();
  EXPECT_EQ(w[0].apply(outside), outside);
  EXPECT_EQ(w[0].blended(0.5).lo, w[0].lo);
}

/// k x k spheres side by side: k² components, so `--charts single` gives k² charts whatever the
/// automatic segmentation would choose.
TriMesh sphere_grid(int k) {
  TriMesh out;
  const TriMesh s = shapes::sphere(24, 12);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      const int base = out.num_vertices();
      for (const Vec3& p : s.positions) out.positions.push_back(p + Vec3(3.0 * a, 3.0 * b, 0));
      for (const Face& f : s.faces) out.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
    }
  return out;
}

/// Thin hard lines in one small region of a 9-component mesh laid out as 9 charts.
struct ManyChartLines {
  TriMesh mesh = sphere_grid(3);
  Parameterization param = [this] {
    UnwrapOptions uo;
    uo.charts = ChartMode::Single;
    return unwrap(mesh, uo).param;
  }();
  StrokeFile strokes = [this] {
    GenerateOptions go;
    go.kind = StrokeKind::Lines;
    go.count = 40;
    go.seed = 7;
    StrokeFile f = generate_strokes(mesh, go);
    for (auto& s : f.strokes) s.radius = 0.003 * bounding_box(mesh).diagonal();
    return f;
  }();
  int N = 128;
  EvalOptions eo = [] {
    EvalOptions o;
    o.samples = 200000;
    return o;
  }();
  /// The strokes painted on the fixed layout at N².
  Painter painted() const {
    PainterOptions po;
    po.width = po.height = N;
    Painter p(mesh, param, po, strokes.background);
    p.paint_all(strokes);
    return p;
  }
  double psnr_none = [this] { return evaluate_texture(mesh, param, painted().texture(), strokes, eo).psnr; }();
  std::unique_ptr<PaintSession> run(const AdaptOptions& adapt) const {
    PaintSessionOptions so;
    so.texture_size = N;
    so.adapt = adapt;
    auto s = std::make_unique<PaintSession>(mesh, param, so, strokes.background);
    for (const auto& st : strokes.strokes) s->add_stroke(st);
    s->finish();
    return s;
  }
};

TEST(AtlasFlow, ManyChartLayoutGainsOverTheFixedLayout) {
  // One flow per re-packed chart, unpolished, at both lattice sizes: a clear gain over the fixed
  // layout (measured: none 23.95 dB, per chart 29.53 / 29.44 dB at 128 / 256 cells), and a valid layout.
  const ManyChartLines c;
  ASSERT_EQ(c.param.num_charts, 9);
  for (int cells : {128, 256}) {
    AdaptOptions ao;
    ao.mode = AdaptMode::DensityFlow;
    ao.density_flow.flow.cells = cells;
    ao.density_flow.polish.sweeps = 0;
    const auto s = c.run(ao);
    ASSERT_EQ(s->reports().size(), 1u);
    ASSERT_TRUE(s->last_result() && s->last_result()->warp);
    EXPECT_EQ(static_cast<int>(s->last_result()->warp->chart_moves().size()), c.param.num_charts);
    const double psnr = evaluate_texture(s->mesh(), s->param(), s->texture(), c.strokes, c.eo).psnr;
    const StretchStats st = measure_stretch(s->mesh(), s->param());
    EXPECT_EQ(st.flipped, 0);
    EXPECT_EQ(st.degenerate, 0);
    EXPECT_EQ(count_overlapping_triangles(s->param()), 0);
    std::printf("9-sphere lines N=%d (%d charts), %d-cell flow: none %.2f dB, density-flow per chart %.2f dB\n", c.N,
                c.param.num_charts, cells, c.psnr_none, psnr);
    EXPECT_GT(psnr, c.psnr_none + 3.0);
  }
}

TEST(AtlasFlow, EveryChartEndsInsideItsNewRectangle) {
  const ManyChartLines c;
  Painter p = c.painted();
  AdaptOptions ao;
  ao.mode = AdaptMode::DensityFlow;
  const AdaptResult r = adapt_parameterization(c.mesh, c.param, p.texture(), p.texel_map(), ao, &c.strokes);
  ASSERT_TRUE(r.warp);
  ASSERT_EQ(static_cast<int>(r.warp->chart_moves().size()), c.param.num_charts);
  EXPECT_EQ(r.report.flow_inverted_cells, 0);
  const Parameterization& q = r.param;
  const std::vector<UvRect> after = chart_boxes(q);
  for (int ch = 0; ch < q.num_charts; ++ch) {
    const UvRect d = r.warp->chart_moves()[ch].dst();
    EXPECT_GE(after[ch].lo.x(), d.lo.x() - 1e-9);
    EXPECT_GE(after[ch].lo.y(), d.lo.y() - 1e-9);
    EXPECT_LE(after[ch].hi.x(), d.hi.x() + 1e-9);
    EXPECT_LE(after[ch].hi.y(), d.hi.y() + 1e-9);
  }
  EXPECT_GT(smallest_box_gap(after), 0.0);
  // The charts with the paint grew: the chart holding the most stroke samples got more UV area.
  const std::vector<UvRect> before = chart_boxes(c.param);
  double grow_max = 0;
  for (int ch = 0; ch < q.num_charts; ++ch) grow_max = std::max(grow_max, after[ch].area() / std::max(before[ch].area(), 1e-30));
  EXPECT_GT(grow_max, 2.0);
}

TEST(AtlasFlow, ChartLatticesArePolishedInParallelWithTheSameResultAndProgress) {
  // The warp method polishes the charts' lattices in parallel (warp_density_flow.cpp): the layout must
  // be the one polishing them in turn gives, and the progress callback is called by one thread at a
  // time, with fractions that never go back, and can still cancel.
  const ManyChartLines c;
  Painter p = c.painted();
  std::vector<double> fractions;
  std::atomic<int> inside{0};
  bool overlapped = false;
  AdaptOptions ao;
  ao.mode = AdaptMode::DensityFlow;
  ao.progress = [&](std::string_view phase, double f) {
    if (phase != "polish") return true;
    if (inside.fetch_add(1) != 0) overlapped = true;
    fractions.push_back(f);
    inside.fetch_sub(1);
    return true;
  };
  const AdaptResult a = adapt_parameterization(c.mesh, c.param, p.texture(), p.texel_map(), ao, &c.strokes);
  ASSERT_EQ(static_cast<int>(a.warp->lattices().size()), c.param.num_charts);
  EXPECT_FALSE(overlapped);
  ASSERT_GE(fractions.size(), 2u);
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_GT(a.report.polish_sweeps, 0);
  ao.progress = nullptr;
  ao.density_flow.polish.parallel = false;
  const AdaptResult b = adapt_parameterization(c.mesh, c.param, p.texture(), p.texel_map(), ao, &c.strokes);
  ASSERT_EQ(a.warp->lattices().size(), b.warp->lattices().size());
  for (size_t g = 0; g < a.warp->lattices().size(); ++g)
    EXPECT_EQ(a.warp->lattices()[g].points, b.warp->lattices()[g].points) << "chart " << g;
  ASSERT_EQ(a.param.uv.size(), b.param.uv.size());
  for (size_t k = 0; k < a.param.uv.size(); ++k) ASSERT_EQ(a.param.uv[k], b.param.uv[k]) << k;
  EXPECT_EQ(a.report.polish_error_after, b.report.polish_error_after);
  int calls = 0;
  ao.progress = [&](std::string_view phase, double) { return phase != "polish" || ++calls < 3; };
  EXPECT_THROW(adapt_parameterization(c.mesh, c.param, p.texture(), p.texel_map(), ao, &c.strokes), CancelledError);
}

TEST(AtlasFlow, ASharpDensityLeavesNoFlipDegenerateOrOverlap) {
  // A 1-cell blur (a per-dot density that tangles the lattice), on code-built closed surfaces of genus
  // 1 and 2.
  for (int shape = 0; shape < 2; ++shape) {
    const TriMesh mesh = shape == 0 ? shapes::torus(48, 24) : shapes::double_torus(32);
    const Parameterization param = unwrap(mesh).param;
    GenerateOptions go;
    go.kind = StrokeKind::Dots;
    go.seed = 5;
    const StrokeFile strokes = generate_strokes(mesh, go);
    const int N = 256;
    PainterOptions po;
    po.width = po.height = N;
    Painter p(mesh, param, po, strokes.background);
    p.paint_all(strokes);
    AdaptOptions ao;
    ao.mode = AdaptMode::DensityFlow;
    ao.density_flow.density.blur_cells = 1.0;
    const AdaptResult r = adapt_parameterization(mesh, param, p.texture(), p.texel_map(), ao, &strokes);
    ASSERT_TRUE(r.warp) << shape;
    const TriMesh& out_mesh = r.refined_mesh ? *r.refined_mesh : mesh;
    const StretchStats st = measure_stretch(out_mesh, r.param);
    EXPECT_EQ(st.flipped, 0) << shape;
    EXPECT_EQ(st.degenerate, 0) << shape;
    EXPECT_EQ(count_overlapping_triangles(r.param), 0) << shape;
    EXPECT_GT(r.report.predicted_gain_db, 1.0) << shape;
    for (const Vec2& uv : r.param.uv) {
      EXPECT_GE(uv.minCoeff(), 0.0);
      EXPECT_LE(uv.maxCoeff(), 1.0);
    }
    // The remap started from the wedges moved by the warp, and kept most of it (the untangling and
    // local damping touch the wedges of faces the refinement budget leaves too large for the density).
    const Parameterization start = r.start_layout(param);
    const Parameterization warped = r.warp->warp_layout(start);
    ASSERT_EQ(start.uv.size(), warped.uv.size());
    for (size_t w = 0; w < start.uv.size(); w += 97) EXPECT_EQ(warped.uv[w], r.warp->map(start.uv[w]));
    EXPECT_GT(r.report.damping, 0.9) << shape;
    double moved = 0;
    for (size_t w = 0; w < start.uv.size(); ++w) moved = std::max(moved, (r.param.uv[w] - start.uv[w]).norm());
    EXPECT_GT(moved, 0.01) << shape;
    // The torus unwraps to one chart (one flow over the square), the genus-2 surface to several (one
    // flow per re-packed chart rectangle): both paths of the method.
    EXPECT_EQ(param.num_charts > 1, shape == 1);
    EXPECT_EQ(r.warp->chart_moves().empty(), param.num_charts == 1);
    // Wedges on the square's sides stay on them.
    for (size_t w = 0; w < start.uv.size(); ++w)
      for (int axis = 0; axis < 2; ++axis)
        for (double side : {0.0, 1.0})
          EXPECT_TRUE(start.uv[w][axis] != side || r.param.uv[w][axis] == side) << shape << " wedge " << w;
    // Charts stay in their disjoint rectangles, with the gutter between them.
    const std::vector<UvRect> after = chart_boxes(r.param);
    for (size_t ch = 0; ch < r.warp->chart_moves().size(); ++ch) {
      const UvRect d = r.warp->chart_moves()[ch].dst();
      EXPECT_GE(after[ch].lo.x(), d.lo.x() - 1e-9);
      EXPECT_GE(after[ch].lo.y(), d.lo.y() - 1e-9);
      EXPECT_LE(after[ch].hi.x(), d.hi.x() + 1e-9);
      EXPECT_LE(after[ch].hi.y(), d.hi.y() + 1e-9);
    }
    EXPECT_GE(smallest_box_gap(after), ao.density_flow.chart_gutter_texels / N - 1e-9) << shape;
  }
}

}  // namespace
}  // namespace adaptex
