// Grid warp of thesis §3.7.1/§3.7.2 and its sampled inverse (two-stage composition, §3.8).
#include "adaptex/adapt/grid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "adaptex/core/errors.h"

namespace adaptex {

GridWarp GridWarp::uniform(int cells) {
  if (cells < 1) throw InvalidInputError("grid must have at least 1 cell per side, got " + std::to_string(cells));
  GridWarp g;
  g.n = cells;
  g.points.resize(static_cast<size_t>(cells + 1) * (cells + 1));
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) g.at(i, j) = Vec2(double(i) / cells, double(j) / cells);
  return g;
}

namespace {
// Uniform cell of uv and local coordinates in it.
inline void locate(int n, const Vec2& uv, int& ci, int& cj, double& s, double& t) {
  const double x = std::clamp(uv.x(), 0.0, 1.0) * n, y = std::clamp(uv.y(), 0.0, 1.0) * n;
  ci = std::min(static_cast<int>(x), n - 1);
  cj = std::min(static_cast<int>(y), n - 1);
  s = x - ci;
  t = y - cj;
}
}  // namespace

bool GridWarp::contains(const Vec2& uv) const {
  // A wedge on the rectangle's side (round-off of the move that placed it) still belongs to it.
  constexpr double eps = 1e-12;
  return !(uv.x() < lo.x() - eps || uv.y() < lo.y() - eps || uv.x() > hi.x() + eps || uv.y() > hi.y() + eps);
}

Vec2 GridWarp::apply(const Vec2& uv) const {
  if (!whole_square()) {
    if (!contains(uv)) return uv;
    const Vec2 size = hi - lo;
    const Vec2 q = ((uv - lo).array() / size.array()).matrix();
    return lo + apply_lattice(q).cwiseProduct(size);
  }
  return apply_lattice(uv);
}

Vec2 GridWarp::apply_lattice(const Vec2& uv) const {
  int ci, cj;
  double s, t;
  locate(n, uv, ci, cj, s, t);
  const Vec2& p00 = at(ci, cj);
  const Vec2& p10 = at(ci + 1, cj);
  const Vec2& p01 = at(ci, cj + 1);
  const Vec2& p11 = at(ci + 1, cj + 1);
  return (1 - t) * ((1 - s) * p00 + s * p10) + t * ((1 - s) * p01 + s * p11);
}

GridWarp GridWarp::blended(double t) const {
  GridWarp g = uniform(n);
  for (size_t k = 0; k < points.size(); ++k) g.points[k] = (1 - t) * g.points[k] + t * points[k];
  g.lo = lo;
  g.hi = hi;
  return g;
}

double GridWarp::max_displacement() const {
  double m = 0;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m = std::max(m, (at(i, j) - Vec2(double(i) / n, double(j) / n)).cwiseProduct(hi - lo).norm());
  return m;
}

namespace {
/// True if the rectangles of \p a and \p b are more than \p gap apart along x or y.
bool apart(const GridWarp& a, const GridWarp& b, double gap) {
  return a.hi.x() + gap < b.lo.x() || b.hi.x() + gap < a.lo.x() || a.hi.y() + gap < b.lo.y() ||
         b.hi.y() + gap < a.lo.y();
}
}  // namespace

WarpChain::WarpChain(std::vector<const GridWarp*> warps) {
  for (const GridWarp* w : warps)
    if (w) warps_.push_back(w);
  if (warps_.size() < 2) return;
  for (const GridWarp* w : warps_)
    if (w->whole_square() || !w->lo.allFinite() || !w->hi.allFinite() ||
        !(w->lo.x() <= w->hi.x() && w->lo.y() <= w->hi.y()))
      return;
  // Pairwise apart, by a sweep over the rectangles sorted by lo.x.
  std::vector<int> order(warps_.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return warps_[a]->lo.x() < warps_[b]->lo.x(); });
  for (size_t a = 0; a < order.size(); ++a)
    for (size_t b = a + 1; b < order.size() && warps_[order[b]]->lo.x() <= warps_[order[a]]->hi.x() + kMinGap; ++b)
      if (!apart(*warps_[order[a]], *warps_[order[b]], kMinGap)) return;
  n_ = std::clamp(static_cast<int>(std::sqrt(double(warps_.size()))) * 2, 1, 256);
  auto cell = [this](double x) { return static_cast<int>(std::clamp(std::floor(x * n_), 0.0, n_ - 1.0)); };
  std::vector<std::vector<int>> buckets(static_cast<size_t>(n_) * n_);
  for (size_t k = 0; k < warps_.size(); ++k) {
    const double pad = 1e-12;  // GridWarp::contains()' tolerance
    for (int y = cell(warps_[k]->lo.y() - pad); y <= cell(warps_[k]->hi.y() + pad); ++y)
      for (int x = cell(warps_[k]->lo.x() - pad); x <= cell(warps_[k]->hi.x() + pad); ++x)
        buckets[static_cast<size_t>(y) * n_ + x].push_back(static_cast<int>(k));
  }
  start_.assign(buckets.size() + 1, 0);
  for (size_t b = 0; b < buckets.size(); ++b) start_[b + 1] = start_[b] + static_cast<int>(buckets[b].size());
  for (const auto& b : buckets) entries_.insert(entries_.end(), b.begin(), b.end());
}

