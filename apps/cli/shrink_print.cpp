#include "shrink_print.h"

#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace adaptex::cli {

void print_shrink_summary(const ShrinkResult& r, const std::vector<std::string>& slots) {
  for (size_t m = 0; m < r.maps.size(); ++m) {
    std::ostringstream line;
    line << std::fixed << std::setprecision(2);
    line << (m < slots.size() ? slots[m] : "map" + std::to_string(m)) << ": psnr " << r.map_psnr[m]
         << " dB, downsized " << r.map_psnr_downsized[m] << " dB, gain " << r.map_psnr[m] - r.map_psnr_downsized[m]
         << " dB";
    std::cout << line.str() << "\n";
  }
  std::ostringstream faces;
  faces << std::fixed << std::setprecision(1) << "faces: " << r.faces_before << " -> " << r.faces_after << " (+"
        << (r.faces_before ? 100.0 * (r.faces_after - r.faces_before) / r.faces_before : 0.0) << " %), "
        << r.lifted_faces << " degenerate UV face(s) given an area";
  std::cout << faces.str() << "\n";
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
