// Tests of the shrink of assets with several materials (adapt/shrink_asset.h, `adaptex shrink`): each
// textured material on its own faces, materials sharing an image shrunk together, untextured materials
// kept, charts in another UV tile moved into [0,1]² so that the clamped output reads what the
// repeating input read, and bad input (a missing map, a tiling chart).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "adaptex/adapt/shrink_asset.h"
#include "adaptex/core/errors.h"
#include "adaptex/io/asset_io.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/export.h"
#include "test_support.h"

namespace adaptex {
namespace {

/// A patch of n x n quads at 3-D offset (x0, 0, 0), UV uv0 + s·(x, y) for local (x, y) in [0,1]².
void patch(TriMesh& mesh, Parameterization& param, double x0, int n, Vec2 uv0, double s) {
  const int v0 = mesh.num_vertices(), w0 = param.num_wedges();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      mesh.positions.push_back(Vec3(x0 + static_cast<double>(i) / n, static_cast<double>(j) / n, 0));
      param.uv.push_back(uv0 + s * Vec2(static_cast<double>(i) / n, static_cast<double>(j) / n));
      param.wedge_vertex.push_back(mesh.num_vertices() - 1);
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      for (const Face& f : {Face{id(i, j), id(i + 1, j), id(i + 1, j + 1)}, Face{id(i, j), id(i + 1, j + 1), id(i, j + 1)}}) {
        mesh.faces.push_back({v0 + f[0], v0 + f[1], v0 + f[2]});
        param.uv_faces.push_back({w0 + f[0], w0 + f[1], w0 + f[2]});
        param.face_chart.push_back(param.num_charts);
      }
  ++param.num_charts;
}

/// Stripes of period 8 texels in colour \p a / \p b.
ImageRGBA8 stripes(int size, std::array<std::uint8_t, 3> a, std::array<std::uint8_t, 3> b) {
  ImageRGBA8 img(size, size, {0, 0, 0, 255});
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const auto& c = ((i / 4 + j / 6) % 2) ? a : b;
      std::copy(c.begin(), c.end(), img.texel(i, j));
    }
  return img;
}

std::string slurp(const std::filesystem::path& p) {
  std::ostringstream s;
  s << std::ifstream(p, std::ios::binary).rdbuf();
  return s.str();
}

/// The material name of every face, keyed by its 3-D centroid (glTF may reorder faces).
std::map<std::array<long, 3>, std::string> material_by_centroid(const TexturedAsset& a) {
  std::map<std::array<long, 3>, std::string> out;
  for (int f = 0; f < a.mesh.num_faces(); ++f) {
    Vec3 c = Vec3::Zero();
    for (int v : a.mesh.faces[f]) c += a.mesh.positions[v] / 3.0;
    const std::array<long, 3> key{std::lround(c.x() * 1e4), std::lround(c.y() * 1e4), std::lround(c.z() * 1e4)};
    out[key] = a.face_material[f] >= 0 ? a.materials[a.face_material[f]].name : "";
  }
  return out;
}

/// Mean colour of the base colour map of \p material at the UV centroids of its faces.
Vec3 mean_colour(const TexturedAsset& a, const std::string& material) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (int f = 0; f < a.mesh.num_faces(); ++f) {
    const Material& m = a.materials[a.face_material[f]];
    if (m.name != material) continue;
    Vec2 uv = Vec2::Zero();
    for (int w : a.param.uv_faces[f]) uv += a.param.uv[w] / 3.0;
    sum += sample_bilinear(m.find(MapSlot::BaseColor)->image, uv.x(), uv.y());
    ++n;
  }
  return sum / std::max(n, 1);
}

/// Two textured materials (red-green stripes with a normal map; blue-white stripes), one untextured
/// material, written as OBJ + MTL + PNGs into a temporary folder.
struct TwoMaterials : ::testing::Test {
  test::TempDir dir;
  TriMesh mesh;
  Parameterization param;
  std::vector<int> face_material;

