// A layered material painted into textures (paint/material_paint.h) and `adaptex paint` with a
// stroke file of version 2: channel textures equal the exact material at the texel centres, the
// normal map follows the height's surface gradient (mirrored charts included), and the exports carry
// a glTF metallic-roughness material and an OBJ/MTL with map_Pr, map_Pm and norm.
// GCC 12 reports a false -Wrestrict inside std::string concatenation (GCC bug 105329).
#pragma GCC diagnostic ignored "-Wrestrict"
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/material_paint.h"
#include "adaptex/paint/material_signal.h"
#include "adaptex/paint/signal.h"
#include "brush_test_util.h"
#include "test_support.h"

namespace adaptex {
namespace {

std::string q(const std::filesystem::path& p) { return "'" + p.string() + "'"; }
std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

MaterialStrokeFile two_layers() {
  return parse_material_strokes(R"({"format": "adaptex.strokes", "version": 2, "height_scale": 0.05, "layers": [
    {"strokes": [{"channels": {"base_color": [0.9, 0.2, 0.1], "roughness": 0.1, "height": 0.9},
                  "radius": 0.2, "hardness": 0.3, "dabs": [[0.3, 0.4, 0], [0.5, 0.5, 0]]}]},
    {"blend": "multiply", "mask": {"value": 0, "strokes": [{"type": "fill", "value": 1, "opacity": 0.5}]},
     "strokes": [{"type": "fill", "channels": {"metallic": 1, "base_color": [0.5, 0.5, 1]}}]}]})",
                                "m.json", ".");
}

/// two_layers() painted at 64² (padding 2) on a 10 x 10 plane whose chart is shrunk to [0.05, 0.95]².
struct PlaneMaterial : ::testing::Test {
  const TriMesh mesh = shapes::plane(10);
  const Parameterization param = test::planar_param(mesh, 0.9, 0.05);
  const MaterialStrokeFile file = two_layers();
  const MaterialPaintOptions o = {64, 2};
  const MaterialTextures tex = paint_material(mesh, param, file, o);
};

TEST_F(PlaneMaterial, TexelsHoldTheExactMaterialAtTheirCentres) {
  const TexelMap map = build_texel_map(mesh, param, 64, 64);
  std::vector<SurfacePoint> pts;
  for (int t : map.inside) pts.push_back({map.face[t], map.bary[t].x(), map.bary[t].y()});
  const std::vector<MaterialValue> v = evaluate_material(mesh, file, pts);
  auto byte = [](double x) { return static_cast<int>(std::lround(x * 255)); };
  int painted = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    const int t = map.inside[k];
    ASSERT_EQ(tex.base_color.data[4 * t], byte(v[k][0]));
    ASSERT_EQ(tex.roughness.data[4 * t], byte(v[k][4]));
    ASSERT_EQ(tex.metallic.data[4 * t], byte(v[k][5]));
    ASSERT_EQ(tex.height.data[4 * t], byte(v[k][6]));
    ASSERT_EQ(tex.metallic_roughness.data[4 * t + 1], byte(v[k][4]));  // glTF: G = roughness
    ASSERT_EQ(tex.metallic_roughness.data[4 * t + 2], byte(v[k][5]));  // B = metallic
    painted += v[k][6] > 0.6;
  }
  EXPECT_GT(painted, 0);
  EXPECT_DOUBLE_EQ(tex.height_scale, 0.05);
  // Texels far outside the charts hold the background (metallic 0 there, roughness 0.5).
  EXPECT_EQ(tex.metallic.data[0], 0);
  EXPECT_EQ(tex.roughness.data[0], byte(0.5));
}

