// adaptex_asset_eval: the measure of docs/assets.md on files (bench helper of asset_table.sh).
//
//   adaptex_asset_eval stats MESH.obj TEXTURE            atlas traps of an asset (JSON)
//   adaptex_asset_eval downsize TEXTURE N OUT.png        the texture box-downsized to N² (renders)
//   adaptex_asset_eval compare MESH.obj TEXTURE --size N [--test NAME=OBJ,TEXTURE]... [--samples K]
//       PSNR (paint/asset_eval.h) of box downsizing to N² with the artist's UVs and of each test result
//       against the original; the downsizing curve over sizes N/2 .. < native in steps of sqrt(2) per
//       side; each result's gain and texel saving factor (texels downsizing needs to match it / N²).
//
// A test mesh with other faces than the original (refined by adaptation) is related to it by locating
// each face's centroid on the original surface (its parent face), then judged at the same surface points.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <unordered_map>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/asset_eval.h"

using namespace adaptex;
using nlohmann::ordered_json;

namespace {

/// How far \p p is from lying on triangle (a, b, c): its distance from the triangle's plane plus how
/// far its projection falls outside (the negative barycentric parts, scaled by the longest edge).
/// 0 exactly for a point on the triangle, which is all locate_parents() needs.
double off_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (!(n2 > 0)) return std::numeric_limits<double>::infinity();
  const double la = n.dot((c - b).cross(p - b)) / n2, lb = n.dot((a - c).cross(p - c)) / n2, lc = 1 - la - lb;
  const double edge = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
  return std::abs(n.dot(p - a)) / std::sqrt(n2) +
         edge * (std::max(0.0, -la) + std::max(0.0, -lb) + std::max(0.0, -lc));
}

Vec3 centroid(const TriMesh& m, int f) {
  return (m.positions[m.faces[f][0]] + m.positions[m.faces[f][1]] + m.positions[m.faces[f][2]]) / 3.0;
}

/// Parent face (on \p ref) of every face of \p test: the ref face its centroid lies on (least
/// off_triangle()), found in a uniform grid of ref face bounding boxes. Empty when test has ref's faces in ref's order.
FaceData<int> locate_parents(const TriMesh& ref, const TriMesh& test, double* max_dist) {
  *max_dist = 0;
  Vec3 lo = ref.positions[0], hi = lo;
  for (const Vec3& x : ref.positions) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  const double diag = (hi - lo).norm();
  if (test.num_faces() == ref.num_faces()) {
    bool same = true;
    for (int f = 0; f < ref.num_faces() && same; ++f) same = (centroid(ref, f) - centroid(test, f)).norm() <= 1e-7 * diag;
    if (same) return {};
  }
  const int res = std::max(1, static_cast<int>(std::cbrt(static_cast<double>(ref.num_faces()))));
  const Vec3 cell = ((hi - lo) / res).cwiseMax(Vec3::Constant(1e-12 * diag + 1e-300));
  auto key = [&](int i, int j, int k) { return (static_cast<long long>(i) * (res + 2) + j) * (res + 2) + k; };
  auto idx = [&](const Vec3& x, int d) { return std::clamp(static_cast<int>((x[d] - lo[d]) / cell[d]), 0, res - 1); };
  std::unordered_map<long long, std::vector<int>> grid;
  for (int f = 0; f < ref.num_faces(); ++f) {
    Vec3 a = ref.positions[ref.faces[f][0]], b = a;
    for (int k = 1; k < 3; ++k) a = a.cwiseMin(ref.positions[ref.faces[f][k]]), b = b.cwiseMax(ref.positions[ref.faces[f][k]]);
    for (int i = idx(a, 0); i <= idx(b, 0); ++i)
      for (int j = idx(a, 1); j <= idx(b, 1); ++j)
        for (int k = idx(a, 2); k <= idx(b, 2); ++k) grid[key(i, j, k)].push_back(f);
  }
  FaceData<int> parent(test.faces.size(), -1);
  for (int f = 0; f < test.num_faces(); ++f) {
    const Vec3 c = centroid(test, f);
    double best = std::numeric_limits<double>::infinity();
    for (int r = 0; r <= res && parent[f] < 0; ++r) {  // grow the searched block until a face is found
      for (int i = idx(c, 0) - r; i <= idx(c, 0) + r; ++i)
        for (int j = idx(c, 1) - r; j <= idx(c, 1) + r; ++j)
          for (int k = idx(c, 2) - r; k <= idx(c, 2) + r; ++k) {
            const auto it = grid.find(key(i, j, k));
            if (it == grid.end()) continue;
            for (int g : it->second) {
              const Face& t = ref.faces[g];
              const double d = off_triangle(c, ref.positions[t[0]], ref.positions[t[1]], ref.positions[t[2]]);
              if (d < best) best = d, parent[f] = g;
            }
          }
    }
    *max_dist = std::max(*max_dist, best);
  }
  return parent;
}

/// Share of the W x H texel centres inside some UV triangle (coverage), and of those inside two or
/// more (shared: overlapping or mirrored charts using the same texels). UVs wrap, as a repeating
/// sampler reads them.
struct TexelCover {
  double coverage = 0, shared = 0;
};

