// Flow-based density-equalizing map (density_flow.h): reaches the density, cannot fold, keeps the square.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "adaptex/adapt/density_flow.h"
#include "adaptex/core/errors.h"

using namespace adaptex;

namespace {
ImageF bump(int L, double peak, double sigma, double cx, double cy) {
  ImageF d(L, L, 1.0f);
  for (int j = 0; j < L; ++j)
    for (int i = 0; i < L; ++i) {
      const double x = (i + 0.5) / L - cx, y = (j + 0.5) / L - cy;
      d.at(i, j) = static_cast<float>(1.0 + (peak - 1.0) * std::exp(-(x * x + y * y) / (2 * sigma * sigma)));
    }
  return d;
}

/// Thin dense lines on a low floor: the flow shears some cells faster than
/// the lattice resolves.
ImageF sharp_lines(int L) {
  ImageF d(L, L, 0.1f);
  for (int j = 0; j < L; ++j)
    for (int i = 0; i < L; ++i) {
      const double x = (i + 0.5) / L, y = (j + 0.5) / L;
      const double r1 = std::abs(y - 0.3 - 0.2 * x), r2 = std::abs(x - 0.6 + 0.1 * y);
      d.at(i, j) = static_cast<float>(0.1 + 8.0 * std::exp(-0.5 * std::pow(std::min(r1, r2) / 0.012, 2)));
    }
  return d;
}

DensityFlowOptions with_cells(int cells, double interpolation = DensityFlowOptions{}.interpolation_tolerance) {
  DensityFlowOptions o;
  o.cells = cells;
  o.interpolation_tolerance = interpolation;
  return o;
}

/// The lattice warp of a density (with its stats; every point advected unless \p interpolation > 0)
/// and the flow it samples.
struct TwoMaps {
  DensityFlowOptions o;
  DensityFlowStats st;
  GridWarp g;
  DensityFlow flow;
  TwoMaps(const ImageF& d, int cells, double interpolation = 0)
      : o(with_cells(cells, interpolation)), g(density_equalizing_warp(d, o, &st)), flow(d) {}
};

/// \p x advected through the exact flow (error bound 2e-3 and steps of at most one density cell).
Vec2 exact(const DensityFlow& flow, const Vec2& x) {
  const double cell = 1.0 / flow.cells();
  return flow.advect(x, 2e-3 * cell, cell, 4000);
}
}  // namespace

TEST(DensityFlow, UniformDensityIsTheIdentity) {
  DensityFlowStats st;
  DensityFlowOptions o;
  o.cells = 32;
  const GridWarp g = density_equalizing_warp(ImageF(16, 16, 3.0f), o, &st);
  EXPECT_LT(g.max_displacement(), 1e-12);
  EXPECT_EQ(st.inverted_cells, 0);
}

TEST(DensityFlow, ReachesAStrongDensityWithoutFolding) {
  for (double peak : {4.0, 16.0, 50.0}) {
    DensityFlowStats st;
    DensityFlowOptions o;
    o.cells = 128;
    const GridWarp g = density_equalizing_warp(bump(128, peak, 0.08, 0.4, 0.55), o, &st);
    EXPECT_EQ(st.inverted_cells, 0) << "peak " << peak;
    EXPECT_EQ(st.tangled_cells, 0) << "peak " << peak;  // a smooth density needs no untangling
    EXPECT_LT(st.density_error, 0.05) << "peak " << peak;
    EXPECT_GT(st.max_displacement, 0.02) << "peak " << peak;
    // The centre cell grew by about the density ratio (peak relative to the mean).
    double mean = 0;
    const ImageF d = bump(128, peak, 0.08, 0.4, 0.55);
    for (float v : d.data) mean += v;
    mean /= d.data.size();
    const int ci = static_cast<int>(0.4 * 128), cj = static_cast<int>(0.55 * 128);
    const Vec2 a = g.at(ci, cj), b = g.at(ci + 1, cj), c = g.at(ci, cj + 1);
    const double area = std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x()) * 128 * 128;
    EXPECT_NEAR(area, d.at(ci, cj) / mean, 0.1 * d.at(ci, cj) / mean) << "peak " << peak;
  }
}

