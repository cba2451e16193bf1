// The stroke file version 2 (docs/strokes.md, "Version 2"): reading, writing, and the layered
// material it defines at surface points (layers, blend modes, masks, erasers, pressure).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <fstream>
#include <random>
#include <sstream>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "adaptex/paint/material_signal.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/signal.h"
#include "brush_test_util.h"
#include "test_support.h"

namespace adaptex {
namespace {

const char* kExample = R"({
  "format": "adaptex.strokes", "version": 2,
  "background": {"base_color": [0.9, 0.9, 0.8], "roughness": 0.6},
  "height_scale": 0.002,
  "layers": [
    {"name": "Paint", "strokes": [
      {"channels": {"base_color": [0.8, 0.1, 0.1]}, "radius": 0.1, "hardness": 0.5,
       "dabs": [[0.3, 0.3, 0], [0.35, 0.32, 0]]}]},
    {"name": "Rust", "visible": true, "opacity": 0.8, "blend": "multiply",
     "mask": {"value": 0, "strokes": [
       {"value": 1, "radius": 0.2, "hardness": 0.3, "dabs": [[0.5, 0.5, 0, 0.7]]},
       {"type": "erase", "radius": 0.05, "hardness": 1, "dabs": [[0.55, 0.5, 0]]}]},
     "strokes": [
       {"type": "fill", "channels": {"base_color": [0.55, 0.25, 0.1], "roughness": 0.9}},
       {"type": "brush", "channels": {"metallic": 1, "height": 0.4}, "radius": 0.04, "hardness": 0.8, "opacity": 1,
        "pressure": {"radius": [[0, 0.25], [1, 1]], "opacity": [[0, 0], [0.3, 1], [1, 1]]},
        "dabs": [[0.5, 0.45, 0, 0.35], [0.52, 0.47, 0, 0.8]]},
       {"type": "erase", "channels": ["height"], "radius": 0.03, "hardness": 1, "dabs": [[0.5, 0.45, 0]]}]}
  ]
})";

MaterialStrokeFile parse(const std::string& text) { return parse_material_strokes(text, "m.json", "."); }

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

