#include "shrink_print.h"

#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace adaptex::cli {

void print_shrink_summary(const ShrinkResult& r, const std::vector<std::string>& slots, const std::string& prefix) {
  for (size_t m = 0; m < r.maps.size(); ++m) {
    std::ostringstream line;
    line << std::fixed << std::setprecision(2);
    line << prefix << (m < slots.size() ? slots[m] : "map" + std::to_string(m)) << ": psnr " << r.map_psnr[m]
         << " dB, downsized " << r.map_psnr_downsized[m] << " dB, gain " << r.map_psnr[m] - r.map_psnr_downsized[m]
         << " dB";
    std::cout << line.str() << "\n";
  }
  std::ostringstream faces;
  faces << std::fixed << std::setprecision(1) << prefix << "faces: " << r.faces_before << " -> " << r.faces_after << " (+"
        << (r.faces_before ? 100.0 * (r.faces_after - r.faces_before) / r.faces_before : 0.0) << " %), "
        << r.lifted_faces << " degenerate UV face(s) given an area";
  std::cout << faces.str() << "\n";
}

void print_asset_summary(const TexturedAsset& asset, const AssetShrinkResult& res, bool one_material) {
  if (one_material) return print_shrink_summary(res.groups[0].result, res.groups[0].slots);
  for (const MaterialGroupShrink& g : res.groups) {
    std::string names;
    for (int m : g.materials) names += (names.empty() ? "" : "+") + asset.materials[m].name;
    print_shrink_summary(g.result, g.slots, names + ": ");
  }
  std::ostringstream line;
  line << std::fixed << std::setprecision(2) << "overall (" << res.groups.size()
       << " material groups, base colour, area-weighted): psnr " << res.psnr << " dB, downsized " << res.psnr_downsized
       << " dB, gain " << res.psnr - res.psnr_downsized << " dB";
  std::cout << line.str() << "\n";
}

ProgressCallback shrink_progress(const Context& ctx, const std::string& prefix) {
  auto last = std::make_shared<std::string>();
  const auto start = std::chrono::steady_clock::now();
  return [&ctx, prefix, last, start](std::string_view phase, double) {
    if (phase != *last) {
      *last = std::string(phase);
      std::ostringstream line;
      line << prefix << ": " << *last << " (" << std::fixed << std::setprecision(2)
           << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s)";
      ctx.info(line.str());
    }
    return true;
  };
}

}  // namespace adaptex::cli
