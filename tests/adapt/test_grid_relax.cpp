// Tests of §3.6 (L_s²), §3.7.1 (grid relaxation), §3.7.2 (remap with the no-flip guarantee).
#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>
#include <limits>
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/adapt/importance.h"
#include "adaptex/adapt/ls2.h"
#include "adaptex/adapt/relax.h"
#include "adaptex/adapt/remap.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"

namespace adaptex {
namespace {

double cell_area(const GridWarp& g, int i, int j) {
  const Vec2 a = g.at(i, j), b = g.at(i + 1, j), c = g.at(i + 1, j + 1), d = g.at(i, j + 1);
  auto cross = [](const Vec2& p, const Vec2& q) { return p.x() * q.y() - p.y() * q.x(); };
  return 0.5 * (cross(a, b) + cross(b, c) + cross(c, d) + cross(d, a));
}

// Weight field 1 everywhere except a disc of radius r around (cx, cy) with weight w_in.
ImageF blob_field(int res, double cx, double cy, double r, float w_in, float w_out = 1.0f) {
  ImageF f(res, res, w_out);
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i) {
      const double x = (i + 0.5) / res - cx, y = (j + 0.5) / res - cy;
      if (x * x + y * y < r * r) f.at(i, j) = w_in;
    }
  return f;
}

TEST(Ls2, FollowsThesisFormulaAndStaysStrictlyPositive) {
  ImageF e(4, 1, 0.0f), s(4, 1, 0.0f);
  e.data = {0.0f, 0.5f, 1.0f, 1.0f};
  s.data = {0.3f, 0.2f, 1.0f, 0.0f};
  Ls2Options o;
  o.alpha = 0.5;
  o.beta = 0.9;
  o.min_weight = 0.05;
  const ImageF w = compute_ls2(e, s, o);
  EXPECT_NEAR(w.data[0], 1.0 - 0.3, 1e-6);                 // E_h = 0: 1 - L2
  EXPECT_NEAR(w.data[1], 1.0 - (0.5 * 0.2 + 0.9 * 0.5), 1e-6);  // 1 - (αL2 + βE)
  EXPECT_FLOAT_EQ(w.data[2], 0.05f);                       // negative -> clamped to min_weight
  EXPECT_NEAR(w.data[3], 0.1, 1e-6);
  for (float x : w.data) EXPECT_GT(x, 0.0f);
  o.min_weight = 0;
  EXPECT_THROW(compute_ls2(e, s, o), InvalidInputError);
  o.min_weight = 0.05;
  o.beta = -1;
  EXPECT_THROW(compute_ls2(e, s, o), InvalidInputError);
}

TEST(Ls2, PoolingKeepsThinLinesVisibleToCoarseGrids) {
  ImageF m(256, 256, 1.0f);
  for (int j = 0; j < 256; ++j) m.at(100, j) = 0.1f;  // one-texel line
  const ImageF mean = pool_for_grid(m, 16, PoolMode::Mean);
  const ImageF mn = pool_for_grid(m, 16, PoolMode::Min);
  EXPECT_EQ(mean.width, 32);
  // Pooled cell containing column 100 (100 / 8 = 12): mean dips by 0.9/8, min sees the full line.
  EXPECT_NEAR(mean.at(12, 5), 1.0 - 0.9 / 8, 1e-5);
  EXPECT_NEAR(mn.at(12, 5), 0.1, 1e-6);
  EXPECT_NEAR(mean.at(3, 5), 1.0, 1e-6);
}

TEST(Importance, SobelMagnitudeNormalizedAndMaskedAtChartBorders) {
  ImageRGBA8 tex(16, 16, {255, 255, 255, 255});
  for (int j = 0; j < 16; ++j)
    for (int i = 8; i < 16; ++i) {
      auto* p = tex.texel(i, j);
      p[0] = p[1] = p[2] = 0;
    }
  const ImageF e = compute_importance(tex, nullptr);
  EXPECT_NEAR(e.at(7, 5), 1.0, 1e-5);  // full-contrast step edge = 1
  EXPECT_NEAR(e.at(8, 5), 1.0, 1e-5);
  EXPECT_NEAR(e.at(3, 5), 0.0, 1e-6);
  // Mask: columns >= 8 are outside every chart (black padding): no importance at the border.
  TexelMap map;
  map.width = map.height = 16;
  map.face.assign(256, -1);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 8; ++i) {
      map.face[j * 16 + i] = 0;
      map.inside.push_back(j * 16 + i);
    }
  const ImageF em = compute_importance(tex, &map);
  for (float x : em.data) EXPECT_EQ(x, 0.0f);
}

