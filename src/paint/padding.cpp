/// \file padding.cpp
/// Seam padding by ring-wise nearest-source propagation (see padding.h).
#include "adaptex/paint/padding.h"

#include <limits>

#include "adaptex/core/errors.h"

namespace adaptex {

SeamPadding build_seam_padding(const std::vector<bool>& inside, int width, int height, int padding) {
  if (width <= 0 || height <= 0 || inside.size() != static_cast<size_t>(width) * height)
    throw InvalidInputError("seam padding: mask size does not match " + std::to_string(width) + "x" +
                            std::to_string(height));
  if (padding < 0) throw InvalidInputError("seam padding: P must be >= 0 (got " + std::to_string(padding) + ")");
  SeamPadding pad;
  pad.width = width;
  pad.height = height;
  const size_t n = static_cast<size_t>(width) * height;
  pad.source.assign(n, -1);
  if (padding == 0) return pad;
  // ring[k]: 0 for chart texels, r for padded texels of ring r, -1 unassigned.
  std::vector<int> ring(n, -1), src(n, -1);
  std::vector<int> frontier;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      const size_t k = static_cast<size_t>(j) * width + i;
      if (!inside[k]) continue;
      ring[k] = 0;
      src[k] = static_cast<int>(k);
      bool border = false;
      for (int dj = -1; dj <= 1 && !border; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, b = j + dj;
          if (a >= 0 && b >= 0 && a < width && b < height && !inside[static_cast<size_t>(b) * width + a]) {
            border = true;
            break;
          }
        }
      if (border) frontier.push_back(static_cast<int>(k));
    }
  std::vector<int> next;
  for (int r = 1; r <= padding && !frontier.empty(); ++r) {
    next.clear();
    for (int k : frontier) {
      const int i = k % width, j = k / width;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, b = j + dj;
          if (a < 0 || b < 0 || a >= width || b >= height) continue;
          const int q = b * width + a;
          if (ring[q] != -1) continue;
          ring[q] = r;  // claimed; its source is chosen below
          next.push_back(q);
        }
    }
    for (int q : next) {
      const int i = q % width, j = q / width;
      double best = std::numeric_limits<double>::max();
      int best_src = -1;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const int a = i + di, b = j + dj;
          if (a < 0 || b < 0 || a >= width || b >= height) continue;
          const int nb = b * width + a;
          if (ring[nb] < 0 || ring[nb] >= r) continue;
          const int s = src[nb];
          const double du = s % width - i, dv = s / width - j;
          const double d = du * du + dv * dv;
          if (d < best || (d == best && s < best_src)) {
            best = d;
            best_src = s;
          }
        }
      src[q] = best_src;
      pad.source[q] = best_src;
      pad.padded.push_back(q);
    }
    frontier.swap(next);
  }
  return pad;
}

SeamPadding build_seam_padding(const TexelMap& map, int padding) {
  std::vector<bool> inside(map.face.size());
  for (size_t k = 0; k < map.face.size(); ++k) inside[k] = map.face[k] >= 0;
  return build_seam_padding(inside, map.width, map.height, padding);
}

void apply_seam_padding(ImageRGBA8& img, const SeamPadding& pad) {
  if (img.width != pad.width || img.height != pad.height)
    throw InvalidInputError("seam padding: image is " + std::to_string(img.width) + "x" +
                            std::to_string(img.height) + ", padding was built for " +
                            std::to_string(pad.width) + "x" + std::to_string(pad.height));
  for (int q : pad.padded) {
    const int s = pad.source[q];
    for (int c = 0; c < 4; ++c) img.data[static_cast<size_t>(q) * 4 + c] = img.data[static_cast<size_t>(s) * 4 + c];
  }
}

}  // namespace adaptex