// Images of channels no layer paints are filled flat without reading the values: the same bytes as
// writing the values, which are the background there exactly.
TEST_F(PlaneMaterial, UnpaintedChannelsGiveTheSameImagesFilledFlat) {
  const unsigned bits = channel_bit(Channel::BaseColor) | channel_bit(Channel::Roughness) |
                        channel_bit(Channel::Metallic) | channel_bit(Channel::Height);
  EXPECT_EQ(painted_channels(file), bits);
  MaterialStrokeFile colour = file;
  colour.layers.pop_back();
  colour.layers[0].strokes[0].channels = channel_bit(Channel::BaseColor);
  ASSERT_EQ(painted_channels(colour), channel_bit(Channel::BaseColor));
  const TexelMap map = build_texel_map(mesh, param, 64, 64);
  const std::vector<MaterialValue> v = evaluate_material(mesh, colour, texel_points(map));
  MaterialTextures flat, all;
  material_textures_from_values(mesh, param, map, v, colour.background, 2, 0.05, flat, painted_channels(colour));
  material_textures_from_values(mesh, param, map, v, colour.background, 2, 0.05, all, kAllChannels);
  EXPECT_EQ(flat.base_color.data, all.base_color.data);
  for (const auto& [a, b] : {std::pair{&flat.roughness, &all.roughness}, {&flat.metallic, &all.metallic},
                             {&flat.height, &all.height}, {&flat.metallic_roughness, &all.metallic_roughness},
                             {&flat.normal, &all.normal}})
    EXPECT_EQ(a->data, b->data);
  EXPECT_NE(tex.normal.data, all.normal.data);  // the painted height does change the normal map
}

// Bytes round halves away from zero (std::lround), also at values within an ulp of a half-way point.
TEST(MaterialPaint, BytesRoundAsLround) {
  const TriMesh mesh = shapes::plane(2);
  const Parameterization param = test::planar_param(mesh, 0.9, 0.05);
  for (const double v : {0.0, 0.5 / 255, 2.5 / 255, 127.5 / 255, std::nextafter(127.5 / 255, 0.0),
                         std::nextafter(127.5 / 255, 1.0), 200.5 / 255, 254.5 / 255, 1.0}) {
    MaterialStrokeFile file = two_layers();
    file.layers.resize(1);
    MaterialStroke& fill = file.layers[0].strokes[0];
    fill.type = MaterialStroke::Type::Fill;
    fill.channels = channel_bit(Channel::Roughness);
    fill.opacity = 1;
    fill.value[channel_offset(Channel::Roughness)] = v;
    const MaterialTextures tex = paint_material(mesh, param, file, {8, 0});
    const int expected = static_cast<int>(std::lround(v * 255));  // the fill's composite is v exactly
    EXPECT_EQ(tex.roughness.data[4 * (4 * 8 + 4)], expected) << "v = " << v;
  }
}

TEST_F(PlaneMaterial, LayersAloneCompositeToTheMaterial) {
  const std::vector<LayerTextures> layers = paint_material_layers(mesh, param, file, o);
  ASSERT_EQ(layers.size(), 2u);
  auto names = [](const LayerTextures& l) {
    std::string out;
    for (const auto& [ch, img] : l.channels) out += std::string(channel_name(ch)) + " ";
    return out;
  };
  EXPECT_EQ(names(layers[0]), "base_color roughness height ");
  EXPECT_EQ(names(layers[1]), "base_color metallic ");
  EXPECT_FALSE(layers[0].mask.has_value());
  ASSERT_TRUE(layers[1].mask.has_value());
  // Composite the layer pictures (8-bit) over the background as docs/strokes.md says: the material's
  // textures, up to rounding. Channels a layer does not list add nothing.
  const TexelMap map = build_texel_map(mesh, param, 64, 64);
  int covered = 0, bare = 0;
  for (int t : map.inside) {
    MaterialValue R = file.background;
    for (size_t l = 0; l < layers.size(); ++l) {
      const double M = layers[l].mask ? layers[l].mask->data[4 * t] / 255.0 : 1.0;
      for (const auto& [ch, img] : layers[l].channels) {
        const std::uint8_t* p = &img.data[4 * t];
        const double k = p[3] / 255.0 * M * file.layers[l].opacity;
        for (int j = 0; j < channel_components(ch); ++j) {
          const int c = channel_offset(ch) + j;
          R[c] = R[c] * (1 - k) + blend_component(file.layers[l].blend, R[c], p[j] / 255.0) * k;
        }
      }
    }
    const std::uint8_t* base = &tex.base_color.data[4 * t];
    for (int j = 0; j < 3; ++j) ASSERT_NEAR(R[j] * 255, base[j], 2.0) << "texel " << t;
    ASSERT_NEAR(R[4] * 255, tex.roughness.data[4 * t], 2.0);
    ASSERT_NEAR(R[5] * 255, tex.metallic.data[4 * t], 2.0);
    ASSERT_NEAR(R[6] * 255, tex.height.data[4 * t], 2.0);
    const std::uint8_t a = layers[0].channels[0].second.data[4 * t + 3];
    covered += a == 255;
    bare += a == 0;
  }
  EXPECT_GT(covered, 0);  // the brush covers some texels fully and leaves others transparent
  EXPECT_GT(bare, 0);
}

