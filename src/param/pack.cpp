/// \file pack.cpp
/// Chart packing (§3.2, one chart per component): shelf packing of squares sized by sqrt(3-D area);
/// rectangles (multi-chart layouts): the best of shelf and MaxRects packings.
#include "adaptex/param/pack.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <string_view>

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
                                     std::vector<char>& turned, double& gap_used) {
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
        gap_used = gap;
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
                                      std::vector<char>* turned_out, double* gap_out = nullptr) {
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
  if (gap_out) *gap_out = padding;
  if (n == 1) {
    if (turned_out) *turned_out = turned;
    return out;
  }
  const std::vector<Vec2> size = normalized_sizes(sizes);
  if (n > kMaxRectsLimit) {
    double gap_used = padding;
    out = pack_many(size, padding, min_side_0, may_turn, options.progress, turned, gap_used);
    if (gap_out) *gap_out = gap_used;
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
      if (gap_out) *gap_out = gap;
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
                                           std::vector<char>* turned, double* gap_used) {
  return pack_rects(sizes, options, turned, gap_used);
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

// ---- Shape packing (pack_shapes) -------------------------------------------------------------

namespace {

/// \p p turned by \p turns quarter turns counter-clockwise.
Vec2 quarter_turn(const Vec2& p, int turns) {
  switch (turns & 3) {
    case 1: return Vec2(-p.y(), p.x());
    case 2: return Vec2(-p.x(), -p.y());
    case 3: return Vec2(p.y(), -p.x());
    default: return p;
  }
}

/// In raster cells: a point closer than kCellEps to the edge of a cell marks the cells on both
/// sides (so rounding in the placed UVs cannot carry a triangle into an unmarked cell), and every
/// chart starts kShift inside its first cell (no vertex lies on the cell edge below or left of it).
constexpr double kCellEps = 1e-6;
constexpr double kShift = 1e-4;

/// A chart rasterized in one orientation at one scale. In raw column j (j in [0, width)) it
/// occupies rows [bottom[j], top[j]) of its own raster (a superset of the cells its closed
/// triangles touch). low[e], for the extended columns e in [0, width + 2 g): the lowest raw row
/// within g columns of raw column e - g (the bottom of the chart dilated by g cells, with its
/// rows counted from g below the raw ones).
struct Profile {
  int width = 0;
  std::vector<int> bottom, top, low;
  long low_sum = 0;
  int low_min_at = 0;  ///< The first extended column of the lowest low.
  int max_top = 0;
  Vec2 origin = Vec2::Zero();  ///< Lower-left corner of the turned and scaled chart (chart units).
};

/// The range [lo, hi] of y over the triangle (a, b, c) within the slab x0 <= x <= x1; false when
/// they do not meet.
bool slab_range(const Vec2& a, const Vec2& b, const Vec2& c, double x0, double x1, double& lo,
                double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  const Vec2* v[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    const Vec2& p = *v[i];
    if (p.x() >= x0 && p.x() <= x1) lo = std::min(lo, p.y()), hi = std::max(hi, p.y());
    const Vec2& q = *v[(i + 1) % 3];
    for (double x : {x0, x1})
      if ((p.x() - x) * (q.x() - x) < 0) {
        const double y = p.y() + (x - p.x()) / (q.x() - p.x()) * (q.y() - p.y());
        lo = std::min(lo, y), hi = std::max(hi, y);
      }
  }
  return lo <= hi;
}

/// Conservative raster of \p chart turned by \p turns and scaled by \p scale, cells of side \p h,
/// dilated by \p g cells (Profile).
Profile rasterize(const ChartShape& chart, double scale, int turns, double h, int g) {
  Profile pr;
  std::vector<Vec2> p(chart.uv.size());
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (size_t i = 0; i < p.size(); ++i) {
    p[i] = scale * quarter_turn(chart.uv[i], turns);
    lo = lo.cwiseMin(p[i]);
    hi = hi.cwiseMax(p[i]);
  }
  if (p.empty()) lo = hi = Vec2::Zero();
  pr.origin = lo;
  for (Vec2& q : p) q = (q - lo) / h + Vec2::Constant(kShift);
  const Vec2 extent = (hi - lo) / h + Vec2::Constant(kShift);
  pr.width = static_cast<int>(std::floor(extent.x() + kCellEps)) + 1;
  pr.bottom.assign(pr.width, std::numeric_limits<int>::max());
  pr.top.assign(pr.width, 0);
  for (const Face& f : chart.faces) {
    const Vec2 &a = p[f[0]], &b = p[f[1]], &c = p[f[2]];
    const int c0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}) - kCellEps)));
    const int c1 = std::min(pr.width - 1,
                            static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}) + kCellEps)));
    for (int col = c0; col <= c1; ++col) {
      double ylo, yhi;
      if (!slab_range(a, b, c, col - kCellEps, col + 1 + kCellEps, ylo, yhi)) continue;
      pr.bottom[col] = std::min(pr.bottom[col], std::max(0, static_cast<int>(std::floor(ylo - kCellEps))));
      pr.top[col] = std::max(pr.top[col], static_cast<int>(std::floor(yhi + kCellEps)) + 1);
    }
  }
  for (int j = 0; j < pr.width; ++j) {
    if (pr.bottom[j] >= pr.top[j]) pr.bottom[j] = 0, pr.top[j] = std::max(1, pr.top[j]);  // a point
    pr.max_top = std::max(pr.max_top, pr.top[j]);
  }
  pr.low.assign(pr.width + 2 * g, std::numeric_limits<int>::max());
  for (int e = 0; e < pr.width + 2 * g; ++e) {
    for (int j = std::max(0, e - 2 * g); j <= std::min(pr.width - 1, e); ++j)
      pr.low[e] = std::min(pr.low[e], pr.bottom[j]);
    pr.low_sum += pr.low[e];
  }
  pr.low_min_at = static_cast<int>(std::min_element(pr.low.begin(), pr.low.end()) - pr.low.begin());
  return pr;
}