Vec2 WarpChain::apply(const Vec2& uv) const {
  if (n_ == 0 || !std::isfinite(uv.x()) || !std::isfinite(uv.y())) {
    Vec2 q = uv;
    for (const GridWarp* w : warps_) q = w->apply(q);
    return q;
  }
  // A point in one rectangle stays in it (within round-off: the lattice points lie in [0,1]²) and so
  // outside every other.
  auto cell = [this](double x) { return static_cast<int>(std::clamp(std::floor(x * n_), 0.0, n_ - 1.0)); };
  const size_t b = static_cast<size_t>(cell(uv.y())) * n_ + cell(uv.x());
  for (int k = start_[b]; k < start_[b + 1]; ++k)
    if (warps_[entries_[k]]->contains(uv)) return warps_[entries_[k]]->apply(uv);
  return uv;
}

ImageF pull_back_field(const ImageF& field, const GridWarp& warp, int res) {
  ImageF out(res, res, -1.0f);
  const int n = warp.n;
  // Rasterize every warped cell: for texel centres in its bounding box, invert the bilinear map by
  // Newton from the cell centre; accept local coordinates inside [0,1]^2 (small tolerance).
  tbb::parallel_for(0, n, [&](int cj) {
    for (int ci = 0; ci < n; ++ci) {
      const Vec2 p00 = warp.at(ci, cj), p10 = warp.at(ci + 1, cj);
      const Vec2 p01 = warp.at(ci, cj + 1), p11 = warp.at(ci + 1, cj + 1);
      const double xmin = std::min({p00.x(), p10.x(), p01.x(), p11.x()});
      const double xmax = std::max({p00.x(), p10.x(), p01.x(), p11.x()});
      const double ymin = std::min({p00.y(), p10.y(), p01.y(), p11.y()});
      const double ymax = std::max({p00.y(), p10.y(), p01.y(), p11.y()});
      const int i0 = std::max(0, static_cast<int>(std::ceil(xmin * res - 0.5)));
      const int i1 = std::min(res - 1, static_cast<int>(std::floor(xmax * res - 0.5)));
      const int j0 = std::max(0, static_cast<int>(std::ceil(ymin * res - 0.5)));
      const int j1 = std::min(res - 1, static_cast<int>(std::floor(ymax * res - 0.5)));
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const Vec2 q((i + 0.5) / res, (j + 0.5) / res);
          double s = 0.5, t = 0.5;
          bool ok = false;
          for (int it = 0; it < 12; ++it) {
            const Vec2 f = (1 - t) * ((1 - s) * p00 + s * p10) + t * ((1 - s) * p01 + s * p11) - q;
            const Vec2 ds = (1 - t) * (p10 - p00) + t * (p11 - p01);
            const Vec2 dt = (1 - s) * (p01 - p00) + s * (p11 - p10);
            const double det = ds.x() * dt.y() - ds.y() * dt.x();
            if (std::abs(det) < 1e-300) break;
            const double es = (f.x() * dt.y() - f.y() * dt.x()) / det;
            const double et = (ds.x() * f.y() - ds.y() * f.x()) / det;
            s -= es;
            t -= et;
            if (std::abs(es) + std::abs(et) < 1e-10) {
              ok = true;
              break;
            }
          }
          const double tol = 1e-7;
          if (!ok || s < -tol || s > 1 + tol || t < -tol || t > 1 + tol) continue;
          const Vec2 p((ci + std::clamp(s, 0.0, 1.0)) / n, (cj + std::clamp(t, 0.0, 1.0)) / n);
          // Cells share edges: any covering cell gives the same p up to round-off.
          std::atomic_ref<float>(out.at(i, j))
              .store(static_cast<float>(sample_bilinear(field, p.x(), p.y())), std::memory_order_relaxed);
        }
    }
  });
  for (int j = 0; j < res; ++j)
    for (int i = 0; i < res; ++i)
      if (out.at(i, j) < 0.0f)
        out.at(i, j) = static_cast<float>(sample_bilinear(field, (i + 0.5) / res, (j + 0.5) / res));
  return out;
}

