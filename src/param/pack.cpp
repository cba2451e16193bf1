/// \file pack.cpp
/// Chart packing (§3.2, one chart per component): shelf packing of squares sized by sqrt(3-D area);
/// rectangles (multi-chart layouts): the best of shelf and MaxRects packings.
#include "adaptex/param/pack.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

/// Axis-aligned box of the packing (lower-left corner, width, height).
struct Box {
  double x, y, w, h;
};

/// MaxRects packing (Jylänki 2010, "A thousand ways to pack the bin", §5 MAXRECTS): the free space
/// is kept as the list of all maximal empty boxes; every rectangle goes to the free box that scores
/// best, and every free box it intersects is split into its (up to four) maximal remainders;
/// boxes contained in others are dropped. Rectangles are inflated by the gap and packed into the
/// box [0, 1 - gap]^2, which leaves exactly the gap between them and to the border.
class MaxRects {
 public:
  /// Heuristic: bottom-left (lowest top edge, then leftmost) or best short side fit (smallest
  /// leftover of the free box along its shorter side, then along its longer side).
  enum class Rule { BottomLeft, BestShortSide };

  MaxRects(double side, Rule rule) : rule_(rule) { free_.push_back({0, 0, side, side}); }

  /// Places a w x h box (turned to h x w if \p may_turn and that scores better). Returns false if
  /// it fits nowhere.
  bool insert(double w, double h, bool may_turn, Box* out, bool* turned) {
    double best1 = kNone, best2 = kNone;
    int best = -1;
    bool best_turned = false;
    for (int turn = 0; turn < (may_turn ? 2 : 1); ++turn) {
      const double bw = turn ? h : w, bh = turn ? w : h;
      for (size_t i = 0; i < free_.size(); ++i) {
        const Box& f = free_[i];
        if (bw > f.w || bh > f.h) continue;
        double s1, s2;
        if (rule_ == Rule::BottomLeft) {
          s1 = f.y + bh;
          s2 = f.x;
        } else {
          s1 = std::min(f.w - bw, f.h - bh);
          s2 = std::max(f.w - bw, f.h - bh);
        }
        if (s1 < best1 || (s1 == best1 && s2 < best2))
          best1 = s1, best2 = s2, best = static_cast<int>(i), best_turned = turn;
      }
    }
    if (best < 0) return false;
    const Box placed{free_[best].x, free_[best].y, best_turned ? h : w, best_turned ? w : h};
    split(placed);
    *out = placed;
    *turned = best_turned;
    return true;
  }

 private:
  static constexpr double kNone = std::numeric_limits<double>::max();

  static bool inside(const Box& a, const Box& b) {
    return a.x >= b.x && a.y >= b.y && a.x + a.w <= b.x + b.w && a.y + a.h <= b.y + b.h;
  }

  /// Splits every free box that \p p intersects into its maximal remainders. Boxes untouched by
  /// \p p were maximal and pairwise non-nested before, so only the new remainders need the
  /// containment test (against all boxes), and old boxes only against the new ones.
  void split(const Box& p) {
    std::vector<Box> old, fresh;
    old.reserve(free_.size());
    for (const Box& f : free_) {
      if (p.x >= f.x + f.w || p.x + p.w <= f.x || p.y >= f.y + f.h || p.y + p.h <= f.y) {
        old.push_back(f);
        continue;
      }
      if (p.x > f.x) fresh.push_back({f.x, f.y, p.x - f.x, f.h});
      if (p.x + p.w < f.x + f.w) fresh.push_back({p.x + p.w, f.y, f.x + f.w - p.x - p.w, f.h});
      if (p.y > f.y) fresh.push_back({f.x, f.y, f.w, p.y - f.y});
      if (p.y + p.h < f.y + f.h) fresh.push_back({f.x, p.y + p.h, f.w, f.y + f.h - p.y - p.h});
    }
    free_.clear();
    for (const Box& o : old) {
      bool gone = false;
      for (const Box& n : fresh) gone = gone || inside(o, n);
      if (!gone) free_.push_back(o);
    }
    // A new box goes if it lies in an old box or in another new one (of two equal ones the
    // first is kept).
    for (size_t i = 0; i < fresh.size(); ++i) {
      bool gone = false;
      for (const Box& o : old) gone = gone || inside(fresh[i], o);
      for (size_t j = 0; j < fresh.size() && !gone; ++j)
        gone = j != i && inside(fresh[i], fresh[j]) && !(j > i && inside(fresh[j], fresh[i]));
      if (!gone) free_.push_back(fresh[i]);
    }
  }

  Rule rule_;
  std::vector<Box> free_;
};

/// Above this many rectangles only the shelf packing is tried (all MaxRects strategies together
/// take about 0.4 s at 200 rectangles).
constexpr int kMaxRectsLimit = 200;

/// One packing strategy: an order of the rectangles and a placement method.
struct Strategy {
  std::vector<int> order;
  int method;  ///< 0 = shelf, 1 = MaxRects bottom-left, 2 = MaxRects best short side fit.
};

