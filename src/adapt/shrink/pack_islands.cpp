/// \file pack_islands.cpp
/// Bitmap packing of UV islands (after xatlas' brute-force packer): every island is rasterized
/// conservatively at its output scale (every texel its triangles touch), dilated by the gutter, and
/// placed bottom-left at the first free position of the output square, in each of four 90° turns
/// (turns keep orientation). The common scale factor is the largest that fits (bisection).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "adaptex/core/errors.h"
#include "shrink_internal.h"

namespace adaptex::shrink_detail {

namespace {

using Word = std::uint64_t;

/// A set of texels as rows of 64-bit words.
struct Bitmap {
  int width = 0, height = 0, words = 0;  ///< words per row (one spare word for shifting).
  std::vector<Word> bits;
  long cells = 0;  ///< Set texels before the dilation.
  Bitmap() = default;
  Bitmap(int w, int h) : width(w), height(h), words((w + 63) / 64 + 1), bits(static_cast<size_t>(words) * h, 0) {}
  bool get(int x, int y) const { return (bits[static_cast<size_t>(y) * words + x / 64] >> (x % 64)) & 1u; }
  void set(int x, int y) { bits[static_cast<size_t>(y) * words + x / 64] |= Word{1} << (x % 64); }
  const Word* row(int y) const { return &bits[static_cast<size_t>(y) * words]; }
  Word* row(int y) { return &bits[static_cast<size_t>(y) * words]; }
};

Vec2 turn(const Vec2& p, int k) {
  switch (k & 3) {
    case 1: return Vec2(-p.y(), p.x());
    case 2: return Vec2(-p.x(), -p.y());
    case 3: return Vec2(p.y(), -p.x());
    default: return p;
  }
}

/// Marks every cell [x, x+1] x [y, y+1] of \p bm that the triangle (a, b, c) (texel units) meets:
/// row by row, the x-extent of the triangle clipped to the row's strip.
void mark_triangle(Bitmap& bm, const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 p[3] = {a, b, c};
  const double ymin = std::min({a.y(), b.y(), c.y()}), ymax = std::max({a.y(), b.y(), c.y()});
  const int y0 = std::max(0, static_cast<int>(std::floor(ymin)));
  const int y1 = std::min(bm.height - 1, static_cast<int>(std::floor(ymax)));
  for (int y = y0; y <= y1; ++y) {
    const double lo = std::max<double>(y, ymin), hi = std::min<double>(y + 1, ymax);
    double xmin = 1e300, xmax = -1e300;
    for (int e = 0; e < 3; ++e) {
      const Vec2 &u = p[e], &v = p[(e + 1) % 3];
      // The part of edge uv inside lo <= y <= hi.
      const double ya = std::min(u.y(), v.y()), yb = std::max(u.y(), v.y());
      const double ca = std::max(lo, ya), cb = std::min(hi, yb);
      if (ca > cb) continue;
      for (double yy : {ca, cb}) {
        const double t = yb > ya ? (yy - u.y()) / (v.y() - u.y()) : 0.0;
        const double x = yb > ya ? u.x() + std::clamp(t, 0.0, 1.0) * (v.x() - u.x()) : std::min(u.x(), v.x());
        const double x2 = yb > ya ? x : std::max(u.x(), v.x());
        xmin = std::min(xmin, x);
        xmax = std::max(xmax, x2);
      }
    }
    if (xmin > xmax) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(xmin)));
    const int x1 = std::min(bm.width - 1, static_cast<int>(std::floor(xmax)));
    for (int x = x0; x <= x1; ++x) bm.set(x, y);
  }
}

/// \p core dilated by \p g cells (Chebyshev), with word operations.
Bitmap dilate(const Bitmap& core, int g) {
  Bitmap h(core.width, core.height);
  for (int y = 0; y < core.height; ++y) {
    const Word* src = core.row(y);
    Word* dst = h.row(y);
    for (int i = 0; i < core.words; ++i) {
      Word w = src[i];
      for (int d = 1; d <= g; ++d) {
        w |= src[i] << d | src[i] >> d;
        if (i > 0) w |= src[i - 1] >> (64 - d);
        if (i + 1 < core.words) w |= src[i + 1] << (64 - d);
      }
      dst[i] = w;
    }
  }
  Bitmap out(core.width, core.height);
  for (int y = 0; y < core.height; ++y)
    for (int yy = std::max(0, y - g); yy <= std::min(core.height - 1, y + g); ++yy)
      for (int i = 0; i < core.words; ++i) out.row(y)[i] |= h.row(yy)[i];
  // Bits past the width stay clear (the last words may have caught some).
  for (int y = 0; y < out.height; ++y)
    for (int x = out.width; x < out.words * 64; ++x) out.row(y)[x / 64] &= ~(Word{1} << (x % 64));
  out.cells = core.cells;
  return out;
}

