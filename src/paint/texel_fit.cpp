/// \file texel_fit.cpp
/// Least-squares texel fit (see texel_fit.h): quadrature samples bucketed by the row of their
/// bilinear footprint, a 9-point stencil assembled row-parallel without races, and a 4-channel
/// Jacobi-preconditioned CG on the covered texels.
#include "adaptex/paint/texel_fit.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/paint/padding.h"

namespace adaptex {

namespace {

using Vec4d = std::array<double, 4>;

/// The bilinear tap of one axis under \p address: clamp gives exactly bilinear_tap() (inlined here,
/// as the quadrature calls it several times per sample); repeat wraps the indices.
inline BilinearTap tap(int size, double u, TextureAddress address) {
  const double x = u * size - 0.5;
  const double xf = std::floor(x);
  if (address == TextureAddress::ClampToEdge) {
    const int xi = static_cast<int>(std::clamp(xf, -1.0, static_cast<double>(size)));
    return BilinearTap{std::clamp(xi, 0, size - 1), std::clamp(xi + 1, 0, size - 1), x - xf};
  }
  double m = std::fmod(xf, static_cast<double>(size));
  if (m < 0) m += size;
  const int i0 = std::clamp(static_cast<int>(m), 0, size - 1);
  return BilinearTap{i0, i0 + 1 == size ? 0 : i0 + 1, x - xf};
}

/// One quadrature sample: the bilinear footprint in the new texture, the original's UV, the area weight.
struct Sample {
  std::uint16_t i0, i1, j0, j1;
  float fx, fy;
  float su, sv;
  float weight;
  float cell;  // area of the sample's cell in the original's UV square (sets the prefilter level)
};

/// A footprint as up to 4 distinct (texel, bilinear weight > 0) entries.
struct Footprint {
  int n = 0;
  int texel[4];
  int col[4], row[4];
  double b[4];
};

Footprint footprint(const Sample& s, int W) {
  Footprint fp;
  const int is[2] = {s.i0, s.i1}, js[2] = {s.j0, s.j1};
  const double wx[2] = {1.0 - s.fx, s.fx}, wy[2] = {1.0 - s.fy, s.fy};
  for (int b = 0; b < 2; ++b)
    for (int a = 0; a < 2; ++a) {
      const double w = wx[a] * wy[b];
      if (w <= 0) continue;
      const int t = js[b] * W + is[a];
      int k = 0;
      while (k < fp.n && fp.texel[k] != t) ++k;
      if (k == fp.n) {
        fp.texel[k] = t;
        fp.col[k] = is[a];
        fp.row[k] = js[b];
        fp.b[k] = 0;
        ++fp.n;
      }
      fp.b[k] += w;
    }
  return fp;
}

/// Stencil slot (0..8) of texel q seen from texel p, offsets canonical under wrapping (see offset()).
inline int axis_offset(int d, int size) {
  if (d == 0) return 0;
  if (d == 1 || d == -(size - 1)) return 1;
  return -1;
}

/// The faces' sample counts m (m² samples on face f), scaled down to fit the cap.
std::vector<int> sample_grid(const TriMesh& mesh, const Parameterization& sp, int sw, int sh,
                             const Parameterization& np, int W, int H, const TexelFitOptions& o) {
  const int F = static_cast<int>(mesh.faces.size());
  std::vector<double> want(F, 0.0);
  double total = 0;
  for (int f = 0; f < F; ++f) {
    if (!(face_area(mesh, f) > 0)) continue;
    const double an = std::abs(uv_signed_area(np, f)) * W * H, as = std::abs(uv_signed_area(sp, f)) * sw * sh;
    want[f] = std::max({o.samples_per_texel * an, o.samples_per_source_texel * as, 1.0});
    total += want[f];
  }
  std::vector<int> m(F, 0);
  for (double scale = std::min(1.0, double(o.max_samples) / std::max(total, 1.0));; scale *= 0.8) {
    long long count = 0;
    for (int f = 0; f < F; ++f) {
      if (want[f] <= 0) continue;
      m[f] = std::max(1, static_cast<int>(std::ceil(std::sqrt(want[f] * scale))));
      count += static_cast<long long>(m[f]) * m[f];
    }
    if (count <= o.max_samples) return m;
    if (scale < 1e-12)
      throw InvalidInputError("texel fit: the mesh has more faces than max_samples (" +
                              std::to_string(o.max_samples) + ")");
  }
}

/// Calls \p emit(s, t) at the centroids of face-local coordinates (P = P0 + s (P1-P0) + t (P2-P0)) of
/// the regular subdivision into n² triangles: "up" (a, b) with a + b <= n-1, "down" with a + b <= n-2.
template <class Emit>
void for_each_centroid(int n, const Emit& emit) {
  for (int a = 0; a < n; ++a)
    for (int b = 0; a + b < n; ++b) {
      emit((a + 1.0 / 3.0) / n, (b + 1.0 / 3.0) / n);
      if (a + b <= n - 2) emit((a + 2.0 / 3.0) / n, (b + 2.0 / 3.0) / n);
    }
}

/// Corner UV and edge vectors of face \p f of \p p.
std::array<Vec2, 3> face_frame(const Parameterization& p, int f) {
  const Face& w = p.uv_faces[f];
  return {p.uv[w[0]], p.uv[w[1]] - p.uv[w[0]], p.uv[w[2]] - p.uv[w[0]]};
}

/// The sample at face-local (s, t). One out-of-line body, so that both passes of generate_samples()
/// compute bit-identical rows.
[[gnu::noinline]] Sample make_sample(const std::array<Vec2, 3>& nf, const std::array<Vec2, 3>& sf, double s, double t,
                                     int W, int H, TextureAddress address, float weight, float cell) {
  const Vec2 uv = nf[0] + s * nf[1] + t * nf[2], suv = sf[0] + s * sf[1] + t * sf[2];
  const BilinearTap x = tap(W, uv.x(), address), y = tap(H, uv.y(), address);
  return Sample{static_cast<std::uint16_t>(x.i0), static_cast<std::uint16_t>(x.i1),
                static_cast<std::uint16_t>(y.i0), static_cast<std::uint16_t>(y.i1),
                static_cast<float>(x.f), static_cast<float>(y.f),
                static_cast<float>(suv.x()), static_cast<float>(suv.y()), weight, cell};
}

/// The samples in buckets by the footprint's first row j0 (\p row_start[j]: first sample of row j);
/// inside a row in face order. Two passes over fixed blocks of faces: count per (block, row), then
/// write every sample to its place, so the order does not depend on the thread count.
std::unique_ptr<Sample[]> generate_samples(const TriMesh& mesh, const Parameterization& sp,
                                           const Parameterization& np, int W, int H, const std::vector<int>& m,
                                           const TexelFitOptions& o, std::vector<long long>& row_start) {
  const int F = static_cast<int>(mesh.faces.size());
  const int blocks = std::clamp(F / 64, 1, 256);
  auto block_begin = [&](int b) { return static_cast<int>(static_cast<long long>(F) * b / blocks); };
  // Pass 1: samples per (block, row).
  std::vector<long long> count(static_cast<size_t>(blocks) * H, 0);
  tbb::parallel_for(0, blocks, [&](int b) {
    long long* c = count.data() + static_cast<size_t>(b) * H;
    for (int f = block_begin(b); f < block_begin(b + 1); ++f) {
      if (m[f] == 0) continue;
      const auto nf = face_frame(np, f), sf = face_frame(sp, f);
      for_each_centroid(m[f], [&](double s, double t) { ++c[make_sample(nf, sf, s, t, W, H, o.address, 0, 0).j0]; });
    }
  });
  // Offsets: row by row, block by block.
  row_start.assign(static_cast<size_t>(H) + 1, 0);
  long long total = 0;
  for (int j = 0; j < H; ++j) {
    row_start[j] = total;
    for (int b = 0; b < blocks; ++b) {
      const long long c = count[static_cast<size_t>(b) * H + j];
      count[static_cast<size_t>(b) * H + j] = total;
      total += c;
    }
  }
  row_start[H] = total;
  // Pass 2: every sample to its place (uninitialised storage: every slot is written once).
  std::unique_ptr<Sample[]> out(new Sample[static_cast<size_t>(total)]);
  tbb::parallel_for(0, blocks, [&](int b) {
    long long* next = count.data() + static_cast<size_t>(b) * H;
    for (int f = block_begin(b); f < block_begin(b + 1); ++f) {
      if (m[f] == 0) continue;
      const float weight = static_cast<float>(face_area(mesh, f) / (double(m[f]) * m[f]));
      const float cell = static_cast<float>(std::abs(uv_signed_area(sp, f)) / (double(m[f]) * m[f]));
      const auto nf = face_frame(np, f), sf = face_frame(sp, f);
      for_each_centroid(m[f], [&](double s, double t) {
        const Sample smp = make_sample(nf, sf, s, t, W, H, o.address, weight, cell);
        out[static_cast<size_t>(next[smp.j0]++)] = smp;
      });
    }
  });
  return out;
}

/// Runs \p body(j) for every row bucket j so that no two concurrent buckets write the same row:
/// bucket j writes rows j0 = j and j1 in {j, j+1 mod H}; even, then odd buckets below H-1, then H-1.
template <class Body>
void for_buckets(int H, const Body& body) {
  for (int parity = 0; parity < 2; ++parity) {
    const int count = (H - 1 - parity + 1) / 2;  // buckets parity, parity+2, ... < H-1
    if (count > 0)
      tbb::parallel_for(0, count, [&](int k) { body(parity + 2 * k); });
  }
  body(H - 1);
}

}  // namespace

std::array<double, 4> sample_bilinear_rgba(const ImageRGBA8& img, double u, double v, TextureAddress address) {
  const BilinearTap x = tap(img.width, u, address), y = tap(img.height, v, address);
  std::array<double, 4> out;
  for (int c = 0; c < 4; ++c) {
    const double a = img.texel(x.i0, y.i0)[c], b = img.texel(x.i1, y.i0)[c];
    const double d = img.texel(x.i0, y.i1)[c], e = img.texel(x.i1, y.i1)[c];
    const double bottom = a + (b - a) * x.f, top = d + (e - d) * x.f;
    out[c] = bottom + (top - bottom) * y.f;
  }
  return out;
}

namespace {

/// \p img, then 2 x 2 box means of it, down to level ceil(max_level) (just \p img when max_level <= 0).
std::vector<ImageRGBA8> box_pyramid(const ImageRGBA8& img, double max_level) {
  std::vector<ImageRGBA8> levels{img};
  const int top = static_cast<int>(std::ceil(std::min(max_level, 16.0)));
  for (int l = 1; l <= top && (levels.back().width > 1 || levels.back().height > 1); ++l) {
    const ImageRGBA8& f = levels.back();
    ImageRGBA8 c((f.width + 1) / 2, (f.height + 1) / 2);
    for (int J = 0; J < c.height; ++J)
      for (int I = 0; I < c.width; ++I)
        for (int ch = 0; ch < 4; ++ch) {
          int sum = 0;
          for (int b = 0; b < 2; ++b)
            for (int a = 0; a < 2; ++a) sum += f.texel(std::min(2 * I + a, f.width - 1), std::min(2 * J + b, f.height - 1))[ch];
          c.texel(I, J)[ch] = static_cast<std::uint8_t>((sum + 2) / 4);
        }
    levels.push_back(std::move(c));
  }
  return levels;
}

/// Trilinear lookup at the level whose texels match the sample's cell (\p texels: level 0's count).
Vec4d sample_trilinear(const std::vector<ImageRGBA8>& levels, const Sample& smp, double texels, TextureAddress address) {
  const double lod = std::clamp(0.5 * std::log2(std::max(1e-30, double(smp.cell) * texels)), 0.0,
                                static_cast<double>(levels.size() - 1));
  const int l0 = static_cast<int>(lod);
  const double f = lod - l0;
  const Vec4d a = sample_bilinear_rgba(levels[l0], smp.su, smp.sv, address);
  if (f <= 0 || l0 + 1 >= static_cast<int>(levels.size())) return a;
  const Vec4d b = sample_bilinear_rgba(levels[l0 + 1], smp.su, smp.sv, address);
  Vec4d out;
  for (int c = 0; c < 4; ++c) out[c] = a[c] + (b[c] - a[c]) * f;
  return out;
}

}  // namespace

struct TexelFitter::Impl {
  int W = 0, H = 0;
  TexelFitOptions options;
  std::unique_ptr<Sample[]> samples;   // bucketed by j0 (row_start)
  std::vector<long long> row_start;    // H + 1
  std::vector<bool> coverage;          // W*H
  std::vector<int> index;              // W*H: compact index of a covered texel, -1 elsewhere
  std::vector<int> texel;              // n: texel of compact index k
  std::vector<int> cols;               // 9n: ELL columns (compact), self with value 0 when unused
  std::vector<float> vals;             // 9n
  std::vector<double> diag;            // n
  std::vector<double> mass;            // n: sum of w * b over the samples touching the texel
  double max_cell = 0;                 // largest Sample::cell
  double anchor = 0;                   // weight of the pull towards the prefiltered start (added to diag)