/// The normal map of H = slope * u on the unit plane, with the layout \p param.
Vec3 normal_at_centre(const TriMesh& mesh, const Parameterization& param, double slope) {
  const TexelMap map = build_texel_map(mesh, param, 32, 32);
  std::vector<double> h(32 * 32, 0.0);
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) h[j * 32 + i] = slope * (i + 0.5) / 32;
  const ImageRGBA8 img = normal_map_from_height(mesh, param, map, h);
  const std::uint8_t* p = img.texel(16, 16);
  return Vec3(p[0], p[1], p[2]) / 127.5 - Vec3::Ones();
}

TEST(MaterialPaint, NormalMapFollowsTheHeightGradientInTangentSpace) {
  const TriMesh mesh = shapes::plane(8);
  const Parameterization param = test::planar_param(mesh);
  const Vec3 expect = Vec3(-0.3, 0, 1).normalized();
  EXPECT_LT((normal_at_centre(mesh, param, 0.3) - expect).norm(), 0.02);
  EXPECT_LT((normal_at_centre(mesh, param, 0.0) - Vec3(0, 0, 1)).norm(), 0.01);
  // A mirrored chart (u = 1 - x): the same height over u gives the same tangent-space normal.
  Parameterization mirrored = param;
  for (Vec2& uv : mirrored.uv) uv.x() = 1 - uv.x();
  EXPECT_LT((normal_at_centre(mesh, mirrored, 0.3) - expect).norm(), 0.02);
  // A chart at half scale (u = x / 2): the same height over u rises half as fast on the surface.
  Parameterization half = test::planar_param(mesh, 0.5);
  const Vec3 gentle = Vec3(-0.3 * 0.5, 0, 1).normalized();
  const TexelMap map = build_texel_map(mesh, half, 32, 32);
  std::vector<double> h(32 * 32);
  for (int t = 0; t < 32 * 32; ++t) h[t] = 0.3 * ((t % 32) + 0.5) / 32;
  const ImageRGBA8 img = normal_map_from_height(mesh, half, map, h);
  const std::uint8_t* p = img.texel(8, 8);
  EXPECT_LT((Vec3(p[0], p[1], p[2]) / 127.5 - Vec3::Ones() - gentle).norm(), 0.02);
}

TEST(MaterialPaint, NormalMapRejectsTheTermsOfAnotherLayoutOfTheSameMesh) {
  const TriMesh mesh = shapes::plane(4);
  const Parameterization param = test::planar_param(mesh);
  // The same chart with three wedges per face: the same faces and vertices, more wedges.
  Parameterization split = param;
  split.uv.clear(), split.wedge_vertex.clear();
  for (size_t f = 0; f < param.uv_faces.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      split.uv_faces[f][c] = static_cast<int>(split.uv.size());
      split.uv.push_back(param.uv[param.uv_faces[f][c]]);
      split.wedge_vertex.push_back(param.wedge_vertex[param.uv_faces[f][c]]);
    }
  ASSERT_GT(split.num_wedges(), param.num_wedges());
  const TexelMap map = build_texel_map(mesh, param, 16, 16);
  const std::vector<double> h(16 * 16, 0.0);
  ImageRGBA8 out;
  const HeightNormalTerms own = height_normal_terms(mesh, param), other = height_normal_terms(mesh, split);
  EXPECT_NO_THROW(normal_map_from_height(mesh, param, map, h, out, &own));
  EXPECT_THROW(normal_map_from_height(mesh, param, map, h, out, &other), InvalidInputError);
}