/// Island \p faces of \p layout at \p sigma texels per UV unit, turned \p k times, rasterized
/// conservatively with \p gutter texels of dilation; \p shift receives the texel translation that
/// maps the turned, scaled island into the bitmap's frame.
Bitmap rasterize_island(const Parameterization& layout, const std::vector<int>& faces, double sigma, int k,
                        int gutter, Vec2& shift) {
  Vec2 lo = Vec2::Constant(1e300), hi = Vec2::Constant(-1e300);
  for (int f : faces)
    for (int w : layout.uv_faces[f]) {
      const Vec2 q = turn(sigma * layout.uv[w], k);
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
  shift = Vec2(gutter - std::floor(lo.x()), gutter - std::floor(lo.y()));
  const int w = static_cast<int>(std::ceil(hi.x() + shift.x())) + gutter;
  const int h = static_cast<int>(std::ceil(hi.y() + shift.y())) + gutter;
  Bitmap core(std::max(w, 1), std::max(h, 1));
  for (int f : faces) {
    const Face& t = layout.uv_faces[f];
    const Vec2 a = turn(sigma * layout.uv[t[0]], k) + shift, b = turn(sigma * layout.uv[t[1]], k) + shift,
               c = turn(sigma * layout.uv[t[2]], k) + shift;
    mark_triangle(core, a, b, c);
  }
  for (const Word& bits : core.bits) core.cells += __builtin_popcountll(bits);
  return dilate(core, gutter);
}

/// True if \p b placed with its cell (0,0) at (X, Y) of \p occ misses every set texel of \p occ.
bool fits(const Bitmap& occ, const Bitmap& b, int X, int Y) {
  const int w0 = X / 64, off = X % 64;
  for (int r = 0; r < b.height; ++r) {
    const Word* br = b.row(r);
    const Word* orow = occ.row(Y + r);
    for (int i = 0; i < b.words - 1; ++i) {
      const Word lo = br[i] << off;
      const Word hi = off ? br[i] >> (64 - off) : 0;
      if ((orow[w0 + i] & lo) || (hi && (orow[w0 + i + 1] & hi))) return false;
    }
  }
  return true;
}

void place(Bitmap& occ, const Bitmap& b, int X, int Y) {
  const int w0 = X / 64, off = X % 64;
  for (int r = 0; r < b.height; ++r) {
    const Word* br = b.row(r);
    Word* orow = occ.row(Y + r);
    for (int i = 0; i < b.words - 1; ++i) {
      orow[w0 + i] |= br[i] << off;
      if (off) orow[w0 + i + 1] |= br[i] >> (64 - off);
    }
  }
}

/// One packing attempt at common factor \p lambda; empty if some island does not fit.
std::vector<IslandPlacement> try_pack(const Parameterization& layout, const std::vector<std::vector<int>>& faces,
                                      const std::vector<double>& scales, int size, int gutter, bool rotate,
                                      double lambda, long& cells, bool count_only = false) {
  const int I = static_cast<int>(faces.size());
  const int E = size + 2 * gutter;  // the square with the gutter's overhang on every side
  const int turns = count_only ? 1 : rotate ? 4 : 1;
  // Bitmaps of every island and turn (in parallel), then placement in order of decreasing size.
  std::vector<Bitmap> bm(static_cast<size_t>(I) * turns);
  std::vector<Vec2> shift(bm.size());
  tbb::parallel_for(0, I * turns, [&](int n) {
    const int i = n / turns;
    bm[n] = rasterize_island(layout, faces[i], size * scales[i] * lambda, n % turns, gutter, shift[n]);
  });
  std::vector<int> order(I);
  for (int i = 0; i < I; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const Bitmap &x = bm[static_cast<size_t>(a) * turns], &y = bm[static_cast<size_t>(b) * turns];
    return static_cast<long>(x.width) * x.height > static_cast<long>(y.width) * y.height;
  });
  Bitmap occ(E + 64, E);
  std::vector<IslandPlacement> out(I);
  cells = 0;
  for (int i = 0; i < I; ++i) cells += bm[static_cast<size_t>(i) * turns].cells;
  if (count_only) return {};
  for (int i : order) {
    int best_k = -1, best_x = 0, best_y = 0;
    for (int k = 0; k < turns; ++k) {
      const Bitmap& b = bm[static_cast<size_t>(i) * turns + k];
      if (b.width > E || b.height > E) continue;
      bool found = false;
      for (int Y = 0; Y + b.height <= E && !found; ++Y) {
        if (best_k >= 0 && Y + b.height > best_y + bm[static_cast<size_t>(i) * turns + best_k].height) break;
        for (int X = 0; X + b.width <= E; ++X)
          if (fits(occ, b, X, Y)) {
            const bool better = best_k < 0 || Y + b.height < best_y + bm[static_cast<size_t>(i) * turns + best_k].height ||
                                (Y + b.height == best_y + bm[static_cast<size_t>(i) * turns + best_k].height && X < best_x);
            if (better) {
              best_k = k;
              best_x = X;
              best_y = Y;
            }
            found = true;
            break;
          }
      }
    }
    if (best_k < 0) return {};
    const size_t n = static_cast<size_t>(i) * turns + best_k;
    place(occ, bm[n], best_x, best_y);
    // Bitmap frame -> output texels: the square's texel 0 is the extended grid's texel `gutter`.
    out[i] = IslandPlacement{size * scales[i] * lambda, best_k,
                             shift[n] + Vec2(best_x - gutter, best_y - gutter)};
  }
  return out;
}

}  // namespace

