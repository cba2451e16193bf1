// Polishing a flow lattice by the anisotropic error model (error_polish.h): lowers the model's error,
// makes the magnified texels rounder, never folds a cell, keeps the square, and does not depend on threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string_view>
#include <utility>
#include <vector>

#include "adaptex/adapt/density_flow.h"
#include "adaptex/adapt/error_polish.h"
#include "adaptex/core/errors.h"

using namespace adaptex;

namespace {

constexpr int kCells = 64;

/// A ring of hard-edge error (p = 1) around (cx, cy), as the edge of a painted dot gives: q > 0 where
/// |r − radius| < width, 0 elsewhere.
PolishFields dot_edge(int n, double cx, double cy, double radius, double width, const ImageF& density) {
  PolishFields f;
  f.error = ImageF(n, n, 0.0f);
  f.exponent = ImageF(n, n, 0.0f);
  f.floor = ImageF(n, n, 0.0f);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double r = std::hypot((i + 0.5) / n - cx, (j + 0.5) / n - cy);
      if (std::abs(r - radius) < width) {
        f.error.at(i, j) = 1.0f;
        f.exponent.at(i, j) = 1.0f;
      } else {
        f.floor.at(i, j) = density.at(i, j);
      }
    }
  return f;
}

/// Target density of that dot: high on the ring and inside it, blurred, floor 0.3 (mean ≈ 1).
ImageF dot_density(int n, double cx, double cy, double radius) {
  ImageF d(n, n, 0.3f);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double r = std::hypot((i + 0.5) / n - cx, (j + 0.5) / n - cy);
      d.at(i, j) = static_cast<float>(0.3 + 6.0 / (1.0 + std::exp((r - radius) / 0.02)));
    }
  return d;
}

/// n x n fields with the same error, exponent and floor in every cell.
PolishFields uniform_fields(int n, float error, float exponent, float floor) {
  PolishFields f;
  f.error = ImageF(n, n, error);
  f.exponent = ImageF(n, n, exponent);
  f.floor = ImageF(n, n, floor);
  return f;
}

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Smallest corner-triangle determinant over every cell (> 0: every cell convex).
double min_corner_det(const GridWarp& w) {
  double m = 1e300;
  for (int j = 0; j < w.n; ++j)
    for (int i = 0; i < w.n; ++i) {
      const Vec2 A = w.at(i, j), B = w.at(i + 1, j), C = w.at(i + 1, j + 1), D = w.at(i, j + 1);
      m = std::min({m, cross(B - A, D - A), cross(B - A, C - B), cross(C - D, C - B), cross(C - D, D - A)});
    }
  return m;
}

/// The square is kept: corners stay, side points stay on their side, every point inside.
void expect_keeps_the_square(const GridWarp& w) {
  const int n = w.n;
  EXPECT_EQ(w.at(0, 0), Vec2(0, 0));
  EXPECT_EQ(w.at(n, n), Vec2(1, 1));
  EXPECT_EQ(w.at(n, 0), Vec2(1, 0));
  EXPECT_EQ(w.at(0, n), Vec2(0, 1));
  for (int k = 0; k <= n; ++k) {
    EXPECT_EQ(w.at(0, k).x(), 0.0);
    EXPECT_EQ(w.at(n, k).x(), 1.0);
    EXPECT_EQ(w.at(k, 0).y(), 0.0);
    EXPECT_EQ(w.at(k, n).y(), 1.0);
  }
  for (const Vec2& x : w.points) {
    EXPECT_GE(x.minCoeff(), 0.0);
    EXPECT_LE(x.maxCoeff(), 1.0);
  }
}

/// Largest |J|²_F / (2 det J) (1: round) of the corner-A triangles over the unpainted cells.
double worst_unpainted_shape(const GridWarp& w, const PolishFields& f) {
  double m = 0;
  for (int j = 0; j < w.n; ++j)
    for (int i = 0; i < w.n; ++i) {
      if (f.error.at(i, j) > 0) continue;
      const Vec2 ex = w.at(i + 1, j) - w.at(i, j), ey = w.at(i, j + 1) - w.at(i, j);
      m = std::max(m, (ex.squaredNorm() + ey.squaredNorm()) / (2 * cross(ex, ey)));
    }
  return m;
}

