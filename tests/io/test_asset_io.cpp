// Tests of io/asset_io: an OBJ + MTL asset built in code with an artist's traps (two materials,
// mirrored and overlapping charts, a chart in another UV tile, a degenerate UV triangle, maps in PNG,
// JPEG and TGA), and every kind of bad input (missing or self-referencing files, NaN UVs, UDIM).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "adaptex/core/errors.h"
#include "adaptex/io/asset_io.h"
#include "adaptex/io/mesh_io.h"
#include "asset_test_support.h"
#include "image_test_files.h"
#include "io_test_files.h"
#include "test_support.h"

namespace adaptex {
namespace {

namespace fs = std::filesystem;

/// A strip of four unit quads along x (10 vertices, z = 0, counter-clockwise seen from +z), one UV
/// chart per quad:
///   quad 0 (skin):  UV [0.1,0.4]^2;
///   quad 1 (skin):  the same square mirrored in u (shares quad 0's texels, reversed orientation);
///   quad 2 (cloth): UV [1.5,1.9] x [0.5,0.9], one tile to the right of the unit square;
///   quad 3 (cloth): a quad whose second triangle is degenerate in UV (three collinear vt).
std::string strip_obj(const std::string& mtllib = "mtllib mat.mtl\n") {
  std::string s = mtllib;
  for (int y = 0; y <= 1; ++y)
    for (int x = 0; x <= 4; ++x) s += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
  // vt 1-4: quad 0; 5-8: quad 1 (mirrored); 9-12: quad 2; 13-16: quad 3.
  s += "vt 0.1 0.1\nvt 0.4 0.1\nvt 0.4 0.4\nvt 0.1 0.4\n";
  s += "vt 0.4 0.1\nvt 0.1 0.1\nvt 0.1 0.4\nvt 0.4 0.4\n";
  s += "vt 1.5 0.5\nvt 1.9 0.5\nvt 1.9 0.9\nvt 1.5 0.9\n";
  s += "vt 0.5 0.125\nvt 0.75 0.125\nvt 0.75 0.375\nvt 0.625 0.25\n";
  const auto quad = [&](int q, int t) {  // bottom-left vertex q+1, vt t..t+3 in the same corner order
    const int a = q + 1, b = q + 2, c = q + 7, d = q + 6;
    const auto c2 = [](int v, int vt) { return " " + std::to_string(v) + "/" + std::to_string(vt); };
    s += "f" + c2(a, t) + c2(b, t + 1) + c2(c, t + 2) + "\n";
    s += "f" + c2(a, t) + c2(c, t + 2) + c2(d, t + 3) + "\n";
  };
  s += "usemtl skin\n";
  quad(0, 1);
  quad(1, 5);
  s += "usemtl cloth\n";
  quad(2, 9);
  s += "f 4/13 5/14 10/15\nf 4/13 10/15 9/16\n";  // vt 13, 15, 16 are collinear
  return s;
}

/// A tangent-space normal map's colour (straight up, slightly tilted), and a grey height map.
ImageRGBA8 normal_colours(int w, int h) { return test::solid(w, h, 140, 128, 250); }

struct StripAsset {
  test::TempDir dir;
  fs::path obj;
  StripAsset() {
    obj = dir.path / "strip.obj";
    test::write_text(obj, strip_obj());
    test::write_text(dir.path / "mat.mtl",
                     "# two materials\nnewmtl skin\nKd 0.8 0.7 0.6\nmap_Kd textures/skin.png\n"
                     "norm -bm 0.5 skin_n.png\nmap_Pr rough.jpg\nbump -bm 2 height.png\n\n"
                     "newmtl cloth\nKd 0.2 0.3 0.4\nd 0.5\nmap_Kd cloth.tga\nmap_Bump -bm 1.0 cloth normal.png\n");
    fs::create_directories(dir.path / "textures");
    test::write_text(dir.path / "textures/skin.png", test::png_bytes(test::solid(8, 4, 200, 150, 120)));
    test::write_text(dir.path / "skin_n.png", test::png_bytes(normal_colours(4, 4)));
    test::write_text(dir.path / "rough.jpg", test::jpeg_bytes(test::solid(16, 16, 90, 90, 90)));
    test::write_text(dir.path / "height.png", test::png_bytes(test::solid(4, 4, 128, 128, 128)));
    test::write_text(dir.path / "cloth.tga", test::tga_bytes(test::solid(6, 2, 10, 20, 30)));
    test::write_text(dir.path / "cloth normal.png", test::png_bytes(normal_colours(2, 2)));
  }
};

std::vector<fs::path> map_files(const Material& m) {
  std::vector<fs::path> out;
  for (const TextureMap& t : m.maps) out.push_back(t.path.filename());
  return out;
}

TEST(AssetIo, ObjWithTwoMaterialsAndEveryMapKind) {
  StripAsset a;
  ReadReport report;
  const TexturedAsset asset = read_textured_asset(a.obj, {}, &report);
  EXPECT_EQ(asset.mesh.num_vertices(), 10);
  ASSERT_EQ(asset.mesh.num_faces(), 8);
  EXPECT_EQ(asset.face_material, (std::vector<int>{0, 0, 0, 0, 1, 1, 1, 1}));
  ASSERT_EQ(asset.materials.size(), 2u);
  const Material& skin = asset.materials[0];
  const Material& cloth = asset.materials[1];
  EXPECT_EQ(skin.name, "skin");
  EXPECT_EQ(cloth.name, "cloth");
  EXPECT_DOUBLE_EQ(skin.base_color[1], 0.7);
  EXPECT_DOUBLE_EQ(cloth.base_color[3], 0.5);
  ASSERT_EQ(skin.maps.size(), 4u);
  const TextureMap* base = skin.find(MapSlot::BaseColor);
  ASSERT_NE(base, nullptr);
  EXPECT_TRUE(base->srgb);
  EXPECT_EQ(base->path, a.dir.path / "textures/skin.png");
  EXPECT_EQ(base->image.width, 8);
  EXPECT_EQ(base->image.texel(0, 0)[0], 200);
  const TextureMap* normal = skin.find(MapSlot::Normal);
  ASSERT_NE(normal, nullptr);
  EXPECT_FALSE(normal->srgb);
  EXPECT_DOUBLE_EQ(normal->scale, 0.5);
  ASSERT_NE(skin.find(MapSlot::Roughness), nullptr);
  EXPECT_EQ(skin.find(MapSlot::Roughness)->image.width, 16);  // the JPEG
  ASSERT_NE(skin.find(MapSlot::Bump), nullptr);                // grey: a height map stays a bump map
  EXPECT_DOUBLE_EQ(skin.find(MapSlot::Bump)->scale, 2.0);
  const TextureMap* cloth_base = cloth.find(MapSlot::BaseColor);
  ASSERT_NE(cloth_base, nullptr);
  EXPECT_EQ(cloth_base->image.texel(5, 1)[2], 30);  // the TGA
  // map_Bump holding a normal map's colours (as Blender writes it) is read as the normal map; its
  // file name has a space.
  ASSERT_NE(cloth.find(MapSlot::Normal), nullptr);
  EXPECT_EQ(cloth.find(MapSlot::Normal)->path.filename(), "cloth normal.png");
  EXPECT_EQ(cloth.find(MapSlot::Bump), nullptr);
  EXPECT_NE(std::find_if(report.warnings.begin(), report.warnings.end(),
                         [](const std::string& w) { return w.find("holds a normal map") != std::string::npos; }),
            report.warnings.end());
}

TEST(AssetIo, AtlasIsReadAsTheArtistMadeIt) {
  StripAsset a;
  const TexturedAsset asset = read_textured_asset(a.obj);
  const UvReport& uv = asset.uv;
  EXPECT_EQ(uv.charts, 4);
  EXPECT_EQ(uv.mirrored_faces, 2);
  EXPECT_EQ(uv.mirrored_charts, 1);
  EXPECT_EQ(uv.degenerate_uv_faces, 1);
  EXPECT_EQ(uv.faces_outside_unit, 2);
  EXPECT_EQ(uv.wrapped_charts, 1);
  EXPECT_EQ(uv.clamped_uvs, 0);
  // Texel usage after wrapping: quads 0 and 1 cover the same 0.3² (shared), quad 2 0.4², quad 3's
  // one non-degenerate triangle 0.03125: 0.28125 of the square, 0.09 of it shared.
  EXPECT_NEAR(uv.covered_fraction, 0.28125, 0.002);
  EXPECT_NEAR(uv.shared_fraction, 0.09 / 0.28125, 0.005);
  // The mirrored chart keeps its reversed orientation and shares the first chart's texels exactly.
  const Parameterization& p = asset.param;
  EXPECT_GT(uv_signed_area(p, 0), 0);
  EXPECT_LT(uv_signed_area(p, 2), 0);
  EXPECT_EQ(p.face_chart[0], p.face_chart[1]);
  EXPECT_NE(p.face_chart[0], p.face_chart[2]);
  std::vector<std::pair<double, double>> chart0, chart1;
  for (int f = 0; f < 4; ++f)
    for (int w : p.uv_faces[f]) (f < 2 ? chart0 : chart1).emplace_back(p.uv[w].x(), p.uv[w].y());
  std::sort(chart0.begin(), chart0.end());
  std::sort(chart1.begin(), chart1.end());
  chart0.erase(std::unique(chart0.begin(), chart0.end()), chart0.end());
  chart1.erase(std::unique(chart1.begin(), chart1.end()), chart1.end());
  EXPECT_EQ(chart0, chart1);
  // The degenerate UV triangle is kept.
  EXPECT_EQ(uv_signed_area(p, 7), 0.0);
  // Every UV in the unit square; the chart one tile to the right moved by exactly (-1, 0).
  for (const Vec2& t : p.uv) {
    EXPECT_GE(t.minCoeff(), 0.0);
    EXPECT_LE(t.maxCoeff(), 1.0);
  }
  const TexturedMesh plain = read_textured_obj(a.obj);
  ASSERT_EQ(plain.param.uv.size(), p.uv.size());
  EXPECT_EQ(plain.param.uv_faces, p.uv_faces);
  EXPECT_EQ(plain.param.wedge_vertex, p.wedge_vertex);
  EXPECT_EQ(plain.param.face_chart, p.face_chart);
  EXPECT_EQ(plain.mesh.faces, asset.mesh.faces);
  EXPECT_EQ(plain.mesh.positions, asset.mesh.positions);
  for (std::size_t w = 0; w < p.uv.size(); ++w) {
    const bool moved = plain.param.uv[w].x() > 1;
    EXPECT_EQ(p.uv[w].x(), moved ? plain.param.uv[w].x() - 1 : plain.param.uv[w].x()) << w;
    EXPECT_EQ(p.uv[w].y(), plain.param.uv[w].y()) << w;
  }
}

TEST(AssetIo, FromMemoryGivesTheSameAssetAndMapsCanBeLeftUndecoded) {
  StripAsset a;
  AssetReadOptions options;
  options.load_images = false;
  const TexturedAsset asset = read_textured_asset_from_memory(strip_obj(), "obj", a.obj, options);
  EXPECT_EQ(asset.face_material, (std::vector<int>{0, 0, 0, 0, 1, 1, 1, 1}));
  ASSERT_EQ(asset.materials.size(), 2u);
  EXPECT_EQ(map_files(asset.materials[1]), (std::vector<fs::path>{"cloth.tga", "cloth normal.png"}));
  EXPECT_TRUE(asset.materials[0].maps[0].image.empty());
  EXPECT_EQ(asset.uv.wrapped_charts, 1);
}

TEST(AssetIo, ObjWithoutMaterialsHasFacesWithoutMaterial) {
  test::TempDir dir;
  test::write_text(dir.path / "plain.obj", strip_obj(""));
  const TexturedAsset asset = read_textured_asset(dir.path / "plain.obj");
  EXPECT_TRUE(asset.materials.empty());
  EXPECT_EQ(asset.face_material, std::vector<int>(8, -1));
}

TEST(AssetIo, WindowsPathsInMaterialFilesAreFoundNextToTheMaterialFile) {
  StripAsset a;
  test::write_text(a.dir.path / "mat.mtl", "newmtl skin\nmap_Kd C:\\Users\\artist\\skin.png\nnewmtl cloth\n");
  test::write_text(a.dir.path / "skin.png", test::png_bytes(test::solid(2, 2, 1, 2, 3)));
  ReadReport report;
  const TexturedAsset asset = read_textured_asset(a.obj, {}, &report);
  ASSERT_EQ(asset.materials[0].maps.size(), 1u);
  EXPECT_EQ(asset.materials[0].maps[0].path, a.dir.path / "skin.png");
  EXPECT_EQ(asset.materials[0].maps[0].image.texel(1, 1)[2], 3);
}

// --- bad input: one line naming the file and the problem ---

using test::expect_asset_rejected;

TEST(AssetIo, MissingMaterialFileOrMap) {
  StripAsset a;
  test::write_text(a.obj, strip_obj("mtllib nothere.mtl\n"));
  expect_asset_rejected(a.obj, "strip.obj: line 1: mtllib 'nothere.mtl'", "file does not exist");
  test::write_text(a.obj, strip_obj());
  fs::remove(a.dir.path / "cloth.tga");
  expect_asset_rejected(a.obj, "mat.mtl: line 12: map_Kd 'cloth.tga'", "file does not exist");
}

TEST(AssetIo, MaterialFilePointingAtItselfOrACycle) {
  StripAsset a;
  test::write_text(a.dir.path / "mat.mtl", "newmtl skin\nmap_Kd mat.mtl\n");
  expect_asset_rejected(a.obj, "mat.mtl: line 2: map_Kd 'mat.mtl'", "mat.mtl itself, not an image");
  test::write_text(a.dir.path / "mat.mtl", "newmtl skin\nmap_Kd strip.obj\n");
  expect_asset_rejected(a.obj, "map_Kd 'strip.obj'", "strip.obj itself, not an image");
  // Two material files naming each other as maps.
  test::write_text(a.obj, strip_obj("mtllib a.mtl b.mtl\n"));
  test::write_text(a.dir.path / "a.mtl", "newmtl skin\nmap_Kd b.mtl\n");
  test::write_text(a.dir.path / "b.mtl", "newmtl cloth\nmap_Kd a.mtl\n");
  expect_asset_rejected(a.obj, "a.mtl: line 2: map_Kd 'b.mtl'", "b.mtl itself, not an image");
  // The OBJ naming itself as its material file.
  test::write_text(a.obj, strip_obj("mtllib strip.obj\n"));
  expect_asset_rejected(a.obj, "strip.obj: line 1: mtllib 'strip.obj'", "is the OBJ file itself");
}

TEST(AssetIo, CorruptMapsAndMalformedMaterialStatements) {
  StripAsset a;
  std::string tga = test::tga_bytes(test::solid(6, 2, 10, 20, 30));
  test::write_text(a.dir.path / "cloth.tga", tga.substr(0, tga.size() - 3));
  expect_asset_rejected(a.obj, "cloth.tga", "corrupt TGA: truncated");
  StripAsset b;
  test::write_text(b.dir.path / "mat.mtl", "newmtl skin\nKd 1 nan 0\n");
  expect_asset_rejected(b.obj, "mat.mtl: line 2", "Kd has a non-numeric or non-finite value: nan");
  test::write_text(b.dir.path / "mat.mtl", "newmtl skin\nmap_Kd -bm\n");
  expect_asset_rejected(b.obj, "mat.mtl: line 2", "'map_Kd': option '-bm' leaves no file name");
  test::write_text(b.dir.path / "mat.mtl", "newmtl skin\nmap_Kd -zz 1 skin.png\n");
  expect_asset_rejected(b.obj, "mat.mtl: line 2", "unknown texture option '-zz'");
}

TEST(AssetIo, NanUvIsRejected) {
  test::TempDir dir;
  std::string obj = strip_obj("");
  obj.replace(obj.find("vt 0.4 0.4"), 10, "vt nan 0.4");
  test::write_text(dir.path / "nan.obj", obj);
  expect_asset_rejected(dir.path / "nan.obj", "nan.obj", "vt 3 is not finite");
}

TEST(AssetIo, StraddlingChartsAreKeptByDefaultAndUdimIsRejectedClearly) {
  test::TempDir dir;
  std::string obj = strip_obj("");
  obj.replace(obj.find("vt 1.5 0.5"), 10, "vt 0.8 0.5");  // quad 2 spans u 0.8 .. 1.9
  test::write_text(dir.path / "straddle.obj", obj);
  AssetReadOptions strict;
  strict.keep_straddling_charts = false;
  expect_asset_rejected(dir.path / "straddle.obj", "straddle.obj: UV chart 2 (face 5 and 1 more) spans u 0.8 to 1.9",
                        "crosses a UV tile border, which is not supported", strict);
  const TexturedAsset kept = read_textured_asset(dir.path / "straddle.obj");  // kept by default
  EXPECT_EQ(kept.uv.straddling_charts, 1);
  EXPECT_EQ(kept.uv.wrapped_charts, 0);
  EXPECT_EQ(kept.param.uv[kept.param.uv_faces[4][1]].x(), 1.9);  // left where it is
  // Maps named per UDIM tile, charts in two tiles.
  StripAsset a;
  test::write_text(a.dir.path / "mat.mtl", "newmtl skin\nmap_Kd skin.1001.png\nnewmtl cloth\n");
  test::write_text(a.dir.path / "skin.1001.png", test::png_bytes(test::solid(2, 2, 1, 2, 3)));
  expect_asset_rejected(a.obj, "strip.obj", "UDIM tiles are not supported: the charts lie in 2 UV tiles");
  test::write_text(a.dir.path / "mat.mtl", "newmtl skin\nmap_Kd skin.<UDIM>.png\n");
  expect_asset_rejected(a.obj, "map_Kd 'skin.<UDIM>.png'", "UDIM texture sets are not supported");
}

TEST(AssetIo, CoordinatesJustOutsideTheirTileAreClamped) {
  test::TempDir dir;
  std::string obj = strip_obj("");
  obj.replace(obj.find("vt 0.75 0.125"), 13, "vt 1.0004 0.125");  // within the default tolerance 1e-3
  test::write_text(dir.path / "edge.obj", obj);
  const TexturedAsset asset = read_textured_asset(dir.path / "edge.obj");
  EXPECT_EQ(asset.uv.clamped_uvs, 1);
  EXPECT_EQ(asset.uv.wrapped_charts, 1);
  AssetReadOptions strict;
  strict.uv_tolerance = 1e-4;
  strict.keep_straddling_charts = false;
  EXPECT_THROW((void)read_textured_asset(dir.path / "edge.obj", strict), InvalidInputError);
  strict.keep_straddling_charts = true;  // the default keeps the chart where it is
  EXPECT_EQ(read_textured_asset(dir.path / "edge.obj", strict).uv.straddling_charts, 1);
}

TEST(AssetIo, TexelUsageCountsSharedEdgesOnceAndOverlapsTwice) {
  // The unit square as two triangles (sharing the diagonal, on which texel centres lie at 4²), and
  // a third triangle over the lower half of it, mirrored.
  Parameterization p;
  p.uv = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  p.uv_faces = {Face{0, 1, 2}, Face{0, 2, 3}};
  const TexelUsage square = measure_texel_usage(p, 4);
  EXPECT_EQ(square.covered_fraction, 1.0);
  EXPECT_EQ(square.shared_fraction, 0.0);
  p.uv.push_back(Vec2(0, 0.5));
  p.uv.push_back(Vec2(1, 0.5));
  p.uv_faces.push_back(Face{0, 4, 1});  // clockwise: mirrored
  const TexelUsage folded = measure_texel_usage(p, 8);
  EXPECT_EQ(folded.covered_fraction, 1.0);
  EXPECT_NEAR(folded.shared_fraction, 0.25, 1.0 / 64);  // the triangle (0,0) (0,0.5) (1,0): a quarter
  EXPECT_THROW((void)measure_texel_usage(p, 0), InvalidInputError);
  // Coordinates far outside the square (found by fuzz_gltf: 3e30 overflowed an int) count nothing there.
  p.uv.push_back(Vec2(3e30, -3e30));
  p.uv_faces.push_back(Face{0, 1, 6});
  const TexelUsage far = measure_texel_usage(p, 8);
  EXPECT_EQ(far.covered_fraction, 1.0);
}

TEST(AssetIo, TexelUsageOfHostilyManyLargeTrianglesIsMeasuredOnACoarserGrid) {
  // 3,000 copies of the square's two triangles: 6,000 bounding boxes of 1024² texels each would be
  // 6 G texel tests; the grid is made coarser so that at most 64 Mi are tested.
  Parameterization p;
  p.uv = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)};
  for (int k = 0; k < 3000; ++k) {
    p.uv_faces.push_back(Face{0, 1, 2});
    p.uv_faces.push_back(Face{0, 2, 3});
  }
  const TexelUsage usage = measure_texel_usage(p);
  EXPECT_EQ(usage.covered_fraction, 1.0);
  EXPECT_EQ(usage.shared_fraction, 1.0);
}

