// Stroke file: strict parsing (every bad case names the stroke index and field), defaults,
// round trip, the contract's falloff.
#include <gtest/gtest.h>

#include <fstream>

#include "adaptex/core/errors.h"
#include "adaptex/paint/strokes.h"
#include "test_support.h"

using namespace adaptex;

namespace {

std::string wrap(const std::string& strokes, const std::string& head = R"("format": "adaptex.strokes", "version": 1)") {
  return "{" + head + ", \"strokes\": [" + strokes + "]}";
}
const std::string kGood = R"({"color": [1, 0, 0], "radius": 0.1, "dabs": [[0, 0, 0]]})";

std::string parse_error(const std::string& text) {
  try {
    parse_strokes(text, "s.json", ".");
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Strokes, ParsesDefaults) {
  const StrokeFile f = parse_strokes(wrap(kGood), "s.json", ".");
  ASSERT_EQ(f.strokes.size(), 1u);
  EXPECT_EQ(f.background, Vec3(1, 1, 1));
  EXPECT_EQ(f.strokes[0].type, Stroke::Type::Brush);
  EXPECT_EQ(f.strokes[0].hardness, 0.5);
  EXPECT_EQ(f.strokes[0].opacity, 1.0);
  EXPECT_EQ(f.strokes[0].radius, 0.1);
  EXPECT_EQ(f.strokes[0].color, Vec3(1, 0, 0));
  EXPECT_TRUE(f.warnings.empty());
  const StrokeFile g = parse_strokes(
      wrap(R"({"type": "brush", "color": [0, 0.5, 1], "radius": 2, "hardness": 0, "opacity": 0.25,
               "dabs": [[1, 2, 3], [4, 5, 6]]})",
           R"("format": "adaptex.strokes", "version": 1, "background": [0, 0.25, 0.5])"),
      "s.json", ".");
  EXPECT_EQ(g.background, Vec3(0, 0.25, 0.5));
  EXPECT_EQ(g.strokes[0].hardness, 0.0);
  EXPECT_EQ(g.strokes[0].opacity, 0.25);
  EXPECT_EQ(g.strokes[0].dabs.size(), 2u);
  EXPECT_EQ(g.strokes[0].dabs[1], Vec3(4, 5, 6));
  EXPECT_EQ(g.num_dabs(), 2);
}

TEST(Strokes, EmptyStrokeListIsValid) {
  EXPECT_TRUE(parse_strokes(wrap(""), "s.json", ".").strokes.empty());
}

TEST(Strokes, UnknownFieldsWarn) {
  const StrokeFile f = parse_strokes(
      wrap(R"({"color": [1, 0, 0], "radius": 0.1, "hardnes": 0.3, "dabs": [[0, 0, 0]]})",
           R"("format": "adaptex.strokes", "version": 1, "author": "x")"),
      "s.json", ".");
  ASSERT_EQ(f.warnings.size(), 2u);
  EXPECT_EQ(f.warnings[0], "s.json: unknown field \"author\" ignored");
  EXPECT_EQ(f.warnings[1], "s.json: stroke 0: unknown field \"hardnes\" ignored");
  EXPECT_EQ(f.strokes[0].hardness, 0.5);
}

struct BadCase {
  std::string name, text, expect;
};