/// Error-weighted mean of σmax/σmin of the corner triangles' Jacobians over the painted cells, in uv
/// of a rectangle of aspect \p aspect (J_uv = S·J·S⁻¹, S = diag(aspect, 1)).
double painted_anisotropy(const GridWarp& w, const PolishFields& f, double aspect = 1) {
  double s = 0, ws = 0;
  for (int j = 0; j < w.n; ++j)
    for (int i = 0; i < w.n; ++i) {
      const double q = f.error.at(i, j);
      if (!(q > 0)) continue;
      const Vec2 A = w.at(i, j), B = w.at(i + 1, j), D = w.at(i, j + 1);
      Eigen::Matrix2d J;
      J.col(0) = B - A, J.col(1) = D - A;
      const Eigen::Matrix2d S = Vec2(aspect, 1).asDiagonal();
      Eigen::JacobiSVD<Eigen::Matrix2d> svd(S * J * S.inverse());
      s += q * svd.singularValues()(0) / svd.singularValues()(1), ws += q;
    }
  return s / ws;
}

/// The flow lattice of a painted dot (radius 0.15 at (0.45, 0.55)) and the error fields of its edge.
struct DotCase {
  GridWarp flow;
  PolishFields fields;
};

DotCase dot_case() {
  const ImageF density = dot_density(kCells, 0.45, 0.55, 0.15);
  DensityFlowOptions fo;
  fo.cells = kCells;
  return {density_equalizing_warp(density, fo), dot_edge(kCells, 0.45, 0.55, 0.15, 0.03, density)};
}

struct Polished {
  GridWarp flow, polished;
  PolishFields fields;
  ErrorPolishStats stats;
};

Polished polish_dot(bool parallel) {
  Polished p;
  DotCase d = dot_case();
  p.flow = std::move(d.flow);
  p.fields = std::move(d.fields);
  p.polished = p.flow;
  ErrorPolishOptions po;
  po.sweeps = 30;
  po.parallel = parallel;
  p.stats = polish_warp_by_error(p.polished, p.fields, po);
  return p;
}

}  // namespace

TEST(ErrorPolish, LowersTheModelErrorAndRoundsTheMagnifiedTexels) {
  const Polished p = polish_dot(true);
  EXPECT_GT(p.stats.sweeps, 0);
  EXPECT_LT(p.stats.energy_after, p.stats.energy_before);
  // The dot's edge gets a clearly lower error (at least 0.5 dB in the model; measured 1.32).
  EXPECT_GT(10 * std::log10(p.stats.error_before / p.stats.error_after), 0.5);
  // ... because the texels on it are rounder than the flow left them.
  const double before = painted_anisotropy(p.flow, p.fields), after = painted_anisotropy(p.polished, p.fields);
  std::printf("model gain %.2f dB, painted anisotropy %.3f -> %.3f, %d sweeps\n",
              10 * std::log10(p.stats.error_before / p.stats.error_after), before, after, p.stats.sweeps);
  EXPECT_LT(after, before - 0.2);
}

TEST(ErrorPolish, TexelsAreRoundInUvOnANonSquareChart) {
  // A chart twice as wide as high: its lattice's local cells are 2:1 in uv. Polished with the
  // chart's aspect, the dot's texels get rounder in uv; polished as if the chart were square, they
  // would be round in the lattice's coordinates, which in uv is round only where the map does not
  // rotate (measured: 1.23 against 1.30, the flow 2.03).
  const DotCase d = dot_case();
  const GridWarp& flow = d.flow;
  PolishFields f = d.fields;
  ErrorPolishOptions po;
  po.sweeps = 30;
  GridWarp square = flow, wide = flow;
  polish_warp_by_error(square, f, po);
  f.aspect = 2;
  const ErrorPolishStats s = polish_warp_by_error(wide, f, po);
  EXPECT_LT(s.error_after, s.error_before);
  const double before = painted_anisotropy(flow, f, 2), after = painted_anisotropy(wide, f, 2);
  const double as_square = painted_anisotropy(square, f, 2);
  std::printf("uv anisotropy on a 2:1 chart: flow %.3f, polished %.3f, polished as square %.3f\n", before, after,
              as_square);
  EXPECT_LT(after, before - 0.2);
  EXPECT_LT(after, as_square - 0.04);
  EXPECT_GT(min_corner_det(wide), 0);
}

