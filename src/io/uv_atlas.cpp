/// \file uv_atlas.cpp
/// An artist's UV atlas as read: analyze_uvs() counts what it holds (mirrored, degenerate, outside the
/// unit square), wrap_uv_charts() moves whole charts that lie in another integer UV tile into [0,1]^2
/// (the same texels under repeat wrapping) and rejects charts that straddle tile borders and UDIM
/// texture sets. Nothing else is changed: mirrored and overlapping charts and degenerate triangles stay.
#include "uv_atlas.h"

#include <algorithm>
#include <cmath>
#include <regex>

#include "adaptex/core/errors.h"

namespace adaptex {

UvReport analyze_uvs(const TriMesh& mesh, const Parameterization& param) {
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

bool is_udim_path(const std::string& path) {
  static const std::regex tile_number(R"([._-]1[01][0-9][0-9]\.[A-Za-z]+$)");
  return path.find("<UDIM>") != std::string::npos || path.find("<UVTILE>") != std::string::npos ||
         path.find("%(UDIM)d") != std::string::npos || path.find("<udim>") != std::string::npos ||
         std::regex_search(path, tile_number);
}

void wrap_uv_charts(Parameterization& param, double tolerance, const std::string& name, const std::string& udim_map,
                    UvReport& report) {
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
  int tiles_used = 0;
  std::vector<std::pair<double, double>> tiles;
  for (std::size_t c = 0; c < static_cast<std::size_t>(nc); ++c) {
    if (first_face[c] < 0) continue;
    double tu = 0, tv = 0;
    if (!tile_of(lo[c].x(), hi[c].x(), tolerance, tu) || !tile_of(lo[c].y(), hi[c].y(), tolerance, tv))
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
    if (wedge_chart[w] < 0) continue;
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
