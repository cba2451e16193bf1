// Tests of io/asset_io on glTF: a GLB built byte by byte with the strip of test_asset_io.cpp (mirrored
// and overlapping charts, a chart one tile to the right, a degenerate UV triangle), two materials with
// every map kind, and images embedded in the BIN chunk, in a data: URI and in files beside the GLB.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "adaptex/core/errors.h"
#include "adaptex/io/asset_io.h"
#include "asset_test_support.h"
#include "image_test_files.h"
#include "io_test_files.h"
#include "test_support.h"

namespace adaptex {
namespace {

namespace fs = std::filesystem;

std::string base64(const std::string& in) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t k = 0; k < in.size(); k += 3) {
    const std::size_t n = std::min<std::size_t>(3, in.size() - k);
    std::uint32_t v = 0;
    for (std::size_t j = 0; j < 3; ++j) v = v << 8 | (j < n ? static_cast<unsigned char>(in[k + j]) : 0u);
    out += abc[(v >> 18) & 63];
    out += abc[(v >> 12) & 63];
    out += n > 1 ? abc[(v >> 6) & 63] : '=';
    out += n > 2 ? abc[v & 63] : '=';
  }
  return out;
}

/// UVs (OBJ convention, v up) of the four quads' corners a, b, c, d, as in test_asset_io.cpp.
constexpr std::array<std::array<std::array<double, 2>, 4>, 4> kQuadUv = {{
    {{{0.125, 0.125}, {0.375, 0.125}, {0.375, 0.375}, {0.125, 0.375}}},
    {{{0.375, 0.125}, {0.125, 0.125}, {0.125, 0.375}, {0.375, 0.375}}},  // mirrored, overlapping quad 0
    {{{1.5, 0.5}, {1.875, 0.5}, {1.875, 0.875}, {1.5, 0.875}}},           // one tile to the right
    {{{0.5, 0.125}, {0.75, 0.125}, {0.75, 0.375}, {0.625, 0.25}}},        // second triangle degenerate
}};

struct GlbOptions {
  std::string embedded_png;      ///< image 0, in the BIN chunk
  float nan_uv = 0;              ///< when NaN: the first UV
  std::string sampler = "";      ///< a "samplers" entry for texture 0, or none
  int untextured_material = -2;  ///< > -2: a third primitive (a quad at z = 1) without TEXCOORD_0, with this material (-1: none)
  bool swap_materials = false;   ///< primitive 0 gets material 1 and primitive 1 material 0
};

/// The strip as a GLB: primitive 0 (quads 0, 1) with material 0, primitive 1 (quads 2, 3) with
/// material 1. Images: 0 in the BIN chunk, 1 a data: URI PNG, 2 "ao map.jpg" and 3 "mr.tga" beside the file.
std::string strip_glb(const GlbOptions& o) {
  std::string bin;
  for (int q = 0; q < 4; ++q) {  // positions: 4 per quad
    const float x = static_cast<float>(q);
    for (const auto& p : {std::array<float, 3>{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x, 1, 0}})
      for (float c : p) test::put(bin, c);
  }
  for (int q = 0; q < 4; ++q)  // texcoords, glTF convention: v down
    for (const auto& t : kQuadUv[q]) {
      test::put(bin, q == 0 && &t == &kQuadUv[0][0] && std::isnan(o.nan_uv) ? o.nan_uv : static_cast<float>(t[0]));
      test::put(bin, static_cast<float>(1.0 - t[1]));
    }
  for (int prim = 0; prim < 2; ++prim)
    for (int q = 0; q < 2; ++q)
      for (int k : {0, 1, 2, 0, 2, 3}) test::put(bin, static_cast<std::uint16_t>(4 * q + k));
  for (const auto& p : {std::array<float, 3>{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}})  // at 368: the z = 1 quad
    for (float c : p) test::put(bin, c);
  for (int k : {0, 1, 2, 0, 2, 3}) test::put(bin, static_cast<std::uint16_t>(k));  // at 416
  bin += std::string(4, '\0');
  const std::size_t png_offset = bin.size();  // 432, a multiple of 4
  bin += o.embedded_png;
  while (bin.size() % 4) bin += '\0';
  const std::string data_png = test::png_bytes(test::solid(2, 2, 128, 128, 255));
  std::string json = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [
    {"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 4, "material": )" + std::string(o.swap_materials ? "1" : "0") + R"(},
    {"attributes": {"POSITION": 1, "TEXCOORD_0": 3}, "indices": 5, "material": )" + std::string(o.swap_materials ? "0" : "1") + R"(})" +
                     (o.untextured_material > -2
                          ? R"(, {"attributes": {"POSITION": 6}, "indices": 7)" +
                                (o.untextured_material >= 0 ? ", \"material\": " + std::to_string(o.untextured_material) : "") + "}"
                          : "") +
                     R"(]}],
  "buffers": [{"byteLength": )" + std::to_string(bin.size()) + R"(}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96}, {"buffer": 0, "byteOffset": 96, "byteLength": 96},
    {"buffer": 0, "byteOffset": 192, "byteLength": 64}, {"buffer": 0, "byteOffset": 256, "byteLength": 64},
    {"buffer": 0, "byteOffset": 320, "byteLength": 24}, {"buffer": 0, "byteOffset": 344, "byteLength": 24},
    {"buffer": 0, "byteOffset": 368, "byteLength": 48}, {"buffer": 0, "byteOffset": 416, "byteLength": 12},
    {"buffer": 0, "byteOffset": )" + std::to_string(png_offset) + R"(, "byteLength": )" +
                     std::to_string(o.embedded_png.size()) + R"(}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3"},
    {"bufferView": 1, "componentType": 5126, "count": 8, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 8, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5126, "count": 8, "type": "VEC2"},
    {"bufferView": 4, "componentType": 5123, "count": 12, "type": "SCALAR"},
    {"bufferView": 5, "componentType": 5123, "count": 12, "type": "SCALAR"},
    {"bufferView": 6, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 7, "componentType": 5123, "count": 6, "type": "SCALAR"}],
  "images": [{"bufferView": 8, "mimeType": "image/png"}, {"uri": "data:image/png;base64,)" + base64(data_png) +
                     R"("}, {"uri": "ao%20map.jpg"}, {"uri": "mr.tga"}],
  "textures": [{"source": 0)" + (o.sampler.empty() ? "" : ", \"sampler\": 0") + R"(}, {"source": 1}, {"source": 2}, {"source": 3}],)" +
                     (o.sampler.empty() ? "" : "\"samplers\": [" + o.sampler + "],") + R"(
  "materials": [
    {"name": "skin", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 3},
       "metallicFactor": 0.25, "roughnessFactor": 0.75},
     "normalTexture": {"index": 1, "scale": 0.5}, "occlusionTexture": {"index": 2, "strength": 0.7}},
    {"name": "cloth", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.3, 0.4, 1.0]},
     "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 0.5, 0]},
    {"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [0, 0.04, 0.02, 1.0]}}]})";
  return test::glb(json, bin);
}