TEST(ErrorPolish, ShapeTermKeepsTheUnpaintedCellsFromCracking) {
  // Without the shape term the unpainted cells only keep their floor area, and the polish pushes
  // the compression into thin sheared cells; the default shape term keeps them rounder.
  const DotCase d = dot_case();
  const GridWarp& flow = d.flow;
  const PolishFields& f = d.fields;
  GridWarp with = flow, without = flow;
  polish_warp_by_error(with, f);
  ErrorPolishOptions none;
  none.shape_weight = 0;
  polish_warp_by_error(without, f, none);
  const double a = worst_unpainted_shape(with, f), b = worst_unpainted_shape(without, f);
  std::printf("worst unpainted cell shape: flow %.2f, polished %.2f, polished without the shape term %.2f\n",
              worst_unpainted_shape(flow, f), a, b);
  EXPECT_LT(a, 0.8 * b);
}

TEST(ErrorPolish, NeverFoldsAndKeepsTheSquare) {
  const Polished p = polish_dot(true);
  ASSERT_GT(min_corner_det(p.flow), 0);
  EXPECT_GT(min_corner_det(p.polished), 0);
  expect_keeps_the_square(p.polished);
}

TEST(ErrorPolish, SameResultOnOneThreadAndMany) {
  const Polished a = polish_dot(true), b = polish_dot(false);
  EXPECT_EQ(a.stats.sweeps, b.stats.sweeps);
  ASSERT_EQ(a.polished.points.size(), b.polished.points.size());
  for (size_t k = 0; k < a.polished.points.size(); ++k) ASSERT_EQ(a.polished.points[k], b.polished.points[k]) << k;
}

TEST(ErrorPolish, LeavesALatticeWithoutErrorAlone) {
  const ImageF density = dot_density(kCells, 0.5, 0.5, 0.2);
  DensityFlowOptions fo;
  fo.cells = kCells;
  const GridWarp flow = density_equalizing_warp(density, fo);
  PolishFields f = uniform_fields(kCells, 0.0f, 0.0f, 0.0f);
  f.floor = density;
  GridWarp w = flow;
  const ErrorPolishStats s = polish_warp_by_error(w, f);
  EXPECT_EQ(s.sweeps, 0);
  EXPECT_EQ(w.points, flow.points);
}

TEST(ErrorPolish, UniformErrorKeepsTheIdentity) {
  // Every cell painted alike: the identity is the optimum (every texel round, the same size).
  GridWarp w = GridWarp::uniform(16);
  const PolishFields f = uniform_fields(16, 1.0f, 2.0f, 0.0f);
  const ErrorPolishStats s = polish_warp_by_error(w, f);
  EXPECT_NEAR(s.error_after, s.error_before, 1e-12 * s.error_before);
  for (int j = 0; j <= 16; ++j)
    for (int i = 0; i <= 16; ++i) EXPECT_LT((w.at(i, j) - Vec2(i / 16.0, j / 16.0)).norm(), 1e-12);
}

