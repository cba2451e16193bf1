/// \file texels.cpp
/// Texels of the shrink's layouts: least squares against the original (paint/texel_fit.h), one fitter
/// per layout shared by every map, and the surface PSNR that picks the candidate (paint/asset_eval.h).
#include "adaptex/paint/asset_eval.h"
#include "adaptex/paint/texel_fit.h"
#include "shrink_internal.h"

namespace adaptex::shrink_detail {

std::vector<ImageRGBA8> fit_maps(const TriMesh& mesh, const Parameterization& src_param,
                                 const std::vector<ShrinkMap>& maps, size_t count, const Parameterization& dst_param,
                                 int size, bool draft, const ProgressCallback& progress) {
  TexelFitOptions opt;
  if (draft) opt.samples_per_source_texel = 0.25;
  opt.source_address = TextureAddress::ClampToEdge;  // the original as the measure and the exporters read it
  opt.address = TextureAddress::ClampToEdge;
  opt.progress = progress;
  const TexelFitter fitter(mesh, src_param, maps[0].image.width, maps[0].image.height, dst_param, size, size, opt);
  std::vector<ImageRGBA8> out;
  for (size_t m = 0; m < std::min(count, maps.size()); ++m) out.push_back(fitter.fit(maps[m].image).texture);
  return out;
}

double layout_psnr(const TriMesh& mesh, const Parameterization& ref_param, const ImageRGBA8& original,
                   const Parameterization& param, const ImageRGBA8& image, long long samples, std::uint64_t seed) {
  SurfacePsnrOptions o;
  o.samples = samples;
  o.seed = seed;
  return surface_psnr(mesh, ref_param, original, mesh, param, image, {}, o).psnr;
}

}  // namespace adaptex::shrink_detail
