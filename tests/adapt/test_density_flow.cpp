// Flow-based density-equalizing map (density_flow.h): reaches the density, cannot fold, keeps the square.
#include <gtest/gtest.h>

#include <cmath>

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
  const int L = 128;
  ImageF d(L, L, 0.1f);
  for (int j = 0; j < L; ++j)
    for (int i = 0; i < L; ++i) {
      const double x = (i + 0.5) / L, y = (j + 0.5) / L;
      const double r1 = std::abs(y - 0.3 - 0.2 * x), r2 = std::abs(x - 0.6 + 0.1 * y);
      d.at(i, j) = static_cast<float>(0.1 + 8.0 * std::exp(-0.5 * std::pow(std::min(r1, r2) / 0.012, 2)));
    }
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