TEST(ErrorPolish, FieldsOnTheWholeSquareAreTheModelsOwn) {
  const int L = 8;
  ImageF error(L, L, 0.0f), exponent(L, L, 0.0f), density(L, L, 0.5f);
  error.at(2, 3) = 4.0f, exponent.at(2, 3) = 1.5f, density.at(2, 3) = 8.0f;
  error.at(5, 5) = 1.0f, exponent.at(5, 5) = 3.0f, density.at(5, 5) = 2.0f;
  const PolishFields f = polish_fields(error, exponent, density, Vec2(0, 0), Vec2(1, 1), L);
  double mean = 0;
  for (float v : density.data) mean += v / (L * L);
  for (int j = 0; j < L; ++j)
    for (int i = 0; i < L; ++i) {
      EXPECT_FLOAT_EQ(f.error.at(i, j), error.at(i, j));
      EXPECT_FLOAT_EQ(f.exponent.at(i, j), exponent.at(i, j));
      EXPECT_FLOAT_EQ(f.floor.at(i, j), error.at(i, j) > 0 ? 0.0f : static_cast<float>(density.at(i, j) / mean));
    }
  // A sub-rectangle on a finer lattice: the exponent stays an error-weighted mean of the taps.
  const PolishFields g = polish_fields(error, exponent, density, Vec2(0.25, 0.375), Vec2(0.375, 0.5), 4);
  // (Every point of that rectangle has cell (2, 3) among its taps: all of it is painted.)
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      EXPECT_GT(g.error.at(i, j), 0.0f);
      EXPECT_FLOAT_EQ(g.exponent.at(i, j), 1.5f);
    }
}

TEST(ErrorPolish, ReportsProgressAndCanBeCancelled) {
  const DotCase d = dot_case();
  const GridWarp& flow = d.flow;
  const PolishFields& f = d.fields;
  ErrorPolishOptions o;
  o.sweeps = 5;
  o.tolerance = 0;
  std::vector<double> seen;
  o.progress = [&](std::string_view phase, double x) {
    EXPECT_EQ(phase, "polish");
    seen.push_back(x);
    return seen.size() < 3;  // cancel after the third sweep
  };
  GridWarp w = flow;
  EXPECT_THROW(polish_warp_by_error(w, f, o), CancelledError);
  ASSERT_EQ(seen.size(), 3u);
  EXPECT_DOUBLE_EQ(seen[0], 0.2);
  EXPECT_DOUBLE_EQ(seen[2], 0.6);
}

TEST(ErrorPolish, RejectsBadInput) {
  GridWarp w = GridWarp::uniform(8);
  PolishFields f = uniform_fields(8, 1.0f, 1.0f, 0.0f);
  f.floor = ImageF(7, 7, 0.0f);
  EXPECT_THROW(polish_warp_by_error(w, f), InvalidInputError);
  f.floor = ImageF(8, 8, 0.0f);
  f.error.at(3, 3) = -1.0f;
  EXPECT_THROW(polish_warp_by_error(w, f), InvalidInputError);
  f.error.at(3, 3) = std::nanf("");
  EXPECT_THROW(polish_warp_by_error(w, f), InvalidInputError);
  f.error.at(3, 3) = 1.0f;
  f.exponent.at(1, 1) = 9.0f;
  EXPECT_THROW(polish_warp_by_error(w, f), InvalidInputError);
  f.exponent.at(1, 1) = 1.0f;
  f.aspect = 0;
  EXPECT_THROW(polish_warp_by_error(w, f), InvalidInputError);
  f.aspect = 1;
  ErrorPolishOptions o;
  o.sweeps = -1;
  EXPECT_THROW(polish_warp_by_error(w, f, o), InvalidInputError);
  EXPECT_THROW(check_polish_options(o), InvalidInputError);
  o.sweeps = 20;
  o.over_relaxation = 2;
  EXPECT_THROW(check_polish_options(o), InvalidInputError);
  o.over_relaxation = 1.8;
  EXPECT_NO_THROW(check_polish_options(o));
  EXPECT_THROW(polish_fields(f.error, f.exponent, ImageF(4, 4, 1.0f), Vec2(0, 0), Vec2(1, 1), 8), InvalidInputError);
  EXPECT_THROW(polish_fields(f.error, f.exponent, f.error, Vec2(0.5, 0), Vec2(0.5, 1), 8), InvalidInputError);
}

namespace {

/// The model's error part of lattice \p w under \p f.
double model_error(const GridWarp& w, const PolishFields& f) { return polish_model_error(w, f); }

/// The dot case polished through a lattice of \p coarse cells (ErrorPolishOptions::cells).
struct Through {
  GridWarp flow, polished;
  PolishFields fine;  ///< The dot's fields on the flow's own lattice.
  ErrorPolishStats stats;
};

Through polish_dot_through(int coarse, bool parallel) {
  Through t;
  DotCase d = dot_case();
  t.flow = d.flow;
  t.fine = std::move(d.fields);
  t.polished = t.flow;
  ErrorPolishOptions po;
  po.cells = coarse;
  po.sweeps = 30;
  po.parallel = parallel;
  const PolishFields f = dot_edge(coarse, 0.45, 0.55, 0.15, 0.03, dot_density(coarse, 0.45, 0.55, 0.15));
  t.stats = polish_warp(t.polished, f, po);
  return t;
}

}  // namespace

