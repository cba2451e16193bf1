/// \file error_model.cpp
/// The error model of the shrink: per island, how much error a box-downsized copy of every map leaves
/// at each texel spacing (measured on surface samples, so each island counts by its surface area),
/// and the island scales that minimise the total error for the texel budget (equal marginal gain).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <queue>

#include "adaptex/core/errors.h"
#include "adaptex/paint/asset_eval.h"
#include "adaptex/paint/eval.h"
#include "shrink_internal.h"

namespace adaptex {

namespace shrink_detail {

namespace {

constexpr int kLevels = 15;  // spacings 1/1024 · 2^(l/2): 1/1024 ... 1/8

double level_spacing(int l) { return std::pow(2.0, 0.5 * l) / 1024.0; }

/// Squared error of \p rec against \p ref for a map of \p kind, in units of colour MSE (mean over RGB):
/// a normal map by the Lambert shading change it causes under a light uniform over the sphere
/// (E[(Δn·l)²] = |Δn|²/3, times the albedo's mean square).
double kind_error(MapKind kind, const Vec3& ref, const Vec3& rec, double albedo_sq) {
  const double d = (ref - rec).squaredNorm();
  switch (kind) {
    case MapKind::Color: return d / 3.0;
    case MapKind::Normal: return albedo_sq * 4.0 * d / 3.0;
    case MapKind::Data: return 0.25 * d / 3.0;
  }
  return d / 3.0;
}

}  // namespace

ErrorCurves island_error_curves(const SampleSet& set, size_t stride, const Parameterization& layout,
                                const std::vector<int>& face_island, int num_islands,
                                const std::vector<ShrinkMap>& maps, double h_min, double h_max) {
  ErrorCurves curves;
  for (int l = 0; l < kLevels; ++l) curves.spacing.push_back(level_spacing(l));
  curves.error.assign(num_islands, std::vector<double>(kLevels, 0.0));
  curves.weight.assign(num_islands, 0.0);
  stride = std::max<size_t>(stride, 1);
  const size_t K = (set.points().size() + stride - 1) / stride;
  const auto point = [&](size_t k) -> const SurfacePoint& { return set.points()[k * stride]; };
  std::vector<Vec2> uv(K);
  for (size_t k = 0; k < K; ++k) {
    const Face& t = layout.uv_faces[point(k).face];
    uv[k] = point(k).b0 * layout.uv[t[0]] + point(k).b1 * layout.uv[t[1]] + (1 - point(k).b0 - point(k).b1) * layout.uv[t[2]];
  }
  // The measured levels: those the budget reads, with one level of margin.
  int l_lo = 0, l_hi = kLevels - 1;
  while (l_lo + 1 < kLevels && level_spacing(l_lo + 1) <= 0.5 * h_min) ++l_lo;
  while (l_hi > l_lo && level_spacing(l_hi - 1) >= 2.0 * h_max) --l_hi;
  // Albedo's mean square at each sample (for normal maps): the first colour map, else mid grey.
  std::vector<double> albedo_sq(K, 0.25);
  for (size_t m = 0; m < maps.size(); ++m)
    if (maps[m].kind == MapKind::Color) {
      for (size_t k = 0; k < K; ++k) albedo_sq[k] = set.reference(m)[k * stride].squaredNorm() / 3.0;
      break;
    }
  std::vector<double> err(K * kLevels, 0.0);
  for (size_t mi = 0; mi < maps.size(); ++mi) {
    const ShrinkMap& m = maps[mi];
    std::vector<ImageRGBA8> level(kLevels);
    for (int l = l_lo; l <= l_hi; ++l) {
      const int S = static_cast<int>(std::lround(1.0 / level_spacing(l)));
      const int w = std::min(m.image.width, S), h = std::min(m.image.height, S);
      if (w == m.image.width && h == m.image.height) continue;  // no coarser than the map: error ~0
      const ImageRGBA8& src = l - 2 >= l_lo && !level[l - 2].empty() ? level[l - 2] : m.image;
      level[l] = box_downsize(src, w, h);
    }
    tbb::parallel_for(tbb::blocked_range<size_t>(0, K, 2048), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t k = r.begin(); k < r.end(); ++k) {
        const Vec3& ref = set.reference(mi)[k * stride];
        for (int l = l_lo; l <= l_hi; ++l)
          if (!level[l].empty())
            err[k * kLevels + l] +=
                kind_error(m.kind, ref, sample_bilinear(level[l], uv[k].x(), uv[k].y()), albedo_sq[k]);
      }
    });
  }
  for (size_t k = 0; k < K; ++k) {  // levels outside the measured range: the nearest measured one
    for (int l = 0; l < l_lo; ++l) err[k * kLevels + l] = err[k * kLevels + l_lo];
    for (int l = l_hi + 1; l < kLevels; ++l) err[k * kLevels + l] = err[k * kLevels + l_hi];
  }
  curves.stride = stride;
  curves.sample_error.assign(err.begin(), err.end());
  std::vector<long> count(num_islands, 0);
  for (size_t k = 0; k < K; ++k) {
    const int i = face_island[point(k).face];
    ++count[i];
    for (int l = 0; l < kLevels; ++l) curves.error[i][l] += err[k * kLevels + l];
  }
  for (int i = 0; i < num_islands; ++i) {
    curves.weight[i] = K ? static_cast<double>(count[i]) / static_cast<double>(K) : 0.0;
    for (int l = 0; l < kLevels; ++l) curves.error[i][l] /= std::max(1L, count[i]);
    // A coarser copy never reconstructs better in the model (measurement noise aside).
    for (int l = 1; l < kLevels; ++l) curves.error[i][l] = std::max(curves.error[i][l], curves.error[i][l - 1]);
  }
  return curves;
}

