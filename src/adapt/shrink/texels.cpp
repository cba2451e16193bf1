/// \file texels.cpp
/// Texels of the shrink's layouts: least squares against the original (paint/texel_fit.h), one fitter
/// per layout shared by every map, and the surface PSNR that picks the candidate (paint/asset_eval.h)
/// on samples drawn once.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "adaptex/paint/eval.h"
#include "adaptex/paint/texel_fit.h"
#include "shrink_internal.h"

namespace adaptex::shrink_detail {

namespace {
Vec2 uv_at(const Parameterization& param, const SurfacePoint& sp) {
  const Face& t = param.uv_faces[sp.face];
  return sp.b0 * param.uv[t[0]] + sp.b1 * param.uv[t[1]] + (1 - sp.b0 - sp.b1) * param.uv[t[2]];
}
}  // namespace

std::vector<ImageRGBA8> fit_maps(const TriMesh& mesh, const Parameterization& src_param,
                                 const std::vector<ShrinkMap>& maps, size_t count, const Parameterization& dst_param,
                                 int size, bool draft, const ProgressCallback& progress) {
  TexelFitOptions opt;
  if (draft) {
    opt.samples_per_source_texel = 0.25;
    opt.samples_per_texel = 4;
  }
  opt.source_address = TextureAddress::ClampToEdge;  // the original as the measure and the exporters read it
  opt.address = TextureAddress::ClampToEdge;
  opt.progress = progress;
  const TexelFitter fitter(mesh, src_param, maps[0].image.width, maps[0].image.height, dst_param, size, size, opt);
  std::vector<ImageRGBA8> out;
  for (size_t m = 0; m < std::min(count, maps.size()); ++m) out.push_back(fitter.fit(maps[m].image).texture);
  return out;
}

SampleSet::SampleSet(const TriMesh& mesh, const Parameterization& param, const std::vector<ShrinkMap>& maps,
                     long long samples, std::uint64_t seed)
    : points_(sample_surface(mesh, samples, seed)), reference_(maps.size()) {
  for (size_t m = 0; m < maps.size(); ++m) {
    reference_[m].resize(points_.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, points_.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t k = r.begin(); k < r.end(); ++k) {
        const Vec2 a = uv_at(param, points_[k]);
        reference_[m][k] = sample_bilinear(maps[m].image, a.x(), a.y());
      }
    });
  }
}

double SampleSet::psnr(size_t m, const Parameterization& param, const ImageRGBA8& image, int stride) const {
  const size_t K = (points_.size() + stride - 1) / stride;
  std::vector<double> err(K);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, K, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k) {
      const Vec2 b = uv_at(param, points_[k * stride]);
      err[k] = (reference_[m][k * stride] - sample_bilinear(image, b.x(), b.y())).squaredNorm() / 3.0;
    }
  });
  double total = 0;
  for (double e : err) total += e;  // fixed order: the same sum whatever the thread count
  const double mse = total / static_cast<double>(std::max<size_t>(K, 1));
  return psnr_from_mse(mse);
}

}  // namespace adaptex::shrink_detail