TEST(ErrorPolish, ModelErrorIsThatOfAPolishWithoutSweeps) {
  const DotCase d = dot_case();
  GridWarp w = d.flow;
  const ErrorPolishStats s = polish_warp_by_error(w, d.fields);
  EXPECT_DOUBLE_EQ(polish_model_error(d.flow, d.fields), s.error_before);
  EXPECT_DOUBLE_EQ(polish_model_error(w, d.fields), s.error_after);
}

TEST(ErrorPolish, ThroughACoarserLatticeLowersTheFineLatticesError) {
  const Through t = polish_dot_through(kCells / 2, true);
  const double gain = 10 * std::log10(model_error(t.flow, t.fine) / model_error(t.polished, t.fine));
  const double before = painted_anisotropy(t.flow, t.fine), after = painted_anisotropy(t.polished, t.fine);
  std::printf("through %d cells: fine-lattice model gain %.2f dB, painted anisotropy %.3f -> %.3f, motion kept %.2f\n",
              kCells / 2, gain, before, after, t.stats.transfer_scale);
  EXPECT_EQ(t.stats.transfer_scale, 1.0);
  EXPECT_GT(gain, 0.5);
  EXPECT_LT(after, before - 0.1);
  EXPECT_GT(min_corner_det(t.polished), 0);
  expect_keeps_the_square(t.polished);
}

TEST(ErrorPolish, ThroughACoarserLatticeIsTheSameOnOneThreadAndMany) {
  const Through a = polish_dot_through(kCells / 2, true), b = polish_dot_through(kCells / 2, false);
  ASSERT_EQ(a.polished.points.size(), b.polished.points.size());
  for (size_t k = 0; k < a.polished.points.size(); ++k) ASSERT_EQ(a.polished.points[k], b.polished.points[k]) << k;
}

TEST(ErrorPolish, ThroughACoarserLatticeNeverTurnsACellOfASharpWarp) {
  // A thin line of 40x density: the flow compresses its neighbourhood into cells far smaller than a
  // cell of an 8x coarser lattice, where the coarse motion turns some of them unless they are
  // untangled (or the motion damped).
  const int n = 128, m = 16;
  auto line = [](int L) {
    ImageF d(L, L, 0.2f);
    for (int j = 0; j < L; ++j)
      for (int i = 0; i < L; ++i) {
        const double r = std::abs((j + 0.5) / L - 0.45 - 0.3 * ((i + 0.5) / L - 0.5));
        d.at(i, j) = static_cast<float>(0.2 + 8.0 * std::exp(-0.5 * std::pow(r / 0.01, 2)));
      }
    return d;
  };
  DensityFlowOptions fo;
  fo.cells = n;
  const GridWarp flow = density_equalizing_warp(line(n), fo);
  ASSERT_GT(min_corner_det(flow), 0);
  const ImageF dm = line(m);
  PolishFields f = uniform_fields(m, 0.0f, 0.0f, 0.0f);
  for (size_t k = 0; k < dm.data.size(); ++k) {
    const bool painted = dm.data[k] > 1.0f;
    f.error.data[k] = painted ? dm.data[k] : 0.0f;
    f.exponent.data[k] = painted ? 1.0f : 0.0f;
    f.floor.data[k] = painted ? 0.0f : dm.data[k];
  }
  ErrorPolishOptions po;
  po.cells = m;
  GridWarp w = flow;
  const ErrorPolishStats s = polish_warp(w, f, po);
  std::printf("sharp warp through %d cells: %d sweeps, %d cells turned, motion kept %.3f, smallest corner det %.3g\n",
              m, s.sweeps, s.turned_cells, s.transfer_scale, min_corner_det(w));
  EXPECT_GT(s.sweeps, 0);
  EXPECT_GT(s.turned_cells, 0);  // the case needs the untangling (measured: 47 cells)
  EXPECT_EQ(s.transfer_scale, 1.0);  // ... and the untangling, not the halving, repairs them
  EXPECT_GT(min_corner_det(w), 0);
  EXPECT_NE(w.points, flow.points);
}