TEST(AssetIo, ParseMtlReadsOptionsAndNamesWithSpaces) {
  std::vector<std::string> warnings;
  const auto mats = parse_mtl(
      "newmtl a b\nPr 0.25\nPm 1\nKe 1 2 3\nmap_Kd -s 2 2 -o 0.5 -blendu off my skin.png\nmap_Ke -t 1 glow.png\n"
      "map_Kd again.png\nnewmtl a b\nmap_Pm metal.png\n",
      "/x/m.mtl", &warnings);
  ASSERT_EQ(mats.size(), 1u);
  EXPECT_EQ(mats[0].name, "a b");
  EXPECT_EQ(*mats[0].roughness, 0.25);
  EXPECT_EQ(*mats[0].metallic, 1.0);
  EXPECT_EQ(mats[0].emissive[2], 3.0);
  EXPECT_EQ(map_files(mats[0]), (std::vector<fs::path>{"my skin.png", "glow.png"}));
  EXPECT_EQ(mats[0].maps[0].path, fs::path("/x/my skin.png"));
  EXPECT_EQ(mats[0].maps[1].slot, MapSlot::Emissive);
  // The texture transform, the second base colour map and the repeated material are reported.
  EXPECT_EQ(warnings.size(), 3u);
}

}  // namespace
}  // namespace adaptex