TEST(DensityFlow, SidePointsSlideAndCornersStay) {
  DensityFlowOptions o;
  o.cells = 64;
  const GridWarp g = density_equalizing_warp(bump(64, 20.0, 0.1, 0.1, 0.5), o);
  const int n = g.n;
  EXPECT_EQ(g.at(0, 0), Vec2(0, 0));
  EXPECT_EQ(g.at(n, n), Vec2(1, 1));
  EXPECT_EQ(g.at(0, n), Vec2(0, 1));
  EXPECT_EQ(g.at(n, 0), Vec2(1, 0));
  double slid = 0;
  for (int k = 0; k <= n; ++k) {
    EXPECT_EQ(g.at(0, k).x(), 0.0);
    EXPECT_EQ(g.at(n, k).x(), 1.0);
    EXPECT_EQ(g.at(k, 0).y(), 0.0);
    EXPECT_EQ(g.at(k, n).y(), 1.0);
    slid = std::max(slid, std::abs(g.at(0, k).y() - double(k) / n));
  }
  for (int k = 1; k <= n; ++k) EXPECT_GT(g.at(0, k).y(), g.at(0, k - 1).y());  // order along the side kept
  EXPECT_GT(slid, 0.01);  // a bump next to the left side pushes the side points apart
}

TEST(DensityFlow, SerialAndParallelAgree) {
  DensityFlowOptions o;
  o.cells = 48;
  const GridWarp a = density_equalizing_warp(bump(32, 10.0, 0.1, 0.3, 0.3), o);
  o.parallel = false;
  const GridWarp b = density_equalizing_warp(bump(32, 10.0, 0.1, 0.3, 0.3), o);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t k = 0; k < a.points.size(); ++k) EXPECT_EQ(a.points[k], b.points[k]);
}

TEST(DensityFlow, RejectsBadDensities) {
  ImageF d(8, 8, 1.0f);
  d.at(3, 3) = 0.0f;
  EXPECT_THROW(density_equalizing_warp(d), InvalidInputError);
  d.at(3, 3) = std::nanf("");
  EXPECT_THROW(density_equalizing_warp(d), InvalidInputError);
  EXPECT_THROW(density_equalizing_warp(ImageF(8, 4, 1.0f)), InvalidInputError);
  for (double step : {0.0, -1.0, std::nan("")}) {
    DensityFlowOptions o;
    o.max_step_cells = step;
    EXPECT_THROW(density_equalizing_warp(ImageF(8, 8, 1.0f), o), InvalidInputError) << step;
  }
  for (double tol : {-0.1, std::nan("")}) {
    DensityFlowOptions o;
    o.interpolation_tolerance = tol;
    EXPECT_THROW(density_equalizing_warp(ImageF(8, 8, 1.0f), o), InvalidInputError) << tol;
  }
}

namespace {
/// Largest and mean distance, in lattice cells, between the points of two lattices of the same size.
std::pair<double, double> lattice_distance(const GridWarp& a, const GridWarp& b) {
  double most = 0, sum = 0;
  for (size_t k = 0; k < a.points.size(); ++k) {
    const double d = (a.points[k] - b.points[k]).norm() * a.n;
    most = std::max(most, d);
    sum += d;
  }
  return {most, sum / a.points.size()};
}
}  // namespace