  void assemble();
  void add_smoothness(const std::vector<float>& stencil);
  std::vector<Vec4d> rhs(const ImageRGBA8& source) const;
  int solve(std::vector<Vec4d>& x, const std::vector<Vec4d>& b, double& residual) const;
};

namespace {

/// Compact index ranges for deterministic block reductions.
constexpr int kBlock = 8192;

Vec4d dot4(const std::vector<Vec4d>& a, const std::vector<Vec4d>& b) {
  const int n = static_cast<int>(a.size());
  const int blocks = (n + kBlock - 1) / kBlock;
  std::vector<Vec4d> part(blocks, Vec4d{0, 0, 0, 0});
  tbb::parallel_for(0, blocks, [&](int blk) {
    Vec4d s{0, 0, 0, 0};
    for (int k = blk * kBlock, e = std::min(n, (blk + 1) * kBlock); k < e; ++k)
      for (int c = 0; c < 4; ++c) s[c] += a[k][c] * b[k][c];
    part[blk] = s;
  });
  Vec4d s{0, 0, 0, 0};
  for (const Vec4d& p : part)
    for (int c = 0; c < 4; ++c) s[c] += p[c];
  return s;
}

}  // namespace

void TexelFitter::Impl::assemble() {
  const size_t N = static_cast<size_t>(W) * H;
  std::vector<float> stencil(N * 9, 0.0f), mass_full(N, 0.0f);
  for_buckets(H, [&](int j) {
    for (long long s = row_start[j]; s < row_start[j + 1]; ++s) {
      const Sample& smp = samples[static_cast<size_t>(s)];
      const Footprint fp = footprint(smp, W);
      for (int p = 0; p < fp.n; ++p) {
        const int tp = fp.texel[p];
        const double wb = double(smp.weight) * fp.b[p];
        mass_full[tp] += static_cast<float>(wb);
        float* st = stencil.data() + static_cast<size_t>(tp) * 9;
        for (int q = 0; q < fp.n; ++q) {
          const int slot = (axis_offset(fp.row[q] - fp.row[p], H) + 1) * 3 + axis_offset(fp.col[q] - fp.col[p], W) + 1;
          st[slot] += static_cast<float>(wb * fp.b[q]);
        }
      }
    }
  });
  coverage.assign(N, false);
  index.assign(N, -1);
  texel.clear();
  for (size_t t = 0; t < N; ++t)
    if (mass_full[t] > 0) {
      coverage[t] = true;
      index[t] = static_cast<int>(texel.size());
      texel.push_back(static_cast<int>(t));
    }
  mass.resize(texel.size());
  for (size_t k = 0; k < texel.size(); ++k) mass[k] = mass_full[texel[k]];
  add_smoothness(stencil);
}

/// Adds the Laplacian between 4-neighbour covered texels and converts the stencil to ELL rows.
void TexelFitter::Impl::add_smoothness(const std::vector<float>& stencil) {
  const int n = static_cast<int>(texel.size());
  double mean_diag = 0;
  for (int k = 0; k < n; ++k) mean_diag += stencil[static_cast<size_t>(texel[k]) * 9 + 4];
  mean_diag /= std::max(1, n);
  const double lambda = options.smoothness * mean_diag;
  anchor = options.anchor * mean_diag;
  const bool wrap = options.address == TextureAddress::Repeat;
  cols.assign(static_cast<size_t>(n) * 9, 0);
  vals.assign(static_cast<size_t>(n) * 9, 0.0f);
  diag.assign(n, 0.0);
  tbb::parallel_for(0, n, [&](int k) {
    const int t = texel[k], i = t % W, j = t / W;
    double row[9];
    for (int s = 0; s < 9; ++s) row[s] = stencil[static_cast<size_t>(t) * 9 + s];
    int nb[9];
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        int a = i + di, b = j + dj;
        if (wrap) {
          a = (a + W) % W;
          b = (b + H) % H;
        }
        const int slot = (dj + 1) * 3 + di + 1;
        nb[slot] = (a < 0 || b < 0 || a >= W || b >= H) ? -1 : index[static_cast<size_t>(b) * W + a];
      }
    // Laplacian: slots 1, 3, 5, 7 are the 4-neighbours (a wrapped neighbour equal to t is skipped).
    for (int slot : {1, 3, 5, 7})
      if (nb[slot] >= 0 && nb[slot] != k) {
        row[4] += lambda;
        row[slot] -= lambda;
      }
    for (int s = 0; s < 9; ++s) {
      const bool used = nb[s] >= 0 && row[s] != 0;
      cols[static_cast<size_t>(k) * 9 + s] = used ? nb[s] : k;
      vals[static_cast<size_t>(k) * 9 + s] = used && s != 4 ? static_cast<float>(row[s]) : 0.0f;
    }
    diag[k] = row[4] + anchor;
  });
}

