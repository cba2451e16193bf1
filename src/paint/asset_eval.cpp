/// \file asset_eval.cpp
/// Surface PSNR of a textured mesh against a reference one, box downsizing, equal-quality texel count.
#include "adaptex/paint/asset_eval.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/point_transfer.h"

namespace adaptex {

namespace {

/// One output texel's source footprint along an axis: texels [first, first + weights.size()) with
/// the fraction of each that the output texel covers, divided by the footprint's length.
struct Footprint {
  int first = 0;
  std::vector<double> weights;
};

std::vector<Footprint> footprints(int src, int dst) {
  std::vector<Footprint> out(static_cast<size_t>(dst));
  const double scale = static_cast<double>(src) / dst;
  for (int o = 0; o < dst; ++o) {
    const double a = o * scale, b = (o + 1) * scale;
    const int i0 = std::min(src - 1, static_cast<int>(std::floor(a)));
    const int i1 = std::min(src - 1, std::max(i0, static_cast<int>(std::ceil(b)) - 1));
    Footprint& fp = out[o];
    fp.first = i0;
    for (int i = i0; i <= i1; ++i)
      fp.weights.push_back((std::min<double>(b, i + 1) - std::max<double>(a, i)) / scale);
  }
  return out;
}

Vec2 uv_at(const Parameterization& param, const SurfacePoint& sp) {
  const Face& t = param.uv_faces[sp.face];
  return sp.b0 * param.uv[t[0]] + sp.b1 * param.uv[t[1]] + (1 - sp.b0 - sp.b1) * param.uv[t[2]];
}

void check_layout(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& tex, const char* what) {
  if (tex.empty()) throw InvalidInputError(std::string("surface_psnr: the ") + what + " texture is empty");
  if (param.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError(std::string("surface_psnr: the ") + what + " layout has " +
                            std::to_string(param.uv_faces.size()) + " faces, its mesh " +
                            std::to_string(mesh.faces.size()));
  for (const Face& t : param.uv_faces)
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= param.num_wedges())
        throw InvalidInputError(std::string("surface_psnr: the ") + what + " layout has a wedge index out of range");
}

}  // namespace

ImageRGBA8 box_downsize(const ImageRGBA8& img, int width, int height) {
  if (img.empty() || img.data.size() != static_cast<size_t>(img.width) * img.height * 4)
    throw InvalidInputError("box_downsize: the image is empty or its data does not match its size");
  if (width < 1 || height < 1)
    throw InvalidInputError("box_downsize: the size must be at least 1x1 (got " + std::to_string(width) + "x" +
                            std::to_string(height) + ")");
  const std::vector<Footprint> fx = footprints(img.width, width), fy = footprints(img.height, height);
  // Rows first: every source row resized to `width` (doubles), then columns.
  std::vector<double> rows(static_cast<size_t>(img.height) * width * 4, 0.0);
  tbb::parallel_for(0, img.height, [&](int j) {
    for (int o = 0; o < width; ++o) {
      double* acc = &rows[(static_cast<size_t>(j) * width + o) * 4];
      for (size_t q = 0; q < fx[o].weights.size(); ++q) {
        const std::uint8_t* s = img.texel(fx[o].first + static_cast<int>(q), j);
        for (int c = 0; c < 4; ++c) acc[c] += fx[o].weights[q] * s[c];
      }
    }
  });
  ImageRGBA8 out(width, height);
  tbb::parallel_for(0, height, [&](int o) {
    for (int i = 0; i < width; ++i) {
      double acc[4] = {0, 0, 0, 0};
      for (size_t q = 0; q < fy[o].weights.size(); ++q) {
        const double* s = &rows[(static_cast<size_t>(fy[o].first + static_cast<int>(q)) * width + i) * 4];
        for (int c = 0; c < 4; ++c) acc[c] += fy[o].weights[q] * s[c];
      }
      std::uint8_t* d = out.texel(i, o);
      for (int c = 0; c < 4; ++c) d[c] = static_cast<std::uint8_t>(std::clamp(std::lround(acc[c]), 0L, 255L));
    }
  });
  return out;
}

SurfacePsnr surface_psnr(const TriMesh& ref_mesh, const Parameterization& ref_param, const ImageRGBA8& ref_texture,
                         const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                         const FaceData<int>& parent_face, const SurfacePsnrOptions& options) {
  check_layout(ref_mesh, ref_param, ref_texture, "reference");
  check_layout(mesh, param, texture, "test");
  if (options.samples < 1)
    throw InvalidInputError("surface_psnr: samples must be >= 1 (got " + std::to_string(options.samples) + ")");
  if (parent_face.empty() && mesh.num_faces() != ref_mesh.num_faces())
    throw InvalidInputError("surface_psnr: the mesh has " + std::to_string(mesh.num_faces()) +
                            " faces and the reference " + std::to_string(ref_mesh.num_faces()) +
                            ", and no parent face map relates them");
  const std::vector<SurfacePoint> ref_pts = sample_surface(ref_mesh, options.samples, options.seed);
  const std::vector<SurfacePoint> pts =
      parent_face.empty() ? ref_pts : transfer_points(ref_pts, ref_mesh, mesh, parent_face);
  std::vector<double> err_d(ref_pts.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, ref_pts.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k) {
      const Vec2 a = uv_at(ref_param, ref_pts[k]), b = uv_at(param, pts[k]);
      const Vec3 d = sample_bilinear(ref_texture, a.x(), a.y()) - sample_bilinear(texture, b.x(), b.y());
      err_d[k] = d.squaredNorm() / 3.0;
    }
  });
  SurfacePsnr res;
  double total = 0;
  for (size_t k = 0; k < err_d.size(); ++k) {  // fixed order: the same sum whatever the thread count
    total += err_d[k];
    res.max_error = std::max(res.max_error, err_d[k]);
  }
  res.samples = options.samples;
  res.seed = options.seed;
  res.mse = total / static_cast<double>(err_d.size());
  res.psnr = psnr_from_mse(res.mse);
  if (options.keep_sample_errors) {
    res.sample_errors.assign(err_d.begin(), err_d.end());
    res.points = ref_pts;
  }
  return res;
}

