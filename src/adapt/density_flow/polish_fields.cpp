// The fields the error-model polish reads (error_polish.h): error, exponent and density resampled to
// the lattice, and the paint's edge directions (structure tensor).
#include "adaptex/adapt/error_polish.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "adaptex/core/errors.h"

namespace adaptex {

PolishFields polish_fields(const ImageF& error, const ImageF& exponent, const ImageF& density, const Vec2& lo,
                           const Vec2& hi, int n, double scale) {
  const int L = error.width;
  if (L < 1 || error.height != L || exponent.width != L || exponent.height != L || density.width != L ||
      density.height != L)
    throw InvalidInputError("polish_fields: error, exponent and density must be L x L, L >= 1");
  if (n < 1) throw InvalidInputError("polish_fields: n must be >= 1");
  if (!(scale > 0) || !std::isfinite(scale)) throw InvalidInputError("polish_fields: scale must be finite and > 0");
  if (!(lo.x() < hi.x() && lo.y() < hi.y() && lo.minCoeff() >= 0 && hi.maxCoeff() <= 1))
    throw InvalidInputError("polish_fields: the rectangle must be non-empty and inside the unit square");
  PolishFields f;
  f.error = ImageF(n, n, 0.0f);
  f.exponent = ImageF(n, n, 0.0f);
  f.floor = ImageF(n, n, 0.0f);
  std::vector<BilinearTap> tu(n), tv(n);
  for (int i = 0; i < n; ++i) {
    tu[i] = bilinear_tap(L, lo.x() + (i + 0.5) / n * (hi.x() - lo.x()));
    tv[i] = bilinear_tap(L, lo.y() + (i + 0.5) / n * (hi.y() - lo.y()));
  }
  std::vector<double> row_density(n, 0.0);  // summed in row order below: thread-independent
  tbb::parallel_for(0, n, [&](int j) {
    for (int i = 0; i < n; ++i) {
      const int xs[2] = {tu[i].i0, tu[i].i1}, ys[2] = {tv[j].i0, tv[j].i1};
      const double wx[2] = {1 - tu[i].f, tu[i].f}, wy[2] = {1 - tv[j].f, tv[j].f};
      double q = 0, qp = 0, rho = 0;
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
          const double w = wx[a] * wy[b], e = error.at(xs[a], ys[b]);
          q += w * e, qp += w * e * exponent.at(xs[a], ys[b]), rho += w * density.at(xs[a], ys[b]);
        }
      const double p = q > 0 ? qp / q : 0.0;
      f.error.at(i, j) = static_cast<float>(scale == 1 ? q : q * std::pow(scale, -p));
      f.exponent.at(i, j) = static_cast<float>(p);
      f.floor.at(i, j) = static_cast<float>(rho);
      row_density[j] += rho;
    }
  });
  double density_sum = 0;
  for (double r : row_density) density_sum += r;
  f.aspect = (hi.x() - lo.x()) / (hi.y() - lo.y());
  const double mean = density_sum / (double(n) * n);
  for (size_t k = 0; k < f.floor.data.size(); ++k)
    f.floor.data[k] = f.error.data[k] > 0 || !(mean > 0) ? 0.0f : static_cast<float>(f.floor.data[k] / mean);
  return f;
}

EdgeTensor edge_tensor(const ImageRGBA8& texture) {
  EdgeTensor t;
  edge_tensor(texture, t);
  return t;
}