/// A one-decal file: the opaque green 4 x 4 "d.png" (written to \p dir) projected straight down onto
/// the middle of the unit plane (fov 20: [0.15, 0.85]^2), with \p channels (empty: none given).
MaterialStrokeFile green_decal(const test::TempDir& dir, const std::string& channels) {
  write_png(dir.path / "d.png", ImageRGBA8(4, 4, {20, 200, 40, 255}));
  return parse_material_strokes(
      R"({"format": "adaptex.strokes", "version": 2, "height_scale": 0.05, "layers": [{"strokes": [
      {"type": "decal", "image": "d.png", "eye": [0.5, 0.5, 2], "target": [0.5, 0.5, 0], "fov": 20)" +
          (channels.empty() ? std::string() : ", \"channels\": " + channels) + "}]}]}",
      "m.json", dir.path);
}

/// Every face centre of \p mesh, sorted into those under the middle of the decal and those outside its frustum.
void decal_points(const TriMesh& mesh, std::vector<SurfacePoint>& inside, std::vector<SurfacePoint>& outside) {
  for (int f = 0; f < mesh.num_faces(); ++f) {
    Vec3 c = Vec3::Zero();
    for (int k = 0; k < 3; ++k) c += mesh.positions[mesh.faces[f][k]] / 3;
    const double d = std::max(std::abs(c.x() - 0.5), std::abs(c.y() - 0.5));
    if (d < 0.25) inside.push_back({f, 1.0 / 3, 1.0 / 3});
    if (d > 0.4) outside.push_back({f, 1.0 / 3, 1.0 / 3});
  }
}

/// How many bytes of \p a and \p b (of one size) differ by more than \p by.
long bytes_apart(const ImageRGBA8& a, const ImageRGBA8& b, int by) {
  long n = 0;
  for (size_t k = 0; k < a.data.size(); ++k) n += std::abs(int(a.data[k]) - int(b.data[k])) > by;
  return n;
}

