/// \file islands.cpp
/// Charts of an artist's atlas (UV-connected faces) grouped into islands by shared texels, and the
/// layout figures (flips per face, shared-texel share) that the shrink reports.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <unordered_map>

#include "adaptex/core/errors.h"
#include "adaptex/core/union_find.h"
#include "shrink_internal.h"

namespace adaptex {

namespace shrink_detail {

void for_each_texel_centre(const Vec2& a, const Vec2& b, const Vec2& c, int width, int height,
                           const std::function<void(int, int)>& fn) {
  const Vec2 s(width, height);
  const Vec2 p0 = a.cwiseProduct(s), p1 = b.cwiseProduct(s), p2 = c.cwiseProduct(s);
  const double area = (p1 - p0).x() * (p2 - p0).y() - (p1 - p0).y() * (p2 - p0).x();
  if (!(std::abs(area) > 1e-12)) return;
  const double sg = area > 0 ? 1.0 : -1.0;
  const double xmin = std::min({p0.x(), p1.x(), p2.x()}), xmax = std::max({p0.x(), p1.x(), p2.x()});
  const double ymin = std::min({p0.y(), p1.y(), p2.y()}), ymax = std::max({p0.y(), p1.y(), p2.y()});
  const int i0 = static_cast<int>(std::ceil(xmin - 0.5)), i1 = static_cast<int>(std::floor(xmax - 0.5));
  const int j0 = static_cast<int>(std::ceil(ymin - 0.5)), j1 = static_cast<int>(std::floor(ymax - 0.5));
  auto edge = [sg](const Vec2& u, const Vec2& v, double x, double y) {
    return sg * ((v.x() - u.x()) * (y - u.y()) - (v.y() - u.y()) * (x - u.x()));
  };
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const double x = i + 0.5, y = j + 0.5;
      if (edge(p0, p1, x, y) >= 0 && edge(p1, p2, x, y) >= 0 && edge(p2, p0, x, y) >= 0) fn(i, j);
    }
}

Parameterization shifted_layout(const Parameterization& param, const UvIslands& islands) {
  Parameterization out = param;
  std::vector<char> done(param.uv.size(), 0);
  for (size_t f = 0; f < param.uv_faces.size(); ++f)
    for (int w : param.uv_faces[f])
      if (!done[w]) {
        done[w] = 1;
        out.uv[w] += islands.chart_shift[islands.face_chart[f]];
      }
  out.face_chart = islands.face_chart;
  out.num_charts = islands.num_charts;
  return out;
}

namespace {

int wrap(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

/// Texel-centre coverage of every chart at resolution x resolution (UVs wrapped): calls
/// \p fn(texel, chart) once per (texel, chart) pair, charts in increasing order.
void chart_coverage(const Parameterization& param, const std::vector<int>& face_chart, int num_charts,
                    int resolution, const std::function<void(int, int)>& fn) {
  std::vector<std::vector<int>> faces(static_cast<size_t>(num_charts));
  for (size_t f = 0; f < face_chart.size(); ++f) faces[face_chart[f]].push_back(static_cast<int>(f));
  std::vector<int> stamp(static_cast<size_t>(resolution) * resolution, -1);
  for (int c = 0; c < num_charts; ++c)
    for (int f : faces[c]) {
      const Face& t = param.uv_faces[f];
      const Vec2 ext = param.uv[t[0]].cwiseMax(param.uv[t[1]]).cwiseMax(param.uv[t[2]]) -
                       param.uv[t[0]].cwiseMin(param.uv[t[1]]).cwiseMin(param.uv[t[2]]);
      if (ext.maxCoeff() > 1.0) continue;  // a tiling face: it covers the whole texture anyway
      for_each_texel_centre(param.uv[t[0]], param.uv[t[1]], param.uv[t[2]], resolution, resolution,
                            [&](int i, int j) {
                              const int k = wrap(j, resolution) * resolution + wrap(i, resolution);
                              if (stamp[k] == c) return;
                              stamp[k] = c;
                              fn(k, c);
                            });
    }
}

}  // namespace

std::vector<double> island_areas(const Parameterization& layout, const std::vector<int>& face_island,
                                 int num_islands, int resolution) {
  std::vector<double> area(num_islands, 0.0);
  const double texel = 1.0 / (static_cast<double>(resolution) * resolution);
  chart_coverage(layout, face_island, num_islands, resolution, [&](int, int i) { area[i] += texel; });
  return area;
}

long shared_island_texels(const Parameterization& layout, const std::vector<int>& face_island, int num_islands,
                          int resolution) {
  std::vector<unsigned char> hits(static_cast<size_t>(resolution) * resolution, 0);
  long shared = 0;
  chart_coverage(layout, face_island, num_islands, resolution, [&](int k, int) {
    if (++hits[k] == 2) ++shared;
    hits[k] = std::min<unsigned char>(hits[k], 2);
  });
  return shared;
}

}  // namespace shrink_detail

using namespace shrink_detail;

UvIslands find_uv_islands(const Parameterization& param, int resolution, double overlap_share) {
  if (resolution < 1) throw InvalidInputError("find_uv_islands: resolution must be >= 1");
  const int U = param.num_wedges(), F = static_cast<int>(param.uv_faces.size());
  for (const Vec2& p : param.uv)
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) throw InvalidInputError("a texture coordinate is not finite");
  UnionFind wedges(U);
  for (const Face& t : param.uv_faces) {
    wedges.unite(t[0], t[1]);
    wedges.unite(t[0], t[2]);
  }
  // Wedges of one vertex at the same UV are one point of the chart (a format that split them).
  if (static_cast<int>(param.wedge_vertex.size()) == U) {
    std::map<std::tuple<int, double, double>, int> seen;
    for (int w = 0; w < U; ++w) {
      auto [it, fresh] = seen.emplace(std::make_tuple(param.wedge_vertex[w], param.uv[w].x(), param.uv[w].y()), w);
      if (!fresh) wedges.unite(w, it->second);
    }
  }
  UvIslands out;
  out.face_chart.assign(static_cast<size_t>(F), 0);
  std::unordered_map<int, int> chart_of_root;
  for (int f = 0; f < F; ++f) {
    const int r = wedges.find(param.uv_faces[f][0]);
    auto [it, fresh] = chart_of_root.emplace(r, static_cast<int>(chart_of_root.size()));
    out.face_chart[f] = it->second;
  }
  const int C = out.num_charts = static_cast<int>(chart_of_root.size());
  // Integer shift of every chart: its bounding-box centre into [0,1)².
  std::vector<Vec2> lo(C, Vec2::Constant(1e300)), hi(C, Vec2::Constant(-1e300));
  for (int f = 0; f < F; ++f)
    for (int w : param.uv_faces[f]) {
      lo[out.face_chart[f]] = lo[out.face_chart[f]].cwiseMin(param.uv[w]);
      hi[out.face_chart[f]] = hi[out.face_chart[f]].cwiseMax(param.uv[w]);
    }
  out.chart_shift.resize(C);
  for (int c = 0; c < C; ++c) {
    const Vec2 m = 0.5 * (lo[c] + hi[c]);
    out.chart_shift[c] = Vec2(-std::floor(m.x()), -std::floor(m.y()));
    if ((hi[c] - lo[c]).maxCoeff() > 1.0 + 1e-9) out.tiling = true;
  }
  const Parameterization shifted = shifted_layout(param, out);
  // Shared texels: the first chart seen at a texel against every later one.
  std::vector<int> owner(static_cast<size_t>(resolution) * resolution, -1);
  std::vector<long> coverage(C, 0);
  std::map<std::pair<int, int>, long> shared;
  chart_coverage(shifted, out.face_chart, C, resolution, [&](int k, int c) {
    ++coverage[c];
    if (owner[k] < 0)
      owner[k] = c;
    else
      ++shared[{owner[k], c}];
  });
  UnionFind charts(C);
  for (const auto& [pair, count] : shared) {
    const double smaller = static_cast<double>(std::min(coverage[pair.first], coverage[pair.second]));
    if (count >= 1 && count >= overlap_share * smaller) charts.unite(pair.first, pair.second);
  }
  out.chart_island.resize(C);
  std::unordered_map<int, int> island_of_root;
  for (int c = 0; c < C; ++c) {
    auto [it, fresh] = island_of_root.emplace(charts.find(c), static_cast<int>(island_of_root.size()));
    out.chart_island[c] = it->second;
  }
  out.num_islands = static_cast<int>(island_of_root.size());
  return out;
}