bool cell_convex(const GridWarp& g, int i, int j) {
  const Vec2 q[4] = {g.at(i, j), g.at(i + 1, j), g.at(i + 1, j + 1), g.at(i, j + 1)};
  for (int k = 0; k < 4; ++k) {
    const Vec2 a = q[(k + 1) % 4] - q[k], b = q[(k + 3) % 4] - q[k];
    if (!(a.x() * b.y() - a.y() * b.x() > 0)) return false;
  }
  return true;
}

std::vector<char> convex_cells(const GridWarp& g) {
  const int n = g.n;
  std::vector<char> ok(static_cast<size_t>(n) * n, 0);
  tbb::parallel_for(0, n, [&](int j) {
    for (int i = 0; i < n; ++i) ok[static_cast<size_t>(j) * n + i] = cell_convex(g, i, j);
  });
  return ok;
}

namespace {
/// Moves lattice point (i, j) of \p g to the mean of its four neighbours; a side point slides along
/// its side (the mean of its two side neighbours); a corner stays.
void smooth_point(GridWarp& g, int i, int j) {
  const int n = g.n;
  const bool side_x = i == 0 || i == n, side_y = j == 0 || j == n;
  if (side_x && side_y) return;
  Vec2& p = g.at(i, j);
  if (side_x) p.y() = 0.5 * (g.at(i, j - 1).y() + g.at(i, j + 1).y());
  else if (side_y) p.x() = 0.5 * (g.at(i - 1, j).x() + g.at(i + 1, j).x());
  else p = 0.25 * (g.at(i - 1, j) + g.at(i + 1, j) + g.at(i, j - 1) + g.at(i, j + 1));
}
}  // namespace

int untangle_lattice(GridWarp& g) {
  const int n = g.n;
  const size_t cells = static_cast<size_t>(n) * n, points = static_cast<size_t>(n + 1) * (n + 1);
  // Only the cells around a smoothed point change, so after the first full scan a round re-checks
  // just those: the same rounds and the same points as re-checking every cell, far fewer tests.
  std::vector<char> convex(cells), bad(cells, 0), mark(points, 0);
  std::vector<int> bad_cells, marked, checked(cells, 0);  // checked: last round that re-checked a cell
  int count = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const size_t c = static_cast<size_t>(j) * n + i;
      convex[c] = cell_convex(g, i, j);
      if (!convex[c]) {
        ++count;
        bad[c] = 1;
        bad_cells.push_back(static_cast<int>(c));
      }
    }
  const int first = count;
  int marked_grow = 0;    // the halo width the marked points were taken with
  size_t halo_done = 0;   // bad_cells[0, halo_done) are marked with that halo
  for (int round = 0; round < 200 && count > 0; ++round) {
    const int grow = 1 + round / 10;  // widen the smoothed region when smoothing alone does not untangle
    // The smoothed region only grows (bad cells stay bad, the halo widens): add the new points, of
    // the new bad cells, or of all of them when the halo widens.
    const size_t before = marked.size();
    if (grow != marked_grow) halo_done = 0;
    marked_grow = grow;
    for (; halo_done < bad_cells.size(); ++halo_done) {
      const int c = bad_cells[halo_done];
      const int i = c % n, j = c / n;
      for (int b = std::max(0, j - grow); b <= std::min(n, j + 1 + grow); ++b)
        for (int a = std::max(0, i - grow); a <= std::min(n, i + 1 + grow); ++a) {
          const int k = b * (n + 1) + a;
          if (!mark[static_cast<size_t>(k)]) {
            mark[static_cast<size_t>(k)] = 1;
            marked.push_back(k);
          }
        }
    }
    // Raster order, as a sweep over the whole lattice visits them.
    const auto mid = marked.begin() + static_cast<std::ptrdiff_t>(before);
    std::sort(mid, marked.end());
    std::inplace_merge(marked.begin(), mid, marked.end());
    for (int sweep = 0; sweep < 4; ++sweep)
      for (int k : marked) smooth_point(g, k % (n + 1), k / (n + 1));
    // Re-check the cells that have a smoothed corner.
    for (int k : marked) {
      const int i = k % (n + 1), j = k / (n + 1);
      for (int b = std::max(0, j - 1); b <= std::min(n - 1, j); ++b)
        for (int a = std::max(0, i - 1); a <= std::min(n - 1, i); ++a) {
          const size_t c = static_cast<size_t>(b) * n + a;
          if (checked[c] == round + 1) continue;
          checked[c] = round + 1;
          const bool now = cell_convex(g, a, b);
          if (now == static_cast<bool>(convex[c])) continue;
          convex[c] = now;
          count += now ? -1 : 1;
          if (!now && !bad[c]) {
            bad[c] = 1;
            bad_cells.push_back(static_cast<int>(c));
          }
        }
    }
  }
  return first;
}

