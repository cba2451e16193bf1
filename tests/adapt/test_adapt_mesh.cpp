// Mesh-level tests of the adaptive re-parameterization: overlap-free multi-chart layouts, geometry-only
// stretch reduction, replay vs resample, the quality property, the session and `adaptex reparam`.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include <filesystem>
#include <fstream>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/error_polish.h"
#include "adaptex/adapt/session.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/texel_map.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"
#include "test_scene.h"
#include "reference_stretch.h"
#include "test_support.h"

namespace adaptex {
namespace {

// Thin hard lines concentrated in one small part of the surface (around the first vertex).
StrokeFile corner_lines(const TriMesh& mesh, int count, double radius_frac) {
  const double d = bounding_box(mesh).diagonal();
  GenerateOptions go;
  go.kind = StrokeKind::Lines;
  go.count = count;
  go.seed = 7;
  StrokeFile f = generate_strokes(mesh, go);
  for (auto& s : f.strokes) s.radius = radius_frac * d;
  return f;
}

ImageRGBA8 paint(const TriMesh& mesh, const Parameterization& p, const StrokeFile& s, int size) {
  PainterOptions po;
  po.width = po.height = size;
  Painter painter(mesh, p, po, s.background);
  painter.paint_all(s);
  return painter.texture();
}

TEST(AdaptMesh, TwoComponentLayoutStaysOverlapFreeAndFlipFree) {
  const TriMesh mesh = shapes::two_components();
  const Parameterization param = unwrap(mesh).param;
  ASSERT_GE(param.num_charts, 2);
  const StrokeFile strokes = corner_lines(mesh, 30, 0.004);
  PainterOptions po;
  po.width = po.height = 256;
  Painter painter(mesh, param, po, strokes.background);
  painter.paint_all(strokes);
  for (AdaptMode mode : {AdaptMode::Single, AdaptMode::TwoStage}) {
    AdaptOptions o;
    o.mode = mode;
    o.thesis.fine_grid = 128;
    o.thesis.geometry_scale = 1.0;  // the thesis' full geometry term: larger warps
    const AdaptResult r = adapt_parameterization(mesh, param, painter.texture(), painter.texel_map(), o);
    EXPECT_EQ(count_overlapping_triangles(r.param), 0);
    const StretchStats st = measure_stretch(mesh, r.param);
    EXPECT_EQ(st.flipped, 0);
    EXPECT_EQ(st.degenerate, 0);
    EXPECT_GT(r.report.damping, 0.0);
    double moved = 0;
    for (size_t k = 0; k < param.uv.size(); ++k) moved = std::max(moved, (r.param.uv[k] - param.uv[k]).norm());
    EXPECT_GT(moved, 1e-3);  // it did re-parameterize
    for (const Vec2& uv : r.param.uv) {
      EXPECT_GE(uv.minCoeff(), 0.0);
      EXPECT_LE(uv.maxCoeff(), 1.0);
    }
  }
}

TEST(AdaptMesh, GeometryOnlyLowersL2Stretch) {
  // A curved disk with a stretchy initial parameterization (Floater only, no Yoshizawa).
  const TriMesh mesh = shapes::sphere(48, 24);
  UnwrapOptions uo;
  uo.yoshizawa_max_iterations = 0;
  const Parameterization param = unwrap(mesh, uo).param;
  PainterOptions po;
  po.width = po.height = 256;
  Painter painter(mesh, param, po);  // nothing painted: no signal
  AdaptOptions o;  // thesis defaults (measured: L2 1.2925 -> 1.2347; geometry_scale 1, the thesis as written,
                   // overshoots to 1.78 and is rejected by the geometry safeguard, docs/adaptive.md)
  o.mode = AdaptMode::TwoStage;
  const AdaptResult r = adapt_parameterization(mesh, param, painter.texture(), painter.texel_map(), o);
  EXPECT_EQ(r.report.signal_fraction, 0.0);
  EXPECT_TRUE(r.report.accepted);
  EXPECT_LT(r.report.l2_after, r.report.l2_before * 0.98);
  // The reported L2 values against Sander's definition computed in the test (reference_stretch.h),
  // not against measure_stretch(), which produced them.
  EXPECT_NEAR(r.report.l2_before, test::reference_l2_stretch(mesh, param), 1e-9 * r.report.l2_before);
  EXPECT_NEAR(r.report.l2_after, test::reference_l2_stretch(mesh, r.param), 1e-9 * r.report.l2_after);
  EXPECT_EQ(measure_stretch(mesh, r.param).flipped, 0);
}

// Thin hard lines on a sphere, with the fixed layout's PSNR at N and 2N: the quality case of both
// adaptive methods.
struct SphereLines {
  TriMesh mesh = shapes::sphere(64, 32);
  Parameterization param = unwrap(mesh).param;
  StrokeFile strokes = corner_lines(mesh, 40, 0.003);
  int N = 128;
  EvalOptions eo = [] {
    EvalOptions o;
    o.samples = 200000;
    return o;
  }();
  double none = evaluate_texture(mesh, param, paint(mesh, param, strokes, N), strokes, eo).psnr;
  double none2 = evaluate_texture(mesh, param, paint(mesh, param, strokes, 2 * N), strokes, eo).psnr;