TEST(ErrorPolish, PolishCellsAndTheirChecks) {
  ErrorPolishOptions o;
  EXPECT_EQ(o.cells, 128);
  EXPECT_EQ(polish_cells(256, o), 128);
  EXPECT_EQ(polish_cells(64, o), 64);
  EXPECT_EQ(polish_cells(256, o, 0.25), 32);  // a chart a quarter of the square wide
  EXPECT_EQ(polish_cells(256, o, 0.01), 4);
  EXPECT_THROW(polish_cells(256, o, 0), InvalidInputError);
  EXPECT_THROW(polish_cells(256, o, 1.5), InvalidInputError);
  o.cells = 0;
  EXPECT_EQ(polish_cells(256, o), 256);
  EXPECT_THROW(polish_cells(0, o), InvalidInputError);
  o.cells = -1;
  EXPECT_THROW(polish_cells(256, o), InvalidInputError);
  EXPECT_THROW(check_polish_options(o), InvalidInputError);
  // polish_warp() polishes a lattice of its fields' size, at most the warp's.
  o.cells = 4;
  GridWarp w = GridWarp::uniform(8);
  EXPECT_THROW(polish_warp(w, uniform_fields(9, 1.0f, 1.0f, 0.0f), o), InvalidInputError);
  EXPECT_NO_THROW(polish_warp(w, uniform_fields(4, 1.0f, 1.0f, 0.0f), o));
  GridWarp broken = GridWarp::uniform(8);
  broken.points.pop_back();
  EXPECT_THROW(polish_warp(broken, uniform_fields(4, 1.0f, 1.0f, 0.0f), o), InvalidInputError);
}

namespace {

/// The dot case's direction tensor: T = (1 − isotropy)·r rᵀ + isotropy·I/2 with r the unit radial
/// direction (the edge's normal) at every cell centre.
void add_radial_tensor(PolishFields& f, double isotropy) {
  const int n = f.error.width;
  f.txx = ImageF(n, n), f.txy = ImageF(n, n), f.tyy = ImageF(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec2 r = Vec2((i + 0.5) / n - 0.45, (j + 0.5) / n - 0.55).normalized();
      f.txx.at(i, j) = static_cast<float>((1 - isotropy) * r.x() * r.x() + 0.5 * isotropy);
      f.txy.at(i, j) = static_cast<float>((1 - isotropy) * r.x() * r.y());
      f.tyy.at(i, j) = static_cast<float>((1 - isotropy) * r.y() * r.y() + 0.5 * isotropy);
    }
}

/// Error-weighted mean over the painted cells of |J⁻ᵀ t| / |J⁻ᵀ r| at corner A (r radial, t
/// tangential): > 1 where the warped texels are finer across the dot's edge than along it.
double across_fineness(const GridWarp& w, const PolishFields& f) {
  double s = 0, ws = 0;
  for (int j = 0; j < w.n; ++j)
    for (int i = 0; i < w.n; ++i) {
      const double q = f.error.at(i, j);
      if (!(q > 0)) continue;
      Eigen::Matrix2d J;
      J.col(0) = w.at(i + 1, j) - w.at(i, j), J.col(1) = w.at(i, j + 1) - w.at(i, j);
      const Eigen::Matrix2d Jit = J.inverse().transpose();
      const Vec2 r = Vec2((i + 0.5) / w.n - 0.45, (j + 0.5) / w.n - 0.55).normalized(), t(-r.y(), r.x());
      s += q * (Jit * t).norm() / (Jit * r).norm(), ws += q;
    }
  return s / ws;
}

}  // namespace