TEST(Relax, ConstantWeightsKeepTheGridUniform) {
  GridWarp g = GridWarp::uniform(32);
  const RelaxStats st = relax_grid(g, ImageF(64, 64, 0.7f));
  EXPECT_TRUE(st.converged);
  EXPECT_LT(g.max_displacement(), 1e-9);
  RelaxOptions four;
  four.ring = GridRing::Four;
  relax_grid(g, ImageF(64, 64, 0.3f), four);
  EXPECT_LT(g.max_displacement(), 1e-9);
}

TEST(Relax, LowWeightBlobGrowsItsCells) {
  for (GridRing ring : {GridRing::Four, GridRing::Eight}) {
    const ImageF field = blob_field(128, 0.5, 0.5, 0.15, 0.1f);
    GridWarp g = GridWarp::uniform(16);
    RelaxOptions o;
    o.ring = ring;
    o.max_iterations = 2000;
    o.epsilon = 1e-7;
    relax_grid(g, field, o);
    // The four cells around the blob centre (uniform area 1/256 each) grow.
    const double centre = (cell_area(g, 7, 7) + cell_area(g, 8, 7) + cell_area(g, 7, 8) + cell_area(g, 8, 8)) / 4;
    EXPECT_GT(centre, 1.5 / 256.0) << (ring == GridRing::Four ? "4-ring" : "8-ring");
    const double corner = cell_area(g, 0, 0);
    EXPECT_LT(corner, 1.0 / 256.0);
    // Inverted weighting (blob of high weight) must do the opposite.
    GridWarp h = GridWarp::uniform(16);
    relax_grid(h, blob_field(128, 0.5, 0.5, 0.15, 1.0f, 0.1f), o);
    const double centre_inv = (cell_area(h, 7, 7) + cell_area(h, 8, 7) + cell_area(h, 7, 8) + cell_area(h, 8, 8)) / 4;
    EXPECT_LT(centre_inv, 1.0 / 256.0);
    // Every cell stays positively oriented.
    for (int j = 0; j < 16; ++j)
      for (int i = 0; i < 16; ++i) EXPECT_GT(cell_area(g, i, j), 0.0);
  }
}

TEST(Relax, SlidingBoundaryStaysOnTheSidesInOrder) {
  const ImageF field = blob_field(128, 0.5, 0.03, 0.12, 0.05f);  // detail touching the bottom side
  GridWarp fixed = GridWarp::uniform(16), slid = GridWarp::uniform(16);
  RelaxOptions o;
  o.max_iterations = 500;
  relax_grid(fixed, field, o);
  o.slide_boundary = true;
  relax_grid(slid, field, o);
  for (int i = 0; i <= 16; ++i) {
    EXPECT_EQ(slid.at(i, 0).y(), 0.0);
    EXPECT_EQ(slid.at(i, 16).y(), 1.0);
    EXPECT_EQ(slid.at(0, i).x(), 0.0);
    EXPECT_EQ(slid.at(16, i).x(), 1.0);
    if (i > 0) {
      EXPECT_GT(slid.at(i, 0).x(), slid.at(i - 1, 0).x());
      EXPECT_GT(slid.at(0, i).y(), slid.at(0, i - 1).y());
    }
  }
  EXPECT_EQ(slid.at(0, 0), Vec2(0, 0));
  EXPECT_EQ(slid.at(16, 16), Vec2(1, 1));
  // The bottom-centre cells grow more when their side points can move apart.
  EXPECT_GT(cell_area(slid, 7, 0) + cell_area(slid, 8, 0), cell_area(fixed, 7, 0) + cell_area(fixed, 8, 0));
}

TEST(Relax, ParallelAndSerialGiveIdenticalResults) {
  const ImageF field = blob_field(256, 0.3, 0.6, 0.1, 0.05f);
  GridWarp a = GridWarp::uniform(128), b = GridWarp::uniform(128);
  RelaxOptions o;
  o.max_iterations = 30;
  o.parallel = true;
  relax_grid(a, field, o);
  o.parallel = false;
  relax_grid(b, field, o);
  for (size_t k = 0; k < a.points.size(); ++k) EXPECT_EQ(a.points[k], b.points[k]);
}