TEST(MaterialPaint, DecalChannelsPaintTheirValuesWithTheImagesCoverage) {
  const test::TempDir dir;
  const TriMesh mesh = shapes::plane(10);
  const Parameterization param = test::planar_param(mesh);
  std::vector<SurfacePoint> inside, outside;
  decal_points(mesh, inside, outside);
  ASSERT_FALSE(inside.empty());
  ASSERT_FALSE(outside.empty());
  const Vec3 green = Vec3(20, 200, 40) / 255.0;
  // Height only: height where the decal covers (and nowhere else), base colour untouched.
  const MaterialStrokeFile height = green_decal(dir, R"({"height": 0.9})");
  for (const MaterialValue& v : evaluate_material(mesh, height, inside)) {
    EXPECT_NEAR(v[channel_offset(Channel::Height)], 0.9, 1e-12);
    EXPECT_EQ(Vec3(v[0], v[1], v[2]), Vec3(1, 1, 1));
  }
  for (const MaterialValue& v : evaluate_material(mesh, height, outside)) EXPECT_EQ(v[channel_offset(Channel::Height)], 0.5);
  MaterialStrokeFile empty = height;
  empty.layers[0].strokes.clear();
  const MaterialPaintOptions o = {64, 2};
  const MaterialTextures flat = paint_material(mesh, param, empty, o), raised = paint_material(mesh, param, height, o);
  EXPECT_EQ(raised.base_color.data, flat.base_color.data);
  EXPECT_EQ(raised.roughness.data, flat.roughness.data);
  EXPECT_GT(bytes_apart(raised.height, flat.height, 100), 0);
  EXPECT_GT(bytes_apart(raised.normal, flat.normal, 20), 0);  // the decal's rim slopes
  // The image's colour and a roughness: both, with the same coverage.
  const MaterialStrokeFile both = green_decal(dir, R"({"base_color": "image", "roughness": 0.2})");
  for (const MaterialValue& v : evaluate_material(mesh, both, inside)) {
    EXPECT_LT((Vec3(v[0], v[1], v[2]) - green).norm(), 1e-9);
    EXPECT_NEAR(v[channel_offset(Channel::Roughness)], 0.2, 1e-12);
    EXPECT_EQ(v[channel_offset(Channel::Height)], 0.5);
  }
  for (const MaterialValue& v : evaluate_material(mesh, both, outside)) {
    EXPECT_EQ(Vec3(v[0], v[1], v[2]), Vec3(1, 1, 1));
    EXPECT_EQ(v[channel_offset(Channel::Roughness)], 0.5);
  }
  // No "channels": the version 1 decal's colour (StrokeSignal, the version 1 path) and the same bytes
  // as {"base_color": "image"} written out.
  const MaterialStrokeFile plain = green_decal(dir, ""), image = green_decal(dir, R"({"base_color": "image"})");
  const MaterialTextures a = paint_material(mesh, param, plain, o), b = paint_material(mesh, param, image, o);
  for (const auto& [x, y] : {std::pair{&a.base_color, &b.base_color}, {&a.roughness, &b.roughness},
                             {&a.metallic, &b.metallic}, {&a.height, &b.height}, {&a.normal, &b.normal}})
    EXPECT_EQ(x->data, y->data);
  EXPECT_EQ(a.normal.data, flat.normal.data);
  StrokeFile v1;
  v1.strokes = {plain.layers[0].strokes[0].decal};
  std::vector<SurfacePoint> all = inside;
  all.insert(all.end(), outside.begin(), outside.end());
  const std::vector<Vec3> expected = StrokeSignal(mesh, v1).evaluate(all);
  const std::vector<MaterialValue> got = evaluate_material(mesh, plain, all);
  for (size_t k = 0; k < all.size(); ++k)
    EXPECT_LT((Vec3(got[k][0], got[k][1], got[k][2]) - expected[k]).norm(), 1e-12) << k;
}

/// FNV-1a (64 bits) of \p bytes.
std::uint64_t fnv1a(const std::vector<std::uint8_t>& bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::uint8_t b : bytes) h = (h ^ b) * 1099511628211ull;
  return h;
}

// Decals without "channels" paint the bytes they painted before decals had channels: the hashes were
// taken from the code of d58db5f (the parent of the change); a brush, two decals of an image with
// varying colour and alpha, a multiply layer.
TEST(MaterialPaint, DecalsWithoutChannelsPaintTheBytesOfBefore) {
  const test::TempDir dir;
  ImageRGBA8 img(8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      std::uint8_t* t = img.texel(x, y);
      t[0] = std::uint8_t(x * 30), t[1] = std::uint8_t(y * 30), t[2] = std::uint8_t(x * y * 13);
      t[3] = (x + y) % 3 ? 255 : 128;
    }
  write_png(dir.path / "d.png", img);
  const MaterialStrokeFile file = parse_material_strokes(
      R"({"format": "adaptex.strokes", "version": 2, "height_scale": 0.05, "layers": [
      {"strokes": [{"channels": {"base_color": [0.2, 0.3, 0.9], "roughness": 0.3}, "radius": 0.2,
                    "dabs": [[0.3, 0.3, 0], [0.4, 0.35, 0]]},
                   {"type": "decal", "image": "d.png", "eye": [0.5, 0.5, 2], "target": [0.5, 0.5, 0], "fov": 25,
                    "opacity": 0.8}]},
      {"blend": "multiply", "opacity": 0.7, "strokes": [
        {"type": "decal", "image": "d.png", "eye": [0.6, 0.4, 1.5], "target": [0.5, 0.5, 0], "fov": 30}]}]})",
      "m.json", dir.path);
  const TriMesh mesh = shapes::plane(10);
  const MaterialTextures t = paint_material(mesh, test::planar_param(mesh, 0.9, 0.05), file, {64, 2});
  EXPECT_EQ(fnv1a(t.base_color.data), 10273555214825857542ull);
  EXPECT_EQ(fnv1a(t.roughness.data), 17547118136741545469ull);
  EXPECT_EQ(fnv1a(t.normal.data), 14166859361396507429ull);
}