TEST(ErrorPolish, TheIsotropicDirectionTensorIsTheRoundModel) {
  // T = I/2 in every cell is the model without a tensor: the same polish, to rounding.
  DotCase a = dot_case(), b = dot_case();
  b.fields.txx = ImageF(kCells, kCells, 0.5f);
  b.fields.txy = ImageF(kCells, kCells, 0.0f);
  b.fields.tyy = ImageF(kCells, kCells, 0.5f);
  const ErrorPolishStats sa = polish_warp_by_error(a.flow, a.fields), sb = polish_warp_by_error(b.flow, b.fields);
  EXPECT_EQ(sa.sweeps, sb.sweeps);
  EXPECT_NEAR(sb.error_after, sa.error_after, 1e-9 * sa.error_after);
  double worst = 0;
  for (size_t k = 0; k < a.flow.points.size(); ++k) worst = std::max(worst, (a.flow.points[k] - b.flow.points[k]).norm());
  EXPECT_LT(worst, 1e-9);
}

TEST(ErrorPolish, TexelsGetFinerAcrossAnEdgeWithItsDirection) {
  // With the edge's direction the error counts the spacing across the dot's edge (radially), so the
  // polish makes the texels finer across it than along it; the round model keeps them round.
  DotCase round = dot_case(), directed = dot_case();
  add_radial_tensor(directed.fields, 0.25);
  const double flow = across_fineness(round.flow, round.fields);
  polish_warp_by_error(round.flow, round.fields);
  const ErrorPolishStats s = polish_warp_by_error(directed.flow, directed.fields);
  const double r_round = across_fineness(round.flow, round.fields), r_dir = across_fineness(directed.flow, directed.fields);
  std::printf("across / along fineness on the dot's edge: flow %.3f, round model %.3f, with the direction %.3f "
              "(model gain %.2f dB)\n", flow, r_round, r_dir, 10 * std::log10(s.error_before / s.error_after));
  EXPECT_GT(r_dir, r_round + 0.08);  // measured 1.093 against 0.963
  EXPECT_LT(s.error_after, s.error_before);
  // Under the directed model, the directed polish beats the round one.
  EXPECT_LT(model_error(directed.flow, directed.fields), 0.99 * model_error(round.flow, directed.fields));  // 0.964
  EXPECT_GT(min_corner_det(directed.flow), 0);
}

TEST(ErrorPolish, EdgeTensorTablesHoldExactBoxSums) {
  // The summed-area tables are built row by row, then column block by column block, in parallel
  // (error_polish.cpp): the sums must still be exact. A noisy non-square texture, large enough for
  // several column blocks; every table entry against the direct sum of its rectangle, bit for bit.
  const int W = 700, H = 37;
  ImageRGBA8 tex(W, H);
  unsigned state = 12345;
  for (auto& c : tex.data) c = static_cast<std::uint8_t>((state = state * 1103515245u + 12345u) >> 24);
  const EdgeTensor e = edge_tensor(tex);
  const std::pair<const ImageF*, const std::vector<double>*> tables[3] = {
      {&e.xx, &e.sum_xx}, {&e.xy, &e.sum_xy}, {&e.yy, &e.sum_yy}};
  for (const auto& [img, sum] : tables) {
    ASSERT_EQ(sum->size(), static_cast<size_t>(W + 1) * (H + 1));
    std::vector<double> column(W, 0.0);  // column[i]: sum of img(i, 0..j-1)
    for (int j = 0; j <= H; ++j) {
      double row = 0;
      for (int i = 0; i <= W; ++i) {
        ASSERT_EQ((*sum)[static_cast<size_t>(j) * (W + 1) + i], row) << i << ", " << j;
        if (i < W) row += column[i];
      }
      if (j < H)
        for (int i = 0; i < W; ++i) column[i] += img->at(i, j);
    }
  }
}