TEST(Grid, ApplyIsIdentityForUniformAndPullBackInvertsAWarp) {
  GridWarp g = GridWarp::uniform(8);
  EXPECT_LT((g.apply(Vec2(0.33, 0.71)) - Vec2(0.33, 0.71)).norm(), 1e-12);
  relax_grid(g, blob_field(64, 0.4, 0.4, 0.2, 0.1f), RelaxOptions{});
  ASSERT_GT(g.max_displacement(), 0.01);
  // Field = x coordinate; pulled back through g, at q it must equal the x of g^{-1}(q).
  ImageF fx(256, 256);
  for (int j = 0; j < 256; ++j)
    for (int i = 0; i < 256; ++i) fx.at(i, j) = static_cast<float>((i + 0.5) / 256);
  const ImageF pb = pull_back_field(fx, g, 64);
  for (double x : {0.2, 0.45, 0.8})
    for (double y : {0.3, 0.6}) {
      const Vec2 q = g.apply(Vec2(x, y));
      const int i = std::clamp(static_cast<int>(q.x() * 64), 0, 63), j = std::clamp(static_cast<int>(q.y() * 64), 0, 63);
      EXPECT_NEAR(pb.at(i, j), x, 0.03);
    }
}

/// A warp of \p n cells on [lo, hi] whose points are moved by a smooth swirl (no fold).
GridWarp swirl_warp(int n, const Vec2& lo, const Vec2& hi, double amount) {
  GridWarp g = GridWarp::uniform(n);
  g.lo = lo, g.hi = hi;
  for (int j = 1; j < n; ++j)
    for (int i = 1; i < n; ++i) {
      const double x = double(i) / n, y = double(j) / n;
      g.at(i, j) += amount / n * Vec2(std::sin(6.3 * y), std::cos(6.3 * x));
    }
  return g;
}

TEST(Grid, AChainOfWarpsOnApartRectanglesIsTheWarpsInTurn) {
  // 3 x 3 chart rectangles with gaps, as a re-packed atlas: looked up in buckets, and the same values,
  // bit for bit, as applying every warp in turn, inside, on and just outside the rectangles.
  std::vector<GridWarp> grids;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      grids.push_back(swirl_warp(6 + a + b, Vec2(0.02 + 0.33 * a, 0.01 + 0.33 * b), Vec2(0.3 + 0.33 * a, 0.31 + 0.33 * b), 0.4));
  std::vector<const GridWarp*> ptrs;
  for (const GridWarp& g : grids) ptrs.push_back(&g);
  const WarpChain chain(ptrs);
  EXPECT_TRUE(chain.bucketed());
  auto in_turn = [&](const Vec2& p) {
    Vec2 q = p;
    for (const GridWarp* w : ptrs) q = w->apply(q);
    return q;
  };
  std::vector<Vec2> probes;
  for (int j = -2; j <= 402; ++j)
    for (int i = -2; i <= 402; ++i) probes.push_back(Vec2(i / 400.0, j / 400.0));
  for (const GridWarp& g : grids)
    for (double d : {-1e-12, -5e-13, 0.0, 5e-13, 1e-12, 2e-12}) {
      probes.push_back(Vec2(g.lo.x() + d, 0.5 * (g.lo.y() + g.hi.y())));
      probes.push_back(Vec2(g.hi.x() + d, g.hi.y() + d));
    }
  int moved = 0;
  for (const Vec2& p : probes) {
    const Vec2 a = chain.apply(p), b = in_turn(p);
    ASSERT_EQ(a, b) << p.transpose();
    moved += a != p;
  }
  EXPECT_GT(moved, 10000);
  // Far outside the square (a bucket index must not overflow): unchanged, as in turn.
  for (const Vec2& far : {Vec2(1e300, -1e300), Vec2(-3e9, 0.5), Vec2(0.5, 4e18)})
    EXPECT_EQ(chain.apply(far), in_turn(far));
  // A rectangle that is not finite: in turn.
  std::vector<const GridWarp*> with_bad = ptrs;
  GridWarp bad = grids[0];
  bad.lo = Vec2(5, 5), bad.hi = Vec2(std::numeric_limits<double>::infinity(), 6);
  with_bad.push_back(&bad);
  EXPECT_FALSE(WarpChain(with_bad).bucketed());
  // Touching or overlapping rectangles, and a warp of the whole square (the two-stage method's
  // composition), are applied in turn.
  grids[1].lo.y() = grids[0].hi.y();
  EXPECT_FALSE(WarpChain(ptrs).bucketed());
  const GridWarp whole = swirl_warp(8, Vec2(0, 0), Vec2(1, 1), 0.4), whole2 = swirl_warp(5, Vec2(0, 0), Vec2(1, 1), -0.3);
  const WarpChain two({&whole, &whole2});
  EXPECT_FALSE(two.bucketed());
  EXPECT_EQ(two.apply(Vec2(0.4, 0.6)), whole2.apply(whole.apply(Vec2(0.4, 0.6))));
}