std::string validation_error_of(const MaterialStroke& s) {
  try {
    validate_material_stroke(s, false, "d");
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

std::string v2_with_stroke(const std::string& stroke) {
  return R"({"format": "adaptex.strokes", "version": 2, "layers": [{"strokes": [{"type": "fill", "channels": {"alpha": 1}}, )" +
         stroke + "]}]}";
}

TEST(MaterialStrokes, ReadsEveryFieldOfTheExample) {
  const MaterialStrokeFile f = parse(kExample);
  EXPECT_EQ(f.source_version, 2);
  EXPECT_DOUBLE_EQ(f.background[0], 0.9);
  EXPECT_DOUBLE_EQ(f.background[4], 0.6);   // roughness
  EXPECT_DOUBLE_EQ(f.background[3], 1.0);   // alpha: default
  EXPECT_DOUBLE_EQ(f.background[6], 0.5);   // height: default
  EXPECT_DOUBLE_EQ(f.height_scale, 0.002);
  ASSERT_EQ(f.layers.size(), 2u);
  const MaterialLayer& rust = f.layers[1];
  EXPECT_EQ(rust.name, "Rust");
  EXPECT_EQ(rust.blend, BlendMode::Multiply);
  EXPECT_DOUBLE_EQ(rust.opacity, 0.8);
  ASSERT_TRUE(rust.mask.has_value());
  EXPECT_DOUBLE_EQ(rust.mask->value, 0);
  ASSERT_EQ(rust.mask->strokes.size(), 2u);
  EXPECT_EQ(rust.mask->strokes[1].type, MaterialStroke::Type::Erase);
  ASSERT_EQ(rust.strokes.size(), 3u);
  EXPECT_EQ(rust.strokes[0].type, MaterialStroke::Type::Fill);
  EXPECT_EQ(rust.strokes[0].channels, channel_bit(Channel::BaseColor) | channel_bit(Channel::Roughness));
  const MaterialStroke& brush = rust.strokes[1];
  EXPECT_EQ(brush.channels, channel_bit(Channel::Metallic) | channel_bit(Channel::Height));
  ASSERT_EQ(brush.pressure.size(), 2u);
  EXPECT_DOUBLE_EQ(brush.pressure[0], 0.35);
  EXPECT_DOUBLE_EQ(brush.radius_curve(0.5), 0.625);
  EXPECT_DOUBLE_EQ(brush.opacity_curve(0.15), 0.5);
  EXPECT_EQ(rust.strokes[2].type, MaterialStroke::Type::Erase);
  EXPECT_EQ(rust.strokes[2].channels, channel_bit(Channel::Height));
  EXPECT_EQ(f.num_dabs(), 2 + 2 + 2 + 1);
}

TEST(MaterialStrokes, WriteThenReadIsExactAndStable) {
  const test::TempDir tmp;
  const auto& dir = tmp.path;
  const MaterialStrokeFile f = parse(kExample);
  write_material_strokes(dir / "a.json", f);
  const MaterialStrokeFile g = read_material_strokes(dir / "a.json");
  write_material_strokes(dir / "b.json", g);
  auto slurp = [](const std::filesystem::path& p) {
    std::ifstream is(p);
    std::stringstream ss;
    ss << is.rdbuf();
    return ss.str();
  };
  EXPECT_EQ(slurp(dir / "a.json"), slurp(dir / "b.json"));
  const TriMesh mesh = shapes::plane(8);
  std::vector<SurfacePoint> pts;
  for (int face = 0; face < mesh.num_faces(); ++face) pts.push_back({face, 0.2, 0.3});
  const auto a = evaluate_material(mesh, f, pts), b = evaluate_material(mesh, g, pts);
  for (size_t k = 0; k < pts.size(); ++k)
    for (int c = 0; c < kMaterialComponents; ++c) ASSERT_EQ(a[k][c], b[k][c]) << k << " " << c;
}

TEST(MaterialStrokes, Version1FileIsOneLayerWithTheSameColour) {
  StrokeFile v1 = test::plane_strokes();
  v1.background = Vec3(0.7, 0.8, 0.9);
  const MaterialStrokeFile m = material_from_v1(v1);
  ASSERT_EQ(m.layers.size(), 1u);
  EXPECT_EQ(m.source_version, 1);
  const TriMesh mesh = shapes::plane(16);
  std::vector<SurfacePoint> pts;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 0.5);
  for (int k = 0; k < 4000; ++k) pts.push_back({static_cast<int>(rng() % mesh.num_faces()), u(rng), u(rng)});
  const std::vector<Vec3> expected = StrokeSignal(mesh, v1).evaluate(pts);
  const std::vector<MaterialValue> got = evaluate_material(mesh, m, pts);
  double worst = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[k][c] - expected[k][c]));
    EXPECT_EQ(got[k][4], 0.5);  // roughness untouched
  }
  EXPECT_LT(worst, 1e-12);
  // The version 1 text reads through the same entry point.
  const test::TempDir tmp;
  write_strokes(tmp.path / "v1.json", v1);
  EXPECT_EQ(read_material_strokes(tmp.path / "v1.json").layers[0].strokes.size(), v1.strokes.size());
  // read_any_strokes keeps a version 1 file as read_strokes gives it.
  const AnyStrokeFile any = read_any_strokes(tmp.path / "v1.json");
  ASSERT_TRUE(std::holds_alternative<StrokeFile>(any));
  EXPECT_EQ(std::get<StrokeFile>(any).num_dabs(), v1.num_dabs());
}

