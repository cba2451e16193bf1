/// \file texels.cpp
/// Texels of a new layout from the original texture (box prefilter by supersampling the new layout's
/// texel map), and the surface PSNR that picks the shrink's candidate.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "adaptex/core/errors.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/padding.h"
#include "adaptex/paint/texel_map.h"
#include "shrink_internal.h"

namespace adaptex::shrink_detail {

ImageRGBA8 transfer_texels(const TriMesh& mesh, const Parameterization& src_param, const ImageRGBA8& src,
                           const Parameterization& dst_param, int size) {
  // Supersampling: the largest minification of any face (source texels per output texel), capped.
  double minification = 1;
  for (size_t f = 0; f < dst_param.uv_faces.size(); ++f) {
    const double a0 = std::abs(uv_signed_area(src_param, static_cast<int>(f))) * src.width * src.height;
    const double a1 = std::abs(uv_signed_area(dst_param, static_cast<int>(f))) * size * size;
    if (a1 > 1e-6) minification = std::max(minification, std::sqrt(a0 / a1));
  }
  const int k = std::clamp(static_cast<int>(std::ceil(minification - 1e-6)), 1, std::max(1, 4096 / size));
  const int S = size * k;
  const TexelMap fine = build_texel_map(mesh, dst_param, S, S);
  ImageRGBA8 out(size, size, {0, 0, 0, 0});
  std::vector<bool> inside(static_cast<size_t>(size) * size, false);
  tbb::parallel_for(tbb::blocked_range<int>(0, size), [&](const tbb::blocked_range<int>& r) {
    for (int j = r.begin(); j < r.end(); ++j)
      for (int i = 0; i < size; ++i) {
        Vec3 acc = Vec3::Zero();
        int n = 0;
        for (int b = 0; b < k; ++b)
          for (int a = 0; a < k; ++a) {
            const int idx = fine.index(i * k + a, j * k + b);
            const int f = fine.face[idx];
            if (f < 0) continue;
            const Face& t = src_param.uv_faces[f];
            const double b0 = fine.bary[idx].x(), b1 = fine.bary[idx].y();
            const Vec2 uv = b0 * src_param.uv[t[0]] + b1 * src_param.uv[t[1]] + (1 - b0 - b1) * src_param.uv[t[2]];
            acc += sample_repeat(src, uv.x(), uv.y());
            ++n;
          }
        if (n == 0) continue;
        acc /= n;
        std::uint8_t* d = out.texel(i, j);
        for (int c = 0; c < 3; ++c) d[c] = static_cast<std::uint8_t>(std::clamp(std::lround(255 * acc[c]), 0L, 255L));
        d[3] = 255;
        inside[static_cast<size_t>(j) * size + i] = true;
      }
  });
  apply_seam_padding(out, build_seam_padding(inside, size, size, std::max(4, size / 16)));
  return out;
}

EvalSet make_eval_set(const TriMesh& mesh, const Parameterization& layout, const ImageRGBA8& image,
                      long long samples, std::uint64_t seed) {
  const std::vector<SurfacePoint> pts = sample_surface(mesh, samples, seed);
  EvalSet set;
  set.face.resize(pts.size());
  set.bary.resize(pts.size());
  set.reference.resize(pts.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, pts.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k) {
      set.face[k] = pts[k].face;
      set.bary[k] = Vec2(pts[k].b0, pts[k].b1);
      const Face& t = layout.uv_faces[pts[k].face];
      const Vec2 uv = pts[k].b0 * layout.uv[t[0]] + pts[k].b1 * layout.uv[t[1]] + (1 - pts[k].b0 - pts[k].b1) * layout.uv[t[2]];
      set.reference[k] = sample_repeat(image, uv.x(), uv.y());
    }
  });
  return set;
}

double eval_psnr(const EvalSet& set, const Parameterization& param, const ImageRGBA8& image) {
  constexpr size_t kBlock = 4096;
  const size_t K = set.face.size(), blocks = (K + kBlock - 1) / kBlock;
  std::vector<double> partial(blocks, 0.0);
  tbb::parallel_for(size_t{0}, blocks, [&](size_t b) {
    double sum = 0;
    for (size_t k = b * kBlock; k < std::min(K, (b + 1) * kBlock); ++k) {
      const Face& t = param.uv_faces[set.face[k]];
      const double b0 = set.bary[k].x(), b1 = set.bary[k].y();
      const Vec2 uv = b0 * param.uv[t[0]] + b1 * param.uv[t[1]] + (1 - b0 - b1) * param.uv[t[2]];
      sum += (set.reference[k] - sample_bilinear(image, uv.x(), uv.y())).squaredNorm();
    }
    partial[b] = sum;
  });
  double total = 0;
  for (double s : partial) total += s;
  const double mse = K ? total / (3.0 * static_cast<double>(K)) : 0.0;
  return mse < 1e-20 ? 200.0 : 10.0 * std::log10(1.0 / mse);
}

}  // namespace adaptex::shrink_detail