Parameterization plane_param(const TriMesh& mesh) {
  Parameterization p;
  const BoundingBox bb = bounding_box(mesh);
  for (const Vec3& v : mesh.positions)
    p.uv.push_back(Vec2((v.x() - bb.min.x()) / (bb.max.x() - bb.min.x()), (v.y() - bb.min.y()) / (bb.max.y() - bb.min.y())));
  p.uv_faces = mesh.faces;
  for (int k = 0; k < mesh.num_vertices(); ++k) p.wedge_vertex.push_back(k);
  p.face_chart.assign(mesh.faces.size(), 0);
  p.num_charts = 1;
  return p;
}

TEST(Remap, AdversarialWarpIsDampedAndNeverFlips) {
  const TriMesh mesh = shapes::plane(40);
  const Parameterization param = plane_param(mesh);
  // A folding warp: interior points pushed past their neighbours.
  GridWarp w = GridWarp::uniform(8);
  w.at(3, 4) = Vec2(0.9, 0.5);
  w.at(5, 4) = Vec2(0.1, 0.5);
  w.at(4, 2) = Vec2(0.5, 0.95);
  const Parameterization raw = remap_parameterization(param, {&w});
  ASSERT_GT(check_remap(param, raw, SafeRemapOptions{}).flipped, 0);  // really adversarial
  const SafeRemapResult r = safe_remap(param, {&w});
  EXPECT_LT(r.mean_damping, 1.0);  // damping happened...
  EXPECT_GT(r.mean_damping, 0.5);  // ...but only locally: most of the warp is kept
  EXPECT_GT(r.locally_damped, 0);
  // Untangling and local damping disabled: the global bisection alone must also give a valid layout.
  SafeRemapOptions global_only;
  global_only.untangle_rounds = 0;
  global_only.max_local_rounds = 0;
  global_only.extended_local_rounds = 0;
  const SafeRemapResult rg = safe_remap(param, {&w}, global_only);
  EXPECT_LT(rg.damping, 1.0);
  EXPECT_TRUE(check_remap(param, rg.param).ok());
  const RemapCheck c = check_remap(param, r.param);
  EXPECT_EQ(c.flipped, 0);
  EXPECT_EQ(c.degenerate, 0);
  EXPECT_EQ(c.overlaps, 0);
  for (const Vec2& uv : r.param.uv) {
    EXPECT_GE(uv.minCoeff(), 0.0);
    EXPECT_LE(uv.maxCoeff(), 1.0);
  }
  // A valid warp is applied in full.
  GridWarp ok = GridWarp::uniform(8);
  relax_grid(ok, blob_field(64, 0.5, 0.5, 0.2, 0.2f));
  const SafeRemapResult r2 = safe_remap(param, {&ok});
  EXPECT_EQ(r2.damping, 1.0);
  EXPECT_EQ(r2.mean_damping, 1.0);
  // The overlap test is skipped only where it is provably unnecessary.
  EXPECT_TRUE(single_chart_on_square(param));
  Parameterization shrunk = param;
  for (Vec2& uv : shrunk.uv) uv = 0.1 * Vec2(1, 1) + 0.8 * uv;
  EXPECT_FALSE(single_chart_on_square(shrunk));
  EXPECT_TRUE(check_remap(param, r2.param).ok());
}


