// Effective texel share of the default layout (issue 8 item 3, docs/charts.md): per mesh, one row
// of Markdown with the auto layout's charts, L2, coverage, share = coverage / L2², how much of the
// square the charts' bounding rectangles take ("rect fill") and how much of its rectangle a chart
// covers on average ("chart fill" = coverage / rect fill), flipped and overlapping triangles,
// UVs outside [0,1]², and wall / CPU seconds. See docs/benchmarks.md.
//
//   bench_share_table [--single] [--detail] [--hash] [--repair] [--speculative S] [--no-probe] [--normal-weight W] [--planar-normal-weight W] [--regrow-l2 L] [--regrow-angle A] [--max-charts K] [--chart-padding P] [--augment-time-budget S] [--no-shape-packing] [--no-top-down-free] [--fill-exponent E] NAME...
//
// NAME: a mesh file (read like the CLI, pinched vertices split), or one of the meshes built in
// code: genusG (genus_surface(G)), sphereS,T (sphere(S, T)), holesK (sphere_with_holes(K)), pinched (genus_surface(3) with a
// pinched hole), pinched_annulus, tiny200 (tiny_components(200)), 1M (torus(2000, 250)),
// scanlikeF (scan_like_mesh(F) of tests/param/scan_fixtures.h: >100 components, handles, holes).
// --single also prints the share of one chart per component; --detail one line per chart.
// --no-probe: UnwrapOptions::single_probe_l2 = 0 (auto as before the probe: the single chart in
// full, then 4, 6, 8, ... charts). "cut+seams" = UnwrapReport::cut_length (the cut of a single
// chart, the seams of several) in bounding-box diagonals.
// --chart-padding P: UnwrapOptions::chart_padding, the smallest gap between charts (the gap is the
// larger of P and the 8-texel gutter at 1024, 0.0078).
// --hash: after each row, a 64-bit FNV-1a hash of the layout (every UV's bits and every face's
// wedges): equal hashes before and after a speed change show that the layout did not change.
// --speculative S: UnwrapOptions::speculative_attempts (chart counts built at the same time).
// --repair: read mesh files as `unwrap --repair` does (split non-manifold vertices, drop duplicate
// faces): real scans.
// --augment-time-budget S: UnwrapOptions::augment_time_budget (wall seconds; a large value keeps
// the layouts independent of the machine's load).
// --no-shape-packing: UnwrapOptions::scan_pack_shapes = false (scans: rectangles only).
// --no-top-down-free: UnwrapOptions::scan_top_down_free_layouts = false (the top-down candidate's
// charts keep their disk layouts).
// --fill-exponent E: UnwrapOptions::scan_layout_fill_exponent.
// --regrow-l2 L, --regrow-angle A, --regrow-max-faces N: UnwrapOptions::scan_regrow_l2,
// scan_regrow_angle, scan_regrow_max_faces (a large N runs the regrowth on the largest scans too).
// --slim-iterations N: UnwrapOptions::scan_slim_iterations (0: no SLIM layouts).
// --slim-second-exponent E: UnwrapOptions::scan_slim_second_exponent (negative: no second build).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <ctime>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "adaptex/core/shapes.h"
#include "../common/named_mesh.h"
#include "adaptex/core/topology.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"
#include "../../tests/param/scan_fixtures.h"

