/// \file padding.cpp
/// Seam padding by ring-wise nearest-source propagation (see padding.h).
#include "adaptex/paint/padding.h"

#include <algorithm>
#include <array>
#include <cmath>
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

namespace {

/// One level of the pull-push pyramid: RGBA colours and coverage weights in [0,1].
struct PullPushLevel {
  int w = 0, h = 0;
  std::vector<std::array<float, 4>> c;
  std::vector<float> wt;
};

/// Level 0: the image's colours, weight 1 on covered texels.
PullPushLevel base_level(const ImageRGBA8& img, const std::vector<bool>& coverage) {
  PullPushLevel L;
  L.w = img.width;
  L.h = img.height;
  const size_t n = coverage.size();
  L.c.resize(n);
  L.wt.resize(n);
  for (size_t k = 0; k < n; ++k) {
    L.wt[k] = coverage[k] ? 1.0f : 0.0f;
    for (int ch = 0; ch < 4; ++ch) L.c[k][ch] = img.data[k * 4 + ch];
  }
  return L;
}

/// The 2 x 2 coverage-weighted mean of \p fine (weights capped at 1).
PullPushLevel pull(const PullPushLevel& fine) {
  PullPushLevel L;
  L.w = (fine.w + 1) / 2;
  L.h = (fine.h + 1) / 2;
  L.c.assign(static_cast<size_t>(L.w) * L.h, {0, 0, 0, 0});
  L.wt.assign(static_cast<size_t>(L.w) * L.h, 0.0f);
  for (int J = 0; J < L.h; ++J)
    for (int I = 0; I < L.w; ++I) {
      double W = 0;
      std::array<double, 4> C{0, 0, 0, 0};
      for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
          const int i = 2 * I + a, j = 2 * J + b;
          if (i >= fine.w || j >= fine.h) continue;
          const size_t k = static_cast<size_t>(j) * fine.w + i;
          W += fine.wt[k];
          for (int ch = 0; ch < 4; ++ch) C[ch] += fine.wt[k] * fine.c[k][ch];
        }
      const size_t K = static_cast<size_t>(J) * L.w + I;
      L.wt[K] = static_cast<float>(std::min(1.0, W));
      if (W > 0)
        for (int ch = 0; ch < 4; ++ch) L.c[K][ch] = static_cast<float>(C[ch] / W);
    }
  return L;
}

/// Bilinear lookup (clamp-to-edge) of the coarse level at the centre of fine texel (i, j).
std::array<float, 4> upsample(const PullPushLevel& coarse, int i, int j) {
  const BilinearTap x = bilinear_tap(coarse.w, (i + 0.5) / (2.0 * coarse.w));
  const BilinearTap y = bilinear_tap(coarse.h, (j + 0.5) / (2.0 * coarse.h));
  auto at = [&](int a, int b) -> const std::array<float, 4>& { return coarse.c[static_cast<size_t>(b) * coarse.w + a]; };
  std::array<float, 4> out{};
  for (int ch = 0; ch < 4; ++ch) {
    const double bottom = at(x.i0, y.i0)[ch] + (at(x.i1, y.i0)[ch] - at(x.i0, y.i0)[ch]) * x.f;
    const double top = at(x.i0, y.i1)[ch] + (at(x.i1, y.i1)[ch] - at(x.i0, y.i1)[ch]) * x.f;
    out[ch] = static_cast<float>(bottom + (top - bottom) * y.f);
  }
  return out;
}

}  // namespace

void pull_push_fill(ImageRGBA8& img, const std::vector<bool>& coverage) {
  const size_t n = static_cast<size_t>(img.width) * img.height;
  if (coverage.size() != n)
    throw InvalidInputError("pull-push fill: the coverage mask has " + std::to_string(coverage.size()) +
                            " entries, the image " + std::to_string(img.width) + "x" + std::to_string(img.height));
  if (n == 0) return;
  std::vector<PullPushLevel> levels;
  levels.push_back(base_level(img, coverage));
  while (levels.back().w > 1 || levels.back().h > 1) levels.push_back(pull(levels.back()));
  if (levels.back().wt[0] <= 0) return;  // nothing covered
  for (size_t l = levels.size() - 1; l-- > 0;) {
    PullPushLevel& fine = levels[l];
    const PullPushLevel& coarse = levels[l + 1];
    for (int j = 0; j < fine.h; ++j)
      for (int i = 0; i < fine.w; ++i) {
        const size_t k = static_cast<size_t>(j) * fine.w + i;
        const float w = fine.wt[k];
        if (w >= 1.0f) continue;
        const std::array<float, 4> up = upsample(coarse, i, j);
        for (int ch = 0; ch < 4; ++ch) fine.c[k][ch] = w * fine.c[k][ch] + (1.0f - w) * up[ch];
      }
  }
  const PullPushLevel& L0 = levels[0];
  for (size_t k = 0; k < n; ++k)
    if (!coverage[k])
      for (int ch = 0; ch < 4; ++ch)
        img.data[k * 4 + ch] = static_cast<std::uint8_t>(std::lround(std::clamp(L0.c[k][ch], 0.0f, 255.0f)));
}

}  // namespace adaptex