/// One fill layer (roughness b) over a background roughness a, in blend mode \p mode.
double blended_roughness(BlendMode mode, double a, double b, double opacity = 1) {
  MaterialStrokeFile f;
  f.background[4] = a;
  MaterialLayer layer;
  layer.blend = mode;
  layer.opacity = opacity;
  MaterialStroke fill;
  fill.type = MaterialStroke::Type::Fill;
  fill.channels = channel_bit(Channel::Roughness);
  fill.value[4] = b;
  layer.strokes.push_back(fill);
  f.layers.push_back(layer);
  return evaluate_material(shapes::plane(1), f, {SurfacePoint{0, 0.3, 0.3}})[0][4];
}

TEST(MaterialStrokes, BlendModesFollowTheirFormulas) {
  EXPECT_NEAR(blended_roughness(BlendMode::Normal, 0.3, 0.8), 0.8, 1e-15);
  EXPECT_NEAR(blended_roughness(BlendMode::Multiply, 0.3, 0.8), 0.24, 1e-15);
  EXPECT_NEAR(blended_roughness(BlendMode::Screen, 0.3, 0.8), 0.86, 1e-15);
  EXPECT_NEAR(blended_roughness(BlendMode::Overlay, 0.3, 0.8), 0.48, 1e-15);
  EXPECT_NEAR(blended_roughness(BlendMode::Overlay, 0.7, 0.8), 0.88, 1e-15);
  EXPECT_NEAR(blended_roughness(BlendMode::Add, 0.3, 0.8), 1.0, 1e-15);
  EXPECT_NEAR(blended_roughness(BlendMode::Add, 0.3, 0.2), 0.5, 1e-15);
  EXPECT_NEAR(blended_roughness(BlendMode::Subtract, 0.3, 0.8), 0.0, 1e-15);
  EXPECT_NEAR(blended_roughness(BlendMode::Subtract, 0.7, 0.2), 0.5, 1e-15);
  // Layer opacity mixes the blend with the backdrop.
  EXPECT_NEAR(blended_roughness(BlendMode::Multiply, 0.3, 0.8, 0.5), 0.27, 1e-15);
}

TEST(MaterialStrokes, EraserRevealsTheLayerBelowAndMaskLimitsALayer) {
  MaterialStrokeFile f = parse(R"({"format": "adaptex.strokes", "version": 2, "layers": [
    {"strokes": [{"type": "fill", "channels": {"base_color": [1, 0, 0]}}]},
    {"strokes": [{"type": "fill", "channels": {"base_color": [0, 0, 1]}},
                 {"type": "erase", "radius": 0.1, "hardness": 1, "dabs": [[0.25, 0.25, 0]]}]},
    {"mask": {"value": 0, "strokes": [{"value": 1, "radius": 0.1, "hardness": 1, "dabs": [[0.75, 0.75, 0]]}]},
     "strokes": [{"type": "fill", "channels": {"metallic": 1}}]}]})");
  const MaterialValue at_erase = evaluate_material_reference(f, Vec3(0.25, 0.25, 0));
  const MaterialValue far = evaluate_material_reference(f, Vec3(0.5, 0.25, 0));
  const MaterialValue in_mask = evaluate_material_reference(f, Vec3(0.75, 0.75, 0));
  EXPECT_EQ(at_erase[0], 1);  // red shows through the erased blue
  EXPECT_EQ(at_erase[2], 0);
  EXPECT_EQ(far[2], 1);       // blue elsewhere
  EXPECT_EQ(far[5], 0);       // metallic masked off
  EXPECT_EQ(in_mask[5], 1);   // metallic where the mask was painted
  f.layers[1].visible = false;
  EXPECT_EQ(evaluate_material_reference(f, Vec3(0.5, 0.25, 0))[0], 1);  // a hidden layer adds nothing
}

