/// \file island_warp.cpp
/// The warp of each island inside itself: a density-equalizing map (density_flow.h) of the island's
/// bounding box whose area follows the error model's error density (more texels where detail is), the
/// same map for every chart of the island, damped towards identity until every face keeps its orientation.
#include <algorithm>
#include <cmath>
#include <functional>

#include "adaptex/adapt/density_flow.h"
#include "adaptex/paint/asset_eval.h"
#include "adaptex/core/predicates.h"
#include "shrink_internal.h"

namespace adaptex::shrink_detail {

namespace {

constexpr int kMaxCells = 64;           // lattice cells per side, at most
constexpr int kMinCells = 4;            // and at least
constexpr double kTexelsPerCell = 2.0;  // lattice cell: about 2 output texels along the island's longer side
constexpr int kSub = 4;                 // coverage raster: kSub x kSub points per cell
constexpr double kExponent = 2.0 / 3.0;  // area ∝ (error per area)^(2/3): optimal for MSE ∝ h (edges)
constexpr double kMinAreaKept = 0.05;    // a face may shrink to 5 % of its area, not below
constexpr double kNoDetail = 1e-9;       // mean error per sample below which an island stays as it is (90 dB)


/// The faces and wedges of every island.
struct IslandParts {
  std::vector<std::vector<int>> faces, wedges;
};
IslandParts island_parts(const Parameterization& layout, const std::vector<int>& face_island, int num_islands) {
  IslandParts p;
  p.faces.resize(num_islands);
  p.wedges.resize(num_islands);
  std::vector<char> seen(layout.uv.size(), 0);
  for (size_t f = 0; f < layout.uv_faces.size(); ++f) {
    p.faces[face_island[f]].push_back(static_cast<int>(f));
    for (int w : layout.uv_faces[f])
      if (!seen[w]) {
        seen[w] = 1;
        p.wedges[face_island[f]].push_back(w);
      }
  }
  return p;
}

/// Target area density of every cell of an L x L lattice (covered cells; 0 elsewhere).
/// Power law: area ∝ (error / covered area)^kExponent from the error \p sum[c · levels + at] at the
/// island's spacing. Measured curves: the allocation of allocate_island_scales() with the cells as
/// islands (each cell's mean error at every spacing, covered area kept), scale² per cell.
std::vector<double> cell_density(const std::vector<double>& sum, const std::vector<double>& count,
                                 const std::vector<double>& cover, const ErrorCurves& curves, size_t at,
                                 double texels, double ratio, bool measured) {
  const size_t C = cover.size(), levels = curves.spacing.size();
  std::vector<double> rho(C, 0.0);
  if (!measured) {
    for (size_t c = 0; c < C; ++c)
      if (cover[c] > 0) rho[c] = std::pow(sum[c * levels + at] / cover[c], kExponent);
    return rho;
  }
  ErrorCurves cells;
  cells.spacing = curves.spacing;
  cells.error.assign(C, std::vector<double>(levels, 0.0));
  cells.weight.assign(C, 0.0);
  double n = 0, budget = 0;
  for (size_t c = 0; c < C; ++c) n += count[c], budget += cover[c];
  for (size_t c = 0; c < C; ++c) {
    if (!(count[c] > 0)) continue;
    cells.weight[c] = count[c] / n;
    for (size_t l = 0; l < levels; ++l) {
      cells.error[c][l] = sum[c * levels + l] / count[c];
      if (l > 0) cells.error[c][l] = std::max(cells.error[c][l], cells.error[c][l - 1]);
    }
  }
  const std::vector<double> s = allocate_island_scales(cells, cover, budget, texels, ratio);
  for (size_t c = 0; c < C; ++c)
    if (cover[c] > 0) rho[c] = s[c] * s[c];
  return rho;
}

/// The 2-D density-equalizing warp (density_flow.h) of an L x L lattice whose cells should get area
/// ∝ \p rho (blurred), uncovered cells the least, clamped to ratio² between cells.
GridWarp lattice_warp(std::vector<double> rho, int L, double ratio) {
  gaussian_blur(rho, L, 1.0);
  const double top = *std::max_element(rho.begin(), rho.end());
  if (!(top > 0)) return GridWarp::uniform(1);
  ImageF density(L, L);
  for (int j = 0; j < L; ++j)
    for (int i = 0; i < L; ++i) density.at(i, j) = static_cast<float>(std::max(rho[j * L + i], top / (ratio * ratio)));
  DensityFlowOptions o;
  o.cells = 2 * L;
  o.parallel = false;
  return density_equalizing_warp(density, o);
}

/// Covered share of every cell of island \p faces' L x L lattice over [lo, lo + ext] (union of the
/// faces, kSub² points a cell).
std::vector<double> lattice_cover(const Parameterization& layout, const std::vector<int>& faces, const Vec2& lo,
                                  const Vec2& ext, int L) {
  const int S = kSub * L;
  std::vector<char> hit(static_cast<size_t>(S) * S, 0);
  for (int f : faces) {
    const Face& t = layout.uv_faces[f];
    auto q = [&](int c) { return Vec2((layout.uv[t[c]] - lo).cwiseQuotient(ext)); };
    for_each_texel_centre(q(0), q(1), q(2), S, S, [&](int a, int b) {
      if (a >= 0 && a < S && b >= 0 && b < S) hit[static_cast<size_t>(b) * S + a] = 1;
    });
  }
  std::vector<double> cover(static_cast<size_t>(L) * L, 0.0);
  for (int b = 0; b < S; ++b)
    for (int a = 0; a < S; ++a)
      if (hit[static_cast<size_t>(b) * S + a]) cover[(b / kSub) * L + a / kSub] += 1.0 / (kSub * kSub);
  return cover;
}

/// Moves island \p wedges of \p out by (1 − t)·identity + t·map for the largest t (1, else bisected) at
/// which every face of \p faces keeps its orientation in \p layout and kMinAreaKept of its area. \return t
double damped_warp(const Parameterization& layout, const std::vector<int>& faces, const std::vector<int>& wedges,
                   const std::function<Vec2(const Vec2&)>& map, Parameterization& out) {
  auto apply = [&](double t) {
    for (int w : wedges) out.uv[w] = layout.uv[w] + t * (map(layout.uv[w]) - layout.uv[w]);
  };
  auto valid = [&](double t) {
    apply(t);
    for (int f : faces) {
      const Face& tf = layout.uv_faces[f];
      const double a0 = triangle_signed_area(layout.uv[tf[0]], layout.uv[tf[1]], layout.uv[tf[2]]);
      const double a1 = triangle_signed_area(out.uv[tf[0]], out.uv[tf[1]], out.uv[tf[2]]);
      if (a0 != 0 && (a0 > 0 ? a1 : -a1) < kMinAreaKept * std::abs(a0)) return false;
    }
    return true;
  };
  if (valid(1.0)) return 1.0;
  double good = 0, bad = 1.0;
  for (int step = 0; step < 8; ++step) {
    const double t = 0.5 * (good + bad);
    (valid(t) ? good : bad) = t;
  }
  apply(good);
  return good;
}

}  // namespace

Parameterization warp_islands(const SampleSet& set, const ErrorCurves& curves, const Parameterization& layout,
                              const std::vector<int>& face_island, int num_islands,
                              const std::vector<double>& texels, const std::vector<double>& face_texels,
                              double max_ratio, bool measured, std::vector<double>* blend) {
  Parameterization out = layout;
  blend->assign(num_islands, 0.0);
  const IslandParts parts = island_parts(layout, face_island, num_islands);
  std::vector<Vec2> lo(num_islands, Vec2::Constant(1e300)), hi(num_islands, Vec2::Constant(-1e300));
  for (int i = 0; i < num_islands; ++i)
    for (int w : parts.wedges[i]) lo[i] = lo[i].cwiseMin(layout.uv[w]), hi[i] = hi[i].cwiseMax(layout.uv[w]);
  // Per island, a square lattice over its bounding box (cells of about kTexelsPerCell output texels).
  std::vector<int> cells(num_islands, 0);
  const size_t levels = curves.spacing.size();
  std::vector<std::vector<double>> sum(num_islands), count(num_islands);  // per cell (x levels) / samples
  std::vector<double> total(num_islands, 0.0);
  std::vector<long> samples(num_islands, 0);
  for (int i = 0; i < num_islands; ++i) {
    const Vec2 ext = hi[i] - lo[i];
    if (parts.wedges[i].empty() || !(ext.x() > 0) || !(ext.y() > 0)) continue;
    cells[i] = std::clamp(static_cast<int>(std::lround(ext.maxCoeff() * texels[i] / kTexelsPerCell)), kMinCells,
                          kMaxCells);
    sum[i].assign(static_cast<size_t>(cells[i]) * cells[i] * levels, 0.0);
    count[i].assign(static_cast<size_t>(cells[i]) * cells[i], 0.0);
  }
  // Error of every measured sample at every spacing (the island's own in slot `at` for the power
  // law: levels are replaced by the interpolated value there), into its lattice cell.
  const size_t at = 0;
  const size_t K = curves.sample_error.size() / std::max<size_t>(1, levels);
  for (size_t k = 0; k < K; ++k) {
    const SurfacePoint& p = set.points()[k * curves.stride];
    const int i = face_island[p.face], L = cells[i];
    if (count[i].empty()) continue;
    const Face& t = layout.uv_faces[p.face];
    const Vec2 uv = p.b0 * layout.uv[t[0]] + p.b1 * layout.uv[t[1]] + (1 - p.b0 - p.b1) * layout.uv[t[2]];
    const Vec2 q = (uv - lo[i]).cwiseQuotient(hi[i] - lo[i]);
    const int cx = std::clamp(static_cast<int>(q.x() * L), 0, L - 1);
    const int cy = std::clamp(static_cast<int>(q.y() * L), 0, L - 1);
    const size_t c = static_cast<size_t>(cy) * L + cx;
    const double e = sample_error(curves, k, 1.0 / (face_texels.empty() ? texels[i] : face_texels[p.face]));
    if (measured)
      for (size_t l = 0; l < levels; ++l) sum[i][c * levels + l] += curves.sample_error[k * levels + l];
    else
      sum[i][c * levels + at] += e;
    count[i][c] += 1;
    total[i] += e, ++samples[i];
  }
  for (int i = 0; i < num_islands; ++i) {
    if (count[i].empty() || !(total[i] > kNoDetail * static_cast<double>(samples[i]))) continue;
    const Vec2 ext = hi[i] - lo[i];
    const std::vector<double> cover = lattice_cover(layout, parts.faces[i], lo[i], ext, cells[i]);
    const GridWarp grid = lattice_warp(
        cell_density(sum[i], count[i], cover, curves, at, texels[i], max_ratio, measured), cells[i], max_ratio);
    const auto map = [&](const Vec2& p) {
      return Vec2(lo[i] + grid.apply_lattice((p - lo[i]).cwiseQuotient(ext)).cwiseProduct(ext));
    };
    (*blend)[i] = damped_warp(layout, parts.faces[i], parts.wedges[i], map, out);
  }
  return out;
}

}  // namespace adaptex::shrink_detail