struct GlbAsset {
  test::TempDir dir;
  fs::path file;
  explicit GlbAsset(GlbOptions o = {}) {
    if (o.embedded_png.empty()) o.embedded_png = test::png_bytes(test::solid(4, 2, 200, 150, 120));
    file = dir.path / "strip.glb";
    test::write_text(file, strip_glb(o));
    test::write_text(dir.path / "ao map.jpg", test::jpeg_bytes(test::solid(16, 8, 180, 180, 180)));
    test::write_text(dir.path / "mr.tga", test::tga_bytes(test::solid(3, 3, 0, 190, 60)));
  }
};

TEST(AssetGltf, MaterialsWithEveryMapKindFromEveryKindOfImageSource) {
  GlbAsset a;
  ReadReport report;
  const TexturedAsset asset = read_textured_asset(a.file, {}, &report);
  EXPECT_EQ(report.format, "glb");
  ASSERT_EQ(asset.mesh.num_faces(), 8);
  EXPECT_EQ(asset.mesh.num_vertices(), 10);  // quads' corners welded by position
  EXPECT_EQ(asset.face_material, (std::vector<int>{0, 0, 0, 0, 1, 1, 1, 1}));
  ASSERT_EQ(asset.materials.size(), 3u);
  EXPECT_TRUE(asset.materials[2].maps.empty());
  EXPECT_EQ(asset.uv.untextured_faces, 0);
  const Material& skin = asset.materials[0];
  EXPECT_EQ(skin.name, "skin");
  EXPECT_EQ(*skin.metallic, 0.25);
  EXPECT_EQ(*skin.roughness, 0.75);
  ASSERT_EQ(skin.maps.size(), 4u);
  const TextureMap* base = skin.find(MapSlot::BaseColor);
  ASSERT_NE(base, nullptr);
  EXPECT_EQ(base->path, fs::path(a.file.string() + "#image0"));
  EXPECT_TRUE(base->srgb);
  EXPECT_EQ(base->image.width, 4);
  EXPECT_EQ(base->image.texel(3, 1)[0], 200);
  const TextureMap* normal = skin.find(MapSlot::Normal);
  ASSERT_NE(normal, nullptr);
  EXPECT_FALSE(normal->srgb);
  EXPECT_DOUBLE_EQ(normal->scale, 0.5);
  EXPECT_EQ(normal->image.texel(1, 1)[2], 255);  // the data: URI PNG
  const TextureMap* ao = skin.find(MapSlot::Occlusion);
  ASSERT_NE(ao, nullptr);
  EXPECT_DOUBLE_EQ(ao->scale, 0.7);
  EXPECT_EQ(ao->path, a.dir.path / "ao map.jpg");  // percent-decoded
  EXPECT_EQ(ao->image.width, 16);
  const TextureMap* mr = skin.find(MapSlot::MetallicRoughness);
  ASSERT_NE(mr, nullptr);
  EXPECT_EQ(mr->image.texel(2, 2)[1], 190);  // the TGA
  const Material& cloth = asset.materials[1];
  EXPECT_DOUBLE_EQ(cloth.base_color[2], 0.4);
  EXPECT_DOUBLE_EQ(cloth.emissive[1], 0.5);
  ASSERT_EQ(cloth.maps.size(), 1u);
  EXPECT_EQ(cloth.maps[0].slot, MapSlot::Emissive);
  EXPECT_EQ(cloth.maps[0].image.texel(0, 0)[1], 150);
}