TEST(MaterialStrokes, PressureScalesRadiusAndOpacity) {
  MaterialStroke s;
  s.channels = channel_bit(Channel::Roughness);
  s.radius = 0.1;
  s.hardness = 1;  // full strength inside the radius: coverage is opacity or 0
  s.dabs = {Vec3(0, 0, 0)};
  s.radius_curve.points = {Vec2(0, 0.5), Vec2(1, 1)};
  s.opacity_curve.points = {Vec2(0, 0), Vec2(1, 1)};
  s.pressure = {1.0};
  EXPECT_DOUBLE_EQ(material_stroke_coverage(s, Vec3(0.075, 0, 0)), 1.0);
  s.pressure = {0.0};  // radius halved, opacity 0
  EXPECT_DOUBLE_EQ(material_stroke_coverage(s, Vec3(0.01, 0, 0)), 0.0);
  s.pressure = {0.5};  // radius 0.075, opacity 0.5
  EXPECT_DOUBLE_EQ(material_stroke_coverage(s, Vec3(0.07, 0, 0)), 0.5);
  EXPECT_DOUBLE_EQ(material_stroke_coverage(s, Vec3(0.08, 0, 0)), 0.0);
}

TEST(MaterialStrokes, FastEvaluationEqualsTheReference) {
  const MaterialStrokeFile f = parse(kExample);
  const TriMesh mesh = shapes::plane(24);
  std::vector<SurfacePoint> pts;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 0.5);
  for (int k = 0; k < 20000; ++k) pts.push_back({static_cast<int>(rng() % mesh.num_faces()), u(rng), u(rng)});
  const std::vector<MaterialValue> got = evaluate_material(mesh, f, pts);
  double worst = 0;
  int painted_height = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    const auto& fc = mesh.faces[pts[k].face];
    const Vec3 p = pts[k].b0 * mesh.positions[fc[0]] + pts[k].b1 * mesh.positions[fc[1]] +
                   (1 - pts[k].b0 - pts[k].b1) * mesh.positions[fc[2]];
    const MaterialValue ref = evaluate_material_reference(f, p);
    for (int c = 0; c < kMaterialComponents; ++c) worst = std::max(worst, std::abs(got[k][c] - ref[c]));
    painted_height += std::abs(got[k][6] - 0.5) > 0.01;
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_GT(painted_height, 0);  // the masked, pressure-driven brush (height, multiplied) reaches some points
}

TEST(MaterialStrokes, ErrorsNameTheLayerStrokeAndField) {
  EXPECT_EQ(error_of(v2_with_stroke(R"({"channels": {"rougness": 0.5}, "radius": 0.1, "dabs": [[0, 0, 0]]})")),
            "m.json: layer 0: stroke 1: unknown channel \"rougness\"");
  EXPECT_EQ(error_of(v2_with_stroke(R"({"channels": {"roughness": 1.5}, "radius": 0.1, "dabs": [[0, 0, 0]]})")),
            "m.json: layer 0: stroke 1: \"channels.roughness\" must be in [0, 1] (got 1.5)");
  EXPECT_EQ(error_of(v2_with_stroke(R"({"channels": {"roughness": 0.5}, "radius": 1e999, "dabs": [[0, 0, 0]]})")),
            "m.json: layer 0: stroke 1: \"radius\" must be finite (got 1e999)");
  EXPECT_EQ(error_of(v2_with_stroke(R"({"channels": {"roughness": 0.5}, "radius": 0.1, "dabs": [[0, 0, 0, 1, 2]]})")),
            "m.json: layer 0: stroke 1: \"dabs[0]\" must be an array of 3 or 4 finite numbers (got an array of 5)");
  EXPECT_EQ(error_of(v2_with_stroke(R"({"channels": {"roughness": 0.5}, "radius": 0.1, "dabs": [[0, 0, 0, 1], [0, 0, 0]]})")),
            "m.json: layer 0: stroke 1: \"dabs[1]\": every dab must have a pressure, or none");
  EXPECT_EQ(error_of(v2_with_stroke(R"({"channels": {"roughness": 0.5}, "radius": 0.1, "dabs": [[0, 0, 0]],
                                       "pressure": {"radius": [[0, 1], [0.9, 1]]}})")),
            "m.json: layer 0: stroke 1: \"pressure.radius\" must start at pressure 0 and end at pressure 1");
  EXPECT_EQ(error_of(v2_with_stroke(R"({"channels": {}, "radius": 0.1, "dabs": [[0, 0, 0]]})")),
            "m.json: layer 0: stroke 1: \"channels\" must be an object with at least one of \"base_color\", \"alpha\", "
            "\"roughness\", \"metallic\", \"height\" (got an empty object)");
  EXPECT_EQ(error_of(R"({"format": "adaptex.strokes", "version": 2, "layers": [{"blend": "dodge", "strokes": []}]})"),
            "m.json: layer 0: \"blend\" must be one of \"normal\", \"multiply\", \"screen\", \"overlay\", \"add\", "
            "\"subtract\" (got string \"dodge\")");
  EXPECT_EQ(error_of(R"({"format": "adaptex.strokes", "version": 2, "layers": [{"mask": {"strokes": [
              {"value": 1, "radius": 1e999, "dabs": [[0, 0, 0]]}]}, "strokes": []}]})"),
            "m.json: layer 0: mask: stroke 0: \"radius\" must be finite (got 1e999)");
  EXPECT_EQ(error_of(R"({"format": "adaptex.strokes", "version": 3, "strokes": []})"),
            "m.json: \"version\" must be 1 or 2 (got 3)");
  EXPECT_EQ(error_of(R"({"format": "adaptex.strokes", "version": 2, "layers": [{"name": "x"}]})"),
            "m.json: layer 0: missing required field \"strokes\"");
}