TexelMatch texels_to_match(const std::vector<double>& texels, const std::vector<double>& psnr, double target_psnr) {
  if (texels.size() != psnr.size() || texels.size() < 2)
    throw InvalidInputError("texels_to_match: needs at least two (texels, PSNR) points of equal count");
  if (!std::isfinite(target_psnr)) throw InvalidInputError("texels_to_match: the target PSNR is not finite");
  std::vector<std::pair<double, double>> pts;  // (log2 texels, PSNR)
  for (size_t i = 0; i < texels.size(); ++i) {
    if (!(texels[i] > 0) || !std::isfinite(texels[i]) || !std::isfinite(psnr[i]))
      throw InvalidInputError("texels_to_match: texel counts must be positive and PSNRs finite");
    pts.emplace_back(std::log2(texels[i]), psnr[i]);
  }
  std::sort(pts.begin(), pts.end());
  for (size_t i = 1; i < pts.size(); ++i) pts[i].second = std::max(pts[i].second, pts[i - 1].second);
  const auto at = [&](size_t i, double y) {  // x on the line through points i, i+1 at PSNR y
    const double dy = pts[i + 1].second - pts[i].second, dx = pts[i + 1].first - pts[i].first;
    return pts[i].first + (y - pts[i].second) * dx / dy;
  };
  TexelMatch m;
  const size_t n = pts.size();
  if (target_psnr < pts[0].second) {
    m.below_range = true;
    const bool flat = !(pts[1].second > pts[0].second) || !(pts[1].first > pts[0].first);
    m.texels = flat ? std::exp2(pts[0].first) : std::exp2(at(0, target_psnr));
  } else if (target_psnr > pts[n - 1].second) {
    m.above_range = true;
    const bool flat = !(pts[n - 1].second > pts[n - 2].second) || !(pts[n - 1].first > pts[n - 2].first);
    m.texels = flat ? std::numeric_limits<double>::infinity() : std::exp2(at(n - 2, target_psnr));
  } else {
    size_t i = 0;
    while (pts[i].second < target_psnr) ++i;  // first point at or above the target (exists)
    m.texels = i == 0 || pts[i].second == target_psnr ? std::exp2(pts[i].first) : std::exp2(at(i - 1, target_psnr));
  }
  return m;
}

}  // namespace adaptex
