// Importance map of thesis §3.5 (Sobel gradient magnitude over RGB, masked to the charts).
#include "adaptex/adapt/importance.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "adaptex/core/errors.h"

namespace adaptex {

ImageF compute_importance(const ImageRGBA8& texture, const TexelMap* mask, const ImportanceOptions& options) {
  const int W = texture.width, H = texture.height;
  if (texture.empty()) throw InvalidInputError("compute_importance: empty texture");
  if (mask && (mask->width != W || mask->height != H))
    throw InvalidInputError("compute_importance: texel map is " + std::to_string(mask->width) + "x" +
                            std::to_string(mask->height) + " but the texture is " + std::to_string(W) +
                            "x" + std::to_string(H));
  ImageF out(W, H, 0.0f);
  const float inv255 = 1.0f / 255.0f;
  tbb::parallel_for(0, H, [&](int j) {
    for (int i = 0; i < W; ++i) {
      if (mask && mask->face[mask->index(i, j)] < 0) continue;
      const std::uint8_t* centre = texture.texel(i, j);
      const std::uint8_t* g[3][3];  // g[row][col], row 0 = j-1, col 0 = i-1
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int x = std::clamp(i + di, 0, W - 1), y = std::clamp(j + dj, 0, H - 1);
          const bool outside = mask && mask->face[mask->index(x, y)] < 0;
          g[dj + 1][di + 1] = outside ? centre : texture.texel(x, y);
        }
      float sum = 0;
      for (int c = 0; c < 3; ++c) {
        auto v = [&](int r, int q) { return static_cast<float>(g[r][q][c]) * inv255; };
        const float du = v(2, 2) + v(0, 2) - v(0, 0) - v(2, 0) + 2 * (v(1, 2) - v(1, 0));
        const float dv = v(2, 0) + v(2, 2) - v(0, 0) - v(0, 2) + 2 * (v(2, 1) - v(0, 1));
        sum += du * du + dv * dv;
      }
      out.at(i, j) = std::sqrt(sum);
    }
  });
  double ref = 4.0 * std::sqrt(3.0);
  if (options.normalization == ImportanceNormalization::Percentile) {
    std::vector<float> nz;
    for (float x : out.data)
      if (x > 0) nz.push_back(x);
    if (nz.empty()) return out;
    const size_t k = std::min(nz.size() - 1, static_cast<size_t>(std::clamp(options.percentile, 0.0, 1.0) * (nz.size() - 1)));
    std::nth_element(nz.begin(), nz.begin() + static_cast<long>(k), nz.end());
    ref = nz[k];
  }
  const float inv = static_cast<float>(1.0 / ref);
  for (float& x : out.data) x = std::min(1.0f, x * inv);
  return out;
}

}  // namespace adaptex