size_t untangle_turned_cells(GridWarp& g, const std::vector<char>& convex, int* turned) {
  const int n = g.n;
  const std::vector<char> now = convex_cells(g);
  std::vector<int> bad, points, cells;
  for (size_t c = 0; c < now.size(); ++c)
    if (convex[c] && !now[c]) bad.push_back(static_cast<int>(c));
  if (turned) *turned = static_cast<int>(bad.size());
  int ring = 0;
  size_t best = bad.size();
  for (int round = 0, since_best = 0; round < 1000 && !bad.empty(); ++round) {
    if (bad.size() < best) best = bad.size(), since_best = 0;
    else if (++since_best >= 20) {
      if (ring == 4) break;
      ++ring, since_best = 0;
    }
    // Interior points only: a turned cell's sides stay where the motion put them.
    points.clear();
    for (int c : bad)
      for (int j = std::max(1, c / n - ring); j <= std::min(n - 1, c / n + 1 + ring); ++j)
        for (int i = std::max(1, c % n - ring); i <= std::min(n - 1, c % n + 1 + ring); ++i)
          points.push_back(j * (n + 1) + i);
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    cells = bad;  // only the cells around moved points can change
    for (int k : points) {
      const int i = k % (n + 1), j = k / (n + 1);
      smooth_point(g, i, j);
      for (int cj = j - 1; cj <= j; ++cj)
        for (int ci = i - 1; ci <= i; ++ci) cells.push_back(cj * n + ci);
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    bad.clear();
    for (int c : cells)
      if (convex[c] && !cell_convex(g, c % n, c / n)) bad.push_back(c);
  }
  return bad.size();
}

void gaussian_blur(std::vector<double>& f, int n, double sigma) {
  if (sigma <= 0) return;
  const int rad = std::max(1, static_cast<int>(std::ceil(3 * sigma)));
  std::vector<double> k(2 * rad + 1);
  for (int d = -rad; d <= rad; ++d) k[d + rad] = std::exp(-0.5 * d * d / (sigma * sigma));
  double w = 0;
  for (double x : k) w += x;
  // Source index of every tap position i + d, reflected at the sides (-1 -> 0, n -> n - 1, ...).
  std::vector<int> src(n + 2 * rad);
  for (int a = -rad; a < n + rad; ++a) {
    const int r = a < 0 ? -a - 1 : a >= n ? 2 * n - a - 1 : a;
    src[a + rad] = std::clamp(r, 0, n - 1);
  }
  std::vector<double> tmp(f.size());
  // Rows, then columns as whole-row sums (contiguous), both in tap order.
  // The row pass reflects the row into a padded copy, then sums tap by tap over the whole row (the
  // same sums in the same order as tap by tap per texel, but contiguous).
  tbb::parallel_for(0, n, [&](int j) {
    const double* row = f.data() + static_cast<size_t>(j) * n;
    std::vector<double> padded(src.size()), acc(n, 0.0);
    for (size_t a = 0; a < src.size(); ++a) padded[a] = row[src[a]];
    for (int d = 0; d <= 2 * rad; ++d) {
      const double kd = k[d], *in = padded.data() + d;
      for (int i = 0; i < n; ++i) acc[i] += kd * in[i];
    }
    for (int i = 0; i < n; ++i) tmp[static_cast<size_t>(j) * n + i] = acc[i] / w;
  });
  tbb::parallel_for(0, n, [&](int i) {
    double* out = f.data() + static_cast<size_t>(i) * n;
    std::fill(out, out + n, 0.0);
    for (int d = 0; d <= 2 * rad; ++d) {
      const double* row = tmp.data() + static_cast<size_t>(src[i + d]) * n;
      for (int j = 0; j < n; ++j) out[j] += k[d] * row[j];
    }
    for (int j = 0; j < n; ++j) out[j] /= w;
  });
}

}  // namespace adaptex