std::vector<Vec4d> TexelFitter::Impl::rhs(const ImageRGBA8& source) const {
  // Where a sample stands for more than one original texel (the sample cap bound), look the original
  // up at the matching level of a 2 x 2 box pyramid (trilinear), so the quadrature does not alias.
  const double texels = double(source.width) * source.height;
  const std::vector<ImageRGBA8> levels = box_pyramid(source, 0.5 * std::log2(std::max(1.0, max_cell * texels)));
  std::vector<Vec4d> b(texel.size(), Vec4d{0, 0, 0, 0});
  for_buckets(H, [&](int j) {
    for (long long s = row_start[j]; s < row_start[j + 1]; ++s) {
      const Sample& smp = samples[static_cast<size_t>(s)];
      const Footprint fp = footprint(smp, W);
      const Vec4d v = levels.size() == 1 ? sample_bilinear_rgba(source, smp.su, smp.sv, options.source_address)
                                         : sample_trilinear(levels, smp, texels, options.source_address);
      for (int p = 0; p < fp.n; ++p) {
        Vec4d& out = b[static_cast<size_t>(index[fp.texel[p]])];
        const double wb = double(smp.weight) * fp.b[p];
        for (int c = 0; c < 4; ++c) out[c] += wb * v[c];
      }
    }
  });
  return b;
}

