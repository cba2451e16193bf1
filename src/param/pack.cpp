/// \file pack.cpp
/// Chart packing (§3.2, one chart per component): shelf packing of squares sized by sqrt(3-D area).
#include "adaptex/param/pack.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "adaptex/core/errors.h"

namespace adaptex {

namespace {

/// Shelf-packs squares of sides sigma * side[order[i]] (largest first) into the unit square with
/// gap \p gap everywhere. Returns false if they do not fit.
bool shelf_pack(const std::vector<double>& side, const std::vector<int>& order, double sigma,
                double gap, std::vector<ChartPlacement>* out) {
  double x = gap, y = gap, shelf = 0;
  for (int i : order) {
    const double a = sigma * side[i];
    if (x + a + gap > 1.0 && x > gap) {  // next shelf
      y += shelf + gap;
      x = gap;
      shelf = 0;
    }
    if (x + a + gap > 1.0 || y + a + gap > 1.0) return false;
    if (out) (*out)[i] = {Vec2(x, y), a};
    x += a + gap;
    shelf = std::max(shelf, a);
  }
  return true;
}

/// Shelf packing of rectangles sigma * size[order[i]] (tallest first) with gap \p gap everywhere.
bool shelf_pack_rects(const std::vector<Vec2>& size, const std::vector<int>& order, double sigma,
                      double gap, std::vector<RectPlacement>* out) {
  double x = gap, y = gap, shelf = 0;
  for (int i : order) {
    const double w = sigma * size[i].x(), h = sigma * size[i].y();
    if (x + w + gap > 1.0 && x > gap) {
      y += shelf + gap;
      x = gap;
      shelf = 0;
    }
    if (x + w + gap > 1.0 || y + h + gap > 1.0) return false;
    if (out) (*out)[i] = {Vec2(x, y), Vec2(w, h)};
    x += w + gap;
    shelf = std::max(shelf, h);
  }
  return true;
}

}  // namespace

std::vector<RectPlacement> pack_rectangles(const std::vector<Vec2>& sizes, double padding) {
  if (sizes.empty()) throw InvalidInputError("pack_rectangles: no charts to pack");
  if (!(padding >= 0 && padding < 0.25))
    throw InvalidInputError("pack_rectangles: padding " + std::to_string(padding) +
                            " is outside [0, 0.25)");
  const int n = static_cast<int>(sizes.size());
  std::vector<RectPlacement> out(n);
  if (n == 1) return out;
  double largest = 0;
  for (const Vec2& s : sizes) largest = std::max({largest, s.x(), s.y()});
  std::vector<Vec2> size(n);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d)
      size[i][d] = std::max(largest > 0 ? sizes[i][d] / largest : 1.0, 1e-3);
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return size[a].y() > size[b].y(); });
  for (double gap = padding;; gap *= 0.5) {
    if (gap < 1e-9) gap = 0;
    if (shelf_pack_rects(size, order, 1e-9, gap, nullptr)) {
      double lo = 0, hi = 1.0;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (shelf_pack_rects(size, order, mid, gap, nullptr)) lo = mid;
        else hi = mid;
      }
      if (lo > 0 && shelf_pack_rects(size, order, lo, gap, &out)) return out;
    }
    if (gap == 0) break;
  }
  throw InvalidInputError("pack_rectangles: " + std::to_string(n) +
                          " charts cannot be packed into the unit square");
}

std::vector<ChartPlacement> pack_charts(const std::vector<double>& areas, double padding) {
  if (areas.empty()) throw InvalidInputError("pack_charts: no charts to pack");
  if (!(padding >= 0 && padding < 0.25))
    throw InvalidInputError("pack_charts: padding " + std::to_string(padding) +
                            " is outside [0, 0.25)");
  const int n = static_cast<int>(areas.size());
  std::vector<ChartPlacement> out(n);
  if (n == 1) return out;  // one chart fills the unit square

  double max_area = 0;
  for (double a : areas) max_area = std::max(max_area, a);
  std::vector<double> side(n);
  for (int i = 0; i < n; ++i) {
    const double rel = max_area > 0 ? std::max(areas[i], 0.0) / max_area : 1.0;
    side[i] = std::max(std::sqrt(rel), 1e-3);  // tiny charts keep a usable size
  }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return side[a] > side[b]; });

  // Largest uniform scale sigma at which the shelf packing fits (bisection). If the gaps alone
  // cannot fit (thousands of charts), the gap is halved until they do.
  for (double gap = padding;; gap *= 0.5) {
    if (gap < 1e-9) gap = 0;
    double lo = 0, hi = 1.0;
    if (!shelf_pack(side, order, 1e-9, gap, nullptr)) {
      if (gap == 0) break;
      continue;
    }
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (shelf_pack(side, order, mid, gap, nullptr)) lo = mid;
      else hi = mid;
    }
    if (lo > 0 && shelf_pack(side, order, lo, gap, &out)) return out;
    if (gap == 0) break;
  }
  throw InvalidInputError("pack_charts: " + std::to_string(n) +
                          " charts cannot be packed into the unit square");
}

}  // namespace adaptex