/// Empty rectangles under the horizon that later charts fill: no chart's raster cell lies in one,
/// and a chart goes in when its raster dilated by the gap (a box of low.size() by max_top + 2 g
/// cells) fits, so it keeps the gap to whatever lies around the hole.
class Holes {
 public:
  struct Rect {
    int x0, y0, x1, y1;
    long area() const { return static_cast<long>(x1 - x0) * (y1 - y0); }
  };
  using Map = std::multimap<long, Rect>;

  /// Holes narrower or lower than \p min_side cells are not kept (they hold no dilated chart).
  explicit Holes(int min_side) : min_side_(min_side) {}

  /// Records the cells enclosed in columns x0 + j, j in [0, width), between the old horizon
  /// floor[j] and the bottom ceil[j] of the chart just placed there.
  void enclose(int x0, const int* floor, const int* ceil, int width) { split(x0, floor, ceil, 0, width, 0); }

  /// The smallest of the first kScan holes (by area) that hold a \p w by \p h box, or end().
  Map::const_iterator find(int w, int h) const {
    int scanned = 0;
    for (auto it = by_area_.lower_bound(static_cast<long>(w) * h); it != by_area_.end(); ++it) {
      if (it->second.x1 - it->second.x0 >= w && it->second.y1 - it->second.y0 >= h) return it;
      if (++scanned == kScan) break;
    }
    return by_area_.end();
  }
  Map::const_iterator end() const { return by_area_.end(); }

  /// Puts a \p w by \p h box (its raster \p g inside it) at the lower-left corner of \p hole
  /// and keeps the two rectangles left around it (the larger one whole; neighbouring boxes
  /// share their g-cell margins, so rasters stay g apart).
  void fill(Map::const_iterator hole, int w, int h, int g) {
    const Rect r = hole->second;
    by_area_.erase(hole);
    const int xr = r.x0 + w - g, yt = r.y0 + h - g;
    const Rect right_tall{xr, r.y0, r.x1, r.y1}, top_short{r.x0, yt, xr, r.y1};
    const Rect right_short{xr, r.y0, r.x1, yt}, top_wide{r.x0, yt, r.x1, r.y1};
    if (std::max(right_tall.area(), top_short.area()) >= std::max(right_short.area(), top_wide.area()))
      add(right_tall), add(top_short);
    else
      add(right_short), add(top_wide);
  }

