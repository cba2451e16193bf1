/// \file eval.cpp
/// Signal approximation error (MSE / PSNR) of a texture against the exact stroke signal.
#include "adaptex/paint/eval.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "adaptex/core/errors.h"

namespace adaptex {

namespace {

inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}
inline double unit(std::uint64_t x) { return static_cast<double>(x >> 11) * 0x1.0p-53; }

/// Sum over \p pts of |truth(k) - reconstruction at pts[k]|^2, in blocks of 4096 points summed in
/// block order (deterministic whatever the thread count). The blocks run in about 32 parallel rounds;
/// \p progress (may be empty) hears ("eval", fraction) after each, on the calling thread.
template <class Truth>
double squared_error_sum(const Parameterization& param, const ImageRGBA8& texture,
                         const std::vector<SurfacePoint>& pts, const Truth& truth,
                         const ProgressCallback& progress = {}) {
  constexpr size_t kBlock = 4096;
  const size_t blocks = (pts.size() + kBlock - 1) / kBlock;
  const size_t per_round = std::max<size_t>(1, (blocks + 31) / 32);
  std::vector<double> partial(blocks, 0.0);
  for (size_t first = 0; first < blocks; first += per_round) {
    const size_t last = std::min(blocks, first + per_round);
    tbb::parallel_for(tbb::blocked_range<size_t>(first, last), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t b = r.begin(); b < r.end(); ++b) {
        double sum = 0;
        for (size_t k = b * kBlock; k < std::min(pts.size(), (b + 1) * kBlock); ++k) {
          const SurfacePoint& sp = pts[k];
          const Face& t = param.uv_faces[sp.face];
          const Vec2 uv = sp.b0 * param.uv[t[0]] + sp.b1 * param.uv[t[1]] + (1 - sp.b0 - sp.b1) * param.uv[t[2]];
          const Vec3 rec = sample_bilinear(texture, uv.x(), uv.y());
          sum += (truth(k) - rec).squaredNorm();
        }
        partial[b] = sum;
      }
    });
    report_progress(progress, "eval", static_cast<double>(last) / static_cast<double>(blocks));
  }
  double total = 0;
  for (double s : partial) total += s;
  return total;
}

}  // namespace

std::vector<SurfacePoint> sample_surface(const TriMesh& mesh, long long count, std::uint64_t seed) {
  if (count < 0) throw InvalidInputError("sample_surface: count must be >= 0");
  std::vector<double> cdf(mesh.faces.size());
  double total = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) cdf[f] = total += face_area(mesh, f);
  if (!(total > 0)) throw InvalidInputError("sample_surface: the mesh has no face of positive area");
  std::vector<SurfacePoint> out(static_cast<size_t>(count));
  const std::uint64_t base = mix64(seed + 0x9E3779B97F4A7C15ULL);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k) {
      const std::uint64_t h = mix64(base ^ (k * 0xD1B54A32D192ED03ULL));
      const double u1 = unit(h), u2 = unit(mix64(h + 1)), u3 = unit(mix64(h + 2));
      int f = static_cast<int>(std::upper_bound(cdf.begin(), cdf.end(), u1 * total) - cdf.begin());
      f = std::min(f, mesh.num_faces() - 1);
      while (f > 0 && cdf[f] == cdf[f - 1]) --f;  // never a zero-area face
      const double s = std::sqrt(u2);
      out[k] = SurfacePoint{f, 1 - s, s * (1 - u3)};
    }
  });
  return out;
}

EvalResult evaluate_texture(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                            const StrokeFile& strokes, const EvalOptions& options) {
  if (texture.empty()) throw InvalidInputError("eval: the texture is empty");
  if (param.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("eval: the parameterization has " + std::to_string(param.uv_faces.size()) +
                            " faces, the mesh " + std::to_string(mesh.faces.size()));
  if (options.samples < 1) throw InvalidInputError("eval: --samples must be >= 1 (got " + std::to_string(options.samples) + ")");
  const StrokeSignal signal(mesh, strokes);
  report_progress(options.progress, "eval", 0.0);
  const std::vector<SurfacePoint> pts = sample_surface(mesh, options.samples, options.seed);
  const double total = squared_error_sum(
      param, texture, pts, [&](size_t k) { return signal.evaluate(pts[k]); }, options.progress);
  EvalResult res;
  res.samples = options.samples;
  res.seed = options.seed;
  res.mse = total / (3.0 * static_cast<double>(pts.size()));
  res.psnr = psnr_from_mse(res.mse);
  return res;
}

double reconstruction_mse(const Parameterization& param, const ImageRGBA8& texture,
                          const std::vector<SurfacePoint>& points, const std::vector<Vec3>& exact) {
  if (exact.size() != points.size())
    throw InvalidInputError("reconstruction_mse: " + std::to_string(points.size()) + " points but " +
                            std::to_string(exact.size()) + " exact values");
  if (points.empty()) return 0;
  if (texture.empty()) throw InvalidInputError("reconstruction_mse: the texture is empty");
  const double total = squared_error_sum(param, texture, points, [&](size_t k) { return exact[k]; });
  return total / (3.0 * static_cast<double>(points.size()));
}

double psnr_from_mse(double mse) { return mse < 1e-20 ? 200.0 : 10.0 * std::log10(1.0 / mse); }

}  // namespace adaptex
