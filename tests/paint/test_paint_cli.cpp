// `adaptex paint` and `adaptex demo` end to end: a small mesh file + generated strokes (+ one decal)
// produce OBJ/MTL/PNG/GLB/report.json; bad inputs exit 2 with one line and leave no files behind.
// Optional: Blender (Debian `blender`) imports the .glb headless.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/strokes.h"
#include "test_support.h"

using namespace adaptex;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

int count_lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  if (!s.empty() && s.back() != '\n') ++n;
  return n;
}

/// Shell-quoted path (built with append: GCC 12 warns falsely on "'" + s + "'").
std::string q(const fs::path& p) {
  std::string s(1, '\'');
  s.append(p.string());
  s.push_back('\'');
  return s;
}

/// A sphere mesh file and a stroke file with generated blobs and one decal (image next to it).
struct Inputs {
  test::TempDir tmp;
  fs::path mesh = tmp.path / "ball.obj";
  fs::path strokes = tmp.path / "s.json";
  TriMesh m = shapes::sphere(24, 12, 1.0);
  StrokeFile s;

  Inputs() {
    write_obj(mesh, m, nullptr);
    GenerateOptions go;
    go.kind = StrokeKind::Blobs;
    go.seed = 3;
    go.count = 3;
    s = generate_strokes(m, go);
    ImageRGBA8 img(8, 8, {20, 200, 40, 255});
    write_png(tmp.path / "decal.png", img);
    Stroke d;
    d.type = Stroke::Type::Decal;
    d.image_path = "decal.png";
    d.image = img;
    d.camera.eye = Vec3(0, 0, 4);
    d.camera.target = Vec3(0, 0, 0);
    d.camera.fov_y_degrees = 20;
    d.camera.aspect = 1.0;
    d.opacity = 0.9;
    s.strokes.push_back(d);
    write_strokes(strokes, s);
  }
};

/// Expects a failed run: exit 2, exactly one line on stderr containing \p needle, and \p outdir
/// absent (or, if it existed, unchanged: only \p keep inside).
void expect_clean_failure(const test::CliResult& r, const std::string& needle, const fs::path& outdir,
                          const std::string& keep = "") {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  if (keep.empty()) {
    EXPECT_FALSE(fs::exists(outdir)) << outdir;
  } else {
    std::vector<std::string> names;
    for (auto& e : fs::directory_iterator(outdir)) names.push_back(e.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{keep});
  }
}

}  // namespace