 private:
  void add(const Rect& r) {
    if (r.x1 - r.x0 >= min_side_ && r.y1 - r.y0 >= min_side_) by_area_.emplace(r.area(), r);
  }

  /// The largest rectangle between floor and ceil over columns [j0, j1) (at most kWidest wide),
  /// then the same on either side of it, kDeepest levels down at most (each level costs at most
  /// kWidest times the chart's width, however the rectangles fall).
  void split(int x0, const int* floor, const int* ceil, int j0, int j1, int depth) {
    if (j1 - j0 < min_side_ || depth == kDeepest) return;
    long best = 0;
    Rect r{};
    for (int a = j0; a < j1; ++a) {
      int f = floor[a], c = ceil[a];
      for (int b = a; b < std::min(j1, a + kWidest); ++b) {
        f = std::max(f, floor[b]), c = std::min(c, ceil[b]);
        if (c - f < min_side_) break;
        const long area = static_cast<long>(b - a + 1) * (c - f);
        if (b - a + 1 >= min_side_ && area > best) best = area, r = {a, f, b + 1, c};
      }
    }
    if (best == 0) return;
    add({x0 + r.x0, r.y0, x0 + r.x1, r.y1});
    split(x0, floor, ceil, j0, r.x0, depth + 1);
    split(x0, floor, ceil, r.x1, j1, depth + 1);
  }

  static constexpr int kScan = 64;
  static constexpr int kWidest = 512;
  static constexpr int kDeepest = 16;
  int min_side_;
  Map by_area_;
};

/// The atlas of one packing trial: the horizon, the top of every column (in cells), with its
/// prefix sums.
class Horizon {
 public:
  explicit Horizon(int n) : n_(n), h_(n, 0), sum_(n + 1, 0) {}
  int size() const { return n_; }

  /// Best column x (and row y) for \p pr: the lowest score c (y + top) + (empty area between the
  /// horizon and the dilated chart's bottom), where top is the chart's height, then the lowest y,
  /// then the lowest x. \p c is the same for every orientation of a chart (its widest extended
  /// width): a turn that stands a sliver on end does not score lower for being narrow. Returns -1
  /// when the chart is wider than the atlas, 1 when it found a position with a lower score than
  /// (\p best_score, \p best_y) (and updated them and \p best_x), else 0.
  int best_drop(const Profile& pr, long c, long& best_score, int& best_x, int& best_y) const {
    const int w = static_cast<int>(pr.low.size());
    if (w > n_) return -1;
    const int max_low = *std::max_element(pr.low.begin(), pr.low.end());
    int improved = 0;
    // The empty area is >= 0 and y >= h[x + e] - max_low, so a column above thr puts the score of
    // every window holding it above the best: such windows are skipped.
    // thr only falls (with the best score); a column is judged when it enters the window.
    long thr = 0, thr_of = -1;
    int tall = -1;  // the last column judged above thr
    int witness = -1;  // the column that last ruled a position out (likely to rule out the next)
    for (int x = 0, next = 0; x + w <= n_; ++x) {
      if (best_score != thr_of) thr = best_score / c - pr.max_top + max_low, thr_of = best_score;
      for (; next < x + w; ++next)
        if (h_[next] > thr) tall = next;
      if (tall >= x) {
        x = tall;
        continue;
      }
      improved |= drop_at(pr, c, x, best_score, best_x, best_y, witness);
    }
    return improved;
  }