namespace {

using namespace adaptex;

bool g_repair = false;

TriMesh make_mesh(const std::string& name) {
  if (!std::filesystem::exists(name))  // a file of that name wins over a code-built mesh's name
    if (std::optional<TriMesh> m = bench::code_built_mesh(name)) return std::move(*m);
  ReadOptions ro;
  ro.repair = g_repair;
  return read_mesh(name, ro);
}

/// Sum over charts of the area of the chart's UV bounding box.
double rect_fill(const Parameterization& p) {
  std::vector<Vec2> lo(p.num_charts, Vec2::Constant(2)), hi(p.num_charts, Vec2::Constant(-1));
  for (size_t f = 0; f < p.uv_faces.size(); ++f)
    for (int w : p.uv_faces[f]) {
      lo[p.face_chart[f]] = lo[p.face_chart[f]].cwiseMin(p.uv[w]);
      hi[p.face_chart[f]] = hi[p.face_chart[f]].cwiseMax(p.uv[w]);
    }
  double sum = 0;
  for (int c = 0; c < p.num_charts; ++c)
    if (hi[c].x() >= lo[c].x()) sum += (hi[c] - lo[c]).prod();
  return sum;
}

/// --detail: one line per chart (faces, share of the 3-D area, own normalized L2, genus and
/// boundary loops of the chart's faces before cutting, UV bounding box aspect).
void detail(const TriMesh& mesh, const Parameterization& p) {
  const std::vector<double> l2 = face_l2_stretch(mesh, p);
  double a3 = 0, a2 = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) a3 += face_area(mesh, f), a2 += uv_signed_area(p, f);
  for (int c = 0; c < p.num_charts; ++c) {
    TriMesh sub;
    std::vector<int> local(mesh.num_vertices(), -1);
    double c3 = 0, c2 = 0, sum = 0;
    Vec2 lo = Vec2::Constant(2), hi = Vec2::Constant(-1);
    for (int f = 0; f < mesh.num_faces(); ++f) {
      if (p.face_chart[f] != c) continue;
      const double a = face_area(mesh, f);
      c3 += a, c2 += uv_signed_area(p, f), sum += a * l2[f] * l2[f];
      Face t;
      for (int k = 0; k < 3; ++k) {
        int& l = local[mesh.faces[f][k]];
        if (l < 0) l = static_cast<int>(sub.positions.size()), sub.positions.push_back(mesh.positions[mesh.faces[f][k]]);
        t[k] = l;
        lo = lo.cwiseMin(p.uv[p.uv_faces[f][k]]);
        hi = hi.cwiseMax(p.uv[p.uv_faces[f][k]]);
      }
      sub.faces.push_back(t);
    }
    const MeshTopology t = analyze_topology(sub);
    std::vector<int> valence(sub.num_vertices(), 0);
    for (const Face& q : sub.faces)
      for (int v : q) ++valence[v];
    int ears = 0;
    for (int v : valence) ears += v == 1;
    const double own = std::sqrt(sum / c3) * std::sqrt((c2 / c3) / (a2 / a3));
    std::printf("  chart %d: %d faces, area %.3e, L2 %.3f, genus %d, loops %d, ears %d, aspect %.2f, fill %.2f\n", c,
                sub.num_faces(), c3 / a3, own, t.total_genus(), t.total_loops(), ears,
                (hi - lo).x() / (hi - lo).y(), c2 / (hi - lo).prod());
  }
}

bool g_detail = false;
/// 64-bit FNV-1a over the bytes of every UV and every face's wedge ids (--hash).
unsigned long long layout_hash(const Parameterization& param) {
  unsigned long long h = 1469598103934665603ULL;
  auto add = [&h](const void* data, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ULL;
  };
  for (const Vec2& t : param.uv) add(t.data(), 2 * sizeof(double));
  for (const auto& f : param.uv_faces) add(f.data(), f.size() * sizeof(f[0]));
  return h;
}

bool g_hash = false;  ///< --hash
UnwrapOptions g_options;  ///< --normal-weight W, --max-charts K, --chart-padding P, --speculative S

void row(const std::string& name, bool single) {
  // scanlikeF: tests/param/scan_fixtures.h's scan_like_mesh(F) (many components, handles, holes).
  const TriMesh mesh = name.rfind("scanlike", 0) == 0
                           ? test::scan_like_mesh(name.size() > 8 ? std::stoi(name.substr(8)) : 60000)
                           : make_mesh(name);
  double single_share = -1;
  if (single) {
    UnwrapOptions o;
    o.charts = ChartMode::Single;
    single_share = unwrap(mesh, o).report.effective_texel_share;
  }
  const std::clock_t cpu0 = std::clock();
  const auto t0 = std::chrono::steady_clock::now();
  const UnwrapResult r = unwrap(mesh, g_options);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  const UnwrapReport& p = r.report;
  const StretchStats s = measure_stretch(mesh, r.param);
  const long overlaps = count_overlapping_triangles(r.param, 1000);
  long outside = 0;
  for (const Vec2& t : r.param.uv) outside += !(t.x() >= 0 && t.x() <= 1 && t.y() >= 0 && t.y() <= 1);
  const double fill = rect_fill(r.param);
  Vec3 lo = mesh.positions.front(), hi = lo;
  for (const Vec3& q : mesh.positions) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double seams = p.cut_length / std::max((hi - lo).norm(), 1e-300);
  const std::string base = std::filesystem::path(name).stem().string();
  char single_col[32] = "";
  if (single) std::snprintf(single_col, sizeof single_col, "%.3f | ", single_share);
  std::printf("| %s | %d | %s%d | %.2f | %.3f | %.3f | %.3f | %.3f | %.3f | %d | %ld | %ld | %.1f | %.1f | %s |\n",
              base.c_str(), mesh.num_faces(), single_col, p.num_charts, seams, p.final_l2, p.coverage,
              fill, fill > 0 ? p.coverage / fill : 0.0, p.effective_texel_share, s.flipped + s.degenerate,
              overlaps, outside, wall, cpu, p.effective_texel_share >= 0.5 ? "yes" : "**not met**");
  if (g_hash) std::printf("  layout hash %s: %016llx\n", base.c_str(), layout_hash(r.param));
  std::fflush(stdout);
  if (g_detail) detail(mesh, r.param);
}

}  // namespace

