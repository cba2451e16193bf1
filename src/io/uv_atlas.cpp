/// \file uv_atlas.cpp
/// An artist's UV atlas as read: analyze_uvs() counts what it holds (mirrored, degenerate, outside the
/// unit square), wrap_uv_charts() moves whole charts that lie in another integer UV tile into [0,1]^2
/// (the same texels under repeat wrapping) and rejects charts that straddle tile borders and UDIM
/// texture sets. Nothing else is changed: mirrored and overlapping charts and degenerate triangles stay.
#include "uv_atlas.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"

namespace adaptex {

UvReport analyze_uvs(const TriMesh& mesh, const Parameterization& param) {
  UvReport r = io_detail::count_uvs(mesh, param);
  const TexelUsage usage = measure_texel_usage(param);
  r.covered_fraction = usage.covered_fraction;
  r.shared_fraction = usage.shared_fraction;
  return r;
}

namespace io_detail {

UvReport count_uvs(const TriMesh& mesh, const Parameterization& param) {
  UvReport r;
  r.charts = param.num_charts;
  std::vector<double> positive(static_cast<std::size_t>(std::max(param.num_charts, 0)), 0.0);
  std::vector<double> negative(positive.size(), 0.0);
  const auto outside = [](const Vec2& p) { return !(p.x() >= 0 && p.x() <= 1 && p.y() >= 0 && p.y() <= 1); };
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const double a = uv_signed_area(param, f);
    const auto c = static_cast<std::size_t>(param.face_chart[f]);
    if (std::abs(a) <= kDegenerateUvArea) {
      ++r.degenerate_uv_faces;
    } else if (a < 0) {
      ++r.mirrored_faces;
      negative[c] -= a;
    } else {
      positive[c] += a;
    }
    const Face& t = param.uv_faces[f];
    if (outside(param.uv[t[0]]) || outside(param.uv[t[1]]) || outside(param.uv[t[2]])) ++r.faces_outside_unit;
  }
  for (std::size_t c = 0; c < positive.size(); ++c) r.mirrored_charts += negative[c] > positive[c];
  return r;
}

}  // namespace io_detail

namespace {

/// Edge function of the directed edge a -> b at s, computed from the edge's endpoints in a fixed
/// (lexicographic) order so that the two triangles sharing the edge get exactly opposite values;
/// \p forward tells whether a -> b is that fixed order (the top-left tie-break uses it).
double edge_function(const Vec2& a, const Vec2& b, const Vec2& s, bool& forward) {
  forward = a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  const Vec2& lo = forward ? a : b;
  const Vec2& hi = forward ? b : a;
  const double e = (hi.x() - lo.x()) * (s.y() - lo.y()) - (hi.y() - lo.y()) * (s.x() - lo.x());
  return forward ? e : -e;
}

/// The texel range [first, last] whose centres (k + 0.5) / n lie in [lo, hi] (clipped to the grid;
/// empty when first > last). Computed in double: coordinates may be huge.
std::pair<int, int> texel_range(double lo, double hi, int n) {
  const double first = std::clamp(std::ceil(lo * n - 0.5), 0.0, static_cast<double>(n));
  const double last = std::clamp(std::floor(hi * n - 0.5), -1.0, static_cast<double>(n - 1));
  return {static_cast<int>(first), static_cast<int>(last)};
}

/// Adds 1 (saturating at 2) to every texel of \p count whose centre lies in the counter-clockwise
/// triangle p (a sample on an edge belongs to the triangle that runs the edge in its fixed order).
void rasterize(const std::array<Vec2, 3>& p, int n, std::vector<std::uint8_t>& count) {
  const auto [i0, i1] = texel_range(std::min({p[0].x(), p[1].x(), p[2].x()}), std::max({p[0].x(), p[1].x(), p[2].x()}), n);
  const auto [j0, j1] = texel_range(std::min({p[0].y(), p[1].y(), p[2].y()}), std::max({p[0].y(), p[1].y(), p[2].y()}), n);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const Vec2 s((i + 0.5) / n, (j + 0.5) / n);
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k) {
        bool forward = false;
        const double e = edge_function(p[k], p[(k + 1) % 3], s, forward);
        inside = e > 0 || (e == 0 && forward);
      }
      std::uint8_t& c = count[static_cast<std::size_t>(j) * n + i];
      if (inside && c < 2) ++c;
    }
}