// Coarse-to-fine advection interpolates only where the map is smooth: on a smooth bump and on sharp
// lines it stays within a fraction of a cell of advecting every point, with far fewer points
// advected; interpolating everywhere (an unbounded tolerance) does not, so the criterion matters.
TEST(DensityFlow, CoarseToFineAdvectionStaysCloseToAdvectingEveryPoint) {
  struct Case {
    const char* name;
    ImageF density;
    double max_cells, mean_cells, advected_share;
  };
  const Case cases[] = {{"bump", bump(128, 16.0, 0.08, 0.4, 0.55), 0.05, 0.01, 0.5},
                        {"sharp lines", sharp_lines(256), 0.5, 0.02, 0.8}};
  for (const Case& c : cases) {
    DensityFlowOptions full = with_cells(128), ctf = with_cells(128), loose = with_cells(128);
    full.interpolation_tolerance = 0;
    ctf.interpolation_tolerance = 0.05;
    loose.interpolation_tolerance = 1e9;
    DensityFlowStats sf, sc, sl;
    const GridWarp gf = density_equalizing_warp(c.density, full, &sf);
    const GridWarp gc = density_equalizing_warp(c.density, ctf, &sc);
    const GridWarp gl = density_equalizing_warp(c.density, loose, &sl);
    EXPECT_EQ(sf.advected_points, 129 * 129) << c.name;
    EXPECT_LT(sc.advected_points, c.advected_share * sf.advected_points) << c.name;
    EXPECT_LT(sc.total_steps, sf.total_steps) << c.name;
    EXPECT_EQ(sc.inverted_cells, 0) << c.name;
    const auto [most, mean] = lattice_distance(gc, gf);
    EXPECT_LT(most, c.max_cells) << c.name;
    EXPECT_LT(mean, c.mean_cells) << c.name;
    EXPECT_NEAR(sc.density_error, sf.density_error, 0.01) << c.name;
    // Everything interpolated from the 8-cell lattice: far off.
    EXPECT_EQ(sl.advected_points, 9 * 9) << c.name;
    EXPECT_GT(lattice_distance(gl, gf).first, 4 * c.max_cells) << c.name;
  }
}

TEST(DensityFlow, LongerStepsReachTheSameDensity) {
  // max_step_cells only limits the step; the error control keeps the accuracy (density_flow.h).
  const ImageF d = bump(64, 12.0, 0.1, 0.45, 0.5);
  DensityFlowOptions fine, coarse;
  fine.cells = coarse.cells = 64;
  fine.max_step_cells = 0.5;
  coarse.max_step_cells = 2.0;
  DensityFlowStats sf, sc;
  const GridWarp a = density_equalizing_warp(d, fine, &sf), b = density_equalizing_warp(d, coarse, &sc);
  EXPECT_LT(sc.total_steps, sf.total_steps);          // fewer steps ...
  EXPECT_LT(sc.density_error, sf.density_error + 0.01);  // ... and the same density
  double most = 0;
  for (int j = 0; j <= a.n; ++j)
    for (int i = 0; i <= a.n; ++i) most = std::max(most, (a.at(i, j) - b.at(i, j)).norm());
  EXPECT_LT(most, 0.5 / 64);  // within half a cell everywhere
}

TEST(DensityFlow, SharpContrastIsUntangledIntoAOneToOneGrid) {
  // Thin dense lines on a low floor: the flow shears some cells faster than the lattice resolves.
  const ImageF d = sharp_lines(128);
  DensityFlowStats st;
  DensityFlowOptions o;
  o.cells = 128;
  const GridWarp g = density_equalizing_warp(d, o, &st);
  EXPECT_EQ(st.inverted_cells, 0);
  for (int j = 0; j < g.n; ++j)
    for (int i = 0; i < g.n; ++i) {
      const Vec2 a = g.at(i, j), b = g.at(i + 1, j), c = g.at(i, j + 1);
      EXPECT_GT((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x(), 0.0) << i << "," << j;
    }
  EXPECT_GT(st.tangled_cells, 0);  // the case needs untangling (else this test tests nothing)
  // The dense lines still get most of the area they ask for.
  double mean = 0;
  for (float v : d.data) mean += v;
  mean /= d.data.size();
  double want = 0, got = 0, share = 0;
  for (int j = 0; j < g.n; ++j)
    for (int i = 0; i < g.n; ++i) {
      if (d.at(i, j) < 2 * mean) continue;
      const Vec2 a = g.at(i, j), b = g.at(i + 1, j), c = g.at(i + 1, j + 1), e = g.at(i, j + 1);
      got += 0.5 * std::abs((c - a).x() * (e - b).y() - (c - a).y() * (e - b).x());
      want += d.at(i, j) / mean / (g.n * g.n);
      share += 1.0 / (g.n * g.n);
    }
  EXPECT_GT(got, 0.5 * want);  // measured 0.53: untangling and the 1.5-cell lines cost some
  EXPECT_GT(got, 2.0 * share);
}

TEST(DensityFlow, TheLatticeMatchesTheExactFlowOnASmoothDensity) {
  // On a smooth density the lattice needs no untangling: both are the same map.
  const TwoMaps m(bump(128, 12.0, 0.1, 0.45, 0.5), 64);
  const GridWarp& g = m.g;
  ASSERT_EQ(m.st.tangled_cells, 0);
  EXPECT_EQ(m.flow.cells(), 128);
  double most = 0;
  for (int j = 0; j <= g.n; ++j)
    for (int i = 0; i <= g.n; ++i)
      most = std::max(most, (g.at(i, j) - exact(m.flow, Vec2(double(i) / g.n, double(j) / g.n))).norm());
  EXPECT_LT(most, 0.05 / 128);
  EXPECT_GT(g.max_displacement(), 0.05);  // and the map is far from the identity
}

TEST(DensityFlow, TheExactFlowKeepsSidesAndCorners) {
  const DensityFlow flow(bump(64, 20.0, 0.1, 0.1, 0.5));
  for (const Vec2& c : {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), Vec2(1, 1)}) EXPECT_EQ(exact(flow, c), c);
  double slid = 0;
  for (int k = 1; k < 32; ++k) {
    const Vec2 p = exact(flow, Vec2(0, k / 32.0));
    EXPECT_EQ(p.x(), 0.0);
    slid = std::max(slid, std::abs(p.y() - k / 32.0));
    EXPECT_EQ(exact(flow, Vec2(k / 32.0, 1)).y(), 1.0);
  }
  EXPECT_GT(slid, 0.01);
}