namespace {
/// Log-log interpolation of the level errors \p e (kLevels of them) at spacing \p h.
template <class T>
double level_error(const T* e, const std::vector<double>& s, double h) {
  if (h <= s.front()) return e[0] * h / s.front();
  if (h >= s.back()) return e[kLevels - 1];
  const double t = std::log2(h / s.front()) * 2.0;
  const int l = std::min(static_cast<int>(t), kLevels - 2);
  const double f = t - l;
  constexpr double kTiny = 1e-12;
  return std::exp((1 - f) * std::log(e[l] + kTiny) + f * std::log(e[l + 1] + kTiny)) - kTiny;
}
}  // namespace

double island_error(const ErrorCurves& curves, int i, double h) {
  return level_error(curves.error[i].data(), curves.spacing, h);
}

double sample_error(const ErrorCurves& curves, size_t k, double h) {
  return level_error(curves.sample_error.data() + k * kLevels, curves.spacing, h);
}

std::vector<double> allocate_island_scales(const ErrorCurves& curves, const std::vector<double>& area,
                                           double budget, double size, double max_ratio) {
  const int I = static_cast<int>(area.size());
  double total_area = 0;
  for (double a : area) total_area += a;
  const double s_uniform = total_area > 0 ? std::sqrt(budget / total_area) : 1.0;
  if (!(total_area > 0) || I == 0) return std::vector<double>(I, s_uniform);
  constexpr int kStepsPerOctave = 8;
  const int T = std::max(0, static_cast<int>(std::lround(kStepsPerOctave * std::log2(std::max(1.0, max_ratio)))));
  // Scales and every island's weighted error at each step, computed once (the hulls read them often).
  const int steps = 2 * T + 1;
  std::vector<double> scales(steps), errors(static_cast<size_t>(I) * steps);
  for (int t = -T; t <= T; ++t) scales[t + T] = s_uniform * std::pow(2.0, static_cast<double>(t) / kStepsPerOctave);
  for (int i = 0; i < I; ++i)
    for (int t = -T; t <= T; ++t)
      errors[static_cast<size_t>(i) * steps + t + T] =
          curves.weight[i] * island_error(curves, i, 1.0 / (size * scales[t + T]));
  auto scale = [&](int t) { return scales[t + T]; };
  auto cost = [&](int i, int t) { return area[i] * scale(t) * scale(t); };
  auto err = [&](int i, int t) { return errors[static_cast<size_t>(i) * steps + t + T]; };
  // Per island, the lower convex hull of (cost, error) over the levels: greedy steps along the hulls
  // give every unit of area where it removes the most error, even across flat stretches of e_i.
  std::vector<std::vector<int>> hull(I);
  for (int i = 0; i < I; ++i) {
    if (!(area[i] > 0)) {
      hull[i] = {T};
      continue;
    }
    std::vector<int>& h = hull[i];
    for (int t = -T; t <= T; ++t) {
      // Pop while the last point lies on or above the segment from its predecessor to t.
      while (h.size() >= 2) {
        const int a = h[h.size() - 2], b = h.back();
        const double cross = (cost(i, b) - cost(i, a)) * (err(i, t) - err(i, a)) -
                             (err(i, b) - err(i, a)) * (cost(i, t) - cost(i, a));
        if (cross <= 0) h.pop_back();  // b is not below the chord a -> t
        else break;
      }
      h.push_back(t);
    }
    // Keep the decreasing part (more area never costs error in the model).
    size_t m = 1;
    while (m < h.size() && err(i, h[m]) < err(i, h[m - 1])) ++m;
    h.resize(m);
  }
  std::vector<size_t> pos(I, 0);
  std::vector<int> partial(I, -T);
  double used = 0;
  for (int i = 0; i < I; ++i) used += cost(i, hull[i][0]);
  struct Step {
    double ratio;
    int island;
    bool operator<(const Step& o) const { return ratio < o.ratio; }
  };
  auto step = [&](int i) {
    const int a = hull[i][pos[i]], b = hull[i][pos[i] + 1];
    return Step{(err(i, a) - err(i, b)) / std::max(1e-300, cost(i, b) - cost(i, a)), i};
  };
  std::priority_queue<Step> queue;
  for (int i = 0; i < I; ++i)
    if (hull[i].size() > 1) queue.push(step(i));
  while (!queue.empty()) {
    const int i = queue.top().island;
    queue.pop();
    const double dc = cost(i, hull[i][pos[i] + 1]) - cost(i, hull[i][pos[i]]);
    if (used + dc > budget) {
      // The whole step does not fit: go as far towards it as the budget allows; the island is done.
      int t = hull[i][pos[i]];
      while (t < hull[i][pos[i] + 1] && used + cost(i, t + 1) - cost(i, hull[i][pos[i]]) <= budget) ++t;
      used += cost(i, t) - cost(i, hull[i][pos[i]]);
      partial[i] = t;
      continue;
    }
    used += dc;
    if (++pos[i] + 1 < hull[i].size()) queue.push(step(i));
  }
  std::vector<int> level(I);
  for (int i = 0; i < I; ++i) level[i] = std::max(hull[i][pos[i]], partial[i]);
  std::vector<double> out(I);
  for (int i = 0; i < I; ++i) out[i] = scale(level[i]);
  return out;
}

}  // namespace shrink_detail

}  // namespace adaptex