  /// Places \p pr at (x, y): its raw column j at x + g + j reaches y + g + top[j]. The cells
  /// it encloses between the horizon and its bottom go to \p holes.
  void place(const Profile& pr, int x, int y, int g, Holes& holes) {
    const int a = x + g;
    ceil_.resize(pr.width);
    for (int j = 0; j < pr.width; ++j) ceil_[j] = y + g + pr.bottom[j];
    holes.enclose(a, h_.data() + a, ceil_.data(), pr.width);
    for (int j = 0; j < pr.width; ++j) h_[a + j] = std::max(h_[a + j], y + g + pr.top[j]);
    for (int i = a; i < n_; ++i) sum_[i + 1] = sum_[i] + h_[i];
  }

 private:
  /// Updates \p best_score, \p best_x, \p best_y if \p pr at column \p x beats them (1).
  /// \p witness: a column (absolute) tried right after the chart's lowest column when it lies
  /// under the chart; set to the column that rules this position out. Only the order of the tests
  /// depends on it, not the result.
  int drop_at(const Profile& pr, long c, int x, long& best_score, int& best_x, int& best_y,
              int& witness) const {
    const int w = static_cast<int>(pr.low.size());
    const long wy = c + w;  // score = wy * y + base
    const long base = pr.low_sum - (sum_[x + w] - sum_[x]) + c * pr.max_top;
    // y only grows: a position is given up once it can no longer beat the best (ties included).
    const auto beaten = [&](int yy) {
      const long sc = wy * yy + base;
      return sc > best_score || (sc == best_score && yy >= best_y);
    };
    // The column of the chart's lowest bottom bounds y first (most positions are pruned by it),
    // then the column that ruled out the last position (y is the max over columns: any one of them
    // gives a lower bound).
    int y = h_[x + pr.low_min_at] - pr.low[pr.low_min_at];
    if (beaten(y)) return 0;
    if (witness >= x && witness < x + w) {
      y = std::max(y, h_[witness] - pr.low[witness - x]);
      if (beaten(y)) return 0;
    }
    // y = max_e (h[x + e] - low[e]), tested every kDropBlock columns (a branch-free inner loop).
    const int* hx = h_.data() + x;
    const int* low = pr.low.data();
    for (int e0 = 0; e0 < w; e0 += kDropBlock) {
      const int e1 = std::min(w, e0 + kDropBlock);
      for (int e = e0; e < e1; ++e) y = std::max(y, hx[e] - low[e]);
      if (beaten(y)) {
        for (int e = e0; e < e1; ++e)
          if (hx[e] - low[e] == y) witness = x + e;
        return 0;
      }
    }
    best_score = wy * y + base, best_x = x, best_y = y;
    return 1;
  }

  static constexpr int kDropBlock = 16;
  int n_;
  std::vector<int> h_;
  std::vector<long> sum_;  ///< sum_[i]: the sum of h_[0, i).
  std::vector<int> ceil_;  ///< place(): the placed chart's bottom row in each of its columns.
};

/// The scale of a chart of bounding-box sides \p shorter <= \p longer at common scale \p s: raised
/// uniformly until its shorter side reaches \p min_side, but its longer side not past
/// 16 min_side (slivers).
double raised_scale(double shorter, double longer, double s, double min_side) {
  if (!(s * shorter < min_side) || !(shorter > 0)) return s;
  return std::max(s, std::min(min_side / shorter, 16 * min_side / longer));
}

/// Charts, their order and fixed figures for the trials of pack_shapes().
struct ShapeSet {
  const std::vector<ChartShape>& charts;
  std::vector<double> shorter;  ///< Shorter side of every chart's bounding box (chart units).
  std::vector<double> longer;   ///< Longer side.
  std::vector<double> box_area; ///< Area of the bounding box.
  std::vector<int> order;       ///< Longest bounding-box side first.
  int turns = 1;                ///< Orientations tried (1 or 4).
  double largest = 0;           ///< Longest side of all.
};