TEST(PaintCli, AdaptModesReparameterizeAsScheduled) {
  Inputs in;
  struct Case {
    std::string flags;
    int reparams;
  };
  const int strokes = static_cast<int>(in.s.strokes.size());
  for (const Case& c : {Case{"--adapt none", 0}, Case{"--adapt single --grid 64", 1},
                        Case{"--adapt two-stage --grid 8,64 --reparam each-stroke", strokes}}) {
    SCOPED_TRACE(c.flags);
    const fs::path out = in.tmp.path / "adapt-out";
    fs::remove_all(out);
    const auto r = test::run_cli("paint " + q(in.mesh) + " --strokes " + q(in.strokes) +
                                 " --size 64 " + c.flags + " -o " + q(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rep = nlohmann::json::parse(slurp(out / "report.json"));
    if (c.reparams == 0) {
      EXPECT_EQ(rep["adapt"]["mode"], "none");
    } else {
      EXPECT_EQ(rep["adapt"]["reparameterizations"]["count"], c.reparams);
    }
    // Whatever the mode, the exported layout is valid: no flipped UV triangle, UVs in [0,1]^2.
    const TexturedMesh tm = read_textured_obj(out / "ball.obj");
    for (int f = 0; f < tm.mesh.num_faces(); ++f) EXPECT_GT(uv_signed_area(tm.param, f), 0.0) << f;
    for (const Vec2& uv : tm.param.uv) {
      EXPECT_GE(uv.minCoeff(), 0.0);
      EXPECT_LE(uv.maxCoeff(), 1.0);
    }
  }
}

TEST(PaintCli, PaintsAndExportsEverything) {
  Inputs in;
  const fs::path out = in.tmp.path / "out";
  const auto r = test::run_cli("paint " + q(in.mesh) + " --strokes " + q(in.strokes) +
                               " --size 96 -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"ball.obj", "ball.mtl", "ball.png", "ball.glb", "report.json"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
  // Nothing else (no temporaries) in OUTDIR.
  int n = 0;
  for ([[maybe_unused]] auto& e : fs::directory_iterator(out)) ++n;
  EXPECT_EQ(n, 5);

  const auto rep = nlohmann::json::parse(slurp(out / "report.json"));
  EXPECT_EQ(rep["texture"]["width"], 96);
  // density-flow refines where the warp needs it: more faces, the input's first.
  EXPECT_EQ(rep["mesh"]["input_faces"], in.m.num_faces());
  EXPECT_GE(rep["mesh"]["faces"].get<int>(), in.m.num_faces());
  EXPECT_EQ(rep["strokes"]["count"], 4);
  EXPECT_EQ(rep["strokes"]["decals"], 1);
  EXPECT_EQ(rep["strokes"]["dabs"], in.s.num_dabs());
  EXPECT_EQ(rep["adapt"]["mode"], "density-flow");  // the default
  EXPECT_EQ(rep["adapt"]["reparam"], "end");
  EXPECT_EQ(rep["adapt"]["reparameterizations"]["count"], 1);
  for (const char* phase : {"read", "unwrap", "paint", "export", "total"})
    EXPECT_GE(rep["times_s"][phase].get<double>(), 0.0) << phase;
  EXPECT_GE(rep["unwrap"]["final_l2"].get<double>(), 1.0);

  // The exported OBJ + PNG reproduce the strokes (the decal included) as well as the texture can.
  const TexturedMesh tm = read_textured_obj(out / "ball.obj");
  EXPECT_EQ(tm.mesh.num_faces(), rep["mesh"]["faces"].get<int>());
  ASSERT_GE(tm.mesh.positions.size(), in.m.positions.size());
  // The input's vertices come first, bit for bit.
  EXPECT_TRUE(std::equal(in.m.positions.begin(), in.m.positions.end(), tm.mesh.positions.begin()));
  EXPECT_NEAR(surface_area(tm.mesh), surface_area(in.m), 1e-6 * surface_area(in.m));
  const ImageRGBA8 tex = read_image(out / "ball.png");
  EXPECT_EQ(tex.width, 96);
  EvalOptions eo;
  eo.samples = 20000;
  const StrokeFile sf = read_strokes(in.strokes);
  const double psnr = evaluate_texture(tm.mesh, tm.param, tex, sf, eo).psnr;
  EXPECT_GT(psnr, 25.0);
  // And the decal really is in the texture: the sphere's pole facing the decal camera is green.
  double best = 1e9;
  Vec3 pole_colour;
  for (int f = 0; f < tm.mesh.num_faces(); ++f) {
    const Vec3 c = point_on_face(tm.mesh, f, 1.0 / 3, 1.0 / 3);
    const double d = (c - Vec3(0, 0, 1)).norm();
    if (d < best) {
      best = d;
      Vec2 uv = Vec2::Zero();
      for (int k = 0; k < 3; ++k) uv += tm.param.uv[tm.param.uv_faces[f][k]] / 3.0;
      pole_colour = sample_bilinear(tex, uv.x(), uv.y());
    }
  }
  EXPECT_NEAR(pole_colour.y(), 0.9 * 200 / 255.0 + 0.1 * 0.0, 0.35);  // mostly decal green
  EXPECT_GT(pole_colour.y(), pole_colour.x() + 0.2);
}

TEST(PaintCli, NoRefineKeepsTheInputMeshBitForBit) {
  Inputs in;
  const fs::path out = in.tmp.path / "norefine";
  const auto r = test::run_cli("paint " + q(in.mesh) + " --strokes " + q(in.strokes) + " --size 96 --no-refine -o " +
                               q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rep = nlohmann::json::parse(slurp(out / "report.json"));
  EXPECT_EQ(rep["mesh"]["faces"], in.m.num_faces());
  const TexturedMesh tm = read_textured_obj(out / "ball.obj");
  EXPECT_EQ(tm.mesh.positions, in.m.positions);
  EXPECT_EQ(tm.mesh.faces, in.m.faces);
}

TEST(PaintCli, NameOptionAndDefaultPadding) {
  Inputs in;
  const fs::path out = in.tmp.path / "named";
  const auto r = test::run_cli("-q paint " + q(in.mesh) + " --strokes " + q(in.strokes) +
                               " --size 40 --padding 0 --name thing -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_TRUE(fs::exists(out / "thing.glb"));
  EXPECT_NE(slurp(out / "thing.obj").find("mtllib thing.mtl"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(slurp(out / "report.json"))["texture"]["padding"], 0);
}

TEST(PaintCli, BadInputsExit2WithOneLineAndNoFiles) {
  Inputs in;
  const fs::path out = in.tmp.path / "out";
  const std::string base = "paint " + q(in.mesh) + " -o " + q(out) + " --strokes ";

  write_file(in.tmp.path / "bad.json", R"({"format": "adaptex.strokes", "version": 2, "strokes": []})");
  expect_clean_failure(test::run_cli(base + q(in.tmp.path / "bad.json")), "version", out);
  write_file(in.tmp.path / "garbage.json", "{ not json");
  expect_clean_failure(test::run_cli(base + q(in.tmp.path / "garbage.json")), "garbage.json", out);
  expect_clean_failure(test::run_cli(base + q(in.tmp.path / "missing.json")), "missing.json", out);

  const std::string good = base + q(in.strokes);
  expect_clean_failure(test::run_cli(good + " --size 0"), "--size", out);
  expect_clean_failure(test::run_cli(good + " --size 1.5"), "--size", out);
  expect_clean_failure(test::run_cli(good + " --size x"), "--size", out);
  expect_clean_failure(test::run_cli(good + " --padding -1"), "--padding", out);
  expect_clean_failure(test::run_cli(good + " --adapt sometimes"), "--adapt", out);
  expect_clean_failure(test::run_cli(good + " --adapt two-stage --grid 64"), "--grid", out);
  expect_clean_failure(test::run_cli(good + " --adapt single --grid 16,256"), "--grid", out);
  expect_clean_failure(test::run_cli(good + " --adapt two-stage --grid 16,x"), "--grid", out);
  expect_clean_failure(test::run_cli(good + " --adapt two-stage --alpha -1"), "--alpha", out);
  expect_clean_failure(test::run_cli(good + " --grid 16,x"), "--grid", out);
  expect_clean_failure(test::run_cli(good + " --grid ''"), "--grid", out);  // given empty: not the default
  expect_clean_failure(test::run_cli(good + " --grid ' 64'"), "--grid", out);
  expect_clean_failure(test::run_cli(good + " --adapt two-stage --grid 256,16"), "--grid", out);
  expect_clean_failure(test::run_cli(good + " --alpha nan"), "--alpha", out);
  expect_clean_failure(test::run_cli(good + " --beta inf"), "--beta", out);
  expect_clean_failure(test::run_cli(good + " --reparam often"), "--reparam", out);
  expect_clean_failure(test::run_cli(good + " --update guess"), "--update", out);
  expect_clean_failure(test::run_cli(good + " --name 'a b'"), "name", out);

  write_file(in.tmp.path / "broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
  expect_clean_failure(test::run_cli("paint " + q(in.tmp.path / "broken.obj") + " -o " + q(out) +
                                     " --strokes " + q(in.strokes)),
                       "broken.obj", out);

  // An existing OUTDIR keeps exactly what it had.
  fs::create_directories(out);
  write_file(out / "keep.txt", "x");
  expect_clean_failure(test::run_cli(base + q(in.tmp.path / "bad.json")), "version", out, "keep.txt");
}

TEST(PaintCli, DemoRunsAndReportsPsnr) {
  test::TempDir tmp;
  const fs::path out = tmp.path / "demo";
  // Smaller texture and fewer samples than the default to keep the suite fast.
  const auto r = test::run_cli("-q demo --size 256 --samples 50000 -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("PSNR"), std::string::npos) << r.out;
  const std::set<std::string> expected = {"trefoil.obj",        "trefoil.mtl",
                                           "trefoil.png",        "trefoil.glb",
                                           "trefoil_layout.png", "trefoil_texture_layout.png",
                                           "strokes.json",       "report.json"};
  std::set<std::string> written;
  for (const auto& e : fs::directory_iterator(out)) written.insert(e.path().filename().string());
  EXPECT_EQ(written, expected);
  // The summary's "files" line names exactly the files in the folder, no more and no fewer.
  const std::string tag = "  files   " + out.string() + "/:";
  const auto at = r.out.find(tag);
  ASSERT_NE(at, std::string::npos) << r.out;
  std::istringstream listed(r.out.substr(at + tag.size(), r.out.find('\n', at) - at - tag.size()));
  std::set<std::string> names;
  for (std::string n; listed >> n;) names.insert(n);
  EXPECT_EQ(names, written);
  const auto rep = nlohmann::json::parse(slurp(out / "report.json"));
  const double psnr = rep["eval"]["psnr_db"].get<double>();
  EXPECT_GT(psnr, 20.0);
  EXPECT_LT(psnr, 200.0);
  // `adaptex eval` on the exported files agrees with the demo's own figure.
  const auto e = test::run_cli("eval " + q(out / "trefoil.obj") + " " + q(out / "trefoil.png") + " " +
                               q(out / "strokes.json") + " --samples 50000");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto ej = nlohmann::json::parse(e.out);
  EXPECT_NEAR(ej["psnr"].get<double>(), psnr, 0.05);
}

TEST(PaintCli, BlenderImportsTheGlb) {
  if (std::system("command -v blender > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "blender not installed (Debian package `blender`); skipping the import smoke test";
  Inputs in;
  const fs::path out = in.tmp.path / "out";
  ASSERT_EQ(test::run_cli("-q paint " + q(in.mesh) + " --strokes " + q(in.strokes) + " --size 64 -o " + q(out))
                .exit_code,
            0);
  const fs::path script = in.tmp.path / "check.py";
  write_file(script,
             "try:\n"
             "    import numpy\n"
             "except ImportError:\n"
             "    print('BLENDER_NO_NUMPY')\n"
             "    raise SystemExit(0)\n"
             "if not hasattr(numpy, 'bool'):\n"
             "    numpy.bool = bool  # Debian's Blender 3.4 glTF add-on uses np.bool (removed in numpy 1.24)\n"
             "import bpy, sys\n"
             "bpy.ops.wm.read_factory_settings(use_empty=True)\n"
             "bpy.ops.import_scene.gltf(filepath=sys.argv[-1])\n"
             "meshes = [o for o in bpy.data.objects if o.type == 'MESH']\n"
             "assert len(meshes) == 1, meshes\n"
             "m = meshes[0].data\n"
             "assert len(m.uv_layers) >= 1\n"
             "imgs = [i for i in bpy.data.images if i.size[0] == 64]\n"
             "assert imgs, list(bpy.data.images)\n"
             "print('BLENDER_OK', len(m.polygons))\n");
  const std::string cmd = "blender -b --factory-startup --python " + q(script) + " -- " + q(out / "ball.glb") +
                          " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string text;
  char buf[4096];
  while (fgets(buf, sizeof buf, p)) text += buf;
  pclose(p);
  if (text.find("BLENDER_NO_NUMPY") != std::string::npos)
    GTEST_SKIP() << "Blender's glTF add-on needs numpy (Debian package python3-numpy), which is not installed";
  // The export carries the refined mesh (density-flow refines by default): Blender must see its faces.
  const TriMesh exported = read_mesh(out / "ball.obj");
  EXPECT_GE(exported.num_faces(), in.m.num_faces());
  EXPECT_NE(text.find("BLENDER_OK " + std::to_string(exported.num_faces())), std::string::npos) << text;
}