void edge_tensor(const ImageRGBA8& texture, EdgeTensor& t) {
  const int W = texture.width, H = texture.height;
  if (texture.empty()) throw InvalidInputError("edge_tensor: the texture is empty");
  for (ImageF* img : {&t.xx, &t.xy, &t.yy}) {  // every texel is written below
    img->width = W, img->height = H;
    img->data.resize(static_cast<size_t>(W) * H);
  }
  tbb::parallel_for(0, H, [&](int j) {
    const int j0 = std::max(0, j - 1), j1 = std::min(H - 1, j + 1);
    for (int i = 0; i < W; ++i) {
      const int i0 = std::max(0, i - 1), i1 = std::min(W - 1, i + 1);
      double xx = 0, xy = 0, yy = 0;
      for (int ch = 0; ch < 3; ++ch) {
        const double gx = (double(texture.texel(i1, j)[ch]) - texture.texel(i0, j)[ch]) / std::max(1, i1 - i0);
        const double gy = (double(texture.texel(i, j1)[ch]) - texture.texel(i, j0)[ch]) / std::max(1, j1 - j0);
        xx += gx * gx, xy += gx * gy, yy += gy * gy;
      }
      t.xx.at(i, j) = static_cast<float>(xx), t.xy.at(i, j) = static_cast<float>(xy), t.yy.at(i, j) = static_cast<float>(yy);
    }
  });
  // Summed-area tables (double: sums of up to W·H squared gradients): prefix sums along the rows,
  // rows in parallel, then down the columns, column blocks in parallel. The terms are multiples of
  // 1/4 below 2^20 (8-bit channels, central differences), so every partial sum is exact and the
  // table does not depend on the order of the additions.
  auto table = [&](const ImageF& img, std::vector<double>& s) {
    const size_t stride = static_cast<size_t>(W) + 1;
    s.assign(stride * (H + 1), 0.0);
    tbb::parallel_for(0, H, [&](int j) {
      double* row = &s[(static_cast<size_t>(j) + 1) * stride];
      for (int i = 0; i < W; ++i) row[i + 1] = row[i] + img.at(i, j);
    });
    tbb::parallel_for(tbb::blocked_range<size_t>(1, stride, 256), [&](const tbb::blocked_range<size_t>& cols) {
      for (int j = 1; j < H; ++j) {
        const double* above = &s[static_cast<size_t>(j) * stride];
        double* row = &s[(static_cast<size_t>(j) + 1) * stride];
        for (size_t i = cols.begin(); i < cols.end(); ++i) row[i] += above[i];
      }
    });
  };
  tbb::parallel_invoke([&] { table(t.xx, t.sum_xx); }, [&] { table(t.xy, t.sum_xy); }, [&] { table(t.yy, t.sum_yy); });
}

void add_edge_directions(PolishFields& fields, const EdgeTensor& edges, const Vec2& lo, const Vec2& hi,
                         double isotropy) {
  const int n = fields.error.width, W = edges.xx.width, H = edges.xx.height;
  if (n < 1 || fields.error.height != n) throw InvalidInputError("add_edge_directions: the fields must be n x n, n >= 1");
  if (W < 1 || H < 1 || edges.xy.width != W || edges.yy.width != W || edges.xy.height != H || edges.yy.height != H)
    throw InvalidInputError("add_edge_directions: the edge tensor's rasters must have one non-empty size");
  if (!(isotropy > 0 && isotropy <= 1)) throw InvalidInputError("add_edge_directions: isotropy must be in (0, 1]");
  if (!(lo.x() < hi.x() && lo.y() < hi.y() && lo.minCoeff() >= 0 && hi.maxCoeff() <= 1))
    throw InvalidInputError("add_edge_directions: the rectangle must be non-empty and inside the unit square");
  const size_t table = static_cast<size_t>(W + 1) * (H + 1);
  if (edges.sum_xx.size() != table || edges.sum_xy.size() != table || edges.sum_yy.size() != table)
    throw InvalidInputError("add_edge_directions: the edge tensor has no summed-area tables of its size (edge_tensor())");
  const std::vector<double>&sxx = edges.sum_xx, &sxy = edges.sum_xy, &syy = edges.sum_yy;
  // Texel index range [a, b) of the cells c - 1 .. c + 1 along one axis (at least one texel).
  auto range = [&](int c, double l, double h, int size) {
    const double u0 = l + (c - 1.0) / n * (h - l), u1 = l + (c + 2.0) / n * (h - l);
    int a = std::clamp(static_cast<int>(std::floor(u0 * size)), 0, size - 1);
    int b = std::clamp(static_cast<int>(std::ceil(u1 * size)), a + 1, size);
    return std::pair<int, int>(a, b);
  };
  fields.txx = ImageF(n, n), fields.txy = ImageF(n, n), fields.tyy = ImageF(n, n);
  for (int j = 0; j < n; ++j) {
    const std::pair<int, int> ys = range(j, lo.y(), hi.y(), H);
    const int y0 = ys.first, y1 = ys.second;  // (clang 14 cannot capture structured bindings)
    for (int i = 0; i < n; ++i) {
      const std::pair<int, int> xs = range(i, lo.x(), hi.x(), W);
      const int x0 = xs.first, x1 = xs.second;
      auto box = [&](const std::vector<double>& s) {
        auto at = [&](int x, int y) { return s[static_cast<size_t>(y) * (W + 1) + x]; };
        return at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
      };
      const double xx = box(sxx), xy = box(sxy), yy = box(syy), tr = xx + yy;
      const double w = tr > 0 ? (1 - isotropy) / tr : 0.0, iso = tr > 0 ? 0.5 * isotropy : 0.5;
      fields.txx.at(i, j) = static_cast<float>(w * xx + iso);
      fields.txy.at(i, j) = static_cast<float>(w * xy);
      fields.tyy.at(i, j) = static_cast<float>(w * yy + iso);
    }
  }
}

}  // namespace adaptex