TEST(DensityFlow, FlowShapeOfTheIdentityAndOfAScaling) {
  const ImageF flat(16, 16, 2.0f);
  const FlowShape id = flow_shape(flat, [](const Vec2& p) { return p; }, 8, 0.5);
  EXPECT_NEAR(id.density_error, 0.0, 1e-12);
  EXPECT_NEAR(id.dense_area, 1.0, 1e-12);
  EXPECT_NEAR(id.dense_anisotropy, 1.0, 1e-12);
  // A map squeezing u by 2: every cell half its area, anisotropy 2, error 0.5.
  const FlowShape sq = flow_shape(flat, [](const Vec2& p) { return Vec2(0.5 * p.x(), p.y()); }, 8, 0.5);
  EXPECT_NEAR(sq.density_error, 0.5, 1e-12);
  EXPECT_NEAR(sq.dense_anisotropy, 2.0, 1e-12);
  EXPECT_THROW(flow_shape(flat, [](const Vec2& p) { return p; }, 0), InvalidInputError);
}

// FFTW plans are made under a lock (its planner is not thread-safe) and FFTW keeps its own tables per
// size: the warp of a density must not depend on which sizes were solved before, nor on other threads
// solving at the same time with the same or other sizes.
TEST(DensityFlow, WarpIsTheSameInAnyOrderAndInParallel) {
  const std::vector<int> sizes{24, 37, 24, 64, 37, 50, 24, 64};
  std::vector<ImageF> densities;
  for (size_t k = 0; k < sizes.size(); ++k)
    densities.push_back(bump(sizes[k], 4.0 + static_cast<double>(k), 0.15, 0.3 + 0.05 * static_cast<double>(k), 0.6));
  auto warp_of = [&](size_t k) {
    DensityFlowOptions o;
    o.cells = 32;
    o.parallel = false;
    return density_equalizing_warp(densities[k], o).points;
  };
  std::vector<std::vector<Vec2>> serial(sizes.size());
  for (size_t k = sizes.size(); k-- > 0;) serial[k] = warp_of(k);  // reverse order: other sizes first
  std::vector<std::vector<Vec2>> parallel(sizes.size());
  tbb::parallel_for(size_t(0), 4 * sizes.size(), [&](size_t j) {
    const size_t k = j % sizes.size();
    std::vector<Vec2> p = warp_of(k);
    if (j < sizes.size()) parallel[k] = std::move(p);
  });
  for (size_t k = 0; k < sizes.size(); ++k) {
    ASSERT_EQ(parallel[k].size(), serial[k].size()) << k;
    for (size_t i = 0; i < serial[k].size(); ++i)
      ASSERT_TRUE(parallel[k][i] == serial[k][i]) << "size " << sizes[k] << " point " << i;
  }
  // Not the identity: the bump moved the lattice.
  EXPECT_GT((serial[0][serial[0].size() / 2] - Vec2(0.5, 0.5)).norm(), 1e-3);
}
