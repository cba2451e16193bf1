// `adaptex unwrap`: outputs (OBJ with the input positions unchanged, vt in [0,1]^2, report JSON,
// layout PNG) and bad input (exit 2, one line on stderr, no partial output).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "test_support.h"
#include "unwrap_checks.h"

namespace adaptex {
namespace {

using test::run_cli;
using test::TempDir;

/// Writes \p mesh as OFF with 17 significant digits, offset and scaled to odd units so that any
/// recentring or rescaling would show.
TriMesh write_off(const std::filesystem::path& path, TriMesh mesh) {
  for (Vec3& p : mesh.positions) p = p * 123.456789 + Vec3(1e3 / 3, -7.25, 0.1);
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fprintf(f, "OFF\n%d %d 0\n", mesh.num_vertices(), mesh.num_faces());
  for (const Vec3& p : mesh.positions) std::fprintf(f, "%.17g %.17g %.17g\n", p.x(), p.y(), p.z());
  for (const Face& t : mesh.faces) std::fprintf(f, "3 %d %d %d\n", t[0], t[1], t[2]);
  std::fclose(f);
  return mesh;
}

std::string q(const std::filesystem::path& p) {
  std::string s(1, '\'');
  s += p.string();
  s += '\'';
  return s;
}

int count_lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(UnwrapCli, WritesObjReportAndLayout) {
  TempDir dir;
  const TriMesh mesh = write_off(dir.path / "in.off", shapes::torus(40, 12));
  const auto out = dir.path / "out.obj", rep = dir.path / "r.json", lay = dir.path / "l.png";
  const auto r = run_cli("unwrap " + q(dir.path / "in.off") + " -o " + q(out) + " --report " +
                         q(rep) + " --layout " + q(lay) + " --layout-size 256 --charts single");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // OBJ: v lines are exactly the input positions, vt in [0,1]^2, f v/vt with valid indices.
  std::ifstream in(out);
  std::string line;
  std::vector<Vec3> v;
  std::vector<Vec2> vt;
  int faces = 0;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      std::string x, y, z;
      ls >> x >> y >> z;
      v.emplace_back(std::strtod(x.c_str(), nullptr), std::strtod(y.c_str(), nullptr),
                     std::strtod(z.c_str(), nullptr));
    } else if (tag == "vt") {
      double a, b;
      ls >> a >> b;
      vt.emplace_back(a, b);
    } else if (tag == "f") {
      ++faces;
      for (int k = 0; k < 3; ++k) {
        std::string c;
        ls >> c;
        int vi = 0, ti = 0;
        ASSERT_EQ(std::sscanf(c.c_str(), "%d/%d", &vi, &ti), 2) << line;
        ASSERT_EQ(vi - 1, mesh.faces[faces - 1][k]);
        ASSERT_GE(ti, 1);
      }
    }
  }
  ASSERT_EQ(v.size(), mesh.positions.size());
  for (size_t i = 0; i < v.size(); ++i) ASSERT_EQ(v[i], mesh.positions[i]) << "vertex " << i;
  EXPECT_EQ(faces, mesh.num_faces());
  ASSERT_GT(vt.size(), v.size());  // the cut duplicates vertices
  for (const Vec2& t : vt) ASSERT_TRUE(t.x() >= 0 && t.x() <= 1 && t.y() >= 0 && t.y() <= 1);
  // Report.
  std::ifstream rf(rep);
  const nlohmann::json j = nlohmann::json::parse(rf);
  for (const char* key : {"vertices", "faces", "components", "genus", "boundary_loops", "charts",
                          "cut_length", "augmentations", "floater_l2", "floater_linf", "final_l2",
                          "final_linf", "coverage", "effective_texel_share", "time"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["faces"].get<int>(), mesh.num_faces());
  EXPECT_EQ(j["vertices"].get<int>(), mesh.num_vertices());
  EXPECT_EQ(j["genus"].get<int>(), 1);
  EXPECT_EQ(j["boundary_loops"].get<int>(), 0);
  EXPECT_EQ(j["charts"].get<int>(), 1);
  EXPECT_DOUBLE_EQ(j["coverage"].get<double>(), 1.0);  // one chart fills the square
  EXPECT_NEAR(j["effective_texel_share"].get<double>(),
              1.0 / (j["final_l2"].get<double>() * j["final_l2"].get<double>()), 1e-9);
  EXPECT_GT(j["cut_length"].get<double>(), 0.0);
  EXPECT_LE(j["final_l2"].get<double>(), j["floater_l2"].get<double>());
  EXPECT_EQ(j["flipped"].get<int>(), 0);
  for (const char* key : {"read", "cut", "floater", "yoshizawa", "augment", "pack", "write", "total"})
    EXPECT_TRUE(j["time"].contains(key)) << key;
  // Layout.
  const ImageRGBA8 img = read_image(lay);
  EXPECT_EQ(img.width, 256);
  EXPECT_EQ(img.height, 256);
}

TEST(UnwrapCli, BadInputExitsWithTwoAndLeavesNoFile) {
  TempDir dir;
  const auto out = dir.path / "out.obj", rep = dir.path / "r.json";
  auto expect_bad = [&](const std::string& args, const std::string& what) {
    SCOPED_TRACE(args);
    std::string cmd = "-q ";
    cmd += args;
    const auto r = run_cli(cmd);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_FALSE(std::filesystem::exists(rep));
  };
  // Missing, corrupt, non-manifold input.
  expect_bad("unwrap " + q(dir.path / "missing.off") + " -o " + q(out), "missing.off");
  {
    std::ofstream(dir.path / "bad.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n";  // truncated
  }
  expect_bad("unwrap " + q(dir.path / "bad.off") + " -o " + q(out) + " --report " + q(rep), "bad.off");
  write_off(dir.path / "fan.off", shapes::nonmanifold_fan());
  expect_bad("unwrap " + q(dir.path / "fan.off") + " -o " + q(out), "manifold");
  write_off(dir.path / "bowtie.off", shapes::bowtie_vertex());  // pinched: split, not an error
  // A failing second output (layout in an impossible place) leaves no OBJ or report behind.
  write_off(dir.path / "ok.off", shapes::sphere(12, 6));
  const auto r = run_cli("-q unwrap " + q(dir.path / "ok.off") + " -o " + q(out) + " --report " +
                         q(rep) + " --layout /proc/adaptex-no-such-dir/l.png");
  EXPECT_EQ(r.exit_code, 3) << r.err;  // an output that cannot be written is not bad input
  EXPECT_NE(r.err.find("adaptex: error: cannot write output: "), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(rep));
  // Bad options.
  expect_bad("unwrap " + q(dir.path / "ok.off") + " -o " + q(out) + " --layout-size 2", "layout-size");
  expect_bad("unwrap " + q(dir.path / "ok.off") + " -o " + q(out) + " --augment-time-budget -1",
             "augment-time-budget");
  expect_bad("unwrap " + q(dir.path / "ok.off") + " -o " + q(out) + " --augment-time-budget nan",
             "augment-time-budget");
  // The budget is an option of the command: 0 (no augmentation after the start) still unwraps.
  const auto budget = run_cli("-q unwrap " + q(dir.path / "ok.off") + " -o " + q(out) +
                              " --augment-time-budget 0");
  EXPECT_EQ(budget.exit_code, 0) << budget.err;
  EXPECT_TRUE(std::filesystem::exists(out));
  std::filesystem::remove(out);
  // --repair keeps the bow-tie usable: two charts.
  const auto ok = run_cli("-q unwrap " + q(dir.path / "bowtie.off") + " --repair -o " + q(out) +
                          " --report " + q(rep));
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(std::filesystem::exists(out));
}

/// Bounding boxes (lo, hi) of the charts of an OBJ's UV layout (read_textured_obj(): the charts are
/// the connected parts of the UV faces).
std::vector<std::pair<Vec2, Vec2>> obj_chart_boxes(const std::filesystem::path& obj) {
  const Parameterization p = read_textured_obj(obj).param;
  const Vec2 inf = Vec2::Constant(std::numeric_limits<double>::infinity());
  std::vector<std::pair<Vec2, Vec2>> box(p.num_charts, {inf, -inf});
  for (size_t f = 0; f < p.uv_faces.size(); ++f)
    for (int w : p.uv_faces[f]) {
      auto& [lo, hi] = box[p.face_chart[f]];
      lo = lo.cwiseMin(p.uv[w]);
      hi = hi.cwiseMax(p.uv[w]);
    }
  return box;
}

TEST(UnwrapCli, ReportsTheGutterAndWarnsWhenItWasNarrowed) {
  // 40 squares: at 1024² they fit with the full 8-texel gutter; at 64² (8 texels = 1/8 of the
  // square each side) they do not, and the gutter they got is in the report and in a warning.
  std::vector<TriMesh> parts;
  for (int k = 0; k < 40; ++k) {
    TriMesh square = shapes::plane(1, 1.0);
    for (Vec3& p : square.positions) p += Vec3(2.0 * (k % 8), 2.0 * (k / 8), 0);
    parts.push_back(square);
  }
  TempDir dir;
  write_off(dir.path / "squares.off", shapes::disjoint_union(parts));
  // The report's requested and kept gutter, and whether a narrowed gutter was warned of.
  const auto run = [&](int size) {
    const auto report = dir.path / ("r" + std::to_string(size) + ".json");
    const auto r = run_cli("unwrap " + q(dir.path / "squares.off") + " --texture-size " +
                           std::to_string(size) + " -o " + q(dir.path / "out.obj") + " --report " +
                           q(report));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(report);
    const nlohmann::json j = nlohmann::json::parse(in);
    return std::tuple(j.at("requested_gutter").get<double>(), j.at("gutter").get<double>(),
                      r.err.find("fit only with a gutter of") != std::string::npos);
  };
  const auto [requested_1024, kept_1024, warned_1024] = run(1024);
  EXPECT_DOUBLE_EQ(requested_1024, 8.0 / 1024);
  EXPECT_DOUBLE_EQ(kept_1024, 8.0 / 1024);
  EXPECT_FALSE(warned_1024);
  const auto [requested_64, kept_64, warned_64] = run(64);
  EXPECT_DOUBLE_EQ(requested_64, 8.0 / 64);
  EXPECT_LT(kept_64, 8.0 / 64);
  EXPECT_GT(kept_64, 0);
  EXPECT_TRUE(warned_64);
  const auto bad = run_cli("unwrap " + q(dir.path / "squares.off") + " --texture-size 32 -o " +
                           q(dir.path / "bad.obj"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir.path / "bad.obj"));
}

TEST(UnwrapCli, PaintUnwrapsWithTheGutterInTexelsOfItsTexture) {
  // `paint --size N` (seam padding 4): every two charts are at least the padding, 4 texels of the N²
  // texture, apart (the unwrap default, 8 texels of a 1024² texture, would leave one texel at 128²).
  TempDir dir;
  write_off(dir.path / "tori.off", test::five_tori());
  const auto gen = run_cli("strokes generate " + q(dir.path / "tori.off") + " --kind blobs -o " +
                           q(dir.path / "s.json"));
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  for (int size : {128, 512}) {
    SCOPED_TRACE(size);
    const auto out = dir.path / ("out" + std::to_string(size));
    const auto r = run_cli("paint " + q(dir.path / "tori.off") + " --strokes " + q(dir.path / "s.json") +
                           " --size " + std::to_string(size) + " --adapt none -o " + q(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto boxes = obj_chart_boxes(out / "tori.obj");
    ASSERT_GE(boxes.size(), 5u);
    double gap = 1;
    for (size_t i = 0; i < boxes.size(); ++i)
      for (size_t j = 0; j < i; ++j) {
        const auto& [a0, a1] = boxes[i];
        const auto& [b0, b1] = boxes[j];
        gap = std::min(gap, std::max({b0.x() - a1.x(), a0.x() - b1.x(), b0.y() - a1.y(), a0.y() - b1.y()}));
      }
    EXPECT_GE(gap * size, 4 - 1e-3);
  }
}

}  // namespace
}  // namespace adaptex