TEST(MaterialPaint, CliRejectsBadDecalChannelsWithOneLine) {
  test::TempDir tmp;
  write_obj(tmp.path / "p.obj", shapes::plane(4), nullptr);
  write_png(tmp.path / "d.png", ImageRGBA8(4, 4, {20, 200, 40, 255}));
  std::ofstream(tmp.path / "bad.json") << R"({"format": "adaptex.strokes", "version": 2, "layers": [{"strokes": [
      {"type": "decal", "image": "d.png", "eye": [0.5, 0.5, 2], "target": [0.5, 0.5, 0], "channels": {"height": 2}}]}]})";
  for (const std::string& cmd : {"strokes check " + q(tmp.path / "bad.json"),
                                 "paint " + q(tmp.path / "p.obj") + " --strokes " + q(tmp.path / "bad.json") +
                                     " --size 32 -o " + q(tmp.path / "out")}) {
    const auto r = test::run_cli(cmd);
    EXPECT_EQ(r.exit_code, 2) << cmd;
    EXPECT_EQ(r.err, "adaptex: error: " + (tmp.path / "bad.json").string() +
                         ": layer 0: stroke 0: \"channels.height\" must be in [0, 1] (got 2)\n")
        << cmd;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_FALSE(std::filesystem::exists(tmp.path / "out" / "p.glb"));
}