TEST(Strokes, EveryBadCaseNamesIndexAndField) {
  const std::string ok1 = kGood + ", ";
  const std::vector<BadCase> cases = {
      {"format", wrap(kGood, R"("format": "adaptex.brushes", "version": 1)"),
       "s.json: \"format\" must be \"adaptex.strokes\" (got string \"adaptex.brushes\")"},
      {"no format", wrap(kGood, R"("version": 1)"), "s.json: missing required field \"format\""},
      {"version", wrap(kGood, R"("format": "adaptex.strokes", "version": 2)"), "s.json: \"version\" must be 1 (got 2)"},
      {"version type", wrap(kGood, R"("format": "adaptex.strokes", "version": "1")"), "\"version\" must be 1 (got string \"1\")"},
      {"no strokes", R"({"format": "adaptex.strokes", "version": 1})", "s.json: missing required field \"strokes\""},
      {"strokes type", R"({"format": "adaptex.strokes", "version": 1, "strokes": {}})", "\"strokes\" must be an array"},
      {"background", wrap(kGood, R"("format": "adaptex.strokes", "version": 1, "background": [1, 2, 0])"),
       "s.json: \"background\"[1] must be in [0, 1] (got 2)"},
      {"missing radius", wrap(ok1 + R"({"color": [1, 0, 0], "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 1: missing required field \"radius\""},
      {"missing color", wrap(ok1 + R"({"radius": 1, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 1: missing required field \"color\""},
      {"missing dabs", wrap(ok1 + R"({"color": [1, 0, 0], "radius": 1})"),
       "s.json: stroke 1: missing required field \"dabs\""},
      {"negative radius", wrap(ok1 + ok1 + ok1 + R"({"color": [1, 0, 0], "radius": -0.1, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 3: \"radius\" must be > 0 (got -0.1)"},
      {"zero radius", wrap(R"({"color": [1, 0, 0], "radius": 0, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 0: \"radius\" must be > 0 (got 0)"},
      {"inf radius", wrap(R"({"color": [1, 0, 0], "radius": 1e999, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 0: \"radius\" must be finite (got 1e999)"},
      {"NaN string", wrap(R"({"color": [1, 0, 0], "radius": "NaN", "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 0: \"radius\" must be a finite number (got string \"NaN\")"},
      {"inf dab", wrap(R"({"color": [1, 0, 0], "radius": 1, "dabs": [[0, 0, 0], [0, -1e999, 0]]})"),
       "s.json: stroke 0: \"dabs[1][1]\" must be finite (got -1e999)"},
      {"hardness high", wrap(ok1 + R"({"color": [1, 0, 0], "radius": 1, "hardness": 1.5, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 1: \"hardness\" must be in [0, 1] (got 1.5)"},
      {"hardness low", wrap(R"({"color": [1, 0, 0], "radius": 1, "hardness": -0.01, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 0: \"hardness\" must be in [0, 1] (got -0.01)"},
      {"opacity", wrap(R"({"color": [1, 0, 0], "radius": 1, "opacity": 2, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 0: \"opacity\" must be in [0, 1] (got 2)"},
      {"color range", wrap(R"({"color": [1, 0, 1.2], "radius": 1, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 0: \"color\"[2] must be in [0, 1] (got 1.2)"},
      {"color size", wrap(R"({"color": [1, 0], "radius": 1, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 0: \"color\" must be an array of 3 finite numbers (got an array of 2)"},
      {"color type", wrap(R"({"color": "red", "radius": 1, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 0: \"color\" must be an array of 3 finite numbers (got string \"red\")"},
      {"empty dabs", wrap(ok1 + R"({"color": [1, 0, 0], "radius": 1, "dabs": []})"),
       "s.json: stroke 1: \"dabs\" must not be empty"},
      {"dabs type", wrap(R"({"color": [1, 0, 0], "radius": 1, "dabs": 3})"),
       "s.json: stroke 0: \"dabs\" must be an array of [x, y, z] points (got 3)"},
      {"dab size", wrap(R"({"color": [1, 0, 0], "radius": 1, "dabs": [[0, 0, 0], [1, 2]]})"),
       "s.json: stroke 0: \"dabs[1]\" must be an array of 3 finite numbers (got an array of 2)"},
      {"dab element type", wrap(R"({"color": [1, 0, 0], "radius": 1, "dabs": [[0, null, 0]]})"),
       "s.json: stroke 0: \"dabs[0][1]\" must be a finite number (got null)"},
      {"radius type", wrap(R"({"color": [1, 0, 0], "radius": true, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 0: \"radius\" must be a finite number (got boolean)"},
      {"stroke type", wrap(ok1 + "[1, 2]"), "s.json: stroke 1: must be a JSON object (got array)"},
      {"unknown type", wrap(R"({"type": "spray", "color": [1, 0, 0], "radius": 1, "dabs": [[0, 0, 0]]})"),
       "s.json: stroke 0: \"type\" must be \"brush\" or \"decal\" (got \"spray\")"},
      {"decal no image", wrap(R"({"type": "decal", "eye": [0, 0, 1], "target": [0, 0, 0]})"),
       "s.json: stroke 0: missing required field \"image\""},
      {"decal missing png", wrap(R"({"type": "decal", "image": "nope.png", "eye": [0, 0, 1], "target": [0, 0, 0]})"),
       "s.json: stroke 0: \"image\": cannot read"},
      {"top level", "[1, 2]", "s.json: the top level must be a JSON object (got array)"},
  };
  for (const BadCase& c : cases) {
    const std::string msg = parse_error(c.text);
    EXPECT_NE(msg.find(c.expect), std::string::npos) << c.name << ": got '" << msg << "'";
    EXPECT_EQ(msg.find('\n'), std::string::npos) << c.name;
  }
}

TEST(Strokes, NotJsonIsIoError) {
  EXPECT_THROW(parse_strokes("{\"format\": NaN}", "s.json", "."), IoError);
  EXPECT_THROW(read_strokes("/nonexistent/dir/s.json"), IoError);
}

TEST(Strokes, WriteReadRoundTrip) {
  StrokeFile f;
  f.background = Vec3(0.1, 0.2, 0.30000000000000004);
  for (int s = 0; s < 3; ++s) {
    Stroke st;
    st.color = Vec3(0.85, 0.1 * s, 1.0 / 3);
    st.radius = 0.004 + s * 1e-17;
    st.hardness = 0.8;
    st.opacity = 0.7;
    for (int d = 0; d < 11; ++d) st.dabs.push_back(Vec3(0.012 + d / 7.0, -0.153 * d, 1e-300 * d));
    f.strokes.push_back(st);
  }
  adaptex::test::TempDir tmp;
  write_strokes(tmp.path / "a.json", f);
  const StrokeFile g = read_strokes(tmp.path / "a.json");
  ASSERT_EQ(g.strokes.size(), f.strokes.size());
  EXPECT_EQ(g.background, f.background);
  for (size_t s = 0; s < f.strokes.size(); ++s) {
    EXPECT_EQ(g.strokes[s].color, f.strokes[s].color);
    EXPECT_EQ(g.strokes[s].radius, f.strokes[s].radius);
    EXPECT_EQ(g.strokes[s].hardness, f.strokes[s].hardness);
    EXPECT_EQ(g.strokes[s].opacity, f.strokes[s].opacity);
    EXPECT_EQ(g.strokes[s].dabs, f.strokes[s].dabs);
  }
  // Writing again gives the same bytes.
  write_strokes(tmp.path / "b.json", g);
  std::ifstream a(tmp.path / "a.json"), b(tmp.path / "b.json");
  std::string sa((std::istreambuf_iterator<char>(a)), {}), sb((std::istreambuf_iterator<char>(b)), {});
  EXPECT_EQ(sa, sb);
}

TEST(Strokes, FalloffIsTheContract) {
  EXPECT_EQ(brush_falloff(0.0, 0.5), 1.0);
  EXPECT_EQ(brush_falloff(0.5, 0.5), 1.0);
  EXPECT_EQ(brush_falloff(1.0, 0.5), 0.0);
  EXPECT_EQ(brush_falloff(2.0, 0.5), 0.0);
  EXPECT_NEAR(brush_falloff(0.75, 0.5), 0.5, 1e-15);  // s = 0.5: 1 - (0.75 - 0.25)
  EXPECT_NEAR(brush_falloff(0.1, 0.0), 1 - (3 * 0.01 - 2 * 0.001), 1e-15);
  EXPECT_EQ(brush_falloff(0.999, 1.0), 1.0);  // hard brush: full strength up to the radius
  EXPECT_EQ(brush_falloff(1.0, 1.0), 1.0);    // t <= h wins at t = h = 1
  for (double t = 0; t < 1; t += 0.01) EXPECT_GE(brush_falloff(t, 0.3), brush_falloff(t + 0.01, 0.3));
}