/// One packing trial at common scale \p s, raster side \p n cells, gap \p g cells, minimum side
/// \p min_side (unit square): returns the rows the packing needs (> n: it does not fit) and, if
/// \p out, the placements. Stops early once it needs more than \p limit rows (and returns that).
/// Reports progress \p frac every 4096 charts.
double shape_trial(const ShapeSet& set, double s, int n, int g, double min_side,
                   const ProgressCallback& progress, double frac, std::vector<ShapePlacement>* out,
                   double limit) {
  const double h = 1.0 / n;
  Horizon horizon(n);
  double needed = 0;
  int done = 0;
  Holes holes(1 + 2 * g);  // the smallest dilated chart: one cell and its gap around
  std::array<Profile, 4> turned;
  std::array<bool, 4> repeat{};
  for (int c : set.order) {
    if ((++done & 4095) == 0) report_progress(progress, "pack", frac);
    const double scale = raised_scale(set.shorter[c], set.longer[c], s, min_side);
    // A turn whose bottom and height match an earlier one's fits and scores the same everywhere:
    // it cannot beat it (ties go to the earlier turn).
    for (int t = 0; t < set.turns; ++t) {
      Profile& pr = turned[t];
      pr = rasterize(set.charts[c], scale, t, h, g);
      repeat[t] = false;
      for (int u = 0; u < t && !repeat[t]; ++u)
        repeat[t] = turned[u].max_top == pr.max_top && turned[u].low == pr.low;
    }
    // A hole left under the horizon first (the smallest that holds the chart in some turn).
    Holes::Map::const_iterator hole = holes.end();
    int ht = 0;
    for (int t = 0; t < set.turns; ++t) {
      if (repeat[t]) continue;
      const auto it = holes.find(static_cast<int>(turned[t].low.size()), turned[t].max_top + 2 * g);
      if (it != holes.end() && (hole == holes.end() || it->first < hole->first)) hole = it, ht = t;
    }
    if (hole != holes.end()) {
      const Profile& pr = turned[ht];
      const int x = hole->second.x0, y = hole->second.y0;
      holes.fill(hole, static_cast<int>(pr.low.size()), pr.max_top + 2 * g, g);
      if (out) (*out)[c] = {Vec2(h * (x + g + kShift), h * (y + g + kShift)) - pr.origin, scale, ht};
      continue;
    }
    long best_waste = std::numeric_limits<long>::max();
    int bx = -1, by = std::numeric_limits<int>::max(), bt = 0;
    // Weight of the height in the score: the widest extended width of the chart.
    const long weight = static_cast<long>(std::ceil(scale * set.longer[c] / h)) + 1 + 2 * g;
    for (int t = 0; t < set.turns; ++t) {
      if (repeat[t]) continue;
      const Profile& pr = turned[t];
      const int found = horizon.best_drop(pr, weight, best_waste, bx, by);
      if (found < 0) {  // wider than the atlas: the scale must shrink by about n / width
        const double w = static_cast<double>(pr.low.size());
        return std::max(needed, w * w / n);
      }
      if (found > 0) bt = t;
    }
    const Profile& best = turned[bt];
    horizon.place(best, bx, by, g, holes);
    needed = std::max(needed, static_cast<double>(by + best.max_top + 2 * g));
    if (needed > limit) return needed;
    if (out)
      (*out)[c] = {Vec2(h * (bx + g + kShift), h * (by + g + kShift)) - best.origin, scale, bt};
  }
  return needed;
}

/// The scale s at which the charts' bounding boxes (areas \p box_area, each side raised to
/// \p min_side), each with its gap, fill 0.65 of the square (at most \p s_max).
double first_shape_scale(const std::vector<double>& box_area, double gap, double min_side, double s_max) {
  const auto filled = [&](double s) {
    double sum = 0;
    for (double a : box_area) sum += std::pow(std::max(s * std::sqrt(a), min_side) + gap, 2);
    return sum;
  };
  double lo = 1e-12, hi = s_max;
  if (filled(hi) <= 0.65) return hi;
  for (int i = 0; i < 60 && hi > lo * 1.001; ++i) {
    const double mid = std::sqrt(lo * hi);
    (filled(mid) <= 0.65 ? lo : hi) = mid;
  }
  return lo;
}