/// A version 2 file in \p dir whose one layer holds \p strokes; decals there use the 4 x 4 "d.png".
std::string decal_file(const test::TempDir& dir, const std::string& strokes) {
  write_png(dir.path / "d.png", ImageRGBA8(4, 4, {20, 200, 40, 255}));
  return R"({"format": "adaptex.strokes", "version": 2, "layers": [{"strokes": [)" + strokes + "]}]}";
}

std::string decal_with(const std::string& channels) {
  return R"({"type": "decal", "image": "d.png", "eye": [0.5, 0.5, 2], "target": [0.5, 0.5, 0])" +
         (channels.empty() ? std::string() : ", \"channels\": " + channels) + "}";
}

TEST(MaterialStrokes, DecalChannelsReadWriteAndReadBackTheSame) {
  const test::TempDir dir;
  const std::string text = decal_file(dir, decal_with("") + ", " + decal_with(R"({"base_color": "image", "roughness": 0.2})") +
                                               ", " + decal_with(R"({"height": 0.9})") + ", " +
                                               decal_with(R"({"base_color": [0.1, 0.2, 0.3], "metallic": 1})"));
  const MaterialStrokeFile f = parse_material_strokes(text, "m.json", dir.path);
  ASSERT_EQ(f.layers[0].strokes.size(), 4u);
  const auto& s = f.layers[0].strokes;
  for (const MaterialStroke& d : s) EXPECT_EQ(d.type, MaterialStroke::Type::Decal);
  EXPECT_EQ(s[0].channels, channel_bit(Channel::BaseColor));  // missing: {"base_color": "image"}
  EXPECT_TRUE(s[0].image_color);
  EXPECT_EQ(s[1].channels, channel_bit(Channel::BaseColor) | channel_bit(Channel::Roughness));
  EXPECT_TRUE(s[1].image_color);
  EXPECT_EQ(s[1].value[channel_offset(Channel::Roughness)], 0.2);
  EXPECT_EQ(s[2].channels, channel_bit(Channel::Height));
  EXPECT_EQ(s[2].value[channel_offset(Channel::Height)], 0.9);
  EXPECT_EQ(s[3].channels, channel_bit(Channel::BaseColor) | channel_bit(Channel::Metallic));
  EXPECT_FALSE(s[3].image_color);
  EXPECT_EQ(s[3].value[2], 0.3);
  for (size_t k = 0; k < s.size(); ++k) EXPECT_NO_THROW(validate_material_stroke(s[k], false, "stroke"));
  // Written: the default is left out, the others as read; read back and written again: the same text.
  const std::string written = material_strokes_json(f);
  const MaterialStrokeFile g = parse_material_strokes(written, "w.json", dir.path);
  EXPECT_EQ(material_strokes_json(g), written);
  for (size_t k = 0; k < s.size(); ++k) {
    EXPECT_EQ(g.layers[0].strokes[k].channels, s[k].channels) << k;
    EXPECT_EQ(g.layers[0].strokes[k].image_color, s[k].image_color) << k;
    EXPECT_EQ(g.layers[0].strokes[k].value, s[k].value) << k;
  }
  EXPECT_EQ(written.find("\"channels\": {\"base_color\": \"image\"}"), std::string::npos) << written;
  EXPECT_NE(written.find("\"channels\": {\"base_color\": \"image\", \"roughness\": 0.2}"), std::string::npos) << written;
  EXPECT_NE(written.find("\"channels\": {\"height\": 0.9}"), std::string::npos) << written;
  EXPECT_TRUE(parse_material_strokes(written, "w.json", dir.path).warnings.empty());  // "channels" is known
  // A decal built in code checks its channels as the parser does.
  MaterialStroke none = s[0];
  none.channels = 0;
  EXPECT_NE(validation_error_of(none).find("\"channels\" must name at least one"), std::string::npos);
  MaterialStroke high = s[2];
  high.value[channel_offset(Channel::Height)] = 1.5;
  EXPECT_EQ(validation_error_of(high), "d: \"channels.height\" must be in [0, 1] (got 1.5)");
}

