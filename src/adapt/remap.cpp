// Re-parameterization by the optimized grid (thesis §3.7.2) with the no-flip / no-overlap guarantee.
#include "adaptex/adapt/remap.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>

#include "adaptex/param/stretch.h"

namespace adaptex {

Parameterization remap_parameterization(const Parameterization& param, const std::vector<const GridWarp*>& warps) {
  Parameterization out = param;
  tbb::parallel_for(size_t(0), out.uv.size(), [&](size_t k) {
    Vec2 p = param.uv[k];
    for (const GridWarp* w : warps) p = w->apply(p);
    out.uv[k] = p.cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1));
  });
  return out;
}

namespace {
struct FlipCount {
  int flipped = 0, degenerate = 0;
};
FlipCount count_flips(const Parameterization& before, const Parameterization& after, double min_area) {
  const int F = static_cast<int>(before.uv_faces.size());
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(0, F, 4096), FlipCount{},
      [&](const tbb::blocked_range<int>& r, FlipCount c) {
        for (int f = r.begin(); f < r.end(); ++f) {
          const double a0 = uv_signed_area(before, f);
          if (std::abs(a0) <= min_area) continue;  // already degenerate in the input
          const double a1 = uv_signed_area(after, f) * (a0 > 0 ? 1.0 : -1.0);
          if (a1 <= 0) ++c.flipped;
          else if (a1 <= min_area) ++c.degenerate;
        }
        return c;
      },
      [](FlipCount a, const FlipCount& b) {
        a.flipped += b.flipped;
        a.degenerate += b.degenerate;
        return a;
      });
}
}  // namespace

RemapCheck check_remap(const Parameterization& before, const Parameterization& after, const SafeRemapOptions& o) {
  RemapCheck c;
  const FlipCount fc = count_flips(before, after, o.min_area);
  c.flipped = fc.flipped;
  c.degenerate = fc.degenerate;
  if (o.check_overlaps && c.flipped == 0 && c.degenerate == 0)
    c.overlaps = std::max(0L, count_overlapping_triangles(after) - count_overlapping_triangles(before));
  return c;
}

bool single_chart_on_square(const Parameterization& param) {
  if (param.num_charts != 1) return false;
  // Boundary edges of the UV mesh: edges used by exactly one UV face.
  std::vector<std::pair<long long, int>> edges;
  edges.reserve(param.uv_faces.size() * 3);
  for (const Face& f : param.uv_faces)
    for (int k = 0; k < 3; ++k) {
      const long long a = std::min(f[k], f[(k + 1) % 3]), b = std::max(f[k], f[(k + 1) % 3]);
      edges.push_back({a * (1LL << 31) + b, 0});
    }
  std::sort(edges.begin(), edges.end());
  auto on_square = [&](int w) {
    const Vec2& p = param.uv[w];
    const double e = 1e-9;
    return p.x() <= e || p.x() >= 1 - e || p.y() <= e || p.y() >= 1 - e;
  };
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    if (j - i == 1) {
      const int a = static_cast<int>(edges[i].first >> 31), b = static_cast<int>(edges[i].first & ((1LL << 31) - 1));
      if (!on_square(a) || !on_square(b)) return false;
    }
    i = j;
  }
  return true;
}

SafeRemapResult safe_remap(const Parameterization& param, const std::vector<const GridWarp*>& warps,
                           const SafeRemapOptions& o_in) {
  SafeRemapOptions o = o_in;
  // One chart whose boundary lies on the square's sides: grid points on the sides only slide along
  // them (here: stay fixed), so the boundary maps injectively onto itself; with no flipped triangle
  // the map is then globally injective (a local homeomorphism of a disk that is injective on its
  // boundary) and the O(F log F) overlap test is unnecessary.
  if (o.check_overlaps && single_chart_on_square(param)) o.check_overlaps = false;
  const long overlaps_before = o.check_overlaps ? count_overlapping_triangles(param) : 0;
  const Parameterization full = remap_parameterization(param, warps);
  const int F = static_cast<int>(param.uv_faces.size());
  SafeRemapResult res;
  std::vector<float> tw;
  // Candidate at global blend t: uv = old + t * tw_w * (warped - old). Faces that flip or degenerate
  // get their wedges' local factor tw halved, round after round (local damping: a few bad triangles
  // do not cost the whole warp); after max_local_rounds the global bisection on t takes over.
  auto attempt = [&](double t, Parameterization& out) {
    ++res.checks;
    out = param;
    tw.assign(param.uv.size(), 1.0f);
    auto place = [&](size_t w) { out.uv[w] = param.uv[w] + (t * tw[w]) * (full.uv[w] - param.uv[w]); };
    tbb::parallel_for(size_t(0), out.uv.size(), place);
    RemapCheck c;
    std::vector<int> bad;
    for (int round = 0; round <= o.max_local_rounds; ++round) {
      bad.clear();
      for (int f = 0; f < F; ++f) {
        const double a0 = uv_signed_area(param, f);
        if (std::abs(a0) <= o.min_area) continue;
        if (uv_signed_area(out, f) * (a0 > 0 ? 1.0 : -1.0) <= o.min_area) bad.push_back(f);
      }
      if (bad.empty() || round == o.max_local_rounds) break;
      for (int f : bad)
        for (int w : param.uv_faces[f]) tw[w] *= 0.5f;
      for (int f : bad)
        for (int w : param.uv_faces[f]) place(static_cast<size_t>(w));
    }
    const FlipCount fc = count_flips(param, out, o.min_area);
    c.flipped = fc.flipped;
    c.degenerate = fc.degenerate;
    if (o.check_overlaps && c.flipped == 0 && c.degenerate == 0)
      c.overlaps = std::max(0L, count_overlapping_triangles(out) - overlaps_before);
    return c;
  };
  auto finish = [&](double t) {
    res.damping = t;
    res.locally_damped = 0;
    double sum = 0;
    for (float x : tw) {
      if (x < 1.0f) ++res.locally_damped;
      sum += x;
    }
    res.mean_damping = tw.empty() ? t : t * sum / tw.size();
  };
  Parameterization cand;
  RemapCheck c = attempt(1.0, cand);
  if (c.ok()) {
    res.param = std::move(cand);
    res.check = c;
    finish(1.0);
    return res;
  }
  double lo = 0.0, hi = 1.0;
  res.param = param;
  res.damping = 0.0;
  res.mean_damping = 0.0;
  std::vector<float> best_tw(param.uv.size(), 0.0f);
  for (int s = 0; s < o.bisection_steps; ++s) {
    const double mid = 0.5 * (lo + hi);
    c = attempt(mid, cand);
    if (c.ok()) {
      lo = mid;
      res.param = std::move(cand);
      best_tw = tw;
    } else {
      hi = mid;
    }
  }
  tw = best_tw;
  finish(lo);
  res.check = RemapCheck{};  // the returned layout is t = lo, checked ok (or the input itself)
  return res;
}

}  // namespace adaptex
