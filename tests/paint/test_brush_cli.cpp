// CLI of the brush part: `adaptex strokes check|generate`, `adaptex eval`. Bad stroke files exit 2
// with one line naming the stroke index and field, and leave no output files.
// GCC 12 reports a false -Wrestrict inside std::string concatenation (GCC bug 105329).
#pragma GCC diagnostic ignored "-Wrestrict"
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/material_signal.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/strokes.h"
#include "brush_test_util.h"
#include "test_support.h"

using namespace adaptex;
using adaptex::test::run_cli;
using adaptex::test::TempDir;

namespace {

void write_text(const std::filesystem::path& p, const std::string& s) {
  std::ofstream(p) << s;
}
std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}
std::string q(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

std::string wrap(const std::string& strokes, const std::string& head = R"("format": "adaptex.strokes", "version": 1)") {
  return "{" + head + ", \"strokes\": [" + strokes + "]}";
}

}  // namespace

TEST(BrushCli, BadStrokeFilesExit2WithOneLineAndNoOutput) {
  TempDir tmp;
  const std::string one = R"({"color": [1, 0, 0], "radius": 0.1, "dabs": [[0, 0, 0]]})", ok = one + ", ";
  struct Case {
    std::string text, expect;
  };
  const std::vector<Case> cases = {
      {wrap(one, R"("format": "other", "version": 1)"), "\"format\" must be \"adaptex.strokes\""},
      {wrap(one, R"("format": "adaptex.strokes", "version": 3)"), "\"version\" must be 1"},
      {wrap(ok + R"({"color": [1, 0, 0], "dabs": [[0, 0, 0]]})"), "stroke 1: missing required field \"radius\""},
      {wrap(ok + R"({"color": [1, 0, 0], "radius": 1e999, "dabs": [[0, 0, 0]]})"), "stroke 1: \"radius\" must be finite"},
      {wrap(ok + R"({"color": [1, 0, 0], "radius": "NaN", "dabs": [[0, 0, 0]]})"), "stroke 1: \"radius\" must be a finite number"},
      {wrap(ok + ok + R"({"color": [1, 0, 0], "radius": -0.1, "dabs": [[0, 0, 0]]})"), "stroke 2: \"radius\" must be > 0 (got -0.1)"},
      {wrap(ok + R"({"color": [1, 0, 0], "radius": 1, "hardness": 2, "dabs": [[0, 0, 0]]})"), "stroke 1: \"hardness\" must be in [0, 1] (got 2)"},
      {wrap(ok + R"({"color": [1, 0, 0], "radius": 1, "opacity": -1, "dabs": [[0, 0, 0]]})"), "stroke 1: \"opacity\" must be in [0, 1] (got -1)"},
      {wrap(ok + R"({"color": [1, 0, 0], "radius": 1, "dabs": []})"), "stroke 1: \"dabs\" must not be empty"},
      {wrap(ok + R"({"color": [1, 0, 0], "radius": 1, "dabs": [[0, "x", 0]]})"), "stroke 1: \"dabs[0][1]\" must be a finite number"},
      {wrap(ok + R"({"color": {"r": 1}, "radius": 1, "dabs": [[0, 0, 0]]})"), "stroke 1: \"color\" must be an array of 3"},
  };
  // A valid mesh + texture for eval.
  const TriMesh mesh = shapes::plane(2);
  const Parameterization param = adaptex::test::planar_param(mesh);
  write_obj(tmp.path / "m.obj", mesh, &param);
  write_png(tmp.path / "t.png", ImageRGBA8(8, 8, {255, 255, 255, 255}));
  for (size_t k = 0; k < cases.size(); ++k) {
    const auto file = tmp.path / ("bad" + std::to_string(k) + ".json");
    const auto out = tmp.path / ("out" + std::to_string(k) + ".json");
    write_text(file, cases[k].text);
    for (const std::string& cmd : {"strokes check " + q(file) + " -o " + q(out),
                                   "eval " + q(tmp.path / "m.obj") + " " + q(tmp.path / "t.png") + " " + q(file)}) {
      const auto r = run_cli(cmd);
      EXPECT_EQ(r.exit_code, 2) << cmd << "\n" << r.err;
      EXPECT_NE(r.err.find(cases[k].expect), std::string::npos) << cmd << ": " << r.err;
      EXPECT_NE(r.err.find(file.string()), std::string::npos) << "message names the file: " << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
      EXPECT_TRUE(r.out.empty());
    }
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  // Only the inputs are left in the folder.
  int files = 0;
  for ([[maybe_unused]] auto& e : std::filesystem::directory_iterator(tmp.path)) ++files;
  EXPECT_EQ(files, static_cast<int>(cases.size()) + 2);
}

TEST(BrushCli, CheckNormalizesAndWarnsAboutUnknownFields) {
  TempDir tmp;
  write_text(tmp.path / "s.json", wrap(R"({"color": [1, 0, 0], "radius": 0.1, "size": 3, "dabs": [[0, 0, 0]]})"));
  const auto r = run_cli("strokes check " + q(tmp.path / "s.json") + " -o " + q(tmp.path / "n.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("stroke 0: unknown field \"size\" ignored"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["strokes"], 1);
  EXPECT_EQ(j["dabs"], 1);
  const StrokeFile n = read_strokes(tmp.path / "n.json");
  EXPECT_EQ(n.strokes[0].hardness, 0.5);
  EXPECT_TRUE(n.warnings.empty());
}

TEST(BrushCli, EvalPrintsJsonAndIsReproducible) {
  TempDir tmp;
  const TriMesh mesh = shapes::plane(4);
  const Parameterization param = adaptex::test::planar_param(mesh);
  const StrokeFile file = adaptex::test::plane_strokes();
  Painter painter(mesh, param, {256, 256, 4});
  painter.paint_all(file);
  write_obj(tmp.path / "m.obj", mesh, &param);
  write_png(tmp.path / "t.png", painter.texture());
  write_strokes(tmp.path / "s.json", file);
  const std::string cmd = "eval " + q(tmp.path / "m.obj") + " " + q(tmp.path / "t.png") + " " +
                          q(tmp.path / "s.json") + " --samples 20000 --seed 9";
  const auto a = run_cli(cmd), b = run_cli(cmd);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
  for (const char* key : {"mse", "psnr", "samples", "seed"}) EXPECT_TRUE(ja.contains(key)) << key;
  EXPECT_EQ(ja["samples"], 20000);
  EXPECT_EQ(ja["seed"], 9);
  EXPECT_EQ(ja["mse"], jb["mse"]);
  EXPECT_GT(ja["psnr"].get<double>(), 25.0);
  EXPECT_NEAR(ja["psnr"].get<double>(), 10 * std::log10(1 / ja["mse"].get<double>()), 1e-9);
  // A blank texture scores worse.
  write_png(tmp.path / "blank.png", ImageRGBA8(256, 256, {255, 255, 255, 255}));
  const auto c = run_cli("eval " + q(tmp.path / "m.obj") + " " + q(tmp.path / "blank.png") + " " +
                         q(tmp.path / "s.json") + " --samples 20000 --seed 9");
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_LT(nlohmann::json::parse(c.out)["psnr"].get<double>(), ja["psnr"].get<double>() - 10);
  // Bad inputs: one line, exit 2.
  for (const std::string& bad : {"eval " + q(tmp.path / "nope.obj") + " " + q(tmp.path / "t.png") + " " + q(tmp.path / "s.json"),
                                 "eval " + q(tmp.path / "m.obj") + " " + q(tmp.path / "nope.png") + " " + q(tmp.path / "s.json"),
                                 cmd + " --samples 0"}) {
    const auto r = run_cli(bad);
    EXPECT_EQ(r.exit_code, 2) << bad << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST(BrushCli, GenerateIsReproducibleAndOnTheSurface) {
  TempDir tmp;
  const TriMesh mesh = shapes::icosphere(3, 1.0);
  write_obj(tmp.path / "s.obj", mesh, nullptr);
  auto gen = [&](const std::string& kind, int seed, const std::string& name) {
    const auto r = run_cli("strokes generate " + q(tmp.path / "s.obj") + " --kind " + kind + " --seed " +
                           std::to_string(seed) + " -o " + q(tmp.path / name));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return slurp(tmp.path / name);
  };
  const std::string a = gen("lines", 3, "a.json"), b = gen("lines", 3, "b.json"), c = gen("lines", 4, "c.json");
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  const StrokeFile lines = read_strokes(tmp.path / "a.json");
  EXPECT_EQ(lines.strokes.size(), 60u);
  const double diag = bounding_box(mesh).diagonal();
  // Inscribed radius of the icosphere's flat faces: every surface point has |p| in [rin, 1].
  const double rin = 0.985;
  Vec3 mean = Vec3::Zero();
  long long n = 0;
  for (const Stroke& s : lines.strokes) {
    EXPECT_GE(s.radius, 0.002 * diag * 0.999);
    EXPECT_LE(s.radius, 0.005 * diag * 1.001);
    EXPECT_GE(s.hardness, 0.8);
    EXPECT_GE(s.dabs.size(), 2u);
    for (size_t d = 0; d < s.dabs.size(); ++d) {
      EXPECT_LE(s.dabs[d].norm(), 1 + 1e-9);
      EXPECT_GE(s.dabs[d].norm(), rin);
      if (d) {
        EXPECT_LE((s.dabs[d] - s.dabs[d - 1]).norm(), 0.5 * s.radius + 1e-12);
      }
      mean += s.dabs[d];
      ++n;
    }
  }
  // Concentrated in one region: the dabs' mean is far from the sphere's centre.
  EXPECT_GT((mean / n).norm(), 0.5);
  const StrokeFile blobs = read_strokes((gen("blobs", 1, "d.json"), tmp.path / "d.json"));
  EXPECT_EQ(blobs.strokes.size(), 6u);
  for (const Stroke& s : blobs.strokes) EXPECT_GE(s.radius, 0.04 * diag * 0.999);
  const StrokeFile mixed = read_strokes((gen("mixed", 1, "e.json"), tmp.path / "e.json"));
  EXPECT_EQ(mixed.strokes.size(), 48u);
  EXPECT_EQ(gen("dots", 2, "f.json"), gen("dots", 2, "g.json"));
  const StrokeFile dots = read_strokes(tmp.path / "f.json");
  EXPECT_GE(dots.strokes.size(), 150u);
  EXPECT_LE(dots.strokes.size(), 400u);
  for (const Stroke& s : dots.strokes) EXPECT_LE(s.radius, 0.002 * diag * 1.001);
  const auto summary = run_cli("strokes generate " + q(tmp.path / "s.obj") + " --kind dots -o " + q(tmp.path / "h.json"));
  ASSERT_EQ(summary.exit_code, 0) << summary.err;
  const auto js = nlohmann::json::parse(summary.out);
  EXPECT_EQ(js["strokes"].get<size_t>(), read_strokes(tmp.path / "h.json").strokes.size());
  EXPECT_GT(js["region"]["radius"].get<double>(), 0.0);
  const auto bad = run_cli("strokes generate " + q(tmp.path / "s.obj") + " --kind speckle -o " + q(tmp.path / "x.json"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_NE(bad.err.find("unknown stroke kind \"speckle\" (expected lines, blobs, mixed, dots or material)"), std::string::npos)
      << bad.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.path / "x.json"));
}

TEST(BrushCli, GenerateRepairsAScanAsPaintDoes) {
  // Scans need `paint --repair`; generating their strokes must not fail where painting works.
  TempDir tmp;
  write_obj(tmp.path / "fan.obj", shapes::nonmanifold_fan(), nullptr);
  const auto bad = run_cli("strokes generate " + q(tmp.path / "fan.obj") + " --count 3 -o " + q(tmp.path / "a.json"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_NE(bad.err.find("--repair"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.path / "a.json"));
  const auto ok = run_cli("-q strokes generate " + q(tmp.path / "fan.obj") + " --repair --count 3 -o " +
                          q(tmp.path / "b.json"));
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(read_strokes(tmp.path / "b.json").strokes.size(), 3u);
}

TEST(BrushCli, GenerateMaterialWritesAVersion2FileThatPaintsEveryChannel) {
  TempDir tmp;
  const TriMesh mesh = shapes::icosphere(3, 1.0);
  write_obj(tmp.path / "s.obj", mesh, nullptr);
  auto gen = [&](int seed, const std::string& name) {
    const auto r = run_cli("strokes generate " + q(tmp.path / "s.obj") + " --kind material --seed " +
                           std::to_string(seed) + " -o " + q(tmp.path / name));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out;
  };
  const std::string summary = gen(2, "a.json");
  gen(2, "b.json");
  gen(3, "c.json");
  EXPECT_EQ(slurp(tmp.path / "a.json"), slurp(tmp.path / "b.json"));
  EXPECT_NE(slurp(tmp.path / "a.json"), slurp(tmp.path / "c.json"));
  const auto js = nlohmann::json::parse(summary);
  EXPECT_EQ(js["version"].get<int>(), 2);
  EXPECT_EQ(js["layers"].size(), 3u);
  const MaterialStrokeFile m = read_material_strokes(tmp.path / "a.json");
  ASSERT_EQ(m.layers.size(), 3u);
  int masked = 0, with_pressure = 0;
  unsigned channels = 0;
  for (const MaterialLayer& l : m.layers) {
    masked += l.mask.has_value();
    for (const MaterialStroke& s : l.strokes) {
      channels |= s.channels;
      with_pressure += !s.pressure.empty();
    }
  }
  EXPECT_GE(masked, 1);
  EXPECT_GT(with_pressure, 0);
  const unsigned painted = channel_bit(Channel::BaseColor) | channel_bit(Channel::Roughness) |
                           channel_bit(Channel::Metallic) | channel_bit(Channel::Height);
  EXPECT_EQ(channels & painted, painted);
  // Every channel varies over the surface (each carries detail for the error model).
  std::vector<SurfacePoint> pts;
  for (int f = 0; f < mesh.num_faces(); ++f) pts.push_back({f, 1.0 / 3, 1.0 / 3});
  const std::vector<MaterialValue> v = evaluate_material(mesh, m, pts);
  for (int c : {0, 4, 5, 6}) {
    double lo = 1, hi = 0;
    for (const MaterialValue& x : v) lo = std::min(lo, x[c]), hi = std::max(hi, x[c]);
    EXPECT_GT(hi - lo, 0.1) << "component " << c;
  }
  // `strokes check` reads it and writes it back unchanged.
  const auto chk = run_cli("strokes check " + q(tmp.path / "a.json") + " -o " + q(tmp.path / "n.json"));
  ASSERT_EQ(chk.exit_code, 0) << chk.err;
  EXPECT_EQ(slurp(tmp.path / "a.json"), slurp(tmp.path / "n.json"));
  const auto bad = run_cli("strokes generate " + q(tmp.path / "s.obj") + " --kind material --count 5 -o " +
                           q(tmp.path / "x.json"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(tmp.path / "x.json"));
}