/// Jacobi-preconditioned CG, the 4 channels at once (own step sizes; a converged channel stops).
int TexelFitter::Impl::solve(std::vector<Vec4d>& x, const std::vector<Vec4d>& b, double& residual) const {
  const int n = static_cast<int>(texel.size());
  auto matvec = [&](const std::vector<Vec4d>& in, std::vector<Vec4d>& out) {
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 2048), [&](const tbb::blocked_range<int>& r) {
      for (int k = r.begin(); k < r.end(); ++k) {
        Vec4d s;
        for (int c = 0; c < 4; ++c) s[c] = diag[k] * in[k][c];
        for (int t = 0; t < 9; ++t) {
          const double v = vals[static_cast<size_t>(k) * 9 + t];
          const Vec4d& o = in[cols[static_cast<size_t>(k) * 9 + t]];
          for (int c = 0; c < 4; ++c) s[c] += v * o[c];
        }
        out[k] = s;
      }
    });
  };
  std::vector<Vec4d> r(n), z(n), p(n), q(n);
  matvec(x, q);
  for (int k = 0; k < n; ++k)
    for (int c = 0; c < 4; ++c) {
      r[k][c] = b[k][c] - q[k][c];
      z[k][c] = r[k][c] / diag[k];
    }
  p = z;
  // Stop on the RMS of the Jacobi-scaled residual r / diag: about the texel change still to come.
  Vec4d rz = dot4(r, z), zz = dot4(z, z);
  bool done[4];
  auto rel = [&](int c) { return std::sqrt(zz[c] / std::max(1, n)); };
  for (int c = 0; c < 4; ++c) done[c] = rel(c) <= options.tolerance;
  int it = 0;
  for (; it < options.max_iterations && !(done[0] && done[1] && done[2] && done[3]); ++it) {
    if (it % 8 == 0) report_progress(options.progress, "fit solve", double(it) / options.max_iterations);
    matvec(p, q);
    const Vec4d pq = dot4(p, q);
    Vec4d alpha;
    for (int c = 0; c < 4; ++c) alpha[c] = done[c] || !(pq[c] > 0) ? 0.0 : rz[c] / pq[c];
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 4096), [&](const tbb::blocked_range<int>& rg) {
      for (int k = rg.begin(); k < rg.end(); ++k)
        for (int c = 0; c < 4; ++c) {
          x[k][c] += alpha[c] * p[k][c];
          r[k][c] -= alpha[c] * q[k][c];
          z[k][c] = r[k][c] / diag[k];
        }
    });
    const Vec4d rz_new = dot4(r, z);
    zz = dot4(z, z);
    Vec4d beta;
    for (int c = 0; c < 4; ++c) {
      if (!done[c] && (rel(c) <= options.tolerance || !(pq[c] > 0))) done[c] = true;
      beta[c] = done[c] || !(rz[c] > 0) ? 0.0 : rz_new[c] / rz[c];
      rz[c] = rz_new[c];
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 4096), [&](const tbb::blocked_range<int>& rg) {
      for (int k = rg.begin(); k < rg.end(); ++k)
        for (int c = 0; c < 4; ++c) p[k][c] = done[c] ? 0.0 : z[k][c] + beta[c] * p[k][c];
    });
  }
  residual = 0;
  for (int c = 0; c < 4; ++c) residual = std::max(residual, rel(c));
  return it;
}