/// Texel centres rasterize() visits for \p param's triangles on an n x n grid (their clipped bounding boxes).
double samples_visited(const Parameterization& param, int n) {
  double visited = 0;
  for (const Face& t : param.uv_faces) {
    const Vec2 &a = param.uv[t[0]], &b = param.uv[t[1]], &c = param.uv[t[2]];
    const auto [i0, i1] = texel_range(std::min({a.x(), b.x(), c.x()}), std::max({a.x(), b.x(), c.x()}), n);
    const auto [j0, j1] = texel_range(std::min({a.y(), b.y(), c.y()}), std::max({a.y(), b.y(), c.y()}), n);
    if (i0 <= i1 && j0 <= j1) visited += static_cast<double>(i1 - i0 + 1) * (j1 - j0 + 1);
  }
  return visited;
}

/// At most this many texel centres are tested (about 0.3 s): an atlas whose triangles' bounding boxes
/// cover the square more than 60 times over (hostile input, not an artist's atlas) is measured on a
/// coarser grid.
constexpr double kMaxSamplesVisited = 64.0 * 1024 * 1024;

}  // namespace

TexelUsage measure_texel_usage(const Parameterization& param, int size) {
  if (size < 1 || size > kMaxTextureSize)
    throw InvalidInputError("measure_texel_usage: size " + std::to_string(size) + " is outside 1.." +
                            std::to_string(kMaxTextureSize));
  if (const double visited = samples_visited(param, size); visited > kMaxSamplesVisited)
    size = std::max(16, static_cast<int>(size * std::sqrt(kMaxSamplesVisited / visited)));
  std::vector<std::uint8_t> count(static_cast<std::size_t>(size) * size, 0);
  for (std::size_t f = 0; f < param.uv_faces.size(); ++f) {
    const Face& t = param.uv_faces[f];
    std::array<Vec2, 3> p{param.uv[t[0]], param.uv[t[1]], param.uv[t[2]]};
    const double a = uv_signed_area(param, static_cast<int>(f));
    if (std::abs(a) <= kDegenerateUvArea) continue;
    if (a < 0) std::swap(p[1], p[2]);
    rasterize(p, size, count);
  }
  std::size_t covered = 0, shared = 0;
  for (std::uint8_t c : count) {
    covered += c > 0;
    shared += c > 1;
  }
  TexelUsage out;
  out.covered_fraction = static_cast<double>(covered) / static_cast<double>(count.size());
  out.shared_fraction = covered ? static_cast<double>(shared) / static_cast<double>(covered) : 0.0;
  return out;
}

