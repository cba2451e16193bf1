/// \file texel_map.cpp
/// §3.4 stroke sampling, CPU version: instead of swapping positions and texture coordinates in a
/// vertex shader (Carr et al.), the UV triangles are rasterized in software. Like a GPU, corners are
/// snapped to a fixed-point grid (1/256 texel) so that edge functions are exact integers and the
/// top-left-style fill rule covers every texel centre of a chart exactly once.
#include "adaptex/paint/texel_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "adaptex/core/errors.h"

namespace adaptex {

namespace {

constexpr std::int64_t kSub = 256;  // fixed-point sub-texel steps
constexpr int kTileRows = 16;       // rows per parallel work item

struct P2 {
  std::int64_t x, y;
};

inline std::int64_t edge(const P2& a, const P2& b, std::int64_t px, std::int64_t py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

/// Exactly one of the two directions of an edge owns the texel centres lying on it.
/// Range of texel indices k with centre k*kSub + kSub/2 in [lo, hi], clamped to [0, n-1].
inline void centre_range(std::int64_t lo, std::int64_t hi, int n, int& k0, int& k1) {
  auto floor_div = [](std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); };
  const std::int64_t a = -floor_div(-(lo - kSub / 2), kSub);  // ceil
  const std::int64_t b = floor_div(hi - kSub / 2, kSub);
  k0 = static_cast<int>(std::clamp<std::int64_t>(a, 0, n));
  k1 = static_cast<int>(std::clamp<std::int64_t>(b, -1, n - 1));
}

inline bool owns(const P2& a, const P2& b) {
  const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
  return dy < 0 || (dy == 0 && dx > 0);
}

}  // namespace

TexelMap build_texel_map(const TriMesh& mesh, const Parameterization& param, int width, int height,
                         bool with_aliases) {
  if (width <= 0 || height <= 0)
    throw InvalidInputError("texel map: size must be positive (got " + std::to_string(width) + "x" +
                            std::to_string(height) + ")");
  if (width > (1 << 16) || height > (1 << 16))
    throw InvalidInputError("texel map: size " + std::to_string(width) + "x" + std::to_string(height) +
                            " exceeds 65536");
  if (param.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("texel map: parameterization has " + std::to_string(param.uv_faces.size()) +
                            " faces, mesh has " + std::to_string(mesh.faces.size()));
  TexelMap map;
  map.width = width;
  map.height = height;
  const size_t n = static_cast<size_t>(width) * height;
  map.face.assign(n, -1);
  map.bary.resize(n);
  map.position.resize(n);

  // Fixed-point corners, one per wedge.
  std::vector<P2> fx(param.uv.size());
  for (size_t w = 0; w < param.uv.size(); ++w) {
    const Vec2& t = param.uv[w];
    if (!t.allFinite()) throw InvalidInputError("texel map: UV of wedge " + std::to_string(w) + " is not finite");
    fx[w] = {std::llround(t.x() * width * kSub), std::llround(t.y() * height * kSub)};
  }

  // Bin faces by tiles of rows (faces stay in increasing order within a tile: deterministic).
  const int tiles = (height + kTileRows - 1) / kTileRows;
  std::vector<std::vector<int>> bins(tiles);
  auto row_range = [&](int f, int& j0, int& j1) {
    const Face& t = param.uv_faces[f];
    centre_range(std::min({fx[t[0]].y, fx[t[1]].y, fx[t[2]].y}),
                 std::max({fx[t[0]].y, fx[t[1]].y, fx[t[2]].y}), height, j0, j1);
  };
  for (int f = 0; f < mesh.num_faces(); ++f) {
    int j0, j1;
    row_range(f, j0, j1);
    if (j1 < j0) continue;
    for (int t = j0 / kTileRows; t <= j1 / kTileRows; ++t) bins[t].push_back(f);
  }

  std::vector<std::vector<TexelAlias>> tile_aliases(tiles);  // each tile owns its rows: no race
  tbb::parallel_for(tbb::blocked_range<int>(0, tiles), [&](const tbb::blocked_range<int>& r) {
    for (int tile = r.begin(); tile < r.end(); ++tile) {
      const int tj0 = tile * kTileRows, tj1 = std::min(height - 1, tj0 + kTileRows - 1);
      for (int f : bins[tile]) {
        const Face& t = param.uv_faces[f];
        P2 a = fx[t[0]], b = fx[t[1]], d = fx[t[2]];
        const std::int64_t area2 = edge(a, b, d.x, d.y);
        if (area2 == 0) continue;
        if (area2 < 0) {
          std::swap(b, d);
        }
        int j0, j1;
        row_range(f, j0, j1);
        j0 = std::max(j0, tj0);
        j1 = std::min(j1, tj1);
        int i0, i1;
        centre_range(std::min({a.x, b.x, d.x}), std::max({a.x, b.x, d.x}), width, i0, i1);
        const bool o0 = owns(b, d), o1 = owns(d, a), o2 = owns(a, b);
        // Exact (double) barycentrics from the unsnapped UVs.
        const Vec2& u0 = param.uv[t[0]];
        const Vec2 e1 = param.uv[t[1]] - u0, e2 = param.uv[t[2]] - u0;
        const double det = e1.x() * e2.y() - e1.y() * e2.x();
        const Vec3& p0 = mesh.positions[mesh.faces[f][0]];
        const Vec3& p1 = mesh.positions[mesh.faces[f][1]];
        const Vec3& p2 = mesh.positions[mesh.faces[f][2]];
        for (int j = j0; j <= j1; ++j) {
          const std::int64_t py = j * kSub + kSub / 2;
          for (int i = i0; i <= i1; ++i) {
            const std::int64_t px = i * kSub + kSub / 2;
            const std::int64_t w0 = edge(b, d, px, py), w1 = edge(d, a, px, py), w2 = edge(a, b, px, py);
            if (w0 < 0 || w1 < 0 || w2 < 0) continue;
            if ((w0 == 0 && !o0) || (w1 == 0 && !o1) || (w2 == 0 && !o2)) continue;
            const Vec2 q((i + 0.5) / width - u0.x(), (j + 0.5) / height - u0.y());
            double b1 = det != 0 ? (q.x() * e2.y() - q.y() * e2.x()) / det : 1.0 / 3;
            double b2 = det != 0 ? (e1.x() * q.y() - e1.y() * q.x()) / det : 1.0 / 3;
            b1 = std::clamp(b1, 0.0, 1.0);
            b2 = std::clamp(b2, 0.0, 1.0);
            if (b1 + b2 > 1) {
              const double s = b1 + b2;
              b1 /= s;
              b2 /= s;
            }
            const double b0 = 1 - b1 - b2;
            const size_t idx = static_cast<size_t>(j) * width + i;
            if (with_aliases && map.face[idx] >= 0)  // a shared texel: the earlier triangle stays reachable
              tile_aliases[tile].push_back({static_cast<int>(idx), map.face[idx], map.bary[idx], map.position[idx]});
            map.face[idx] = f;
            map.bary[idx] = Eigen::Vector2f(static_cast<float>(b0), static_cast<float>(b1));
            map.position[idx] = (b0 * p0 + b1 * p1 + b2 * p2).cast<float>();
          }
        }
      }
    }
  });

  for (auto& list : tile_aliases) {
    std::stable_sort(list.begin(), list.end(), [](const TexelAlias& a, const TexelAlias& b) { return a.texel < b.texel; });
    map.aliases.insert(map.aliases.end(), list.begin(), list.end());
  }
  size_t count = 0;
  for (size_t k = 0; k < n; ++k) count += map.face[k] >= 0;
  map.inside.reserve(count);
  for (size_t k = 0; k < n; ++k)
    if (map.face[k] >= 0) map.inside.push_back(static_cast<int>(k));
  return map;
}

}  // namespace adaptex