ShrinkLayoutStats layout_stats(const TriMesh& mesh, const Parameterization& reference, const Parameterization& param,
                               const std::vector<int>& face_chart, int resolution) {
  ShrinkLayoutStats st;
  constexpr double kDegenerate = 1e-15;
  const double texels = static_cast<double>(resolution) * resolution;
  for (int f = 0; f < static_cast<int>(param.uv_faces.size()); ++f) {
    const double a0 = uv_signed_area(reference, f), a1 = uv_signed_area(param, f);
    if (std::abs(a1) * texels < kDegenerateTexelArea) {
      ++st.degenerate;
      continue;
    }
    if (std::abs(a0) > kDegenerate && (a0 > 0) != (a1 > 0)) ++st.flipped;
  }
  int C = 0;
  for (int c : face_chart) C = std::max(C, c + 1);
  std::vector<unsigned char> count(static_cast<size_t>(resolution) * resolution, 0);
  chart_coverage(param, face_chart, C, resolution, [&](int k, int) {
    if (count[k] < 2) ++count[k];
  });
  long covered = 0, multi = 0;
  for (unsigned char n : count) {
    covered += n >= 1;
    multi += n >= 2;
  }
  st.shared_fraction = covered ? static_cast<double>(multi) / static_cast<double>(covered) : 0.0;
  double total = 0, shared = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Face& t = param.uv_faces[f];
    const Vec2 c = (param.uv[t[0]] + param.uv[t[1]] + param.uv[t[2]]) / 3.0 * resolution;
    const int k = wrap(static_cast<int>(std::floor(c.y())), resolution) * resolution +
                  wrap(static_cast<int>(std::floor(c.x())), resolution);
    const double a = face_area(mesh, f);
    total += a;
    if (count[k] >= 2) shared += a;
  }
  st.shared_surface = total > 0 ? shared / total : 0.0;
  return st;
}

}  // namespace adaptex