  void SetUp() override {
    patch(mesh, param, 0, 4, Vec2(0.1, 0.1), 0.8);  // "skin": faces 0..31
    patch(mesh, param, 2, 4, Vec2(0.2, 0.2), 0.6);  // "cloth": faces 32..63
    patch(mesh, param, 4, 2, Vec2(0.0, 0.0), 0.5);  // "metal", no map: faces 64..71
    for (int f = 0; f < mesh.num_faces(); ++f) face_material.push_back(f < 32 ? 0 : f < 64 ? 1 : 2);
    std::swap(face_material[5], face_material[40]);  // interleaved runs: face order must survive
    std::swap(mesh.faces[5], mesh.faces[40]);
    std::swap(param.uv_faces[5], param.uv_faces[40]);
    write_files("a.png");
  }
  void write_files(const std::string& skin_map) {
    const std::vector<std::string> names{"skin", "cloth spot", "metal"};
    write_obj(dir.path / "m.obj", mesh, param, "m.mtl", names, face_material);
    std::ofstream(dir.path / "m.mtl") << "newmtl skin\nmap_Kd " << skin_map
                                      << "\nnorm a_n.png\nnewmtl cloth spot\nKd 0.5 0.5 0.5\nmap_Kd b.png\n"
                                         "newmtl metal\nKd 0.2 0.3 0.4\nPm 1\n";
    write_png(dir.path / "a.png", stripes(128, {220, 30, 30}, {30, 200, 40}));
    write_png(dir.path / "a_n.png", ImageRGBA8(64, 64, {128, 128, 255, 255}));
    write_png(dir.path / "b.png", stripes(64, {20, 40, 230}, {240, 240, 240}));
  }
  /// `shrink m.obj --size 32 FLAGS` fails with exit 2 and one error line holding every one of \p needles,
  /// and writes nothing.
  void expect_bad_input(const std::string& flags, const std::vector<std::string>& needles) {
    const auto out = dir.path / "out";
    const auto r = test::run_cli("-q shrink " + (dir.path / "m.obj").string() + " --size 32 " + flags + " -o " +
                                 out.string());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << n << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
};

TEST_F(TwoMaterials, EachMaterialKeepsItsMapsAndFaces) {
  const auto out = dir.path / "out";
  const auto r = test::run_cli("shrink " + (dir.path / "m.obj").string() + " --size 32 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"m.obj", "m.mtl", "m_skin.png", "m_skin_normal.png", "m_cloth_spot.png", "m.glb", "report.json"})
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  EXPECT_FALSE(std::filesystem::exists(out / "m.png"));
  EXPECT_EQ(read_image(out / "m_skin.png").width, 32);
  EXPECT_EQ(read_image(out / "m_cloth_spot.png").width, 32);
  const std::string mtl = slurp(out / "m.mtl");
  EXPECT_NE(mtl.find("newmtl skin\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("map_Kd -clamp on m_skin.png\nnorm -clamp on m_skin_normal.png\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("newmtl cloth_spot\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("map_Kd -clamp on m_cloth_spot.png\n"), std::string::npos) << mtl;
  EXPECT_NE(mtl.find("newmtl metal\nKa 0 0 0\nKd 0.2 0.3 0.4\n"), std::string::npos) << mtl;
  EXPECT_NE(r.out.find("skin: base_color: psnr"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cloth spot: base_color: psnr"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("overall (2 material groups"), std::string::npos) << r.out;

  // OBJ and GLB read back: every face keeps its material, and each material's map holds its colours.
  const TexturedAsset in = read_textured_asset(dir.path / "m.obj");
  for (const char* file : {"m.obj", "m.glb"}) {
    const TexturedAsset back = read_textured_asset(out / file);
    ASSERT_EQ(back.mesh.num_faces(), mesh.num_faces()) << file;
    auto expect = material_by_centroid(in);
    for (auto& [key, name] : expect)
      if (name == "cloth spot") name = "cloth_spot";
    EXPECT_EQ(material_by_centroid(back), expect) << file;
    // Blue tells the maps apart: red-green (blue 0.12) on skin, blue-white (blue >= 0.9) on cloth.
    EXPECT_LT(mean_colour(back, "skin").z(), 0.25) << file;
    EXPECT_GT(mean_colour(back, "cloth_spot").z(), 0.7) << file;
    ASSERT_NE(back.materials[0].find(MapSlot::Normal), nullptr) << file;
  }
  const TexturedAsset glb = read_textured_asset(out / "m.glb");
  EXPECT_EQ(glb.materials.size(), 3u);
  // report.json: a section per material, overall figures between the materials'.
  const auto j = nlohmann::json::parse(std::ifstream(out / "report.json"));
  ASSERT_EQ(j["materials"].size(), 3u);
  EXPECT_EQ(j["materials"][0]["faces"], 32);
  EXPECT_EQ(j["materials"][2]["maps"].size(), 0u);
  const double a = j["materials"][0]["psnr"], b = j["materials"][1]["psnr"];
  EXPECT_GE(j["psnr"].get<double>(), std::min(a, b) - 1e-9);
  EXPECT_LE(j["psnr"].get<double>(), std::max(a, b) + 1e-9);
  EXPECT_EQ(j["materials"][1]["chosen"], j["materials"][1]["shrink"]["chosen"]);
}

TEST_F(TwoMaterials, MaterialsSharingAnImageAreShrunkTogether) {
  std::ofstream(dir.path / "m.mtl") << "newmtl skin\nmap_Kd a.png\nnewmtl cloth spot\nmap_Kd a.png\nnewmtl metal\n";
  const auto out = dir.path / "out";
  const auto r = test::run_cli("shrink " + (dir.path / "m.obj").string() + " --factor 16 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(out / "m_skin.png"));
  EXPECT_FALSE(std::filesystem::exists(out / "m_cloth_spot.png"));
  EXPECT_EQ(read_image(out / "m_skin.png").width, 32);  // 128 / sqrt(16)
  const std::string mtl = slurp(out / "m.mtl");
  EXPECT_EQ(std::count(mtl.begin(), mtl.end(), '\n') > 0, true);
  size_t at = 0, refs = 0;
  while ((at = mtl.find("map_Kd -clamp on m_skin.png", at)) != std::string::npos) ++refs, ++at;
  EXPECT_EQ(refs, 2u) << mtl;
  const auto j = nlohmann::json::parse(std::ifstream(out / "report.json"));
  EXPECT_EQ(j["materials"][0]["shrunk_with"][0], "cloth spot");
  EXPECT_EQ(j["materials"][0]["psnr"], j["materials"][1]["psnr"]);
}

TEST_F(TwoMaterials, AMissingMapIsBadInputAndWritesNothing) {
  write_files("gone.png");
  expect_bad_input("", {"gone.png"});
}

TEST_F(TwoMaterials, ATilingChartIsBadInputAndWritesNothing) {
  for (int w = 0; w < 25; ++w) param.uv[w].x() *= 3;  // skin's chart spans u 0.3 .. 2.7
  write_files("a.png");
  expect_bad_input("", {"material 'skin'", "tiling"});
}

TEST_F(TwoMaterials, AnUnknownCandidateIsBadInputAndWritesNothing) {
  expect_bad_input("--candidate best", {"unknown candidate 'best'"});
}

/// One material on every face: the files are those of the one-material shrink and export, byte for byte.
TEST_F(TwoMaterials, OneMaterialOutputIsTheOneMaterialExport) {
  std::fill(face_material.begin(), face_material.end(), 0);
  write_obj(dir.path / "m.obj", mesh, param, "m.mtl", {"skin"}, face_material);
  std::ofstream(dir.path / "m.mtl") << "newmtl skin\nmap_Kd a.png\nnorm a_n.png\n";
  const auto out = dir.path / "out";
  const auto r = test::run_cli("-q shrink " + (dir.path / "m.obj").string() + " --size 32 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const TexturedAsset in = read_textured_asset(dir.path / "m.obj");
  ShrinkOptions so;
  so.size = 32;
  const std::vector<ShrinkMap> maps{{"base_color", in.materials[0].maps[0].image, MapKind::Color},
                                    {"normal", in.materials[0].maps[1].image, MapKind::Normal}};
  const ShrinkResult res = shrink_textured_mesh(in.mesh, in.param, maps, so);
  ExportOptions eo;
  eo.mtl_clamp = true;
  eo.maps.push_back({"normal", res.maps[1]});
  const auto ref = dir.path / "ref";
  AtomicOutput o;
  export_textured_mesh(o, ref, "m", in.mesh, res.param, res.maps[0], eo);
  o.commit();
  for (const char* f : {"m.obj", "m.mtl", "m.png", "m_normal.png", "m.glb"})
    EXPECT_EQ(slurp(out / f), slurp(ref / f)) << f;
  EXPECT_FALSE(std::filesystem::exists(out / "m_skin.png"));
}

TEST(ShrinkAsset, WrapsChartsOfOtherTilesAndKeepsStraddlingOnes) {
  TriMesh mesh;
  Parameterization param;
  patch(mesh, param, 0, 2, Vec2(1.2, -0.9), 0.5);  // tile (1, -1)
  patch(mesh, param, 2, 2, Vec2(-0.1, 0.2), 0.5);  // crosses u = 0, centre inside [0,1)
  patch(mesh, param, 4, 2, Vec2(0.2, 0.2), 0.5);   // inside
  const Parameterization before = param;
  EXPECT_EQ(wrap_charts_into_unit_square(param, 1e-3, "test"), 1);
  for (int w = 0; w < param.num_wedges(); ++w) {
    const Vec2 shift = w < 9 ? Vec2(-1, 1) : Vec2(0, 0);
    EXPECT_EQ(param.uv[w], before.uv[w] + shift) << w;
  }
  for (Vec2& p : param.uv) p.x() *= 2.5;  // the first chart now spans 1.25 in u
  EXPECT_THROW(wrap_charts_into_unit_square(param, 1e-3, "test"), InvalidInputError);
}

/// Largest colour difference, at the UV centroid of every face, between \p in_map read with repeat
/// wrapping on \p in and \p out_map read clamped on \p out (whose UVs must lie in [0,1]).
double worst_wrapped_read(const Parameterization& in, const ImageRGBA8& in_map, const Parameterization& out,
                          const ImageRGBA8& out_map) {
  double worst = 0;
  for (size_t f = 0; f < in.uv_faces.size(); ++f) {
    Vec2 a = Vec2::Zero(), b = Vec2::Zero();
    for (int k = 0; k < 3; ++k) {
      a += in.uv[in.uv_faces[f][k]] / 3.0;
      b += out.uv[out.uv_faces[f][k]] / 3.0;
    }
    EXPECT_GE(b.minCoeff(), 0.0);
    EXPECT_LE(b.maxCoeff(), 1.0);
    const Vec3 wrapped = sample_bilinear(in_map, a.x() - std::floor(a.x()), a.y() - std::floor(a.y()));
    worst = std::max(worst, (wrapped - sample_bilinear(out_map, b.x(), b.y())).norm());
  }
  return worst;
}

/// The artist's layout written as it is ("downsized" at the input size) for a chart in the tile
/// [1,2] x [0,1]: the clamped output must show what the input showed under repeat wrapping.
TEST(ShrinkAsset, ArtistLayoutInAnotherTileReadsTheSameTexelsClamped) {
  TexturedAsset a;
  patch(a.mesh, a.param, 0, 6, Vec2(1.1, 0.1), 0.8);
  a.face_material.assign(a.mesh.faces.size(), 0);
  Material m;
  m.name = "m";
  m.maps.push_back({MapSlot::BaseColor, "t.png", stripes(64, {200, 20, 20}, {20, 20, 200}), true, 1.0, "t"});
  a.materials.push_back(m);
  AssetShrinkOptions o;
  o.size = 64;  // box downsizing to the input size: the input map itself
  o.shrink.force_candidate = "downsized";
  o.shrink.eval_samples = o.shrink.error_samples = 4000;
  const AssetShrinkResult r = shrink_textured_asset(a, o);
  ASSERT_EQ(r.groups.size(), 1u);
  EXPECT_EQ(r.groups[0].result.chosen, "downsized");
  EXPECT_EQ(r.groups[0].wrapped_charts, 1);
  EXPECT_LT(worst_wrapped_read(a.param, m.maps[0].image, r.param, r.groups[0].result.maps[0]), 1e-6);
  EXPECT_GT(r.psnr, 60.0);
}

/// The same through shrink_textured_mesh() itself (what the Python module and the Blender add-on call),
/// for a chart in the tile [-1,0] x [1,2] and one inside [0,1]².
TEST(ShrinkAsset, ShrinkMovesChartsOfOtherTilesItself) {
  TriMesh mesh;
  Parameterization param;
  patch(mesh, param, 0, 6, Vec2(-0.9, 1.1), 0.45);
  patch(mesh, param, 2, 6, Vec2(0.5, 0.1), 0.45);
  const ImageRGBA8 tex = stripes(64, {200, 20, 20}, {20, 20, 200});
  ShrinkOptions o;
  o.size = 64;
  o.force_candidate = "downsized";
  o.eval_samples = o.error_samples = 4000;
  const ShrinkResult r = shrink_textured_mesh(mesh, param, {{"base_color", tex, MapKind::Color}}, o);
  EXPECT_EQ(r.chosen, "downsized");
  EXPECT_LT(worst_wrapped_read(param, tex, r.param, r.maps[0]), 1e-6);
  for (int w = 49; w < param.num_wedges(); ++w) EXPECT_EQ(r.param.uv[w], param.uv[w]) << w;  // kept
  EXPECT_GT(r.psnr, 60.0);
}

}  // namespace
}  // namespace adaptex