int main(int argc, char** argv) {
  bool single = false;
  std::vector<std::string> names;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--single") == 0) single = true;
    else if (std::strcmp(argv[i], "--detail") == 0) g_detail = true;
    else if (std::strcmp(argv[i], "--hash") == 0) g_hash = true;
    else if (std::strcmp(argv[i], "--repair") == 0) g_repair = true;
    else if (std::strcmp(argv[i], "--speculative") == 0 && i + 1 < argc)
      g_options.speculative_attempts = std::stoi(argv[++i]);
    else if (std::strcmp(argv[i], "--no-probe") == 0) g_options.single_probe_l2 = 0;
    else if (std::strcmp(argv[i], "--no-shape-packing") == 0) g_options.scan_pack_shapes = false;
    else if (std::strcmp(argv[i], "--no-top-down-free") == 0) g_options.scan_top_down_free_layouts = false;
    else if (std::strcmp(argv[i], "--fill-exponent") == 0 && i + 1 < argc)
      g_options.scan_layout_fill_exponent = std::stod(argv[++i]);
    else if (std::strcmp(argv[i], "--normal-weight") == 0 && i + 1 < argc)
      g_options.chart_normal_weight = std::stod(argv[++i]);
    else if (std::strcmp(argv[i], "--planar-normal-weight") == 0 && i + 1 < argc)
      g_options.scan_planar_normal_weight = std::stod(argv[++i]);
    else if (std::strcmp(argv[i], "--regrow-l2") == 0 && i + 1 < argc)
      g_options.scan_regrow_l2 = std::stod(argv[++i]);
    else if (std::strcmp(argv[i], "--regrow-angle") == 0 && i + 1 < argc)
      g_options.scan_regrow_angle = std::stod(argv[++i]);
    else if (std::strcmp(argv[i], "--regrow-max-faces") == 0 && i + 1 < argc)
      g_options.scan_regrow_max_faces = std::stoi(argv[++i]);
    else if (std::strcmp(argv[i], "--slim-iterations") == 0 && i + 1 < argc)
      g_options.scan_slim_iterations = std::stoi(argv[++i]);
    else if (std::strcmp(argv[i], "--slim-second-exponent") == 0 && i + 1 < argc)
      g_options.scan_slim_second_exponent = std::stod(argv[++i]);
    else if (std::strcmp(argv[i], "--chart-padding") == 0 && i + 1 < argc)
      g_options.chart_padding = std::stod(argv[++i]);
    else if (std::strcmp(argv[i], "--max-charts") == 0 && i + 1 < argc)
      g_options.max_charts = std::stoi(argv[++i]);
    else if (std::strcmp(argv[i], "--augment-time-budget") == 0 && i + 1 < argc)
      g_options.augment_time_budget = std::stod(argv[++i]);
    else names.emplace_back(argv[i]);
  }
  std::printf("| mesh | faces | %scharts | cut+seams (bbox diag.) | L2 | coverage | rect fill | chart fill | share | flipped+degenerate | "
              "overlaps | UVs outside | wall s | CPU s | ≥ 0.5 |\n",
              single ? "single: share | " : "");
  std::printf("|---|---:|%s---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n",
              single ? "---:|" : "");
  for (const std::string& n : names) {
    try {
      row(n, single);
    } catch (const std::exception& e) {
      std::printf("| %s | error: %s |\n", n.c_str(), e.what());
    }
  }
  return 0;
}