TexelCover texel_cover(const Parameterization& p, int W, int H) {
  std::vector<std::uint8_t> hits(static_cast<size_t>(W) * H, 0);
  const auto cross = [](const Vec2& u, const Vec2& v, const Vec2& w) {
    return (v.x() - u.x()) * (w.y() - u.y()) - (v.y() - u.y()) * (w.x() - u.x());
  };
  for (size_t f = 0; f < p.uv_faces.size(); ++f) {
    const Face& t = p.uv_faces[f];
    const Vec2 a = p.uv[t[0]], b = p.uv[t[1]], c = p.uv[t[2]];
    const double s = cross(a, b, c) > 0 ? 1 : -1;
    if (cross(a, b, c) == 0) continue;
    const double x0 = std::min({a.x(), b.x(), c.x()}) * W - 0.5, x1 = std::max({a.x(), b.x(), c.x()}) * W - 0.5;
    const double y0 = std::min({a.y(), b.y(), c.y()}) * H - 0.5, y1 = std::max({a.y(), b.y(), c.y()}) * H - 0.5;
    for (long long j = static_cast<long long>(std::ceil(y0)); j <= static_cast<long long>(std::floor(y1)); ++j)
      for (long long i = static_cast<long long>(std::ceil(x0)); i <= static_cast<long long>(std::floor(x1)); ++i) {
        const Vec2 q((i + 0.5) / W, (j + 0.5) / H);  // strictly inside the triangle
        if (s * cross(a, b, q) <= 0 || s * cross(b, c, q) <= 0 || s * cross(c, a, q) <= 0) continue;
        const long long wi = ((i % W) + W) % W, wj = ((j % H) + H) % H;
        std::uint8_t& h = hits[static_cast<size_t>(wj) * W + wi];
        h = static_cast<std::uint8_t>(std::min(255, h + 1));
      }
  }
  long long covered = 0, shared = 0;
  for (std::uint8_t h : hits) covered += h > 0, shared += h > 1;
  return {static_cast<double>(covered) / (static_cast<double>(W) * H),
          covered ? static_cast<double>(shared) / covered : 0.0};
}

/// UV triangles of under a millionth of a texel at W x H.
bool degenerate_uv(const Parameterization& p, int f, int W, int H) { return std::abs(uv_signed_area(p, f)) * W * H < 1e-6; }

/// Atlas traps: UV range, faces outside [0,1], degenerate and mirrored UV faces, coverage and overlap
/// of the texture's texel centres.
ordered_json atlas_stats(const TexturedMesh& tm, int W, int H) {
  const Parameterization& p = tm.param;
  int outside = 0, degenerate = 0, mirrored = 0;
  Vec2 lo = p.uv[0], hi = lo;
  for (const Vec2& u : p.uv) lo = lo.cwiseMin(u), hi = hi.cwiseMax(u);
  std::vector<double> chart_area(p.num_charts, 0.0);
  for (int f = 0; f < tm.mesh.num_faces(); ++f) {
    bool out = false;
    for (int k = 0; k < 3; ++k) {
      const Vec2& u = p.uv[p.uv_faces[f][k]];
      out = out || u.x() < 0 || u.x() > 1 || u.y() < 0 || u.y() > 1;
    }
    outside += out;
    const double area = uv_signed_area(p, f);
    chart_area[p.face_chart[f]] += area;
    degenerate += degenerate_uv(p, f, W, H);
    mirrored += area < 0;
  }
  int mirrored_charts = 0;
  for (double a : chart_area) mirrored_charts += a < 0;
  const TexelCover cover = texel_cover(p, W, H);
  ordered_json j;
  j["faces"] = tm.mesh.num_faces();
  j["charts"] = p.num_charts;
  j["texture"] = {W, H};
  j["uv_min"] = {lo.x(), lo.y()};
  j["uv_max"] = {hi.x(), hi.y()};
  j["faces_outside_01"] = outside;
  j["degenerate_uv_faces"] = degenerate;
  j["mirrored_faces"] = mirrored;
  j["mirrored_charts"] = mirrored_charts;
  j["coverage"] = cover.coverage;
  j["shared_texels"] = cover.shared;
  return j;
}

/// Geometry of a result against its input: UV faces whose orientation differs from their input (parent)
/// face's (a mirrored input face stays mirrored), degenerate UV faces, face growth, texel sharing.
ordered_json result_geometry(const TexturedMesh& ref, const TexturedMesh& t, const FaceData<int>& parent, int W, int H) {
  int flipped = 0, degenerate = 0;
  for (int f = 0; f < t.mesh.num_faces(); ++f) {
    const double a = uv_signed_area(t.param, f), b = uv_signed_area(ref.param, parent.empty() ? f : parent[f]);
    flipped += (a > 0 && b < 0) || (a < 0 && b > 0);
    degenerate += degenerate_uv(t.param, f, W, H);
  }
  const TexelCover cover = texel_cover(t.param, W, H);
  ordered_json j;
  j["faces"] = t.mesh.num_faces();
  j["face_growth"] = static_cast<double>(t.mesh.num_faces()) / ref.mesh.num_faces() - 1.0;
  j["flipped_vs_input"] = flipped;
  j["degenerate_uv_faces"] = degenerate;
  j["coverage"] = cover.coverage;
  j["shared_texels"] = cover.shared;
  return j;
}