TEST(AssetGltf, AtlasMatchesTheObjStripExactly) {
  GlbAsset a;
  const TexturedAsset asset = read_textured_asset(a.file);
  const UvReport& uv = asset.uv;
  // glTF corners are matched by value (position and UV): quad 1, the mirror image of quad 0, shares
  // its mirror edge with quad 0 in 3-D and in UV, so the two make one chart, half mirrored (as a
  // mirror modifier's seam does). The OBJ strip gives them separate vt and so two charts.
  EXPECT_EQ(uv.charts, 3);
  EXPECT_EQ(asset.param.face_chart[0], asset.param.face_chart[2]);
  EXPECT_EQ(uv.mirrored_faces, 2);
  EXPECT_EQ(uv.mirrored_charts, 0);
  EXPECT_EQ(uv.degenerate_uv_faces, 1);
  EXPECT_EQ(uv.faces_outside_unit, 2);
  EXPECT_EQ(uv.wrapped_charts, 1);
  // Face f = quad f/2, triangle (a, b, c) or (a, c, d); v flipped back to OBJ's convention and the
  // chart one tile to the right moved by (-1, 0).
  for (int f = 0; f < 8; ++f) {
    const int q = f / 2;
    const std::array<int, 3> corners = f % 2 ? std::array<int, 3>{0, 2, 3} : std::array<int, 3>{0, 1, 2};
    for (int k = 0; k < 3; ++k) {
      const Vec2 t = asset.param.uv[asset.param.uv_faces[f][k]];
      EXPECT_EQ(t.x(), kQuadUv[q][corners[k]][0] - (q == 2 ? 1.0 : 0.0)) << f << " " << k;
      EXPECT_EQ(t.y(), kQuadUv[q][corners[k]][1]) << f << " " << k;
    }
  }
}

using test::expect_asset_rejected;

TEST(AssetGltf, BadImagesMissingFilesNanUvsAndClampedSamplers) {
  const std::string jpeg = test::jpeg_bytes(test::solid(32, 32, 1, 2, 3));
  GlbAsset cut({jpeg.substr(0, jpeg.size() - 40)});
  expect_asset_rejected(cut.file, "strip.glb#image0", "corrupt JPEG: truncated");
  GlbAsset missing;
  fs::remove(missing.dir.path / "mr.tga");
  expect_asset_rejected(missing.file, "strip.glb: material 0 'skin': metallicRoughnessTexture (image 3)", "file does not exist");
  GlbAsset nan({"", std::numeric_limits<float>::quiet_NaN()});
  expect_asset_rejected(nan.file, "strip.glb", "texture coordinate 1 is not finite");
  GlbAsset clamp({"", 0, R"({"wrapS": 33071, "wrapT": 33071})"});
  expect_asset_rejected(clamp.file, "baseColorTexture", "the sampler does not repeat, but 1 UV chart lies outside [0,1]");
  GlbAsset repeat({"", 0, R"({"wrapS": 10497})"});
  EXPECT_EQ(read_textured_asset(repeat.file).uv.wrapped_charts, 1);
  GlbAsset textured_without_uvs({"", 0, "", 0});  // material 0 has maps
  expect_asset_rejected(textured_without_uvs.file, "strip.glb",
                        "has a primitive with material 0, which has texture maps, but no texture coordinates (TEXCOORD_0)");
}

TEST(AssetGltf, FaceMaterialsAreTheFilesIndicesWhateverOrderAssimpLoadsThemIn) {
  // assimp numbers materials in the order primitives first use them: here material 1 comes first.
  GlbAsset a({"", 0, "", -2, true});
  const TexturedAsset asset = read_textured_asset(a.file);
  EXPECT_EQ(asset.face_material, (std::vector<int>{1, 1, 1, 1, 0, 0, 0, 0}));
  EXPECT_EQ(asset.materials[0].name, "skin");
}

TEST(AssetGltf, PrimitivesWithoutUvsAndWithoutMapsGetUvZero) {
  for (int material : {2, -1}) {  // a material without maps (glass), or none
    GlbAsset a({"", 0, "", material});
    ReadReport report;
    const TexturedAsset asset = read_textured_asset(a.file, {}, &report);
    ASSERT_EQ(asset.mesh.num_faces(), 10);
    EXPECT_EQ(asset.face_material[8], material);
    EXPECT_EQ(asset.uv.untextured_faces, 2);
    EXPECT_EQ(asset.uv.degenerate_uv_faces, 3);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(asset.param.uv[asset.param.uv_faces[9][k]], Vec2(0, 0));
    EXPECT_NE(report.warnings.back().find("2 faces without texture coordinates"), std::string::npos);
  }
}

}  // namespace
}  // namespace adaptex