/// Packs rectangles sigma * size[i] in strategy \p s with gap \p gap everywhere (turning them by
/// 90° where that fits better if \p may_turn; the shelf method never turns). Returns false if they
/// do not fit.
bool pack_with(const std::vector<Vec2>& size, const Strategy& s, double sigma, double gap,
               bool may_turn, std::vector<RectPlacement>* out, std::vector<char>* turned) {
  if (s.method == 0) {  // shelves: rows left to right, bottom to top
    double x = gap, y = gap, shelf = 0;
    for (int i : s.order) {
      const double w = sigma * size[i].x(), h = sigma * size[i].y();
      if (x + w + gap > 1.0 && x > gap) {
        y += shelf + gap;
        x = gap;
        shelf = 0;
      }
      if (x + w + gap > 1.0 || y + h + gap > 1.0) return false;
      if (out) {
        (*out)[i] = {Vec2(x, y), Vec2(w, h)};
        (*turned)[i] = 0;
      }
      x += w + gap;
      shelf = std::max(shelf, h);
    }
    return true;
  }
  MaxRects bin(1.0 - gap, s.method == 1 ? MaxRects::Rule::BottomLeft : MaxRects::Rule::BestShortSide);
  for (int i : s.order) {
    const double w = sigma * size[i].x(), h = sigma * size[i].y();
    Box b{};
    bool t = false;
    if (!bin.insert(w + gap, h + gap, may_turn, &b, &t)) return false;
    if (out) {
      (*out)[i] = {Vec2(b.x + gap, b.y + gap), t ? Vec2(h, w) : Vec2(w, h)};
      (*turned)[i] = t;
    }
  }
  return true;
}

/// The largest uniform scale at which strategy \p s fits with gap \p gap (bisection, relative
/// accuracy 1e-4), or 0 if it does not fit at any scale.
double best_scale(const std::vector<Vec2>& size, const Strategy& s, double gap, bool may_turn) {
  if (!pack_with(size, s, 1e-9, gap, may_turn, nullptr, nullptr)) return 0;
  // No rectangle is larger than 1 (sizes are normalized by the largest side), and the rectangles
  // cannot cover more than the square: sigma <= min(1, 1 / sqrt(sum of areas)).
  double area = 0;
  for (const Vec2& r : size) area += r.x() * r.y();
  double lo = 1e-9, hi = std::min(1.0, 1.0 / std::sqrt(area));
  if (pack_with(size, s, hi, gap, may_turn, nullptr, nullptr)) return hi;
  while (hi - lo > 1e-4 * hi) {
    const double mid = 0.5 * (lo + hi);
    if (pack_with(size, s, mid, gap, may_turn, nullptr, nullptr)) lo = mid;
    else hi = mid;
  }
  return lo;
}

/// Shared body of pack_rectangles() and pack_rectangles_turning().
std::vector<RectPlacement> pack_rects(const std::vector<Vec2>& sizes, double padding, bool may_turn,
                                      std::vector<char>* turned_out) {
  if (sizes.empty()) throw InvalidInputError("pack_rectangles: no charts to pack");
  if (!(padding >= 0 && padding < 0.25))
    throw InvalidInputError("pack_rectangles: padding " + std::to_string(padding) +
                            " is outside [0, 0.25)");
  const int n = static_cast<int>(sizes.size());
  std::vector<RectPlacement> out(n);
  std::vector<char> turned(n, 0);
  if (n == 1) {
    if (turned_out) *turned_out = turned;
    return out;
  }
  double largest = 0;
  for (const Vec2& s : sizes) largest = std::max({largest, s.x(), s.y()});
  std::vector<Vec2> size(n);
  for (int i = 0; i < n; ++i)
    for (int d = 0; d < 2; ++d)
      size[i][d] = std::max(largest > 0 ? sizes[i][d] / largest : 1.0, 1e-3);
  // Orders: tallest, largest area, longest side, widest first (stable: ties keep input order).
  std::vector<std::vector<int>> orders;
  auto sorted = [&](auto key) {
    std::vector<int> o(n);
    std::iota(o.begin(), o.end(), 0);
    std::stable_sort(o.begin(), o.end(), [&](int a, int b) { return key(size[a]) > key(size[b]); });
    orders.push_back(std::move(o));
  };
  sorted([](const Vec2& s) { return s.y(); });
  sorted([](const Vec2& s) { return s.x() * s.y(); });
  sorted([](const Vec2& s) { return std::max(s.x(), s.y()); });
  sorted([](const Vec2& s) { return s.x(); });
  std::vector<Strategy> strategies{{orders[0], 0}};
  if (n <= kMaxRectsLimit)
    for (const auto& o : orders)
      for (int method : {1, 2}) strategies.push_back({o, method});
  // With turning: also the same strategies without turning on the rectangles all turned to
  // landscape (rows of alike shapes), whichever reaches the larger scale.
  std::vector<Vec2> landscape(size);
  std::vector<char> flat(n, 0);
  for (int i = 0; i < n; ++i)
    if (size[i].y() > size[i].x()) landscape[i] = Vec2(size[i].y(), size[i].x()), flat[i] = 1;
  for (double gap = padding;; gap *= 0.5) {
    if (gap < 1e-9) gap = 0;
    double best = 0;
    const Strategy* winner = nullptr;
    int variant = 0;  // 0: as given (turning if may_turn); 1: landscape, not turning
    for (int v = 0; v < (may_turn ? 2 : 1); ++v)
      for (const Strategy& s : strategies) {
        const double sigma = best_scale(v ? landscape : size, s, gap, v ? false : may_turn);
        if (sigma > best) best = sigma, winner = &s, variant = v;
      }
    if (winner && pack_with(variant ? landscape : size, *winner, best, gap, variant ? false : may_turn,
                            &out, &turned)) {
      if (variant) turned = flat;
      if (turned_out) *turned_out = turned;
      return out;
    }
    if (gap == 0) break;
  }
  throw InvalidInputError("pack_rectangles: " + std::to_string(n) +
                          " charts cannot be packed into the unit square");
}

}  // namespace

std::vector<RectPlacement> pack_rectangles(const std::vector<Vec2>& sizes, double padding) {
  return pack_rects(sizes, padding, false, nullptr);
}

std::vector<RectPlacement> pack_rectangles_turning(const std::vector<Vec2>& sizes, double padding,
                                                   std::vector<char>& turned) {
  return pack_rects(sizes, padding, true, &turned);
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