TEST(MaterialPaint, CliPaintsAVersion2FileIntoAPbrMaterial) {
  test::TempDir tmp;
  write_obj(tmp.path / "s.obj", shapes::icosphere(3, 1.0), nullptr);
  const auto gen = test::run_cli("strokes generate " + q(tmp.path / "s.obj") + " --kind material -o " +
                                 q(tmp.path / "m.json"));
  ASSERT_EQ(gen.exit_code, 0) << gen.err;
  const auto r = test::run_cli("paint " + q(tmp.path / "s.obj") + " --strokes " + q(tmp.path / "m.json") +
                               " --size 128 -o " + q(tmp.path / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string mtl = slurp(tmp.path / "out" / "s.mtl");
  for (const char* statement : {"map_Kd s.png", "map_Pr s_roughness.png", "map_Pm s_metallic.png", "norm s_normal.png"})
    EXPECT_NE(mtl.find(statement), std::string::npos) << statement << " in\n" << mtl;
  // The height map is named by a comment only: Blender's OBJ importer reads `bump` as a normal map.
  EXPECT_NE(mtl.find("# height: s_height.png"), std::string::npos) << mtl;
  EXPECT_EQ(mtl.find("bump"), std::string::npos) << mtl;
  for (const char* f : {"s.obj", "s.png", "s_roughness.png", "s_metallic.png", "s_normal.png", "s_height.png", "s.glb"})
    EXPECT_TRUE(std::filesystem::exists(tmp.path / "out" / f)) << f;
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (tmp.path / "out" / "s.glb").string())) << err;
  ASSERT_EQ(model.materials.size(), 1u);
  const tinygltf::Material& m = model.materials[0];
  EXPECT_GE(m.pbrMetallicRoughness.baseColorTexture.index, 0);
  EXPECT_GE(m.pbrMetallicRoughness.metallicRoughnessTexture.index, 0);
  EXPECT_GE(m.normalTexture.index, 0);
  EXPECT_EQ(model.images.size(), 3u);  // no unused image in the .glb
  const auto report = nlohmann::json::parse(slurp(tmp.path / "out" / "report.json"));
  EXPECT_EQ(report["material"]["layers"].size(), 3u);
  EXPECT_EQ(report["input"]["version"].get<int>(), 2);
  // The default adaptation ran on the material's error model and kept the better layout.
  EXPECT_EQ(report["adapt"]["mode"], "density-flow");
  EXPECT_GT(report["adapt"]["report"]["predicted_gain_db"].get<double>(), 0.0);
  EXPECT_TRUE(report["adapt"]["adapted"].get<bool>());
  EXPECT_LT(report["adapt"]["error_adapted"].get<double>(), report["adapt"]["error_fixed"].get<double>());
  const auto thesis = test::run_cli("paint " + q(tmp.path / "s.obj") + " --strokes " + q(tmp.path / "m.json") +
                                    " --size 64 --adapt single -o " + q(tmp.path / "single"));
  EXPECT_EQ(thesis.exit_code, 2);
  EXPECT_NE(thesis.err.find("adapts with density-flow or none"), std::string::npos) << thesis.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.path / "single" / "s.glb"));
  // --layers: every layer alone, as report.json lists them; a version 1 file has none to write.
  const auto lay = test::run_cli("-q paint " + q(tmp.path / "s.obj") + " --strokes " + q(tmp.path / "m.json") +
                                 " --size 64 --adapt none --layers -o " + q(tmp.path / "layers"));
  ASSERT_EQ(lay.exit_code, 0) << lay.err;
  const auto lrep = nlohmann::json::parse(slurp(tmp.path / "layers" / "report.json"));
  const auto& lfiles = lrep["files"]["layers"];
  ASSERT_EQ(lfiles.size(), 3u);
  EXPECT_EQ(lfiles[1]["mask"], "s_layer2_mask.png");  // the generated "Metal" layer is masked
  EXPECT_TRUE(lfiles[0]["mask"].is_null());
  EXPECT_EQ(lfiles[2]["channels"]["height"], "s_layer3_height.png");
  for (const auto& l : lfiles)
    for (const auto& [ch, f] : l["channels"].items())
      EXPECT_EQ(read_image(tmp.path / "layers" / f.get<std::string>()).width, 64) << f;
  EXPECT_EQ(read_image(tmp.path / "layers" / "s_layer2_mask.png").width, 64);
  EXPECT_FALSE(report["files"].contains("layers"));  // only with --layers
  std::ofstream(tmp.path / "v1.json") << R"({"format": "adaptex.strokes", "version": 1, "strokes": []})";
  const auto v1 = test::run_cli("paint " + q(tmp.path / "s.obj") + " --strokes " + q(tmp.path / "v1.json") +
                                " --size 64 --layers -o " + q(tmp.path / "v1_out"));
  EXPECT_EQ(v1.exit_code, 2);
  EXPECT_NE(v1.err.find("v1.json: --layers needs a stroke file of version 2"), std::string::npos) << v1.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.path / "v1_out"));
  // A broken version 2 file: exit 2, one line naming layer and stroke, nothing written.
  std::ofstream(tmp.path / "bad.json") << R"({"format": "adaptex.strokes", "version": 2, "layers": [{"strokes": [
      {"channels": {"rougness": 1}, "radius": 0.1, "dabs": [[0, 0, 1]]}]}]})";
  const auto bad = test::run_cli("paint " + q(tmp.path / "s.obj") + " --strokes " + q(tmp.path / "bad.json") +
                                 " --size 64 -o " + q(tmp.path / "bad_out"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("layer 0: stroke 0: unknown channel \"rougness\""), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.path / "bad_out" / "s.glb"));
}

}  // namespace
}  // namespace adaptex
