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

  /// \p max_free bounds the free list (normally O(n)): a packing whose free list grows past it is
  /// given up (insert() returns false), so that no input makes a strategy quadratic per insert.
  MaxRects(double side, Rule rule, size_t max_free) : rule_(rule), max_free_(max_free) {
    free_.push_back({0, 0, side, side});
  }

  /// Places a w x h box (turned to h x w if \p may_turn and that scores better). Returns false if
  /// it fits nowhere.
  bool insert(double w, double h, bool may_turn, Box* out, bool* turned) {
    if (free_.size() > max_free_) return false;
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
  size_t max_free_;
  std::vector<Box> free_;
};

/// Above this many rectangles only the shelf packings are tried (all MaxRects strategies together
/// take about 0.12 s of CPU at 200 rectangles, 0.5 s at 500: docs/bench_unwrap.md).
constexpr int kMaxRectsLimit = 500;

/// One packing strategy: an order of the rectangles and a placement method.
struct Strategy {
  std::vector<int> order;
  int method;  ///< 0 = shelf, 1 = MaxRects bottom-left, 2 = MaxRects best short side fit.
};

/// Rectangle \p size at scale \p sigma, enlarged uniformly so that its shorter side is at least
/// \p min_side (RectPackOptions::min_side).
Vec2 scaled(const Vec2& size, double sigma, double min_side) {
  const Vec2 r = sigma * size;
  const double shorter = std::min(r.x(), r.y());
  return shorter < min_side ? Vec2(r * (min_side / shorter)) : r;
}