struct Asset {
  TexturedMesh tm;
  ImageRGBA8 tex;
};

/// Reads with repair: a renderer shows non-manifold assets too, so the measure takes them as they are.
Asset load(const std::string& mesh, const std::string& tex) {
  ReadOptions ro;
  ro.repair = true;
  return {read_textured_obj(mesh, ro), read_image(tex)};
}

ordered_json compare(const Asset& ref, int size, const std::vector<std::string>& tests, const SurfacePsnrOptions& o) {
  const TriMesh& m = ref.tm.mesh;
  const Parameterization& p = ref.tm.param;
  auto downsized = [&](int n) {
    return surface_psnr(m, p, ref.tex, m, p, box_downsize(ref.tex, n, n), {}, o).psnr;
  };
  ordered_json j;
  j["size"] = size;
  j["input"] = atlas_stats(ref.tm, ref.tex.width, ref.tex.height);
  j["downsized"] = downsized(size);
  // The downsizing curve: N/2 .. below the native size, sqrt(2) apart per side.
  std::vector<double> texels, psnr;
  ordered_json curve = ordered_json::array();
  for (int k = -2;; ++k) {
    const int n = static_cast<int>(std::lround(size * std::pow(2.0, k / 2.0)));
    if (n >= std::min(ref.tex.width, ref.tex.height) && k > 0) break;
    texels.push_back(static_cast<double>(n) * n);
    psnr.push_back(k == 0 ? j["downsized"].get<double>() : downsized(n));
    curve.push_back({n, psnr.back()});
  }
  j["curve"] = curve;
  ordered_json results = ordered_json::object();
  for (const std::string& spec : tests) {
    const auto eq = spec.find('='), comma = spec.find(',', eq + 1);
    if (eq == std::string::npos || comma == std::string::npos)
      throw InvalidInputError("--test must be NAME=OBJ,TEXTURE (got '" + spec + "')");
    const Asset t = load(spec.substr(eq + 1, comma - eq - 1), spec.substr(comma + 1));
    double max_dist = 0;
    const FaceData<int> parent = locate_parents(m, t.tm.mesh, &max_dist);
    const SurfacePsnr r = surface_psnr(m, p, ref.tex, t.tm.mesh, t.tm.param, t.tex, parent, o);
    const TexelMatch match = texels_to_match(texels, psnr, r.psnr);
    const double own = static_cast<double>(t.tex.width) * t.tex.height;
    ordered_json rj;
    rj["psnr"] = r.psnr;
    rj["gain"] = r.psnr - j["downsized"].get<double>();
    rj["texture"] = {t.tex.width, t.tex.height};
    rj["geometry"] = result_geometry(ref.tm, t.tm, parent, t.tex.width, t.tex.height);
    rj["saving"] = std::isfinite(match.texels) ? match.texels / own : -1.0;  // -1: downsizing never matches
    rj["saving_extrapolated"] = match.above_range || match.below_range;
    rj["parent_max_distance"] = max_dist;
    results[spec.substr(0, eq)] = rj;
  }
  j["results"] = results;
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The asset measure of docs/assets.md (surface PSNR against the original texture)"};
  app.require_subcommand(1);
  std::string mesh, tex;
  int size = 256;
  std::vector<std::string> tests;
  SurfacePsnrOptions o;
  auto* st = app.add_subcommand("stats", "Atlas traps of an OBJ with vt and its texture");
  auto* cmp = app.add_subcommand("compare", "PSNR of box downsizing and of test results at one size");
  for (auto* s : {st, cmp}) {
    s->add_option("mesh", mesh, "OBJ with vt")->required();
    s->add_option("texture", tex, "Its texture (the original)")->required();
  }
  cmp->add_option("--size", size, "Texture side N of the comparison")->check(CLI::Range(1, 16384));
  cmp->add_option("--test", tests, "NAME=OBJ,TEXTURE: a result to judge (repeatable)");
  cmp->add_option("--samples", o.samples, "Surface samples")->check(CLI::Range(1LL, 100000000LL));
  cmp->add_option("--seed", o.seed, "Sample seed");
  std::string out_png;
  auto* ds = app.add_subcommand("downsize", "Write the texture box-downsized to N x N (plain downsizing)");
  ds->add_option("texture", tex, "The original texture")->required();
  ds->add_option("size", size, "N")->required()->check(CLI::Range(1, 16384));
  ds->add_option("output", out_png, "PNG to write")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    if (ds->parsed()) {
      write_png(out_png, box_downsize(read_image(tex), size, size));
      return 0;
    }
    const Asset a = load(mesh, tex);
    const ordered_json j = st->parsed() ? atlas_stats(a.tm, a.tex.width, a.tex.height) : compare(a, size, tests, o);
    std::cout << j.dump() << "\n";
  } catch (const Error& e) {
    std::cerr << "adaptex_asset_eval: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