namespace {

void check_layout(const TriMesh& mesh, const Parameterization& param, const char* what) {
  if (param.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError(std::string("texel fit: the ") + what + " layout has " +
                            std::to_string(param.uv_faces.size()) + " faces, the mesh " +
                            std::to_string(mesh.faces.size()));
  for (const Face& f : param.uv_faces)
    for (int k = 0; k < 3; ++k)
      if (f[k] < 0 || f[k] >= param.num_wedges())
        throw InvalidInputError(std::string("texel fit: the ") + what + " layout has a UV index out of range");
  for (const Vec2& uv : param.uv)
    if (!std::isfinite(uv.x()) || !std::isfinite(uv.y()) || std::abs(uv.x()) > 1e6 || std::abs(uv.y()) > 1e6)
      throw InvalidInputError(std::string("texel fit: the ") + what + " layout has a UV that is not finite");
}

void check_size(int w, int h, const char* what) {
  if (w < 1 || h < 1 || w > kMaxTextureSize || h > kMaxTextureSize)
    throw InvalidInputError(std::string("texel fit: ") + what + " size " + std::to_string(w) + "x" +
                            std::to_string(h) + " is outside 1.." + std::to_string(kMaxTextureSize));
}

}  // namespace

TexelFitter::TexelFitter(const TriMesh& mesh, const Parameterization& source_param, int source_width,
                         int source_height, const Parameterization& param, int width, int height,
                         const TexelFitOptions& options)
    : impl_(std::make_unique<Impl>()) {
  check_layout(mesh, source_param, "original");
  check_layout(mesh, param, "new");
  check_size(source_width, source_height, "original texture");
  check_size(width, height, "output texture");
  if (static_cast<long long>(width) * height > kMaxFitTexels)
    throw InvalidInputError("texel fit: output " + std::to_string(width) + "x" + std::to_string(height) +
                            " has more than 4096x4096 texels (about 300 bytes each while fitting)");
  if (!(options.samples_per_texel >= 0) || !(options.samples_per_source_texel >= 0) || options.max_samples < 1 ||
      !(options.smoothness >= 0) || !(options.anchor >= 0) || options.max_iterations < 0 || !(options.tolerance >= 0))
    throw InvalidInputError("texel fit: sample densities, smoothness, anchor and tolerance must be >= 0, max_samples >= 1");
  Impl& m = *impl_;
  m.W = width;
  m.H = height;
  m.options = options;
  report_progress(options.progress, "fit samples", 0.0);
  const std::vector<int> grid = sample_grid(mesh, source_param, source_width, source_height, param, width, height, options);
  m.samples = generate_samples(mesh, source_param, param, width, height, grid, options, m.row_start);
  for (size_t f = 0; f < grid.size(); ++f)
    if (grid[f] > 0)
      m.max_cell = std::max(m.max_cell, std::abs(uv_signed_area(source_param, static_cast<int>(f))) / (double(grid[f]) * grid[f]));
  report_progress(options.progress, "fit matrix", 0.0);
  m.assemble();
  report_progress(options.progress, "fit matrix", 1.0);
}

TexelFitter::~TexelFitter() = default;
TexelFitter::TexelFitter(TexelFitter&&) noexcept = default;
TexelFitter& TexelFitter::operator=(TexelFitter&&) noexcept = default;

const std::vector<bool>& TexelFitter::coverage() const { return impl_->coverage; }
long long TexelFitter::samples() const { return impl_->row_start.back(); }

TexelFitResult TexelFitter::fit(const ImageRGBA8& source) const {
  if (source.empty()) throw InvalidInputError("texel fit: empty original texture");
  const Impl& m = *impl_;
  report_progress(m.options.progress, "fit solve", 0.0);
  const size_t n = m.texel.size();
  // Start from the footprint-weighted mean of the original (a matched prefilter); the anchor term
  // pulls towards it, which decides the texels that only a sliver of a footprint touches.
  std::vector<Vec4d> b = m.rhs(source);
  std::vector<Vec4d> x(n);
  for (size_t k = 0; k < n; ++k)
    for (int c = 0; c < 4; ++c) {
      x[k][c] = b[k][c] / m.mass[k];
      b[k][c] += m.anchor * x[k][c];
    }
  TexelFitResult res;
  res.iterations = m.solve(x, b, res.residual);
  report_progress(m.options.progress, "fit solve", 1.0);
  res.texture = ImageRGBA8(m.W, m.H, m.options.outside);
  for (size_t k = 0; k < n; ++k)
    for (int c = 0; c < 4; ++c)
      res.texture.data[static_cast<size_t>(m.texel[k]) * 4 + c] =
          static_cast<std::uint8_t>(std::lround(std::clamp(x[k][c], 0.0, 255.0)));
  res.coverage = m.coverage;
  res.samples = samples();
  if (m.options.fill_outside) pull_push_fill(res.texture, res.coverage);
  return res;
}

TexelFitResult fit_texels(const TriMesh& mesh, const Parameterization& source_param, const ImageRGBA8& source,
                          const Parameterization& param, int width, int height, const TexelFitOptions& options) {
  if (source.empty()) throw InvalidInputError("texel fit: empty original texture");
  return TexelFitter(mesh, source_param, source.width, source.height, param, width, height, options).fit(source);
}

TexelFitResult fit_resize(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture, int width,
                          int height, const TexelFitOptions& options) {
  return fit_texels(mesh, param, texture, param, width, height, options);
}

}  // namespace adaptex