TEST(Remap, AWarpGivenAsALayoutIsTheGridWarpGivenAsPoints) {
  // safe_remap_layout (the warp's result given per wedge, as direct flow advection gives it) is
  // safe_remap on the same positions; blend_layouts damps it.
  const TriMesh mesh = shapes::plane(40);
  const Parameterization param = plane_param(mesh);
  GridWarp w = GridWarp::uniform(8);
  w.at(3, 4) = Vec2(0.9, 0.5);  // folding, so that untangling and damping run
  w.at(5, 4) = Vec2(0.1, 0.5);
  const SafeRemapResult a = safe_remap(param, {&w});
  const SafeRemapResult b = safe_remap_layout(param, remap_parameterization(param, {&w}));
  ASSERT_EQ(a.param.uv.size(), b.param.uv.size());
  for (size_t k = 0; k < a.param.uv.size(); ++k) EXPECT_EQ(a.param.uv[k], b.param.uv[k]);
  EXPECT_EQ(a.mean_damping, b.mean_damping);
  EXPECT_LT(b.mean_damping, 1.0);
  EXPECT_TRUE(check_remap(param, b.param).ok());
  // Blending toward the warped layout is blending the lattice (bilinear in its points).
  const Parameterization full = remap_parameterization(param, {&w});
  const GridWarp half = w.blended(0.5);
  const Parameterization by_grid = remap_parameterization(param, {&half});
  const Parameterization by_layout = blend_layouts(param, full, 0.5);
  for (size_t k = 0; k < param.uv.size(); ++k) EXPECT_NEAR((by_grid.uv[k] - by_layout.uv[k]).norm(), 0.0, 1e-12);
  Parameterization fewer = param;
  fewer.uv.pop_back();
  EXPECT_THROW(blend_layouts(param, fewer, 0.5), InvalidInputError);
  EXPECT_THROW(safe_remap_layout(param, fewer), InvalidInputError);
}

TEST(Remap, UntanglingKeepsMoreOfAWarpThanDamping) {
  const TriMesh mesh = shapes::plane(40);
  const Parameterization param = plane_param(mesh);
  // A smooth warp with one small fold: a lattice point pushed just past its right neighbour.
  GridWarp w = GridWarp::uniform(8);
  relax_grid(w, blob_field(64, 0.5, 0.5, 0.2, 0.2f));
  w.at(4, 4) = w.at(5, 4) + Vec2(0.02, 0.0);
  ASSERT_GT(check_remap(param, remap_parameterization(param, {&w})).flipped, 0);
  SafeRemapOptions off;
  off.untangle_rounds = 0;
  const SafeRemapResult damped = safe_remap(param, {&w}, off);
  const SafeRemapResult untangled = safe_remap(param, {&w});
  EXPECT_TRUE(check_remap(param, damped.param).ok());
  EXPECT_TRUE(check_remap(param, untangled.param).ok());
  std::printf("mean blend kept: damping %.3f, untangling %.3f\n", damped.mean_damping, untangled.mean_damping);
  EXPECT_GT(untangled.mean_damping, damped.mean_damping);
  EXPECT_GT(untangled.mean_damping, 0.9);
  // The rounds as before session 11 (Jacobi: every wedge from the previous round's positions) reach
  // the same: both orders converge to the ring means.
  SafeRemapOptions jacobi;
  jacobi.untangle_in_place = false;
  const SafeRemapResult j = safe_remap(param, {&w}, jacobi);
  EXPECT_TRUE(check_remap(param, j.param).ok());
  EXPECT_GT(j.mean_damping, 0.9);
  EXPECT_NEAR(j.mean_damping, untangled.mean_damping, 0.05);
  // Over-relaxed rounds (SafeRemapOptions::untangle_over_relaxation) untangle the fold as well.
  SafeRemapOptions sor;
  sor.untangle_over_relaxation = 1.5;
  const SafeRemapResult s = safe_remap(param, {&w}, sor);
  EXPECT_TRUE(check_remap(param, s.param).ok());
  EXPECT_GT(s.mean_damping, 0.9);
  // untangle_patience: past untangle_rounds the rounds go on while they make progress (here: while
  // fewer faces fail than 2 rounds before). Stopped after 2 rounds the fold is not untangled and
  // local damping has to take more of the warp.
  SafeRemapOptions one_round;
  one_round.untangle_rounds = 2;
  one_round.untangle_patience = 0;
  SafeRemapOptions patient = one_round;
  patient.untangle_patience = 2;
  const SafeRemapResult stopped = safe_remap(param, {&w}, one_round);
  const SafeRemapResult went_on = safe_remap(param, {&w}, patient);
  EXPECT_TRUE(check_remap(param, stopped.param).ok());
  EXPECT_TRUE(check_remap(param, went_on.param).ok());
  std::printf("mean blend kept: 2 rounds %.4f, with patience %.4f, default %.4f\n", stopped.mean_damping,
              went_on.mean_damping, untangled.mean_damping);
  EXPECT_GT(went_on.mean_damping, stopped.mean_damping);
  EXPECT_NEAR(went_on.mean_damping, untangled.mean_damping, 1e-9);
  for (double bad : {0.0, 2.0, -1.0, std::nan("")}) {
    SafeRemapOptions o;
    o.untangle_over_relaxation = bad;
    EXPECT_THROW(safe_remap(param, {&w}, o), InvalidInputError) << bad;
  }
}