namespace io_detail {

namespace {

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

/// Integer tile of a chart's extent [lo, hi] along one axis, tolerating \p tol on either side; false
/// when the extent crosses a tile border by more.
bool tile_of(double lo, double hi, double tol, double& tile) {
  tile = std::floor(lo + tol);
  return hi <= tile + 1 + tol;
}

}  // namespace

namespace {

/// True when \p path ends in a UDIM tile number and an extension: `[._-]1[01]NN.ext` (letters only).
/// Hand-written rather than std::regex, which trips GCC 12's -Wmaybe-uninitialized under sanitizers.
bool has_tile_number(const std::string& path) {
  const std::size_t dot = path.rfind('.');
  if (dot == std::string::npos || dot + 1 == path.size() || dot < 5) return false;
  for (std::size_t i = dot + 1; i < path.size(); ++i)
    if (!std::isalpha(static_cast<unsigned char>(path[i]))) return false;
  const auto digit = [&](std::size_t i) { return std::isdigit(static_cast<unsigned char>(path[i])) != 0; };
  const char sep = path[dot - 5];
  return (sep == '.' || sep == '_' || sep == '-') && path[dot - 4] == '1' &&
         (path[dot - 3] == '0' || path[dot - 3] == '1') && digit(dot - 2) && digit(dot - 1);
}

}  // namespace

bool is_udim_path(const std::string& path) {
  return path.find("<UDIM>") != std::string::npos || path.find("<UVTILE>") != std::string::npos ||
         path.find("%(UDIM)d") != std::string::npos || path.find("<udim>") != std::string::npos ||
         has_tile_number(path);
}

void wrap_uv_charts(Parameterization& param, const AssetReadOptions& options, const std::string& name,
                    const std::string& udim_map, UvReport& report) {
  const double tolerance = options.uv_tolerance;
  const int nc = param.num_charts;
  std::vector<Vec2> lo(static_cast<std::size_t>(nc), Vec2::Constant(HUGE_VAL));
  std::vector<Vec2> hi(static_cast<std::size_t>(nc), Vec2::Constant(-HUGE_VAL));
  std::vector<int> first_face(static_cast<std::size_t>(nc), -1), faces(static_cast<std::size_t>(nc), 0);
  std::vector<int> wedge_chart(param.uv.size(), -1);
  for (std::size_t f = 0; f < param.uv_faces.size(); ++f) {
    const auto c = static_cast<std::size_t>(param.face_chart[f]);
    if (first_face[c] < 0) first_face[c] = static_cast<int>(f);
    ++faces[c];
    for (int w : param.uv_faces[f]) {
      wedge_chart[static_cast<std::size_t>(w)] = static_cast<int>(c);
      lo[c] = lo[c].cwiseMin(param.uv[w]);
      hi[c] = hi[c].cwiseMax(param.uv[w]);
    }
  }
  std::vector<Vec2> offset(static_cast<std::size_t>(nc), Vec2::Zero());
  std::vector<char> keep(static_cast<std::size_t>(nc), 0);  // straddling charts left as they are
  int tiles_used = 0;
  std::vector<std::pair<double, double>> tiles;
  for (std::size_t c = 0; c < static_cast<std::size_t>(nc); ++c) {
    if (first_face[c] < 0) continue;
    double tu = 0, tv = 0;
    const bool one_tile = tile_of(lo[c].x(), hi[c].x(), tolerance, tu) && tile_of(lo[c].y(), hi[c].y(), tolerance, tv);
    if (!one_tile && options.keep_straddling_charts) {
      ++report.straddling_charts;
      keep[c] = 1;
      continue;
    }
    if (!one_tile)
      throw InvalidInputError(name + ": UV chart " + std::to_string(c) + " (face " + std::to_string(first_face[c] + 1) +
                              " and " + std::to_string(faces[c] - 1) + " more) spans u " + number(lo[c].x()) + " to " +
                              number(hi[c].x()) + ", v " + number(lo[c].y()) + " to " + number(hi[c].y()) +
                              ": it crosses a UV tile border, which is not supported (only whole charts inside one "
                              "integer tile, moved into [0,1] as repeat wrapping shows them; no UDIM)");
    if (std::find(tiles.begin(), tiles.end(), std::make_pair(tu, tv)) == tiles.end()) tiles.emplace_back(tu, tv);
    offset[c] = Vec2(tu, tv);
    report.wrapped_charts += tu != 0.0 || tv != 0.0;
  }
  tiles_used = static_cast<int>(tiles.size());
  if (!udim_map.empty() && tiles_used > 1)
    throw InvalidInputError(name + ": UDIM tiles are not supported: the charts lie in " + std::to_string(tiles_used) +
                            " UV tiles and the maps are named per tile ('" + udim_map + "')");
  for (std::size_t w = 0; w < param.uv.size(); ++w) {
    if (wedge_chart[w] < 0 || keep[static_cast<std::size_t>(wedge_chart[w])]) continue;
    Vec2& p = param.uv[w];
    p -= offset[static_cast<std::size_t>(wedge_chart[w])];
    for (int k = 0; k < 2; ++k) {
      const double clamped = std::clamp(p[k], 0.0, 1.0);
      report.clamped_uvs += clamped != p[k];
      p[k] = clamped;
    }
  }
}

}  // namespace io_detail
}  // namespace adaptex