TEST(MaterialStrokes, BadDecalChannelsAreOneLineErrors) {
  const test::TempDir dir;
  const auto error = [&](const std::string& channels) {
    try {
      parse_material_strokes(decal_file(dir, decal_with(channels)), "m.json", dir.path);
    } catch (const InvalidInputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(error(R"({"rougness": 0.5})"), "m.json: layer 0: stroke 0: unknown channel \"rougness\"");
  EXPECT_EQ(error(R"({"height": 1.5})"), "m.json: layer 0: stroke 0: \"channels.height\" must be in [0, 1] (got 1.5)");
  EXPECT_EQ(error(R"({"base_color": [0, 2, 0]})"),
            "m.json: layer 0: stroke 0: \"channels.base_color\"[1] must be in [0, 1] (got 2)");
  EXPECT_EQ(error("{}"), "m.json: layer 0: stroke 0: \"channels\" must be an object with at least one of \"base_color\", "
                         "\"alpha\", \"roughness\", \"metallic\", \"height\" (got an empty object)");
  EXPECT_EQ(error(R"(["height"])"), "m.json: layer 0: stroke 0: \"channels\" must be an object with at least one of "
                                    "\"base_color\", \"alpha\", \"roughness\", \"metallic\", \"height\" (got array)");
  EXPECT_EQ(error(R"({"base_color": "picture"})"),
            "m.json: layer 0: stroke 0: \"channels.base_color\" must be \"image\" or an array of 3 numbers in [0, 1] "
            "(got string \"picture\")");
  // "image" is a decal's only: a brush's base colour is an array.
  EXPECT_EQ(error_of(v2_with_stroke(R"({"channels": {"base_color": "image"}, "radius": 0.1, "dabs": [[0, 0, 0]]})")),
            "m.json: layer 0: stroke 1: \"channels.base_color\" must be an array of 3 finite numbers (got string "
            "\"image\")");
}

}  // namespace
}  // namespace adaptex

