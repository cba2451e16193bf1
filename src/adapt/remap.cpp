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

SafeRemapResult safe_remap(const Parameterization& param, const std::vector<const GridWarp*>& warps,
                           const SafeRemapOptions& o) {
  const long overlaps_before = o.check_overlaps ? count_overlapping_triangles(param) : 0;
  SafeRemapResult res;
  auto attempt = [&](double t, Parameterization& out) {
    std::vector<GridWarp> damped;
    damped.reserve(warps.size());
    std::vector<const GridWarp*> ptrs;
    for (const GridWarp* w : warps) {
      damped.push_back(t == 1.0 ? *w : w->blended(t));
      ptrs.push_back(&damped.back());
    }
    out = remap_parameterization(param, ptrs);
    ++res.checks;
    RemapCheck c;
    const FlipCount fc = count_flips(param, out, o.min_area);
    c.flipped = fc.flipped;
    c.degenerate = fc.degenerate;
    if (o.check_overlaps && c.flipped == 0 && c.degenerate == 0)
      c.overlaps = std::max(0L, count_overlapping_triangles(out) - overlaps_before);
    return c;
  };
  Parameterization cand;
  RemapCheck c = attempt(1.0, cand);
  if (c.ok()) {
    res.param = std::move(cand);
    res.damping = 1.0;
    res.check = c;
    return res;
  }
  double lo = 0.0, hi = 1.0;
  res.param = param;
  res.damping = 0.0;
  for (int s = 0; s < o.bisection_steps; ++s) {
    const double mid = 0.5 * (lo + hi);
    c = attempt(mid, cand);
    if (c.ok()) {
      lo = mid;
      res.param = std::move(cand);
      res.damping = mid;
    } else {
      hi = mid;
    }
  }
  res.check = RemapCheck{};  // the returned layout is t = lo, checked ok (or the input itself)
  return res;
}

}  // namespace adaptex