/// Packs rectangles scaled(size[i], sigma, min_side) in strategy \p s with gap \p gap everywhere
/// (turning them by 90° where that fits better if \p may_turn; the shelf method never turns).
/// Returns false if they do not fit.
bool pack_with(const std::vector<Vec2>& size, const Strategy& s, double sigma, double gap,
               double min_side, bool may_turn, std::vector<RectPlacement>* out,
               std::vector<char>* turned) {
  if (s.method == 0) {  // shelves: rows left to right, bottom to top
    double x = gap, y = gap, shelf = 0;
    for (int i : s.order) {
      const Vec2 r = scaled(size[i], sigma, min_side);
      const double w = r.x(), h = r.y();
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
  MaxRects bin(1.0 - gap, s.method == 1 ? MaxRects::Rule::BottomLeft : MaxRects::Rule::BestShortSide,
               1000 + 64 * s.order.size());
  for (int i : s.order) {
    const Vec2 r = scaled(size[i], sigma, min_side);
    const double w = r.x(), h = r.y();
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
double best_scale(const std::vector<Vec2>& size, const Strategy& s, double gap, double min_side,
                  bool may_turn) {
  if (!pack_with(size, s, 1e-9, gap, min_side, may_turn, nullptr, nullptr)) return 0;
  // No rectangle is larger than 1 (sizes are normalized by the largest side), and the rectangles
  // cannot cover more than the square: sigma <= min(1, 1 / sqrt(sum of areas)).
  double area = 0;
  for (const Vec2& r : size) area += r.x() * r.y();
  double lo = 1e-9, hi = std::min(1.0, 1.0 / std::sqrt(area));
  if (pack_with(size, s, hi, gap, min_side, may_turn, nullptr, nullptr)) return hi;
  while (hi - lo > 1e-4 * hi) {
    const double mid = 0.5 * (lo + hi);
    if (pack_with(size, s, mid, gap, min_side, may_turn, nullptr, nullptr)) lo = mid;
    else hi = mid;
  }
  return lo;
}

/// Max-tree over the free widths of the shelves of pack_ffdh(): the first shelf with at least a
/// given free width in O(log n).
class ShelfWidths {
 public:
  explicit ShelfWidths(int n) {
    while (cap_ < n) cap_ *= 2;
    tree_.assign(2 * static_cast<size_t>(cap_), -1.0);
  }
  double get(int i) const { return tree_[cap_ + i]; }
  void set(int i, double w) {
    i += cap_;
    tree_[i] = w;
    for (i /= 2; i >= 1; i /= 2) tree_[i] = std::max(tree_[2 * i], tree_[2 * i + 1]);
  }
  /// The lowest shelf index with free width >= \p w, or -1.
  int first_at_least(double w) const {
    if (tree_[1] < w) return -1;
    int i = 1;
    while (i < cap_) i = tree_[2 * i] >= w ? 2 * i : 2 * i + 1;
    return i - cap_;
  }

 private:
  int cap_ = 1;
  std::vector<double> tree_;
};

/// First-fit decreasing-height shelf packing (Coffman et al. 1980) of the rectangles
/// scaled(size[i], sigma, min_side) with gap \p gap everywhere: by decreasing height, each goes
/// to the lowest shelf with room for it, or opens a shelf on top. O(n log n). Returns false if
/// they do not fit. \p order is scratch space (n entries).
bool pack_ffdh(const std::vector<Vec2>& size, double sigma, double gap, double min_side,
               std::vector<int>& order, std::vector<RectPlacement>* out) {
  const int n = static_cast<int>(size.size());
  std::vector<Vec2> r(n);
  for (int i = 0; i < n; ++i) r[i] = scaled(size[i], sigma, min_side);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return r[a].y() > r[b].y(); });
  ShelfWidths free(n);
  std::vector<double> shelf_y;
  double top = gap;  // lower edge of the next shelf
  for (int i : order) {
    const double w = r[i].x(), h = r[i].y();
    if (w + 2 * gap > 1.0) return false;
    int s = free.first_at_least(w + gap);
    if (s < 0) {
      if (top + h + gap > 1.0) return false;
      s = static_cast<int>(shelf_y.size());
      shelf_y.push_back(top);
      top += h + gap;
      free.set(s, 1.0 - gap);
    }
    if (out) (*out)[i] = {Vec2(1.0 - free.get(s), shelf_y[s]), Vec2(w, h)};
    free.set(s, free.get(s) - w - gap);
  }
  return true;
}

/// The largest scale at which pack_ffdh() fits (bisection on log(sigma) to a relative 1e-4, at
/// most 40 steps), or 0 if it fits at no scale. Reports "pack" progress from \p frac0 to \p frac1.
double ffdh_scale(const std::vector<Vec2>& size, double gap, double min_side,
                  const ProgressCallback& progress, double frac0, double frac1) {
  std::vector<int> order(size.size());
  double lo = 1e-9;
  if (!pack_ffdh(size, lo, gap, min_side, order, nullptr)) return 0;
  double area = 0;
  for (const Vec2& r : size) area += r.x() * r.y();
  double hi = std::min(1.0, 1.0 / std::sqrt(area));
  if (pack_ffdh(size, hi, gap, min_side, order, nullptr)) return hi;
  for (int step = 0; step < 40 && hi > lo * (1 + 1e-4); ++step) {
    report_progress(progress, "pack", frac0 + (frac1 - frac0) * step / 40.0);
    const double mid = std::sqrt(lo * hi);
    if (pack_ffdh(size, mid, gap, min_side, order, nullptr)) lo = mid;
    else hi = mid;
  }
  return lo;
}

/// Sizes normalized by the largest finite side; a rectangle with a side below 1e-3 is enlarged
/// uniformly to that side (its shape kept, the longer side at most 1). Non-finite and
/// non-positive entries get the smallest size, 1e-3 square.
std::vector<Vec2> normalized_sizes(const std::vector<Vec2>& sizes) {
  constexpr double kSmallest = 1e-3;
  double largest = 0;
  for (const Vec2& s : sizes)
    for (int d = 0; d < 2; ++d)
      if (std::isfinite(s[d])) largest = std::max(largest, s[d]);
  std::vector<Vec2> size(sizes.size(), Vec2(kSmallest, kSmallest));
  if (!(largest > 0)) return size;
  for (size_t i = 0; i < sizes.size(); ++i) {
    const Vec2& s = sizes[i];
    if (!(std::isfinite(s.x()) && std::isfinite(s.y()) && s.x() > 0 && s.y() > 0)) continue;
    Vec2 v = s / largest;
    if (v.minCoeff() < kSmallest) v *= kSmallest / v.minCoeff();
    size[i] = v.cwiseMin(1.0);
  }
  return size;
}

/// More than kMaxRectsLimit rectangles: FFDH shelves and next-fit shelves (tallest first), each as
/// given and, if \p may_turn, all turned landscape; the largest scale wins. The gap and the
/// minimum side are halved while even they alone do not fit.
std::vector<RectPlacement> pack_many(const std::vector<Vec2>& size, double padding, double min_side_0,
                                     bool may_turn, const ProgressCallback& progress,
                                     std::vector<char>& turned) {
  const int n = static_cast<int>(size.size());
  std::vector<Vec2> landscape(size);
  std::vector<char> flat(n, 0);
  for (int i = 0; i < n; ++i)
    if (size[i].y() > size[i].x()) landscape[i] = Vec2(size[i].y(), size[i].x()), flat[i] = 1;
  std::vector<RectPlacement> out(n);
  std::vector<int> order(n);
  for (double gap = padding, min_side = min_side_0;; gap *= 0.5, min_side *= 0.5) {
    if (gap < 1e-9) gap = 0;
    if (min_side < 1e-9) min_side = 0;
    const int variants = may_turn ? 2 : 1;
    double best = 0;
    int winner = -1;  // 2 v + (0: FFDH, 1: next fit)
    Strategy shelf[2];
    for (int v = 0; v < variants; ++v) {
      const std::vector<Vec2>& sz = v ? landscape : size;
      shelf[v].method = 0;
      shelf[v].order.resize(n);
      std::iota(shelf[v].order.begin(), shelf[v].order.end(), 0);
      std::stable_sort(shelf[v].order.begin(), shelf[v].order.end(),
                       [&](int a, int b) { return sz[a].y() > sz[b].y(); });
      const double f0 = static_cast<double>(v) / variants, f1 = (v + 1.0) / variants;
      const double ffdh = ffdh_scale(sz, gap, min_side, progress, f0, 0.5 * (f0 + f1));
      if (ffdh > best) best = ffdh, winner = 2 * v;
      const double next_fit = best_scale(sz, shelf[v], gap, min_side, false);
      if (next_fit > best) best = next_fit, winner = 2 * v + 1;
    }
    if (winner >= 0) {
      const int v = winner / 2;
      const std::vector<Vec2>& sz = v ? landscape : size;
      const bool ok = winner % 2 == 0
                          ? pack_ffdh(sz, best, gap, min_side, order, &out)
                          : pack_with(sz, shelf[v], best, gap, min_side, false, &out, &turned);
      if (ok) {
        turned = v ? flat : std::vector<char>(n, 0);
        return out;
      }
    }
    if (gap == 0 && min_side == 0) break;
  }
  throw InvalidInputError("pack_rectangles: " + std::to_string(n) +
                          " charts cannot be packed into the unit square");
}

/// Body of every pack_rectangles(): up to kMaxRectsLimit rectangles the best of the shelf and
/// MaxRects strategies, above that pack_many().
std::vector<RectPlacement> pack_rects(const std::vector<Vec2>& sizes, const RectPackOptions& options,
                                      std::vector<char>* turned_out) {
  const double padding = options.padding, min_side_0 = options.min_side;
  const bool may_turn = options.may_turn;
  if (sizes.empty()) throw InvalidInputError("pack_rectangles: no charts to pack");
  if (!(padding >= 0 && padding < 0.25))
    throw InvalidInputError("pack_rectangles: padding " + std::to_string(padding) +
                            " is outside [0, 0.25)");
  if (!(min_side_0 >= 0 && min_side_0 < 0.25))
    throw InvalidInputError("pack_rectangles: min_side " + std::to_string(min_side_0) +
                            " is outside [0, 0.25)");
  const int n = static_cast<int>(sizes.size());
  std::vector<RectPlacement> out(n);
  std::vector<char> turned(n, 0);
  if (n == 1) {
    if (turned_out) *turned_out = turned;
    return out;
  }
  const std::vector<Vec2> size = normalized_sizes(sizes);
  if (n > kMaxRectsLimit) {
    out = pack_many(size, padding, min_side_0, may_turn, options.progress, turned);
    if (turned_out) *turned_out = turned;
    return out;
  }
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
  for (const auto& o : orders)
    for (int method : {1, 2}) strategies.push_back({o, method});
  // With turning: also the same strategies without turning on the rectangles all turned to
  // landscape (rows of alike shapes), whichever reaches the larger scale.
  std::vector<Vec2> landscape(size);
  std::vector<char> flat(n, 0);
  for (int i = 0; i < n; ++i)
    if (size[i].y() > size[i].x()) landscape[i] = Vec2(size[i].y(), size[i].x()), flat[i] = 1;
  const double tries = static_cast<double>(strategies.size()) * (may_turn ? 2 : 1);
  for (double gap = padding, min_side = min_side_0;; gap *= 0.5, min_side *= 0.5) {
    if (gap < 1e-9) gap = 0;
    if (min_side < 1e-9) min_side = 0;
    double best = 0;
    const Strategy* winner = nullptr;
    int variant = 0;  // 0: as given (turning if may_turn); 1: landscape, not turning
    int tried = 0;
    for (int v = 0; v < (may_turn ? 2 : 1); ++v)
      for (const Strategy& s : strategies) {
        report_progress(options.progress, "pack", tried++ / tries);
        const double sigma =
            best_scale(v ? landscape : size, s, gap, min_side, v ? false : may_turn);
        if (sigma > best) best = sigma, winner = &s, variant = v;
      }
    if (winner && pack_with(variant ? landscape : size, *winner, best, gap, min_side,
                            variant ? false : may_turn, &out, &turned)) {
      if (variant) turned = flat;
      if (turned_out) *turned_out = turned;
      return out;
    }
    if (gap == 0 && min_side == 0) break;
  }
  throw InvalidInputError("pack_rectangles: " + std::to_string(n) +
                          " charts cannot be packed into the unit square");
}

}  // namespace

std::vector<RectPlacement> pack_rectangles(const std::vector<Vec2>& sizes, double padding) {
  RectPackOptions o;
  o.padding = padding;
  return pack_rects(sizes, o, nullptr);
}

std::vector<RectPlacement> pack_rectangles_turning(const std::vector<Vec2>& sizes, double padding,
                                                   std::vector<char>& turned) {
  RectPackOptions o;
  o.padding = padding;
  o.may_turn = true;
  return pack_rects(sizes, o, &turned);
}

std::vector<RectPlacement> pack_rectangles(const std::vector<Vec2>& sizes,
                                           const RectPackOptions& options,
                                           std::vector<char>* turned) {
  return pack_rects(sizes, options, turned);
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