/// The charts of pack_shapes() with their bounding boxes, largest first by the longest side.
/// \throw InvalidInputError a non-finite uv or a triangle index out of range
ShapeSet make_shape_set(const std::vector<ChartShape>& charts, int turns) {
  const int nc = static_cast<int>(charts.size());
  ShapeSet set{charts, std::vector<double>(nc, 0.0), std::vector<double>(nc, 0.0),
               std::vector<double>(nc, 0.0), std::vector<int>(nc), turns};
  for (int c = 0; c < nc; ++c) {
    const ChartShape& ch = charts[c];
    Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec2& p : ch.uv) {
      if (!p.allFinite())
        throw InvalidInputError("pack_shapes: chart " + std::to_string(c) + " has a non-finite uv");
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
    for (const Face& f : ch.faces)
      for (int k = 0; k < 3; ++k)
        if (f[k] < 0 || f[k] >= static_cast<int>(ch.uv.size()))
          throw InvalidInputError("pack_shapes: chart " + std::to_string(c) +
                                  " has a triangle index out of range");
    if (ch.uv.empty()) continue;
    set.shorter[c] = (hi - lo).minCoeff();
    set.longer[c] = (hi - lo).maxCoeff();
    set.box_area[c] = (hi - lo).prod();
    set.largest = std::max(set.largest, set.longer[c]);
  }
  std::iota(set.order.begin(), set.order.end(), 0);
  // Longest side first (on the charts of docs/bench_unwrap.md it beat largest area first and the
  // shorter side first).
  std::stable_sort(set.order.begin(), set.order.end(),
                   [&](int a, int b) { return set.longer[a] > set.longer[b]; });
  return set;
}

/// The scale search of pack_shapes() on an n² raster, with progress over all its calls.
struct ShapeSearch {
  const ShapeSet& set;
  const ShapePackOptions& options;
  int n;
  int reported = 0;
  double frac = 0;

  void tick() {
    frac = std::min(1.0, reported++ / (options.trials + 2.0));
    report_progress(options.progress, "pack", frac);
  }

  double trial(double s, int g, double min_side, std::vector<ShapePlacement>* out, double limit) {
    return shape_trial(set, s, n, g, min_side, options.progress, frac, out, limit);
  }

  /// Packs at gap \p gap and minimum side \p min_side at the largest scale found into \p out;
  /// false when even the gaps and minimum sides alone (every chart a point or raised to
  /// min_side) do not fit. The first scale: the charts' bounding boxes with their gaps fill 0.65
  /// of the square; then the packed height is taken as a power of the scale (its exponent from
  /// the last two trials, 2 at first), aiming 0.5 % below the top.
  bool fit(double gap, double min_side, std::vector<ShapePlacement>& out) {
    const int g = static_cast<int>(std::ceil(gap * n - 1e-9));
    tick();
    // A chart takes at least (1 + g)² cells of the (n + g)² that the square and half a gap hold.
    const double nc = static_cast<double>(set.order.size());
    if (nc * (1 + g) * (1 + g) > static_cast<double>(n + g) * (n + g)) return false;
    const double s_max = set.largest > 0 ? (1.0 - 2 * gap) / set.largest : 1.0;
    double s = first_shape_scale(set.box_area, gap, min_side, s_max);
    double lo = 0, hi = std::numeric_limits<double>::infinity(), prev_s = 0, prev_needed = 0;
    std::vector<ShapePlacement> placed(out.size());
    for (int t = 0; t < options.trials; ++t) {
      tick();
      const double needed = trial(s, g, min_side, &placed, 2.0 * n);
      if (needed <= n) lo = s, out.swap(placed);
      else hi = s;
      // Done when the square is filled to 1 % of its height or the bracket is within 0.3 %.
      if (needed <= n && needed >= 0.99 * n) break;
      if (hi < std::numeric_limits<double>::infinity() && hi <= lo * 1.003) break;
      double k = 2;
      if (prev_s > 0 && std::abs(std::log(s / prev_s)) > 1e-6 && needed > 0 && prev_needed > 0)
        k = std::clamp(std::log(needed / prev_needed) / std::log(s / prev_s), 0.5, 3.0);
      prev_s = s, prev_needed = needed;
      double next = s * std::pow(0.995 * n / std::max(needed, 1.0), 1.0 / k);
      if (next >= hi || next <= lo) next = lo > 0 ? std::sqrt(lo * std::min(hi, 4 * lo)) : 0.7 * s;
      s = std::min(next, s_max);
    }
    if (lo > 0) return true;
    // No fit yet: whether the charts fit at all (each a point, raised to min_side; about as costly
    // as a trial, so only asked here), then shrink until they do (the tiny trial fitted, so this
    // ends).
    tick();
    if (trial(1e-12, g, min_side, nullptr, n) > n) return false;
    for (int t = 0; lo == 0 && t < 64; ++t) {
      tick();
      s *= 0.8;
      if (trial(s, g, min_side, &placed, n) <= n) lo = s, out.swap(placed);
    }
    return lo > 0;
  }
};