namespace adaptex {
namespace {

std::string validation_error(const MaterialStroke& s, bool in_mask) {
  try {
    validate_material_stroke(s, in_mask, "painted");
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

MaterialStroke valid_brush() {
  MaterialStroke s;
  s.channels = channel_bit(Channel::Roughness);
  s.value[channel_offset(Channel::Roughness)] = 0.3;
  s.dabs = {Vec3(0, 0, 0), Vec3(0.1, 0, 0)};
  return s;
}

TEST(MaterialStrokeValidation, AcceptsValidStrokesAndNamesTheBrokenField) {
  EXPECT_EQ(validation_error(valid_brush(), false), "");
  MaterialStroke s = valid_brush();
  s.value[channel_offset(Channel::Roughness)] = 1.5;
  EXPECT_EQ(validation_error(s, false), "painted: \"channels.roughness\" must be in [0, 1] (got 1.5)");
  s = valid_brush();
  s.channels = 0;
  EXPECT_NE(validation_error(s, false).find("\"channels\" must name at least one"), std::string::npos);
  s = valid_brush();
  s.pressure = {0.5};
  EXPECT_EQ(validation_error(s, false),
            "painted: \"dabs\": every dab must have a pressure, or none (1 pressures for 2 dabs)");
  s.pressure = {0.5, 1.2};
  EXPECT_EQ(validation_error(s, false), "painted: \"dabs[1][3]\" must be in [0, 1] (got 1.2)");
  s = valid_brush();
  s.dabs[1].x() = std::nan("");
  EXPECT_EQ(validation_error(s, false), "painted: \"dabs[1][0]\" must be finite (got nan)");
  s = valid_brush();
  s.radius_curve.points = {Vec2(0, 0.2), Vec2(0.9, 1)};
  EXPECT_EQ(validation_error(s, false), "painted: \"pressure.radius\" must start at pressure 0 and end at pressure 1");
  s.radius_curve.points = {Vec2(0, 0.2), Vec2(0, 0.5), Vec2(1, 1)};
  EXPECT_EQ(validation_error(s, false), "painted: \"pressure.radius\" pressures must increase (point 1)");
  s = valid_brush();
  s.radius = -1;
  EXPECT_EQ(validation_error(s, false), "painted: \"radius\" must be > 0 (got -1)");
  s.radius = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validation_error(s, false), "painted: \"radius\" must be finite (got inf)");
  // A mask's stroke paints its value (the channels are unused) and holds no decal.
  s = valid_brush();
  s.channels = 0;
  s.mask_value = 0.25;
  EXPECT_EQ(validation_error(s, true), "");
  s.mask_value = -0.5;
  EXPECT_EQ(validation_error(s, true), "painted: \"value\" must be in [0, 1] (got -0.5)");
  s.type = MaterialStroke::Type::Fill;  // a fill needs no dabs
  s.mask_value = 0;
  s.dabs.clear();
  EXPECT_EQ(validation_error(s, true), "");
  s.type = MaterialStroke::Type::Decal;
  EXPECT_NE(validation_error(s, true).find("in a mask"), std::string::npos);
}

TEST(MaterialStrokeValidation, LayerMessagesNameTheMaskAndStroke) {
  MaterialLayer layer;
  layer.strokes = {valid_brush()};
  EXPECT_NO_THROW(validate_material_layer(layer, "layer 0"));
  layer.mask = LayerMask{0.5, {valid_brush()}};
  layer.mask->strokes[0].opacity = 2;
  try {
    validate_material_layer(layer, "layer 0");
    ADD_FAILURE() << "a mask stroke of opacity 2 passed";
  } catch (const InvalidInputError& e) {
    EXPECT_STREQ(e.what(), "layer 0: mask: stroke 0: \"opacity\" must be in [0, 1] (got 2)");
  }
  layer.mask->strokes[0].opacity = 1;
  layer.opacity = -0.1;
  EXPECT_THROW(validate_material_layer(layer, "layer 0"), InvalidInputError);
}

// Every valid file's strokes pass the validator (the parser and the validator agree).
TEST(MaterialStrokeValidation, ParsedStrokesPass) {
  const MaterialStrokeFile f = parse(kExample);
  for (size_t k = 0; k < f.layers.size(); ++k) EXPECT_NO_THROW(validate_material_layer(f.layers[k], "layer"));
}

}  // namespace
}  // namespace adaptex