TEST(Remap, AFaceBarelyAboveMinAreaDoesNotCostTheWholeWarp) {
  // A UV triangle whose input area is barely above min_area (a 3-D sliver, or a refined child of
  // one: triceratops' 12-chart layout at 128²) flips under a warp that is not affine across it, and
  // halving its wedges' displacement moves its area by only |edge|·|disp|: after the 24 local rounds
  // it was still flipped, and the remap went on to the global bisection (10 more checks) and to the
  // 100-round attempt (1.3 s of remap there). Snapping the wedges of a face that still fails back to
  // their input UV (SafeRemapOptions::snap_round) settles it in the first attempt.
  const int n = 40;
  const TriMesh mesh = shapes::plane(n);
  Parameterization param = plane_param(mesh);
  SafeRemapOptions o;
  // No untangling (it would move the squashed corner back to its ring's mean; on triceratops the
  // corners sat on a chart border, which untangling never moves): damping alone must settle it.
  o.untangle_rounds = 0;
  // The face nearest the centre, its corner v opposite its longest edge (a, b: a lattice cell's
  // diagonal) squashed onto that edge, 1.5 × min_area of area left.
  int f = 0;
  for (int g = 1; g < mesh.num_faces(); ++g) {
    auto centre = [&](int h) -> Vec2 {
      const Face& t = param.uv_faces[h];
      return (param.uv[t[0]] + param.uv[t[1]] + param.uv[t[2]]) / 3.0 - Vec2(0.5, 0.5);
    };
    if (centre(g).norm() < centre(f).norm()) f = g;
  }
  Face t = param.uv_faces[f];
  while ((param.uv[t[1]] - param.uv[t[2]]).norm() < (param.uv[t[0]] - param.uv[t[1]]).norm() - 1e-12 ||
         (param.uv[t[1]] - param.uv[t[2]]).norm() < (param.uv[t[2]] - param.uv[t[0]]).norm() - 1e-12)
    t = Face{t[1], t[2], t[0]};  // t[0] = v, opposite the longest edge
  const Vec2 a = param.uv[t[1]], b = param.uv[t[2]], v0 = param.uv[t[0]];
  const Vec2 e = b - a, normal = Vec2(-e.y(), e.x()) / e.norm();  // toward v (positive orientation)
  param.uv[t[0]] = 0.5 * (a + b) + (2 * 1.5 * o.min_area / e.norm()) * normal;
  ASSERT_GT(uv_signed_area(param, f), o.min_area);
  ASSERT_LT(uv_signed_area(param, f), 2 * o.min_area);
  for (int g = 0; g < mesh.num_faces(); ++g) ASSERT_GT(uv_signed_area(param, g), 0.0) << "face " << g;
  // The warp: the lattice (one cell per mesh cell) with the cell's two corners that are not a or b
  // pushed 0.15 cell across the diagonal; v, at the cell's centre, follows by half of that.
  GridWarp w = GridWarp::uniform(n);
  const Vec2 d = a + b - v0;  // the cell's fourth corner
  for (const Vec2& c : {v0, d}) w.at(static_cast<int>(std::lround(c.x() * n)), static_cast<int>(std::lround(c.y() * n))) -= 0.15 / n * normal;
  ASSERT_GT(check_remap(param, remap_parameterization(param, {&w}), o).flipped, 0);
  const SafeRemapResult r = safe_remap(param, {&w}, o);
  EXPECT_TRUE(check_remap(param, r.param, o).ok());
  EXPECT_EQ(r.checks, 1);           // settled in the first attempt...
  EXPECT_EQ(r.damping, 1.0);        // ...with no global damping...
  EXPECT_GT(r.mean_damping, 0.99);  // ...and only a few wedges damped locally
  SafeRemapOptions halving = o;
  halving.snap_round = -1;
  const SafeRemapResult h = safe_remap(param, {&w}, halving);
  EXPECT_TRUE(check_remap(param, h.param, o).ok());
  std::printf("checks %d with snapping, %d halving only (mean blend kept %.4f, %.4f)\n", r.checks, h.checks,
              r.mean_damping, h.mean_damping);
  EXPECT_GT(h.checks, 1);  // halving alone: the first attempt failed
}

}  // namespace
}  // namespace adaptex