/// The raster side of pack_shapes() for \p nc charts (ShapePackOptions::resolution = 0): 1024 up
/// to 64 charts, 2048 up to 4096 charts, 8192 from 7169 to 12288 charts, 4096 otherwise (a chart
/// of the mean size at least 37 cells across up to 12k charts, 32 up to 16k). A conservative
/// raster adds about a cell around each chart: at 2,048 cells the 13-16k charts of a million-face
/// scan are about 16 cells across and lost a sixth of the square to it. 8,192 cells give about
/// 0.01 more share for about twice the packing time, which above 12k charts made a 688k-face scan
/// 30 % slower (docs/decisions.md, "Packing: a finer raster for many charts"). Powers of two keep
/// a gap of whole texels a whole number of cells.
int default_shape_resolution(int nc) {
  if (nc <= 64) return 1024;
  if (nc <= 4096) return 2048;
  return nc <= 7168 || nc > 12288 ? 4096 : 8192;
}

}  // namespace

Vec2 ShapePlacement::apply(const Vec2& uv) const { return offset + scale * quarter_turn(uv, turns); }

std::vector<ShapePlacement> pack_shapes(const std::vector<ChartShape>& charts,
                                        const ShapePackOptions& options, double* gap_used) {
  const int nc = static_cast<int>(charts.size());
  if (nc == 0) throw InvalidInputError("pack_shapes: no charts to pack");
  if (!(options.padding >= 0 && options.padding < 0.25) ||
      !(options.min_side >= 0 && options.min_side < 0.25))
    throw InvalidInputError("pack_shapes: padding " + std::to_string(options.padding) +
                            " or min_side " + std::to_string(options.min_side) +
                            " is outside [0, 0.25)");
  if (options.resolution != 0 && (options.resolution < 64 || options.resolution > 16384))
    throw InvalidInputError("pack_shapes: resolution " + std::to_string(options.resolution) +
                            " is outside [64, 16384]");
  if (options.trials < 1) throw InvalidInputError("pack_shapes: trials must be >= 1");
  const ShapeSet set = make_shape_set(charts, options.may_turn ? 4 : 1);
  const int n = options.resolution ? options.resolution : default_shape_resolution(nc);
  ShapeSearch search{set, options, n};
  std::vector<ShapePlacement> out(nc);
  for (double gap = options.padding, min_side = options.min_side;; gap *= 0.5, min_side *= 0.5) {
    if (gap < 1e-9) gap = 0;
    if (min_side < 1e-9) min_side = 0;
    if (search.fit(gap, min_side, out)) {
      if (gap_used) *gap_used = gap;
      return out;
    }
    if (gap == 0 && min_side == 0) break;
  }
  throw InvalidInputError("pack_shapes: " + std::to_string(nc) +
                          " charts cannot be packed into the unit square");
}

}  // namespace adaptex