  /// Paints every stroke in a session with \p adapt (end mode) and returns it.
  std::unique_ptr<PaintSession> run(const AdaptOptions& adapt, bool safeguard = true) const {
    PaintSessionOptions so;
    so.texture_size = N;
    so.safeguard = safeguard;
    so.adapt = adapt;
    auto s = std::make_unique<PaintSession>(mesh, param, so, strokes.background);
    for (const auto& st : strokes.strokes) s->add_stroke(st);
    s->finish();
    return s;
  }
  double psnr(PaintSession& s) const { return evaluate_texture(s.mesh(), s.param(), s.texture(), strokes, eo).psnr; }
};

TEST(AdaptMesh, QualityTwoStageBeatsFixedParameterizationOnConcentratedLines) {
  const SphereLines c;
  AdaptOptions ao;
  ao.mode = AdaptMode::TwoStage;
  for (bool safeguard : {false, true}) {
    const auto s = c.run(ao, safeguard);
    ASSERT_EQ(s->reports().size(), 1u);
    const double ad = c.psnr(*s);
    std::printf("sphere lines N=%d: none %.2f dB, two-stage %.2f dB, none at 2N %.2f dB (safeguard %d)\n", c.N,
                c.none, ad, c.none2, safeguard);
    // A real gain, measured against a reference computed here rather than a hard-coded number: at
    // least 15% of what doubling the texture side (4x the texels) gains on the fixed layout
    // (measured: +1.00 dB of +3.58 dB, 28%).
    ASSERT_GT(c.none2, c.none + 1.0);  // the reference gain exists
    EXPECT_GT(ad, c.none + 0.15 * (c.none2 - c.none));
    EXPECT_EQ(measure_stretch(s->mesh(), s->param()).flipped, 0);
  }
}

TEST(AdaptMesh, DensityFlowGainsMostWithRefinementOnConcentratedLines) {
  const SphereLines c;
  for (bool refine : {true, false}) {
    AdaptOptions ao;
    ao.mode = AdaptMode::DensityFlow;
    ao.refine.enabled = refine;
    const auto s = c.run(ao);
    ASSERT_EQ(s->reports().size(), 1u);
    const AdaptReport& r = s->reports().back();
    const double ad = c.psnr(*s);
    std::printf("sphere lines N=%d: none %.2f dB, density-flow %.2f dB (refine %d: %d -> %d faces), none at 2N %.2f dB\n",
                c.N, c.none, ad, refine, r.faces_before, r.faces_after, c.none2);
    EXPECT_TRUE(r.accepted);
    // Against the gain of doubling the texture side on the fixed layout (computed here): measured
    // +1.54 dB of +3.58 dB (43%) with refinement (two-stage: 28%), +0.93 dB (26%) without (the coarse
    // triangles cannot follow the warp, so safe_remap damps it).
    ASSERT_GT(c.none2, c.none + 1.0);
    EXPECT_GT(ad, c.none + (refine ? 0.33 : 0.1) * (c.none2 - c.none));
    const StretchStats st = measure_stretch(s->mesh(), s->param());
    EXPECT_EQ(st.flipped, 0);
    EXPECT_EQ(st.degenerate, 0);
    EXPECT_EQ(r.flow_inverted_cells, 0);
    // Refinement happens exactly when it is on, and the session's mesh is the refined one.
    EXPECT_EQ(r.faces_after > r.faces_before, refine);
    EXPECT_EQ(s->mesh().num_faces(), r.faces_after);
    EXPECT_NEAR(surface_area(s->mesh()), surface_area(c.mesh), 1e-9 * surface_area(c.mesh));
  }
}

TEST(AdaptMesh, OverlapsAroundASliverAreDampedLocally) {
  // triceratops.off has a 3-D sliver (face 828: 6.8e-8 of the mean face area). In its 12-chart layout
  // the sliver and its refined children sit on a chart's border; the warp made their neighbours
  // overlap at every global blend down to 0.005, and the remap's global bisection then kept 0.5 % of
  // the warp (texel saving 1.7× at 128² against 6.5× at 512²). SafeRemapOptions::damp_overlaps damps
  // the faces of the new overlapping pairs locally instead.
  ADAPTEX_REQUIRE_SHARED();
  const TriMesh mesh = read_mesh(*test::shared_meshes_dir() / "triceratops.off");
  UnwrapOptions uo;
  uo.probe_first_charts = 12;
  const Parameterization param = unwrap(mesh, uo).param;
  ASSERT_EQ(param.num_charts, 12);
  GenerateOptions go;
  go.kind = StrokeKind::Lines;
  go.seed = 1;
  const StrokeFile strokes = generate_strokes(mesh, go);
  const int N = 128;
  const ImageRGBA8 texture = paint(mesh, param, strokes, N);
  const TexelMap map = build_texel_map(mesh, param, N, N);
  auto adapt = [&](bool damp) {
    AdaptOptions ao;
    ao.mode = AdaptMode::DensityFlow;
    ao.remap.damp_overlaps = damp;
    AdaptResult r = adapt_parameterization(mesh, param, texture, map, ao, &strokes);
    std::printf("damp_overlaps %d: global blend %.4f, mean %.4f, %d checks\n", damp, r.report.global_damping,
                r.report.damping, r.report.remap_checks);
    const TriMesh& out = r.refined_mesh ? *r.refined_mesh : mesh;
    EXPECT_EQ(count_overlapping_triangles(r.param), 0);
    const StretchStats st = measure_stretch(out, r.param);
    EXPECT_EQ(st.flipped, 0);
    EXPECT_EQ(st.degenerate, 0);
    return r.report;
  };
  const AdaptReport damped = adapt(true), global = adapt(false);
  EXPECT_EQ(damped.global_damping, 1.0);
  EXPECT_GT(damped.damping, 0.9);
  EXPECT_LT(global.global_damping, 0.5);  // without: the global bisection
}

TEST(AdaptMesh, ThePolishRunsCoarseToFine) {
  // ErrorPolishOptions::prepass_sweeps: the polish lattice's coarser levels first (prepass_levels),
  // then sweeps_after_prepass sweeps on the full lattice (instead of sweeps). Every way gives a valid,
  // better layout.
  std::vector<std::vector<Vec2>> layouts;
  const SphereLines c;
  auto run = [&](int prepass, int levels = ErrorPolishOptions{}.prepass_levels) {
    AdaptOptions ao;
    ao.mode = AdaptMode::DensityFlow;
    ao.density_flow.polish.prepass_sweeps = prepass;
    ao.density_flow.polish.prepass_levels = levels;
    const auto s = c.run(ao);
    layouts.push_back(s->param().uv);
    const AdaptReport r = s->reports().back();
    EXPECT_TRUE(r.accepted);
    EXPECT_LT(r.polish_error_after, r.polish_error_before);
    const StretchStats st = measure_stretch(s->mesh(), s->param());
    EXPECT_EQ(st.flipped, 0);
    EXPECT_EQ(st.degenerate, 0);
    EXPECT_GT(c.psnr(*s), c.none + 1.0);
    return r;
  };
  const ErrorPolishOptions defaults;
  ASSERT_GT(defaults.prepass_sweeps, 0);
  ASSERT_LT(defaults.sweeps_after_prepass, defaults.sweeps);
  const AdaptReport cascade = run(defaults.prepass_sweeps), plain = run(0);
  EXPECT_LE(cascade.polish_sweeps, defaults.sweeps_after_prepass);
  EXPECT_GT(plain.polish_sweeps, defaults.sweeps_after_prepass);
  // prepass_levels: one level more or less than the default is another, equally valid, layout (the
  // sphere's one chart polishes through 128 cells: a 16-cell coarsest level is allowed up to 3 levels).
  const int more = defaults.prepass_levels + 1, fewer = std::max(1, defaults.prepass_levels - 1);
  run(defaults.prepass_sweeps, defaults.prepass_levels == 1 ? more : fewer);
  ASSERT_EQ(layouts.size(), 3u);
  EXPECT_NE(layouts[2], layouts[0]);
  ErrorPolishOptions bad;
  bad.prepass_sweeps = -1;
  GridWarp g = GridWarp::uniform(4);
  PolishFields f;
  f.error = f.exponent = f.floor = ImageF(4, 4, 0.0f);
  EXPECT_THROW(polish_warp(g, f, bad), InvalidInputError);
  for (int levels : {0, 5}) {
    ErrorPolishOptions o;
    o.prepass_levels = levels;
    EXPECT_THROW(polish_warp(g, f, o), InvalidInputError) << levels;
  }
}

TEST(AdaptMesh, ReplayEqualsFreshPaintAndResampleLosesSomething) {
  const TriMesh mesh = shapes::torus(48, 24);
  const Parameterization param = unwrap(mesh).param;
  StrokeFile strokes = corner_lines(mesh, 6, 0.01);
  const int N = 128;
  PaintSessionOptions so;
  so.texture_size = N;
  so.schedule = ReparamSchedule::EachStroke;
  so.safeguard = false;  // every stroke re-parameterizes
  so.min_gain_db = 0;    // and no cycle is skipped for a small predicted gain
  so.adapt.thesis.fine_grid = 64;
  PaintSession replay(mesh, param, so, strokes.background);
  so.update = TextureUpdate::Resample;
  PaintSession resample(mesh, param, so, strokes.background);
  for (const auto& st : strokes.strokes) {
    replay.add_stroke(st);
    resample.add_stroke(st);
  }
  EXPECT_EQ(replay.reports().size(), strokes.strokes.size());
  // Replay: byte-identical to painting the whole history afresh on the final parameterization.
  const ImageRGBA8 fresh = paint(replay.mesh(), replay.param(), replay.history(), N);
  EXPECT_EQ(fresh.data, replay.texture().data);
  // Resample accumulates blur: its error is not lower than replay's on the same final layout family.
  EvalOptions eo;
  eo.samples = 100000;
  const double p_replay = evaluate_texture(replay.mesh(), replay.param(), replay.texture(), strokes, eo).psnr;
  const double p_resample = evaluate_texture(resample.mesh(), resample.param(), resample.texture(), strokes, eo).psnr;
  std::printf("torus 6 each-stroke re-parameterizations: replay %.2f dB, resample %.2f dB\n", p_replay, p_resample);
  EXPECT_GT(p_replay, p_resample);
  EXPECT_GT(p_resample, 15.0);  // but it is still the same picture
}

TEST(AdaptMesh, SafeguardNeverAcceptsAWorseLayout) {
  const test::Scene sc = test::torus_scene(40, 20, StrokeKind::Blobs, 3);
  const TriMesh& mesh = sc.mesh;
  const Parameterization& param = sc.param;
  const StrokeFile& strokes = sc.strokes;
  PaintSessionOptions so;
  so.texture_size = 64;
  so.schedule = ReparamSchedule::EachStroke;
  so.min_gain_db = 0;  // a cycle, and so a safeguard run, after every stroke
  PaintSession s(mesh, param, so, strokes.background);
  for (const auto& st : strokes.strokes) {
    s.add_stroke(st);
    const AdaptReport& r = s.reports().back();
    // The safeguard measured both layouts, accepted the new one exactly when it is better, and a
    // rejected step keeps the old layout (damping 0).
    ASSERT_GE(r.error_before, 0.0);
    EXPECT_EQ(r.accepted, r.error_after < r.error_before) << r.error_after << " vs " << r.error_before;
    EXPECT_TRUE(r.accepted || r.damping == 0.0) << r.damping;
  }
}

TEST(ReparamCli, WritesAllOutputsOrNothing) {
  test::TempDir dir;
  // A textured mesh: unwrapped sphere + a painted texture.
  const TriMesh mesh = shapes::sphere(32, 16);
  const Parameterization param = unwrap(mesh).param;
  const StrokeFile strokes = corner_lines(mesh, 10, 0.01);
  write_obj(dir.path / "in.obj", mesh, &param);
  write_png(dir.path / "in.png", paint(mesh, param, strokes, 128));
  const auto out = dir.path / "out";
  auto r = test::run_cli("reparam " + (dir.path / "in.obj").string() + " " + (dir.path / "in.png").string() +
                         " --grid 8,64 -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"in.obj", "in.mtl", "in.png", "in.glb", "report.json"}) EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  const TexturedMesh back = read_textured_obj(out / "in.obj");
  EXPECT_EQ(measure_stretch(back.mesh, back.param).flipped, 0);
  // Bad input: exit 2, one line, no output directory.
  const auto bad = dir.path / "bad";
  r = test::run_cli("reparam " + (dir.path / "in.obj").string() + " " + (dir.path / "in.png").string() +
                    " --grid 8,zz -o " + bad.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(bad));
  std::ofstream(dir.path / "broken.png") << "not a png";
  r = test::run_cli("reparam " + (dir.path / "in.obj").string() + " " + (dir.path / "broken.png").string() +
                    " -o " + bad.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(bad));
}

}  // namespace
}  // namespace adaptex