TEST(ErrorPolish, EdgeTensorIntoUsedStorageIsTheFreshOne) {
  // A session's density-flow method keeps one EdgeTensor between cycles: written over a tensor of a
  // larger, then of a smaller texture, it must equal a fresh one bit for bit.
  auto noisy = [](int W, int H, unsigned state) {
    ImageRGBA8 tex(W, H);
    for (auto& c : tex.data) c = static_cast<std::uint8_t>((state = state * 1103515245u + 12345u) >> 24);
    return tex;
  };
  const ImageRGBA8 large = noisy(90, 70, 7), small = noisy(40, 50, 8);
  EdgeTensor kept;
  for (const ImageRGBA8* tex : {&large, &small}) {
    edge_tensor(*tex, kept);
    const EdgeTensor fresh = edge_tensor(*tex);
    EXPECT_EQ(kept.xx.width, tex->width);
    EXPECT_EQ(kept.xx.height, tex->height);
    EXPECT_EQ(kept.xx.data, fresh.xx.data);
    EXPECT_EQ(kept.xy.data, fresh.xy.data);
    EXPECT_EQ(kept.yy.data, fresh.yy.data);
    EXPECT_EQ(kept.sum_xx, fresh.sum_xx);
    EXPECT_EQ(kept.sum_xy, fresh.sum_xy);
    EXPECT_EQ(kept.sum_yy, fresh.sum_yy);
  }
  EXPECT_THROW(edge_tensor(ImageRGBA8(), kept), InvalidInputError);
}

TEST(ErrorPolish, EdgeTensorOfAStripeFollowsItsEdges) {
  // A vertical stripe (texels 12..19 of 32 red): the gradient is along u at its two edges, zero
  // elsewhere.
  ImageRGBA8 tex(32, 32, {255, 255, 255, 255});
  for (int j = 0; j < 32; ++j)
    for (int i = 12; i < 20; ++i) tex.texel(i, j)[1] = tex.texel(i, j)[2] = 0;
  const EdgeTensor e = edge_tensor(tex);
  EXPECT_GT(e.xx.at(12, 5), 0.0f);
  EXPECT_EQ(e.yy.at(12, 5), 0.0f);
  EXPECT_EQ(e.xy.at(12, 5), 0.0f);
  EXPECT_EQ(e.xx.at(4, 5), 0.0f);
  PolishFields f = uniform_fields(8, 1.0f, 1.0f, 0.0f);
  add_edge_directions(f, e, Vec2(0, 0), Vec2(1, 1), 0.25);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) EXPECT_NEAR(f.txx.at(i, j) + f.tyy.at(i, j), 1.0f, 1e-6f);
  // Cell 3 (texels 12..15) sees the stripe's edge: its normal is u. Cell 0 (texels 0..3, and the
  // ring up to texel 7) sees none: isotropic.
  EXPECT_NEAR(f.txx.at(3, 4), 1 - 0.125, 1e-6);
  EXPECT_NEAR(f.tyy.at(3, 4), 0.125, 1e-6);
  EXPECT_NEAR(f.txx.at(0, 4), 0.5, 1e-6);
  // The summed-area tables hold the rasters' sums.
  double total = 0;
  for (float v : e.xx.data) total += v;
  EXPECT_DOUBLE_EQ(e.sum_xx.back(), total);
  // Bad input.
  EXPECT_THROW(edge_tensor(ImageRGBA8()), InvalidInputError);
  EdgeTensor bare;  // rasters without their tables
  bare.xx = e.xx, bare.xy = e.xy, bare.yy = e.yy;
  EXPECT_THROW(add_edge_directions(f, bare, Vec2(0, 0), Vec2(1, 1), 0.25), InvalidInputError);
  EXPECT_THROW(add_edge_directions(f, e, Vec2(0, 0), Vec2(1, 1), 0), InvalidInputError);
  EXPECT_THROW(add_edge_directions(f, e, Vec2(0.5, 0), Vec2(0.5, 1), 0.25), InvalidInputError);
  GridWarp w = GridWarp::uniform(8);
  f.txy.at(2, 2) = 1.0f;  // not positive definite
  EXPECT_THROW(polish_warp_by_error(w, f), InvalidInputError);
  f.txy = ImageF(4, 4, 0.0f);
  EXPECT_THROW(polish_warp_by_error(w, f), InvalidInputError);
  ErrorPolishOptions o;
  o.isotropy = 0;
  EXPECT_THROW(check_polish_options(o), InvalidInputError);
  o.isotropy = 1.5;
  EXPECT_THROW(check_polish_options(o), InvalidInputError);
}
