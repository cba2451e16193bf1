// Debug pictures of one re-parameterization.
#include "adaptex/adapt/debug_maps.h"

#include <algorithm>
#include <cmath>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"

namespace adaptex {

namespace {
ImageRGBA8 grey(const ImageF& img) {
  ImageRGBA8 out(img.width, img.height, {0, 0, 0, 255});
  for (size_t k = 0; k < img.data.size(); ++k) {
    const auto v = static_cast<std::uint8_t>(std::lround(std::clamp(img.data[k], 0.0f, 1.0f) * 255));
    out.data[4 * k] = out.data[4 * k + 1] = out.data[4 * k + 2] = v;
  }
  return out;
}
void draw_line(ImageRGBA8& img, Vec2 a, Vec2 b, std::array<std::uint8_t, 3> c) {
  const double len = std::max(std::abs(b.x() - a.x()) * img.width, std::abs(b.y() - a.y()) * img.height);
  const int steps = std::max(1, static_cast<int>(std::ceil(len)));
  for (int s = 0; s <= steps; ++s) {
    const Vec2 p = a + (b - a) * (double(s) / steps);
    const int i = std::clamp(static_cast<int>(p.x() * img.width), 0, img.width - 1);
    const int j = std::clamp(static_cast<int>(p.y() * img.height), 0, img.height - 1);
    std::uint8_t* px = img.texel(i, j);
    px[0] = c[0];
    px[1] = c[1];
    px[2] = c[2];
  }
}
ImageRGBA8 draw_grid(const ImageF& under, const GridWarp& g, int max_lines) {
  ImageRGBA8 img = grey(under);
  const int step = std::max(1, g.n / max_lines);
  for (int j = 0; j <= g.n; ++j)
    for (int i = 0; i <= g.n; ++i) {
      if (j % step == 0 && i < g.n) draw_line(img, g.at(i, j), g.at(std::min(g.n, i + 1), j), {220, 30, 30});
      if (i % step == 0 && j < g.n) draw_line(img, g.at(i, j), g.at(i, std::min(g.n, j + 1)), {220, 30, 30});
    }
  return img;
}
}  // namespace

void write_debug_maps(const std::filesystem::path& dir, const std::string& prefix, const AdaptResult& r) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError(dir.string() + ": cannot create the debug-map directory: " + ec.message());
  if (!r.importance.data.empty()) write_png(dir / (prefix + "_importance.png"), grey(r.importance));
  if (!r.stretch.data.empty()) write_png(dir / (prefix + "_stretch.png"), grey(r.stretch));
  if (!r.ls2.data.empty()) write_png(dir / (prefix + "_ls2.png"), grey(r.ls2));
  ImageF log_density;
  if (!r.density.data.empty()) {
    // log2 density from 1/16 (black) to 16 (white); 1 (unchanged) is mid-grey.
    log_density = r.density;
    for (float& v : log_density.data) v = static_cast<float>(std::clamp((std::log2(v) + 4.0) / 8.0, 0.0, 1.0));
    write_png(dir / (prefix + "_density.png"), grey(log_density));
  }
  const ImageF& under = !r.ls2.data.empty() ? r.ls2 : log_density;
  const auto warps = r.warps();
  for (size_t k = 0; k < warps.size() && !under.data.empty(); ++k) {
    const std::string name = warps.size() == 2 ? (k == 0 ? "coarse" : "fine") : std::to_string(k);
    write_png(dir / (prefix + "_grid_" + name + ".png"), draw_grid(under, *warps[k], 64));
  }
}


}  // namespace adaptex