std::vector<IslandPlacement> pack_islands(const Parameterization& layout, const std::vector<int>& face_island,
                                          int num_islands, const std::vector<double>& scales, int size,
                                          int gutter, bool rotate, double fill_hint, double* fill) {
  std::vector<std::vector<int>> faces(num_islands);
  for (size_t f = 0; f < face_island.size(); ++f) faces[face_island[f]].push_back(static_cast<int>(f));
  long cells = 0;
  double lo = 0, hi = 0, lambda = 1;
  std::vector<IslandPlacement> best;
  long best_cells = 0;
  auto attempt = [&](double l) {
    std::vector<IslandPlacement> p = try_pack(layout, faces, scales, size, gutter, rotate, l, cells);
    if (p.empty()) {
      hi = hi > 0 ? std::min(hi, l) : l;
      return false;
    }
    if (l > lo) {
      lo = l;
      best = std::move(p);
      best_cells = cells;
    }
    return true;
  };
  // First guess from the cells the islands cover at factor 1 (they grow as its square) and the fill
  // a packing is expected to reach; then bracket the largest factor that fits, and bisect.
  try_pack(layout, faces, scales, size, gutter, rotate, 1.0, cells, true);
  if (cells > 0) lambda = std::sqrt(std::clamp(fill_hint, 0.05, 1.0) * size * size / static_cast<double>(cells));
  for (int n = 0; n < 80 && (lo == 0 || hi == 0) && lambda > 1e-6; ++n) lambda = attempt(lambda) ? lambda * 1.04 : lambda / 1.04;
  for (int n = 0; n < 3 && lo > 0 && hi > 0; ++n) attempt(std::sqrt(lo * hi));
  if (fill) *fill = static_cast<double>(best_cells) / (static_cast<double>(size) * size);
  return best;
}

Parameterization apply_placements(const Parameterization& layout, const std::vector<int>& face_island,
                                  const std::vector<IslandPlacement>& placements, int size) {
  Parameterization out = layout;
  std::vector<char> done(layout.uv.size(), 0);
  for (size_t f = 0; f < layout.uv_faces.size(); ++f)
    for (int w : layout.uv_faces[f])
      if (!done[w]) {
        done[w] = 1;
        const IslandPlacement& p = placements[face_island[f]];
        const Vec2 t = turn(p.sigma * layout.uv[w], p.turns) + p.offset;
        out.uv[w] = (t / size).cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1));
      }
  return out;
}

}  // namespace adaptex::shrink_detail
