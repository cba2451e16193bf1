/// \file test_studio_app.cpp
/// Unit tests of the adaptex-studio App logic with the null renderer (no window, no GL):
/// camera math, picking, brush spacing and symmetry, UI capture, eyedropper, undo/redo over 100 steps,
/// project round trip, autosave / recovery, bad files, cancel, adaptation while painting, the library's
/// default method and re-parameterization from the initial layout, unsaved-work prompts, Save / Save As,
/// and the same layout and texture as `adaptex paint`.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <thread>

#include <sys/stat.h>

#include "adaptex/core/limits.h"
#include "adaptex/core/shapes.h"
#include "adaptex/io/asset_io.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/input_file.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/asset_eval.h"
#include "adaptex/paint/material_paint.h"
#include "adaptex/paint/material_signal.h"
#include "adaptex/paint/painter.h"
#include "app.h"
#include "brush_preset.h"
#include "tablet.h"
#include "file_browser.h"
#include "live_adaptation.h"
#include "test_support.h"

namespace adaptex::studio {
namespace {

using adaptex::test::TempDir;

struct Harness {
  NullRenderer* renderer = nullptr;
  std::unique_ptr<App> app;
  /// \p mode: the adaptation (None by default here: most tests are about painting mechanics).
  explicit Harness(AppOptions opt = {}, int texture_size = 256, const std::string& mesh = "builtin:sphere",
                   AdaptMode mode = AdaptMode::None) {
    auto r = std::make_unique<NullRenderer>();
    renderer = r.get();
    app = std::make_unique<App>(std::move(r), std::move(opt));
    app->on_resize(400, 300);
    app->brush().screen_space = false;  // world-space radius: most tests set brush().radius (model units)
    app->session_options().texture_size = texture_size;
    app->session_options().adapt.mode = mode;
    if (!mesh.empty()) {
      app->open_mesh(mesh);
      EXPECT_TRUE(app->wait_idle(120));
      EXPECT_TRUE(app->has_model());
      app->render();  // the first frame uploads the whole texture
    }
  }
  /// A left-button drag along a straight line, in steps of \p step pixels, as window events.
  void drag(double x0, double y0, double x1, double y1, double step = 5.0) {
    app->on_cursor(x0, y0);
    app->on_mouse_button(MouseButton::Left, true, {});
    const int n = std::max(1, int(std::hypot(x1 - x0, y1 - y0) / step));
    for (int k = 1; k <= n; ++k) app->on_cursor(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n);
    app->on_mouse_button(MouseButton::Left, false, {});
    app->begin_frame();
    app->render();
    app->end_frame();
  }
  void click(double x, double y) { drag(x, y, x, y); }
};

ImageRGBA8 replay_texture(const App& app) {
  const int n = app.session_options().texture_size;
  Painter p(*app.mesh(), *app.param(), PainterOptions{n, n, app.session_options().padding},
            app.history().background());
  p.paint_all(app.history().to_file());
  return p.texture();
}

/// Runs frames (background jobs, autosave) until \p path exists, for up to 4 s.
void run_frames_until_exists(App& app, const std::filesystem::path& path) {
  for (int k = 0; k < 400 && !std::filesystem::exists(path); ++k) {
    app.begin_frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

int max_abs_diff(const ImageRGBA8& a, const ImageRGBA8& b) {
  if (a.width != b.width || a.height != b.height) return 256;
  int m = 0;
  for (size_t k = 0; k < a.data.size(); ++k) m = std::max(m, std::abs(int(a.data[k]) - int(b.data[k])));
  return m;
}

// ---- camera -----------------------------------------------------------------------------------

TEST(StudioCamera, PixelRayPassesThroughProjectedPoint) {
  Camera c;
  c.width = 640;
  c.height = 480;
  c.target = Vec3(0.3, -0.2, 0.5);
  c.distance = 4;
  c.yaw = 0.7;
  c.pitch = -0.4;
  for (const Vec3& p : {Vec3(0, 0, 0), Vec3(0.5, 0.4, -0.3), Vec3(-0.8, 0.1, 0.9)}) {
    const Vec3 s = c.project(p);
    const Ray r = c.pixel_ray(s.x(), s.y());
    const Vec3 d = p - r.origin;
    EXPECT_LT((d - d.dot(r.dir) * r.dir).norm(), 1e-9) << p.transpose();
    EXPECT_GT(d.dot(r.dir), 0);
  }
  const Ray centre = c.pixel_ray(320, 240);
  EXPECT_LT((centre.dir - c.forward()).norm(), 1e-12);
}

TEST(StudioCamera, FrameShowsTheWholeBoxAndOrbitPanZoomBehave) {
  Camera c;
  c.width = 800;
  c.height = 400;
  BoundingBox box;
  box.min = Vec3(-1, -2, 0);
  box.max = Vec3(3, 1, 0.5);
  c.yaw = 2.0;
  c.pitch = 0.6;
  c.frame(box);
  for (int k = 0; k < 8; ++k) {
    const Vec3 p((k & 1) ? box.max.x() : box.min.x(), (k & 2) ? box.max.y() : box.min.y(),
                 (k & 4) ? box.max.z() : box.min.z());
    const Vec3 s = c.project(p);
    EXPECT_GE(s.x(), 0);
    EXPECT_LE(s.x(), 800);
    EXPECT_GE(s.y(), 0);
    EXPECT_LE(s.y(), 400);
  }
  const double d = c.distance;
  c.orbit(50, -30);
  EXPECT_NEAR((c.eye() - c.target).norm(), d, 1e-9);
  const Vec3 t = c.target;
  c.pan(40, 0);  // the old target moves 40 pixels right on screen with the model
  const Vec3 s = c.project(t);
  EXPECT_NEAR(s.x(), 400 + 40, 1e-6);
  EXPECT_NEAR(s.y(), 200, 1e-6);
  c.zoom(2);
  EXPECT_NEAR(c.distance, d * 0.85 * 0.85, 1e-9);
  EXPECT_LT(c.pitch, 3.14159 / 2);
  c.orbit(0, 1e6);
  EXPECT_LT(c.pitch, 3.14159 / 2);
}

// ---- picking and painting --------------------------------------------------------------------

TEST(StudioApp, PicksTheVisibleFrontSurface) {
  Harness h;
  auto hit = h.app->pick(200, 150);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->point.norm(), 1.0, 2e-3);
  EXPECT_GT(hit->point.z(), 0.99);  // camera on +Z: the near pole, not the far one
  EXPECT_TRUE(hit->front_facing);
  EXPECT_FALSE(h.app->pick(2, 2));  // background
}

TEST(StudioApp, DragPaintsDabsOnTheSurfaceAtTheChosenSpacing) {
  Harness h;
  h.app->brush().spacing = 0.3;
  h.app->brush().radius = 0.03;
  const ImageRGBA8 before = *h.app->texture();
  h.drag(120, 150, 280, 150, 7.0);
  ASSERT_EQ(h.app->history().strokes().size(), 1u);
  const Stroke& s = h.app->history().strokes()[0];
  const double r = h.app->world_radius();
  EXPECT_NEAR(s.radius, r, 1e-12);
  EXPECT_EQ(s.color, h.app->brush().color);
  ASSERT_GE(s.dabs.size(), 10u);
  const double pixel = 2 * h.app->camera().distance * std::tan(40 * 3.14159265 / 360) / 300;  // world per pixel
  for (size_t k = 0; k < s.dabs.size(); ++k) {
    EXPECT_NEAR(s.dabs[k].norm(), 1.0, 2e-3);
    EXPECT_GT(s.dabs[k].z(), 0);
    if (k == 0) continue;
    const double step = (s.dabs[k] - s.dabs[k - 1]).norm();
    EXPECT_GE(step, 0.3 * r * (1 - 1e-9));
    EXPECT_LE(step, 0.3 * r + 3 * pixel);  // one ray per pixel of cursor travel
  }
  // The texture changed, and only inside the dab footprint (texels away from any dab untouched).
  const ImageRGBA8& after = *h.app->texture();
  EXPECT_GT(max_abs_diff(before, after), 100);
  EXPECT_GT(h.renderer->texture_updates, 0);
  EXPECT_EQ(max_abs_diff(after, replay_texture(*h.app)), 0);
}

TEST(StudioApp, SymmetryMirrorsEveryDab) {
  Harness h;
  h.app->brush().symmetry_axis = 0;
  h.drag(230, 120, 300, 170, 4.0);
  ASSERT_EQ(h.app->history().strokes().size(), 1u);
  const auto& dabs = h.app->history().strokes()[0].dabs;
  int right = 0;
  for (const Vec3& d : dabs) {
    if (d.x() <= 0) continue;
    ++right;
    double best = 1e9;
    for (const Vec3& e : dabs) best = std::min(best, (e - Vec3(-d.x(), d.y(), d.z())).norm());
    EXPECT_LT(best, 1e-6) << d.transpose();
  }
  EXPECT_GE(right, 3);
  EXPECT_EQ(int(dabs.size()), 2 * right);
}

TEST(StudioApp, NoPaintWhenTheUiHasTheMouseOrWhenOrbiting) {
  Harness h;
  h.app->set_ui_capture(true, false);
  h.drag(150, 150, 250, 150);
  EXPECT_TRUE(h.app->history().strokes().empty());
  h.app->set_ui_capture(false, false);
  const double yaw = h.app->camera().yaw;
  h.app->on_cursor(150, 150);
  h.app->on_mouse_button(MouseButton::Left, true, Mods{false, false, true});  // Alt+left orbits
  h.app->on_cursor(250, 150);
  h.app->on_mouse_button(MouseButton::Left, false, {});
  EXPECT_TRUE(h.app->history().strokes().empty());
  EXPECT_NE(h.app->camera().yaw, yaw);
}

TEST(StudioApp, KeysChangeRadiusAndEyedropperSamplesThePaint) {
  Harness h;
  const double r = h.app->brush().radius;
  h.app->on_key(']', true, {});
  EXPECT_NEAR(h.app->brush().radius, r * 1.15, 1e-12);
  h.app->on_key('[', true, {});
  EXPECT_NEAR(h.app->brush().radius, r, 1e-12);
  h.app->brush().color = Vec3(0.1, 0.2, 0.9);
  h.app->brush().radius = 0.1;
  h.app->brush().hardness = 1.0;
  h.click(200, 150);
  h.app->brush().color = Vec3(0, 0, 0);
  h.app->brush().tool = Tool::Eyedropper;
  h.click(200, 150);
  EXPECT_LT((h.app->brush().color - Vec3(0.1, 0.2, 0.9)).norm(), 0.02);
  EXPECT_EQ(h.app->history().strokes().size(), 1u);  // the eyedropper does not paint
}

TEST(StudioApp, UndoRedoHundredStepsReplaysTheHistory) {
  Harness h;
  h.app->brush().radius = 0.01;
  for (int k = 0; k < 110; ++k) {
    h.app->brush().color = Vec3((k % 7) / 7.0, (k % 3) / 3.0, (k % 5) / 5.0);
    h.click(140 + (k % 11) * 11, 110 + (k / 11) * 8);
  }
  ASSERT_EQ(h.app->history().strokes().size(), 110u);
  const ImageRGBA8 full = *h.app->texture();
  for (int k = 0; k < 100; ++k) h.app->on_key('Z', true, Mods{false, true, false});
  EXPECT_EQ(h.app->history().strokes().size(), 10u);
  ASSERT_TRUE(h.app->wait_idle(60));
  EXPECT_EQ(max_abs_diff(*h.app->texture(), replay_texture(*h.app)), 0);
  for (int k = 0; k < 50; ++k) h.app->on_key('Z', true, Mods{true, true, false});  // Ctrl+Shift+Z
  for (int k = 0; k < 50; ++k) h.app->on_key('Y', true, Mods{false, true, false});  // Ctrl+Y
  EXPECT_EQ(h.app->history().strokes().size(), 110u);
  ASSERT_TRUE(h.app->wait_idle(60));
  EXPECT_EQ(max_abs_diff(*h.app->texture(), full), 0);
}

TEST(StudioApp, ProjectSaveLoadRoundTrip) {
  TempDir dir;
  Harness h;
  h.app->brush().color = Vec3(0.2, 0.7, 0.3);
  h.drag(150, 140, 250, 160);
  h.app->brush().hardness = 0.8;
  h.app->brush().symmetry_axis = 2;
  h.app->session_options().adapt.thesis.alpha = 0.3;
  h.app->view().wireframe = true;
  h.app->set_background_colour(Vec3(0.9, 0.9, 0.8));
  h.app->camera().orbit(40, 25);
  h.app->camera().pan(12, -7);
  h.app->camera().zoom(2);
  const auto path = dir.path / "p.json";
  h.app->save_project(path);
  ASSERT_TRUE(std::filesystem::exists(path));
  ASSERT_TRUE(h.app->wait_idle(60));

  Harness g({}, 256, "");
  g.app->open_project(path);
  ASSERT_TRUE(g.app->wait_idle(120));
  ASSERT_TRUE(g.app->has_model());
  EXPECT_EQ(g.app->mesh_path(), "builtin:sphere");
  ASSERT_EQ(g.app->history().strokes().size(), 1u);
  EXPECT_EQ(g.app->history().strokes()[0].dabs, h.app->history().strokes()[0].dabs);
  EXPECT_EQ(g.app->history().background(), Vec3(0.9, 0.9, 0.8));
  EXPECT_EQ(g.app->brush().hardness, 0.8);
  EXPECT_EQ(g.app->brush().symmetry_axis, 2);
  EXPECT_EQ(g.app->session_options().adapt.thesis.alpha, 0.3);
  EXPECT_EQ(g.app->session_options().adapt.mode, AdaptMode::None);  // the project's, not the default
  EXPECT_EQ(g.app->project_path(), std::filesystem::absolute(path).lexically_normal());
  EXPECT_FALSE(g.app->unsaved());
  EXPECT_TRUE(g.app->view().wireframe);
  EXPECT_EQ(max_abs_diff(*g.app->texture(), *h.app->texture()), 0);
  // The view is the saved one (not the model framed again).
  EXPECT_EQ(g.app->camera().target, h.app->camera().target);
  EXPECT_EQ(g.app->camera().distance, h.app->camera().distance);
  EXPECT_EQ(g.app->camera().yaw, h.app->camera().yaw);
  EXPECT_EQ(g.app->camera().pitch, h.app->camera().pitch);
  EXPECT_EQ(g.app->camera().fov_y_degrees, h.app->camera().fov_y_degrees);
}

/// DIR/atlas.obj + .mtl + .png: two unit squares in z = 0 (x in [0,1] and [2,3]) on one chart, the
/// second mirrored onto the first's texels; a third square (x in [4,5]) on a chart in the tile u in
/// [1,2] (wrapped); a fourth (x in [6,7]) on a chart across the border v = 1 (straddling); a sliver
/// face with a degenerate UV triangle. The \p size^2 texture (64 by default): every texel a
/// different colour (r = 4i, g = 4j at 64^2). \p uv_scale < 1 scales every UV towards the origin (an
/// atlas that wastes most of the square; the charts then lie inside [0,1]^2).
std::filesystem::path write_atlas_obj(const std::filesystem::path& dir, int size = 64, double uv_scale = 1) {
  ImageRGBA8 tex(size, size, {0, 0, 0, 255});
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      tex.texel(i, j)[0] = std::uint8_t(256 * i / size);
      tex.texel(i, j)[1] = std::uint8_t(256 * j / size);
      tex.texel(i, j)[2] = 100;
    }
  write_png(dir / "atlas.png", tex);
  std::ofstream(dir / "atlas.mtl") << "newmtl m\nmap_Kd atlas.png\n";
  std::ofstream o(dir / "atlas.obj");
  o << "mtllib atlas.mtl\nusemtl m\n";
  const double xs[4] = {0, 2, 4, 6};
  for (double x : xs) o << "v " << x << " 0 0\nv " << x + 1 << " 0 0\nv " << x + 1 << " 1 0\nv " << x << " 1 0\n";
  o << "v 0 -1 0\nv 1 -1 0\nv 0.5 -0.5 0\n";  // 17-19
  const double uvs[17][2] = {{0.05, 0.05}, {0.45, 0.05}, {0.45, 0.95}, {0.05, 0.95},  // 1-4: the shared chart
                             {0.45, 0.05}, {0.05, 0.05}, {0.05, 0.95}, {0.45, 0.95},  // 5-8: its mirror image
                             {1.55, 0.05}, {1.95, 0.05}, {1.95, 0.95}, {1.55, 0.95},  // 9-12: in the next tile
                             {0.6, 0.96},  {0.9, 0.96},  {0.9, 1.1},   {0.6, 1.1},    // 13-16: across v = 1
                             {0.7, 0.5}};                                             // 17: degenerate triangle
  for (const auto& t : uvs) o << "vt " << t[0] * uv_scale << " " << t[1] * uv_scale << "\n";
  for (int s = 0; s < 4; ++s) {
    const int v = 4 * s + 1;
    o << "f " << v << "/" << v << " " << v + 1 << "/" << v + 1 << " " << v + 2 << "/" << v + 2 << "\n";
    o << "f " << v << "/" << v << " " << v + 2 << "/" << v + 2 << " " << v + 3 << "/" << v + 3 << "\n";
  }
  o << "f 17/17 18/17 19/17\n";
  return dir / "atlas.obj";
}

TEST(StudioAtlas, AModelWithItsOwnAtlasIsPaintedOnItAndKeepsItThroughSaveExportAndUnwrap) {
  TempDir dir;
  const auto obj = write_atlas_obj(dir.path);
  const TexturedAsset input = read_textured_asset(obj);
  Harness h({}, 256, obj.string());  // no adaptation (StudioAtlas.AdaptingKeeps... adapts it)
  App& app = *h.app;
  ASSERT_TRUE(app.on_artist_atlas());
  EXPECT_GT(std::max_element(app.param()->uv.begin(), app.param()->uv.end(),
                              [](const Vec2& a, const Vec2& b) { return a.y() < b.y(); })
                ->y(),
            1.05);  // the straddling chart keeps its UVs
  EXPECT_EQ(app.session_options().texture_size, 64);  // the texture's own size
  EXPECT_NE(app.status_line().find("artist's UV atlas"), std::string::npos) << app.status_line();
  EXPECT_TRUE(app.atlas_adaptation().empty());
  EXPECT_EQ(app.param()->uv, input.param.uv);
  EXPECT_EQ(app.param()->uv_faces, input.param.uv_faces);
  const ImageRGBA8 original = read_image(dir.path / "atlas.png");
  // Every chart texel is the artist's (the wrapped chart's included).
  Painter probe(*app.mesh(), *app.param(), PainterOptions{64, 64, 0});
  const std::vector<int>& inside = probe.texel_map().inside;
  ASSERT_GT(inside.size(), 1000u);
  auto same_at = [&](const ImageRGBA8& a, int t) {
    return std::equal(a.data.begin() + 4 * t, a.data.begin() + 4 * t + 3, original.data.begin() + 4 * t);
  };
  for (int t : inside) ASSERT_TRUE(same_at(*app.texture(), t)) << t;

  // A stroke on the first square (x = 0.25, u = 0.15), then no adaptation: the layout stays.
  Stroke st;
  st.color = Vec3(1, 0, 0);
  st.radius = 0.1;
  st.hardness = 1;
  st.dabs = {Vec3(0.25, 0.4, 0), Vec3(0.25, 0.5, 0), Vec3(0.25, 0.6, 0)};
  app.add_stroke(st);
  ASSERT_TRUE(app.wait_idle(60));
  EXPECT_EQ(app.param()->uv, input.param.uv);
  EXPECT_EQ(app.live_adaptation(), nullptr);
  const std::uint8_t* red = app.texture()->texel(9, 32);  // uv (0.148, 0.508)
  EXPECT_EQ(red[0], 255);
  EXPECT_EQ(red[1], 0);
  int kept = 0;
  for (int t : inside)
    if (std::abs((t % 64 + 0.5) / 64 - 0.15) > 0.06) kept += same_at(*app.texture(), t) ? 1 : -100000;
  EXPECT_GT(kept, 900);

  // Export GLB: the same UVs, corner by corner, and the painted texture.
  const auto glb = dir.path / "out.glb";
  app.export_glb(glb);
  const TexturedAsset out = read_textured_asset(glb);
  ASSERT_EQ(out.mesh.num_faces(), input.mesh.num_faces());
  double err = 0;
  for (int f = 0; f < out.mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      err = std::max(err, (out.param.uv[size_t(out.param.uv_faces[f][k])] -
                           input.param.uv[size_t(input.param.uv_faces[f][k])]).norm());
  EXPECT_LT(err, 1e-6);
  const TextureMap* base = out.materials.at(0).find(MapSlot::BaseColor);
  ASSERT_NE(base, nullptr);
  for (int t : inside)
    ASSERT_TRUE(std::equal(base->image.data.begin() + 4 * t, base->image.data.begin() + 4 * t + 3,
                           app.texture()->data.begin() + 4 * t)) << t;

  // Save, reopen: the same layout and texture.
  const auto project = dir.path / "atlas.adaptex";
  ASSERT_TRUE(app.save_project(project));
  Harness g({}, 256, "");
  g.app->open_project(project);
  ASSERT_TRUE(g.app->wait_idle(120));
  ASSERT_TRUE(g.app->on_artist_atlas());
  EXPECT_EQ(g.app->param()->uv, input.param.uv);
  EXPECT_EQ(max_abs_diff(*g.app->texture(), *app.texture()), 0);

  // A fresh unwrap keeps the stroke; a project without "layout" (written before it existed) opens
  // unwrapped, as it was painted.
  app.set_unwrap(true);
  ASSERT_TRUE(app.wait_idle(120));
  EXPECT_FALSE(app.on_artist_atlas());
  EXPECT_EQ(app.history().strokes().size(), 1u);
  EXPECT_NE(app.status_line().find("fresh unwrap"), std::string::npos) << app.status_line();
  std::string text = read_input_file(project);
  const auto at = text.find("\"layout\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find(',', at) - at + 1, "");
  std::ofstream(dir.path / "old.adaptex") << text;
  Harness old({}, 256, "");
  old.app->open_project(dir.path / "old.adaptex");
  ASSERT_TRUE(old.app->wait_idle(120));
  ASSERT_TRUE(old.app->has_model());
  EXPECT_FALSE(old.app->on_artist_atlas());
  EXPECT_EQ(old.app->history().strokes().size(), 1u);
}

/// Surface PSNR of \p texture on \p param against \p reference on \p ref_param, over the first
/// \p faces faces of \p mesh.
double psnr_against(const TriMesh& mesh, const Parameterization& ref_param, const ImageRGBA8& reference,
                    const Parameterization& param, const ImageRGBA8& texture, int faces) {
  TriMesh m = mesh;
  m.faces.resize(size_t(faces));
  auto first = [faces](Parameterization p) {
    p.uv_faces.resize(size_t(faces));
    p.face_chart.resize(size_t(faces));
    return p;
  };
  return surface_psnr(m, first(ref_param), reference, m, first(param), texture).psnr;
}

TEST(StudioAtlas, AdaptingTheArtistsAtlasKeepsSharedTexelsSharedFlipsNothingAndReconstructsBetter) {
  TempDir dir;
  const int n = 128;
  const auto obj = write_atlas_obj(dir.path, n, 0.5);  // charts on a quarter of the square
  {  // Detail in the texture too: a checker of 16 texels over the gradient.
    ImageRGBA8 tex = read_image(dir.path / "atlas.png");
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) tex.texel(i, j)[2] = (i / 16 + j / 16) % 2 ? 200 : 60;
    write_png(dir.path / "atlas.png", tex);
  }
  const TexturedAsset input = read_textured_asset(obj);
  std::vector<Stroke> strokes;
  for (int k = 0; k < 5; ++k) {  // thin lines on the shared square, finer than its texels
    Stroke st;
    st.color = Vec3(k % 2, 0.2 * k, 1 - k % 2);
    st.radius = 0.02;
    st.hardness = 1;
    for (int d = 0; d <= 60; ++d) st.dabs.push_back(Vec3(0.1 + 0.8 * d / 60.0, 0.1 + 0.18 * k, 0));
    strokes.push_back(st);
  }
  // Before: painted on the atlas as it is.
  Harness fixed({}, 256, obj.string());
  for (const Stroke& st : strokes) fixed.app->add_stroke(st);
  ASSERT_TRUE(fixed.app->wait_idle(60));
  const Parameterization atlas = *fixed.app->param();
  const ImageRGBA8 before = *fixed.app->texture();

  AppOptions with_recovery;
  with_recovery.recovery_dir = dir.path / "recovery";
  std::filesystem::create_directories(with_recovery.recovery_dir);
  Harness h(with_recovery, 256, obj.string(), AdaptMode::DensityFlow);
  App& app = *h.app;
  ASSERT_TRUE(app.on_artist_atlas());
  EXPECT_NE(app.atlas_adaptation().find("overlapping charts"), std::string::npos);
  for (const Stroke& st : strokes) app.add_stroke(st);
  ASSERT_TRUE(app.wait_idle(300));
  const Parameterization adapted = *app.param();
  ASSERT_NE(adapted.uv, atlas.uv) << "the atlas was kept";
  ASSERT_EQ(app.mesh()->num_faces(), input.mesh.num_faces());  // no face added
  const auto said = std::find_if(app.messages().begin(), app.messages().end(), [](const Message& m) {
    return m.text.find("adapted the artist's atlas") != std::string::npos;
  });
  ASSERT_NE(said, app.messages().end());
  EXPECT_NE(app.status_line().find("adapt the atlas (adapted)"), std::string::npos) << app.status_line();

  // Shared texels stay shared: corners that had one UV (the mirrored squares' shared chart) still do.
  const int F = app.mesh()->num_faces();
  int pairs = 0;
  for (int f = 0; f < F - 1; ++f)  // not the degenerate face (last): the library gives it an area
    for (int g = 0; g < F - 1; ++g)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          const Vec2 p = atlas.uv[size_t(atlas.uv_faces[f][a])], q = atlas.uv[size_t(atlas.uv_faces[g][b])];
          if ((f == g && a == b) || (p - q).norm() > 1e-12) continue;
          ++pairs;
          EXPECT_LT((adapted.uv[size_t(adapted.uv_faces[f][a])] - adapted.uv[size_t(adapted.uv_faces[g][b])]).norm(),
                    1e-9) << f << " " << g;
        }
  EXPECT_GE(pairs, 12);  // the two mirrored squares' corners, at least
  // No flips: every face with a UV area keeps its orientation (mirrored ones stay mirrored).
  auto signed_area = [](const Parameterization& p, int f) {
    const Vec2 a = p.uv[size_t(p.uv_faces[f][0])], b = p.uv[size_t(p.uv_faces[f][1])], c = p.uv[size_t(p.uv_faces[f][2])];
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  int oriented = 0;
  for (int f = 0; f < F; ++f) {
    if (std::abs(signed_area(atlas, f)) < 1e-9) continue;
    ++oriented;
    EXPECT_GT(signed_area(atlas, f) * signed_area(adapted, f), 0) << "face " << f << " flipped";
  }
  EXPECT_GE(oriented, 8);
  // Better: closer to the painting at 4x the size on the atlas than the atlas's own texture was (on
  // the faces with a UV area: the degenerate face shows one texel's colour, which a fit shares).
  const int m = 4 * n;
  Painter fine(*app.mesh(), atlas, PainterOptions{m, m, 4}, app.history().background());
  {
    const ImageRGBA8 base = read_image(dir.path / "atlas.png");
    std::vector<Vec3f> colours(fine.texel_map().inside.size());
    for (size_t k = 0; k < colours.size(); ++k) {
      const int t = fine.texel_map().inside[k];
      colours[k] = sample_bilinear(base, (t % m + 0.5) / m, (t / m + 0.5) / m).cast<float>();
    }
    fine.fill_colours(colours);
  }
  for (const Stroke& st : strokes) fine.paint_stroke(st);
  const double psnr_before = psnr_against(*app.mesh(), atlas, fine.texture(), atlas, before, F - 1);
  const double psnr_after = psnr_against(*app.mesh(), atlas, fine.texture(), adapted, *app.texture(), F - 1);
  EXPECT_GT(psnr_after, psnr_before + 0.5) << psnr_before << " -> " << psnr_after;

  const ImageRGBA8 adapted_texture = *app.texture();
  // Save, reopen: the same layout and texture (the layout is a function of the history).
  const auto project = dir.path / "adapted.adaptex";
  ASSERT_TRUE(app.save_project(project));
  {
    Harness g({}, 256, "");
    g.app->open_project(project);
    ASSERT_TRUE(g.app->wait_idle(300));
    ASSERT_TRUE(g.app->on_artist_atlas());
    EXPECT_EQ(g.app->param()->uv, adapted.uv);
    EXPECT_EQ(max_abs_diff(*g.app->texture(), adapted_texture), 0);
  }
  // Export GLB: the adapted UVs, corner by corner.
  const auto glb = dir.path / "adapted.glb";
  app.export_glb(glb);
  const TexturedAsset out = read_textured_asset(glb);
  ASSERT_EQ(out.mesh.num_faces(), F);
  double err = 0;
  for (int f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k)
      err = std::max(err, (out.param.uv[size_t(out.param.uv_faces[f][k])] - adapted.uv[size_t(adapted.uv_faces[f][k])]).norm());
  EXPECT_LT(err, 1e-6);
  // Undo every stroke: back on the atlas as it was, with the artist's texture.
  for (size_t k = 0; k < strokes.size(); ++k) app.undo();
  ASSERT_TRUE(app.wait_idle(300));
  EXPECT_EQ(app.param()->uv, atlas.uv);
  // Redo: adapted again, to the same layout.
  for (size_t k = 0; k < strokes.size(); ++k) app.redo();
  ASSERT_TRUE(app.wait_idle(300));
  EXPECT_EQ(app.param()->uv, adapted.uv);
  EXPECT_EQ(max_abs_diff(*app.texture(), adapted_texture), 0);
  // Left unsaved (undo and redo), then recovered: adapted again to the same layout.
  ASSERT_TRUE(app.unsaved());
  h.app.reset();
  Harness r(with_recovery, 256, "");
  ASSERT_TRUE(r.app->recovery_offer());
  r.app->accept_recovery();
  ASSERT_TRUE(r.app->wait_idle(300));
  ASSERT_TRUE(r.app->on_artist_atlas());
  EXPECT_EQ(r.app->param()->uv, adapted.uv);
  EXPECT_EQ(max_abs_diff(*r.app->texture(), adapted_texture), 0);
}

TEST(StudioAtlas, AnAtlasAdaptedOnRequestReopensAdaptedToTheSameStrokesAndAnAdaptationCanBeCancelled) {
  TempDir dir;
  const auto obj = write_atlas_obj(dir.path, 128, 0.5);
  Harness h({}, 256, "", AdaptMode::DensityFlow);
  App& app = *h.app;
  app.session_options().schedule = ReparamSchedule::End;  // adapts only when asked
  app.open_mesh(obj.string());
  ASSERT_TRUE(app.wait_idle(60));
  Stroke st;
  st.color = Vec3(1, 0, 0);
  st.radius = 0.02;
  st.hardness = 1;
  for (int d = 0; d <= 40; ++d) st.dabs.push_back(Vec3(0.1 + 0.02 * d, 0.5, 0));
  app.add_stroke(st);
  ASSERT_TRUE(app.wait_idle(60));
  const Parameterization atlas = *app.param();
  app.request_adapt();
  ASSERT_TRUE(app.wait_idle(300));
  const Parameterization adapted = *app.param();
  ASSERT_NE(adapted.uv, atlas.uv);
  st.color = Vec3(0, 0, 1);  // painted on the adapted layout, not adapted to
  for (Vec3& d : st.dabs) d.y() = 0.3;
  app.add_stroke(st);
  ASSERT_TRUE(app.wait_idle(60));
  EXPECT_EQ(app.param()->uv, adapted.uv);
  const auto project = dir.path / "p.adaptex";
  ASSERT_TRUE(app.save_project(project));
  EXPECT_EQ(read_project(project).adapted_strokes, std::optional<size_t>(1));
  Harness g({}, 256, "");
  g.app->open_project(project);
  ASSERT_TRUE(g.app->wait_idle(300));
  EXPECT_EQ(g.app->history().strokes().size(), 2u);
  EXPECT_EQ(g.app->param()->uv, adapted.uv);
  EXPECT_EQ(max_abs_diff(*g.app->texture(), *app.texture()), 0);
  // A running adaptation can be cancelled: the layout stays, and it does not start again by itself.
  g.app->request_adapt();
  g.app->begin_frame();
  ASSERT_TRUE(g.app->adapting());
  g.app->cancel_adaptation();
  EXPECT_FALSE(g.app->adapting());
  ASSERT_TRUE(g.app->wait_idle(60));
  EXPECT_EQ(g.app->param()->uv, adapted.uv);
  EXPECT_NE(g.app->messages().back().text.find("adaptation cancelled"), std::string::npos);
  // A count beyond the strokes is refused with one line naming the file.
  std::string text = read_input_file(project);
  const auto at = text.find("\"adapted_strokes\": 1");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 20, "\"adapted_strokes\": 3");
  std::ofstream(dir.path / "bad.adaptex") << text;
  try {
    read_project(dir.path / "bad.adaptex");
    ADD_FAILURE() << "read";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.adaptex: \"adapted_strokes\""), std::string::npos) << e.what();
  }
}

TEST(StudioAtlas, AnAtlasThatNoNewLayoutBeatsIsKeptAndTheUserIsTold) {
  TempDir dir;
  const auto obj = write_atlas_obj(dir.path);
  {  // Texel-sized noise: any resampling of it loses more than a new layout could win.
    ImageRGBA8 tex(64, 64, {0, 0, 0, 255});
    std::uint32_t h = 12345;
    for (size_t k = 0; k < tex.data.size(); ++k)
      if (k % 4 != 3) h = h * 1664525u + 1013904223u, tex.data[k] = std::uint8_t(h >> 24);
    write_png(dir.path / "atlas.png", tex);
  }
  Stroke st;  // a broad, soft stroke: no detail finer than the texels
  st.color = Vec3(0.9, 0.5, 0.1);
  st.radius = 0.4;
  st.hardness = 0;
  st.opacity = 0.5;
  st.dabs = {Vec3(0.3, 0.5, 0), Vec3(0.7, 0.5, 0)};
  Harness fixed({}, 256, obj.string());
  fixed.app->add_stroke(st);
  ASSERT_TRUE(fixed.app->wait_idle(60));
  Harness h({}, 256, obj.string(), AdaptMode::DensityFlow);
  h.app->add_stroke(st);
  ASSERT_TRUE(h.app->wait_idle(300));
  EXPECT_EQ(h.app->param()->uv, fixed.app->param()->uv);
  EXPECT_EQ(max_abs_diff(*h.app->texture(), *fixed.app->texture()), 0);
  const auto said = std::find_if(h.app->messages().begin(), h.app->messages().end(), [](const Message& m) {
    return m.text.find("kept the artist's atlas") != std::string::npos;
  });
  EXPECT_NE(said, h.app->messages().end());
  EXPECT_NE(h.app->status_line().find("adapt the atlas (kept as it was)"), std::string::npos) << h.app->status_line();
}

TEST(StudioAtlas, AProjectWhoseTextureIsGoneOpensUnwrappedSayingWhyAndKeepsItsStrokesAndLayout) {
  TempDir dir;
  const auto obj = write_atlas_obj(dir.path);
  Harness h({}, 256, obj.string());
  ASSERT_TRUE(h.app->on_artist_atlas());
  Stroke st;
  st.color = Vec3(1, 0, 0);
  st.radius = 0.1;
  st.dabs = {Vec3(0.25, 0.4, 0), Vec3(0.25, 0.6, 0)};
  h.app->add_stroke(st);
  ASSERT_TRUE(h.app->wait_idle(60));
  const auto project = dir.path / "p.adaptex";
  ASSERT_TRUE(h.app->save_project(project));

  // The texture is re-read from the model's files, not stored in the project.
  const auto png = dir.path / "atlas.png", aside = dir.path / "aside.png";
  std::filesystem::rename(png, aside);
  Harness g({}, 256, "");
  g.app->open_project(project);
  ASSERT_TRUE(g.app->wait_idle(120));
  ASSERT_TRUE(g.app->has_model());
  EXPECT_FALSE(g.app->on_artist_atlas());
  EXPECT_EQ(g.app->history().strokes().size(), 1u);
  const auto said = std::find_if(g.app->messages().begin(), g.app->messages().end(),
                                 [](const Message& m) { return m.text.find("atlas.png") != std::string::npos; });
  ASSERT_NE(said, g.app->messages().end());
  EXPECT_NE(said->text.find("fresh unwrap"), std::string::npos) << said->text;
  // Saved again meanwhile, the project still asks for the atlas: back with the texture, it opens on it.
  ASSERT_TRUE(g.app->save_project(project));
  EXPECT_NE(read_input_file(project).find("\"layout\": \"atlas\""), std::string::npos);
  std::filesystem::rename(aside, png);
  Harness back({}, 256, "");
  back.app->open_project(project);
  ASSERT_TRUE(back.app->wait_idle(120));
  EXPECT_TRUE(back.app->on_artist_atlas());
  EXPECT_EQ(back.app->history().strokes().size(), 1u);
  EXPECT_EQ(max_abs_diff(*back.app->texture(), *h.app->texture()), 0);
}

TEST(StudioApp, AutosaveIsOfferedAsRecoveryNextTime) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path;
  opt.autosave_delay = 0.1;
  {
    Harness h(opt);
    h.drag(150, 150, 250, 150);
    run_frames_until_exists(*h.app, dir.path / "recovery.json");
    ASSERT_TRUE(std::filesystem::exists(dir.path / "recovery.json"));
    EXPECT_TRUE(h.app->unsaved());
  }
  // Leaving without saving or discarding keeps the unsaved stroke recoverable.
  ASSERT_TRUE(std::filesystem::exists(dir.path / "recovery.json"));
  Harness g(opt, 256, "");
  ASSERT_TRUE(g.app->recovery_offer());
  EXPECT_EQ(g.app->recovery_offer()->project.mesh_path, "builtin:sphere");
  EXPECT_EQ(g.app->recovery_offer()->project.strokes.strokes.size(), 1u);
  g.app->accept_recovery();
  ASSERT_TRUE(g.app->wait_idle(120));
  EXPECT_EQ(g.app->history().strokes().size(), 1u);
  EXPECT_EQ(g.app->mesh_path(), "builtin:sphere");
  EXPECT_TRUE(g.app->unsaved());  // recovered work is not saved work
  // Saving removes the recovery files.
  ASSERT_TRUE(g.app->save_project(dir.path / "p.json"));
  EXPECT_FALSE(g.app->unsaved());
  EXPECT_FALSE(std::filesystem::exists(dir.path / "recovery.json"));
  EXPECT_FALSE(std::filesystem::exists(dir.path / "recovery.offered.json"));
}

TEST(StudioApp, RecoveredStrokesCanBeSavedWhileTheirModelLoads) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path;
  Project rec;
  rec.mesh_path = "builtin:sphere";
  Stroke s;
  s.dabs = {Vec3(0, 0, 1), Vec3(0.1, 0, 0.99)};
  rec.strokes.strokes = {s};
  write_project(dir.path / "recovery.json", rec);
  Harness h(opt, 256, "");
  ASSERT_TRUE(h.app->recovery_offer());
  h.app->accept_recovery();
  ASSERT_FALSE(h.app->has_model());  // loading: the stroke waits for its model
  ASSERT_TRUE(h.app->unsaved());
  const auto path = dir.path / "p.json";
  ASSERT_TRUE(h.app->save_project(path));
  EXPECT_EQ(read_project(path).strokes.strokes.size(), 1u);
  EXPECT_FALSE(h.app->unsaved());
  ASSERT_TRUE(h.app->wait_idle(120));
  ASSERT_EQ(h.app->history().strokes().size(), 1u);
  EXPECT_FALSE(h.app->unsaved());  // still saved once the model is there
  EXPECT_EQ(h.app->project_path(), path);
}

TEST(StudioApp, BadFilesShowAnErrorAndKeepTheModel) {
  TempDir dir;
  Harness h;
  const std::string good = h.app->mesh_path();
  h.app->clear_messages();
  h.app->open_mesh((dir.path / "missing.obj").string());
  ASSERT_TRUE(h.app->wait_idle(30));
  ASSERT_FALSE(h.app->messages().empty());
  EXPECT_TRUE(h.app->messages().back().error);
  EXPECT_NE(h.app->messages().back().text.find("missing.obj"), std::string::npos);
  std::ofstream(dir.path / "junk.obj") << "v 0 0 0\nf 1 2 3\nthis is not an obj\n";
  h.app->open_mesh((dir.path / "junk.obj").string());
  ASSERT_TRUE(h.app->wait_idle(30));
  EXPECT_TRUE(h.app->messages().back().error);
  EXPECT_EQ(h.app->mesh_path(), good);
  h.app->on_drop({(dir.path / "nope.json").string()});
  EXPECT_TRUE(h.app->messages().back().error);
}

/// The last message is an error naming \p name.
void expect_error_naming(const App& app, const std::string& name) {
  ASSERT_FALSE(app.messages().empty());
  EXPECT_TRUE(app.messages().back().error);
  EXPECT_NE(app.messages().back().text.find(name), std::string::npos) << app.messages().back().text;
}

TEST(StudioApp, BadDroppedJsonFilesNameTheFileAndChangeNothing) {
  TempDir dir;
  Harness h;
  h.drag(150, 150, 250, 150);
  ASSERT_EQ(h.app->history().strokes().size(), 1u);
  const auto drop = [&](const std::filesystem::path& p) {
    h.app->clear_messages();
    h.app->on_drop({p.string()});
    EXPECT_FALSE(h.app->confirm());
    EXPECT_FALSE(h.app->load_running());
    EXPECT_EQ(h.app->history().strokes().size(), 1u);
  };
  drop(dir.path / "missing.json");
  expect_error_naming(*h.app, "missing.json");
  std::filesystem::create_directory(dir.path / "folder.json");
  drop(dir.path / "folder.json");
  expect_error_naming(*h.app, "folder.json");
  ASSERT_EQ(mkfifo((dir.path / "pipe.json").c_str(), 0600), 0);
  drop(dir.path / "pipe.json");  // a FIFO: an error at once, not a UI thread waiting for a writer
  expect_error_naming(*h.app, "pipe.json");
  std::ofstream(dir.path / "junk.json") << "{\"format\": \"adaptex.strokes\", ";
  drop(dir.path / "junk.json");
  expect_error_naming(*h.app, "junk.json");
  std::ofstream(dir.path / "list.json") << "[1, 2, 3]";
  drop(dir.path / "list.json");
  expect_error_naming(*h.app, "list.json");
  std::ofstream(dir.path / "bad_stroke.json")
      << R"({"format": "adaptex.strokes", "version": 1, "strokes": [{"type": "brush", "dabs": []}]})";
  drop(dir.path / "bad_stroke.json");
  expect_error_naming(*h.app, "bad_stroke.json");
}

TEST(StudioApp, SaveAsToAnUnwritablePlaceKeepsTheWorkAndLeavesNoFile) {
  TempDir dir;
  Harness h;
  h.drag(150, 150, 250, 150);
  const auto good = dir.path / "p.json";
  ASSERT_TRUE(h.app->save_project(good));
  const std::string saved = read_input_file(good);
  h.drag(200, 100, 200, 200);
  ASSERT_TRUE(h.app->unsaved());
  std::ofstream(dir.path / "file") << "a regular file";
  for (const std::filesystem::path& bad : {dir.path / "file" / "p.json", dir.path, std::filesystem::path("/proc/p.json")}) {
    h.app->clear_messages();
    EXPECT_FALSE(h.app->save_project(bad)) << bad;
    expect_error_naming(*h.app, bad.string());
    EXPECT_TRUE(h.app->unsaved()) << bad;
    EXPECT_EQ(h.app->project_path(), good) << bad;  // Save still writes to the last good file
  }
  EXPECT_EQ(read_input_file(good), saved);  // untouched by the failed attempts
  EXPECT_FALSE(std::filesystem::exists("/proc/p.json"));
  std::vector<std::string> left;
  for (const auto& e : std::filesystem::directory_iterator(dir.path)) left.push_back(e.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"file", "p.json"}));  // no temporary left behind
  ASSERT_TRUE(h.app->save());
  EXPECT_EQ(read_project(good).strokes.strokes.size(), 2u);
}

TEST(StudioProject, FilesInsideTheProjectFolderAreRelativeSoTheFolderCanMove) {
  TempDir dir;
  const auto folder = dir.path / "work", shared = dir.path / "library";
  std::filesystem::create_directories(folder / "decals");
  std::filesystem::create_directories(shared);
  write_png(folder / "decals" / "inside.png", ImageRGBA8(8, 8, {200, 30, 30, 255}));
  write_png(shared / "outside.png", ImageRGBA8(8, 8, {30, 30, 200, 255}));
  const auto decal = [](const std::filesystem::path& img) {
    Stroke s;
    s.type = Stroke::Type::Decal;
    s.image_path = img.string();
    s.image = read_image(img);
    s.camera.eye = Vec3(0, 0, 3);
    return s;
  };
  Project p;
  p.mesh_path = (folder / "model.obj").string();
  p.strokes.strokes = {decal(folder / "decals" / "inside.png"), decal(shared / "outside.png")};
  p.material = material_from_v1(p.strokes);
  write_project(folder / "work.adaptex", p);
  const std::string text = read_input_file(folder / "work.adaptex");
  EXPECT_NE(text.find("\"mesh\": \"model.obj\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"decals/inside.png\""), std::string::npos);
  EXPECT_EQ(text.find((folder / "decals").string()), std::string::npos);  // no absolute path into the folder
  EXPECT_NE(text.find((shared / "outside.png").string()), std::string::npos);

  // The folder moved: the project finds its mesh and decal there, and the library where it was.
  const auto moved = dir.path / "moved";
  std::filesystem::rename(folder, moved);
  const Project q = read_project(moved / "work.adaptex");
  EXPECT_EQ(q.mesh_path, (moved / "model.obj").string());
  ASSERT_EQ(q.strokes.strokes.size(), 2u);
  EXPECT_EQ(q.strokes.strokes[0].image_path, (moved / "decals" / "inside.png").string());
  EXPECT_EQ(q.strokes.strokes[0].image.data, p.strokes.strokes[0].image.data);
  EXPECT_EQ(q.strokes.strokes[1].image_path, (shared / "outside.png").string());
  ASSERT_TRUE(q.material);
  EXPECT_EQ(q.material->layers[0].strokes[0].decal.image_path, (moved / "decals" / "inside.png").string());
  EXPECT_EQ(q.material->layers[0].strokes[1].decal.image_path, (shared / "outside.png").string());
  // Saved again one folder up, the same files are named relative to that folder.
  write_project(dir.path / "elsewhere.adaptex", q);
  const Project r = read_project(dir.path / "elsewhere.adaptex");
  EXPECT_EQ(r.mesh_path, q.mesh_path);
  EXPECT_EQ(r.strokes.strokes[0].image_path, q.strokes.strokes[0].image_path);
  EXPECT_NE(read_input_file(dir.path / "elsewhere.adaptex").find("\"moved/model.obj\""), std::string::npos);
}

TEST(StudioProject, NumbersBeyondAnIntAreClampedAndNotConverted) {
  // fuzz_project (session 8, after 9.1 M executions): "texture_size": 5166...62 (a float of 1e123)
  // was converted straight to int, undefined behaviour (UBSan), in practice INT_MIN -> 16.
  TempDir dir;
  const auto p = dir.path / "p.json";
  std::ofstream(p) << R"({"format": "adaptex.studio-project", "version": 1, "mesh": "builtin:torus",
    "strokes": {"format": "adaptex.strokes", "version": 1, "strokes": []},
    "brush": {"tool": 1e40, "symmetry_axis": -1e300},
    "adapt": {"texture_size": 5166666666666666666666666666666666666666666666666666666666666666662,
              "fine_grid": -1e300, "coarse_grid": 1e19, "padding": 3.9}})";
  const Project pr = read_project(p);
  EXPECT_EQ(pr.session.texture_size, kMaxTextureSize);
  EXPECT_EQ(pr.session.adapt.thesis.fine_grid, 2);
  EXPECT_EQ(pr.session.adapt.thesis.coarse_grid, kMaxGridCells);
  EXPECT_EQ(pr.session.padding, 3);
  EXPECT_EQ(pr.brush.tool, Tool::Eyedropper);
  EXPECT_EQ(pr.brush.symmetry_axis, -1);
  std::ofstream(p) << R"({"format": "adaptex.studio-project", "version": 1, "mesh": "builtin:torus",
    "strokes": {"format": "adaptex.strokes", "version": 1, "strokes": []}, "adapt": {"texture_size": "big"}})";
  EXPECT_THROW(read_project(p), InvalidInputError);
}

TEST(StudioApp, ProjectWithABadBrushIsAnErrorAndKeepsTheModel) {
  // Such a brush used to be accepted and then throw out of the first drag (a crash of the window).
  TempDir dir;
  Harness h;
  const std::string good = h.app->mesh_path();
  for (const char* brush : {R"({"opacity": 7})", R"({"radius": -1})", R"({"hardness": 2})",
                            R"({"color": [0, 2, 0]})"}) {
    const auto p = dir.path / "p.json";
    std::ofstream(p) << R"({"format": "adaptex.studio-project", "version": 1, "mesh": "builtin:torus",
      "strokes": {"format": "adaptex.strokes", "version": 1, "strokes": []}, "brush": )"
                     << brush << "}";
    h.app->clear_messages();
    h.app->open_project(p);
    expect_error_naming(*h.app, p.string() + ": brush");
    ASSERT_TRUE(h.app->wait_idle(60));
    EXPECT_EQ(h.app->mesh_path(), good) << brush;
    h.drag(150, 150, 250, 150);  // the brush is still the old one: painting works
  }
  EXPECT_EQ(h.app->history().strokes().size(), 4u);
  // A camera that cannot show anything is refused too.
  const auto p = dir.path / "cam.json";
  std::ofstream(p) << R"({"format": "adaptex.studio-project", "version": 1, "mesh": "builtin:torus",
    "strokes": {"format": "adaptex.strokes", "version": 1, "strokes": []}, "camera": {"distance": 0}})";
  h.app->open_project(p);
  expect_error_naming(*h.app, p.string() + ": camera");
}

TEST(StudioApp, LoadingCanBeCancelled) {
  Harness h({}, 256, "");
  h.app->open_mesh("builtin:trefoil");
  h.app->cancel_load();
  ASSERT_TRUE(h.app->wait_idle(60));
  EXPECT_FALSE(h.app->has_model());
}

TEST(StudioApp, AdaptsInTheBackgroundWhilePaintingContinues) {
  Harness h;
  h.app->session_options().adapt.mode = AdaptMode::TwoStage;
  h.app->session_options().adapt.thesis.fine_grid = 64;
  h.app->brush().radius = 0.05;
  h.app->brush().hardness = 0.9;
  const auto serial = h.app->surface_serial();
  h.drag(150, 150, 250, 150);
  h.app->begin_frame();  // starts the re-parameterization job
  // A second stroke while the job may still run: painted at once (the texture changes now).
  const int updates = h.renderer->texture_updates;
  h.app->brush().color = Vec3(0.1, 0.1, 0.9);
  h.drag(200, 100, 200, 200);
  EXPECT_GT(h.renderer->texture_updates + h.renderer->texture_uploads, updates);
  ASSERT_TRUE(h.app->wait_idle(300));
  EXPECT_GT(h.app->surface_serial(), serial);
  EXPECT_FALSE(h.app->last_cycle().empty());
  ASSERT_NE(h.app->adapt_maps(), nullptr);
  EXPECT_EQ(h.app->history().strokes().size(), 2u);
  const Parameterization& p = *h.app->param();
  int flipped = 0;
  for (int f = 0; f < int(p.uv_faces.size()); ++f) flipped += uv_signed_area(p, f) <= 0;
  EXPECT_EQ(flipped, 0);
  EXPECT_LE(max_abs_diff(*h.app->texture(), replay_texture(*h.app)), 1);
}

TEST(StudioApp, DecalFromTheViewAndExports) {
  TempDir dir;
  Harness h;
  ImageRGBA8 img(16, 16, {20, 200, 40, 255});
  write_png(dir.path / "d.png", img);
  const ImageRGBA8 before = *h.app->texture();
  std::filesystem::copy_file(dir.path / "d.png", dir.path / "D.PNG");
  h.app->on_drop({(dir.path / "D.PNG").string()});  // an image in any case of extension is a decal
  ASSERT_TRUE(h.app->decal_image());
  EXPECT_FALSE(h.app->load_running());
  h.app->load_decal(dir.path / "d.png");
  h.app->project_decal(1.0);
  ASSERT_TRUE(h.app->wait_idle(60));
  ASSERT_EQ(h.app->history().strokes().size(), 1u);
  const Stroke& s = h.app->history().strokes()[0];
  EXPECT_EQ(s.type, Stroke::Type::Decal);
  EXPECT_LT((s.camera.eye - h.app->camera().eye()).norm(), 1e-12);
  EXPECT_GT(max_abs_diff(before, *h.app->texture()), 100);
  EXPECT_EQ(max_abs_diff(*h.app->texture(), replay_texture(*h.app)), 0);
  // The surface point under the centre of the view got the decal colour.
  const auto hit = h.app->pick(200, 150);
  ASSERT_TRUE(hit);
  EXPECT_LT((h.app->sample_colour(*hit) - Vec3(20, 200, 40) / 255.0).norm(), 0.02);

  h.app->export_obj(dir.path / "out");
  h.app->export_glb(dir.path / "out" / "m.glb");
  h.app->save_history(dir.path / "h.json");
  int objs = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path / "out"))
    objs += e.path().extension() == ".obj" || e.path().extension() == ".mtl" || e.path().extension() == ".png";
  EXPECT_EQ(objs, 3);
  EXPECT_GT(std::filesystem::file_size(dir.path / "out" / "m.glb"), 1000u);
  const StrokeFile back = load_strokes(dir.path / "h.json");
  ASSERT_EQ(back.strokes.size(), 1u);
  EXPECT_EQ(back.strokes[0].type, Stroke::Type::Decal);
}

// ---- brush size and stencil (Blender's Texture Paint conventions) -----------------------------

TEST(StudioBrush, ScreenSpaceRadiusKeepsItsSizeOnScreenWhileZooming) {
  Harness h;
  BrushSettings& b = h.app->brush();
  b.screen_space = true;
  b.pixel_radius = 20;
  h.app->on_cursor(200, 150);
  auto c = h.app->brush_cursors();
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].radius, 20, 1e-9);
  EXPECT_NEAR(c[0].centre.x(), 200, 1e-9);
  const double world_far = h.app->world_radius();
  h.app->on_scroll(4);  // zoom in
  h.app->on_cursor(200, 150);
  c = h.app->brush_cursors();
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0].radius, 20, 1e-9);           // the same on the screen ...
  const double world_near = h.app->world_radius();
  EXPECT_LT(world_near, world_far * 0.8);       // ... so smaller on the model
  // A stroke records the world radius of its first dab's depth: 20 pixels there.
  h.drag(200, 150, 230, 150);
  ASSERT_EQ(h.app->history().strokes().size(), 1u);
  const Stroke& s = h.app->history().strokes()[0];
  EXPECT_NEAR(s.radius, 20 * h.app->camera().pixel_size_at(s.dabs.front()), 1e-9);
  // World-space mode: the circle grows on the screen when zooming in.
  b.screen_space = false;
  h.app->on_cursor(200, 150);
  const double before = h.app->brush_cursors().at(0).radius;
  h.app->on_scroll(2);
  h.app->on_cursor(200, 150);
  EXPECT_GT(h.app->brush_cursors().at(0).radius, before * 1.2);
}

TEST(StudioBrush, BracketsAndFResizeChangeTheActiveRadiusAndEscapeCancels) {
  Harness h;
  BrushSettings& b = h.app->brush();
  b.screen_space = true;
  b.pixel_radius = 20;
  h.app->on_key(']', true, {});
  EXPECT_NEAR(b.pixel_radius, 23, 1e-9);
  h.app->on_key('[', true, {});
  EXPECT_NEAR(b.pixel_radius, 20, 1e-9);
  // F: the circle stays, its radius follows the cursor; a left click keeps it and paints nothing.
  h.app->on_cursor(200, 150);
  h.app->on_key('F', true, {});
  ASSERT_TRUE(h.app->resizing_brush());
  EXPECT_NEAR(h.app->brush_cursors().at(0).centre.x(), 180, 1e-9);
  h.app->on_cursor(240, 150);
  EXPECT_NEAR(b.pixel_radius, 60, 1e-9);
  EXPECT_NEAR(h.app->brush_cursors().at(0).radius, 60, 1e-9);
  h.click(240, 150);
  EXPECT_FALSE(h.app->resizing_brush());
  EXPECT_NEAR(b.pixel_radius, 60, 1e-9);
  EXPECT_TRUE(h.app->history().strokes().empty());
  // Escape restores the radius from before the resize.
  h.app->on_key('F', true, {});
  h.app->on_cursor(300, 150);
  EXPECT_GT(b.pixel_radius, 100);
  h.app->on_key(keys::Escape, true, {});
  EXPECT_FALSE(h.app->resizing_brush());
  EXPECT_NEAR(b.pixel_radius, 60, 1e-9);
  // World-space mode: F sets the radius so that it is that many pixels on the model.
  b.screen_space = false;
  h.app->on_cursor(200, 150);
  const auto hit = h.app->pick(200, 150);
  ASSERT_TRUE(hit);
  h.app->on_key('F', true, {});
  const double cx = h.app->brush_cursors().at(0).centre.x();
  h.app->on_cursor(cx + 50, 150);
  h.app->on_key('F', true, {});  // F again keeps it
  EXPECT_FALSE(h.app->resizing_brush());
  EXPECT_NEAR(h.app->world_radius() / h.app->camera().pixel_size_at(hit->point), 50, 1e-6);
}

TEST(StudioBrush, NoCursorCircleOverTheUi) {
  Harness h;
  h.app->on_cursor(200, 150);
  EXPECT_EQ(h.app->brush_cursors().size(), 1u);
  h.app->set_ui_capture(true, false);
  EXPECT_TRUE(h.app->brush_cursors().empty());
  h.app->set_ui_capture(false, false);
  h.app->brush().tool = Tool::Eyedropper;
  EXPECT_TRUE(h.app->brush_cursors().empty());
}

TEST(StudioStencil, RightDragsMoveScaleAndRotateTheStencilAndOnlyItsRegionIsPainted) {
  TempDir dir;
  Harness h;
  write_png(dir.path / "d.png", ImageRGBA8(32, 16, {20, 200, 40, 255}));
  h.app->load_decal(dir.path / "d.png");
  ASSERT_TRUE(h.app->stencil());
  EXPECT_TRUE(h.app->history().strokes().empty());  // loading projects nothing
  const Stencil fitted = *h.app->stencil();
  EXPECT_NEAR(fitted.centre.x(), 200, 1e-9);
  EXPECT_NEAR(fitted.aspect, 2.0, 1e-12);
  const double yaw = h.app->camera().yaw;
  auto right_drag = [&](double x0, double y0, double x1, double y1, Mods m) {
    h.app->on_cursor(x0, y0);
    h.app->on_mouse_button(MouseButton::Right, true, m);
    h.app->on_cursor((x0 + x1) / 2, (y0 + y1) / 2);
    h.app->on_cursor(x1, y1);
    h.app->on_mouse_button(MouseButton::Right, false, m);
  };
  right_drag(200, 150, 150, 130, {});  // move
  EXPECT_NEAR(h.app->stencil()->centre.x(), 150, 1e-9);
  EXPECT_NEAR(h.app->stencil()->centre.y(), 130, 1e-9);
  EXPECT_EQ(h.app->camera().yaw, yaw);  // no orbit while a stencil is shown
  right_drag(190, 130, 170, 130, Mods{true, false, false});  // Shift: scale by 20/40
  EXPECT_NEAR(h.app->stencil()->height, fitted.height * 0.5, 1e-9);
  right_drag(190, 130, 150, 90, Mods{false, true, false});  // Ctrl: rotate by 90 degrees
  EXPECT_NEAR(h.app->stencil()->angle, 3.14159265358979 / 2, 1e-9);
  EXPECT_TRUE(h.app->history().strokes().empty());
  // P projects it; the surface under the preview gets the decal, nothing outside it.
  h.app->on_key('P', true, {});
  ASSERT_TRUE(h.app->wait_idle(60));
  ASSERT_EQ(h.app->history().strokes().size(), 1u);
  const Stencil& st = *h.app->stencil();
  int inside = 0, outside = 0, inside_unpainted = 0, outside_painted = 0;
  for (int y = 20; y < 290; y += 6)
    for (int x = 20; x < 390; x += 6) {
      const auto hit = h.app->pick(x, y);
      if (!hit) continue;
      const bool green = (h.app->sample_colour(*hit) - Vec3(20, 200, 40) / 255.0).norm() < 0.05;
      const bool white = (h.app->sample_colour(*hit) - Vec3(1, 1, 1)).norm() < 0.05;
      // Away from the outline (texture filtering, seams): inside green, outside unpainted.
      Stencil smaller = st, larger = st;
      smaller.height *= 0.85, larger.height *= 1.15;
      const bool in = smaller.contains(h.app->camera(), x, y), out = !larger.contains(h.app->camera(), x, y);
      inside += in;
      outside += out;
      inside_unpainted += in && !green;
      outside_painted += out && !white;
    }
  EXPECT_GT(inside, 20);
  EXPECT_GT(outside, 200);
  EXPECT_EQ(inside_unpainted, 0);
  EXPECT_EQ(outside_painted, 0);
  // The stencil is rotated by 90 degrees: taller than wide on the screen (the image is 2:1).
  const auto c = st.corners(h.app->camera());
  EXPECT_GT(std::abs(c[1].y() - c[0].y()), 2.5 * std::abs(c[1].x() - c[0].x()));
  // Without a stencil a right drag orbits again.
  h.app->clear_decal();
  right_drag(200, 150, 260, 150, {});
  EXPECT_NE(h.app->camera().yaw, yaw);
}

// ---- file dialogs -------------------------------------------------------------------------------

TEST(StudioFiles, InAppBrowserListsFoldersFirstThenMatchingFilesInAnyCase) {
  TempDir dir;
  std::filesystem::create_directories(dir.path / "b_meshes");
  std::filesystem::create_directories(dir.path / "A_old");
  std::filesystem::create_directories(dir.path / ".hidden");
  for (const char* f : {"cow.OBJ", "bunny.ply", "notes.txt", "a.obj", ".secret.obj", "pic.png"})
    std::ofstream(dir.path / f) << "x";
  const auto mesh = list_folder(dir.path, file_request(FileKind::OpenMesh).extensions);
  std::vector<std::string> names;
  for (const auto& e : mesh) names.push_back(e.name + (e.folder ? "/" : ""));
  EXPECT_EQ(names, (std::vector<std::string>{"A_old/", "b_meshes/", "a.obj", "bunny.ply", "cow.OBJ"}));
  const auto images = list_folder(dir.path, file_request(FileKind::LoadImage).extensions);
  ASSERT_EQ(images.size(), 3u);
  EXPECT_EQ(images[2].name, "pic.png");
  EXPECT_TRUE(list_folder(dir.path / "missing", {}).empty());  // unreadable: empty, no throw
  EXPECT_TRUE(file_request(FileKind::SaveProject).save);
  EXPECT_TRUE(file_request(FileKind::ExportObjFolder).folder);
  EXPECT_FALSE(file_request(FileKind::OpenProject).save);
}

// ---- layout ------------------------------------------------------------------------------------

TEST(StudioApp, AnotherModelIsFramedFromTheFrontAndTheStatusLineForgetsTheLastCycle) {
  Harness h({}, 256, "builtin:sphere", studio_session_options().adapt.mode);
  h.app->brush().radius = 0.05;
  h.drag(150, 150, 250, 160);
  ASSERT_TRUE(h.app->wait_idle(300));
  EXPECT_NE(h.app->status_line().find("last cycle"), std::string::npos) << h.app->status_line();
  h.app->camera().orbit(120, 40);
  ASSERT_NE(h.app->camera().yaw, 0);
  h.app->open_mesh("builtin:torus");
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_EQ(h.app->camera().yaw, 0);  // from the front (+Z)
  EXPECT_EQ(h.app->camera().pitch, 0);
  EXPECT_EQ(h.app->status_line().find("last cycle"), std::string::npos) << h.app->status_line();
  EXPECT_NE(h.app->status_line().find("torus"), std::string::npos);
}

TEST(StudioApp, F1TogglesTheShortcutsAndEveryCommandKeyIsListed) {
  Harness h;
  h.app->on_key(keys::F1, true, {});
  EXPECT_TRUE(h.app->view().show_help);
  h.app->on_key(keys::F1, true, {});
  EXPECT_FALSE(h.app->view().show_help);
  // Every single-key command appears in the help's list of keys.
  std::string listed;
  for (const Shortcut& s : shortcuts()) listed += std::string(s.keys) + " ";
  for (char k : std::string("[]FBEIPCLW")) {
    ASSERT_NE(key_command(k, {}), Command::None) << k;
    EXPECT_NE(listed.find(k), std::string::npos) << k;
  }
}

// ---- making the adaptation visible ------------------------------------------------------------

TEST(StudioView, CheckerKeyTurnsTheTexelDensityCheckerOnAndOff) {
  Harness h;
  h.app->render();
  EXPECT_FALSE(h.renderer->last_view.checker);
  h.app->on_key('C', true, {});
  h.app->render();
  EXPECT_TRUE(h.renderer->last_view.checker);
  h.app->on_key('C', true, {});
  h.app->render();
  EXPECT_FALSE(h.renderer->last_view.checker);
}

TEST(StudioView, LKeyShowsTheFixedLayoutAtTheSameTextureSizeAndBack) {
  Harness h({}, 256, "builtin:sphere", studio_session_options().adapt.mode);  // the default method
  h.app->brush().radius = 0.05;
  h.drag(150, 150, 250, 160);
  ASSERT_TRUE(h.app->wait_idle(300));
  ASSERT_NE(h.app->adapt_maps(), nullptr);  // the layout adapted to the stroke
  h.app->on_key('L', true, {});
  for (int k = 0; k < 3000 && !h.app->showing_fixed_layout(); ++k) {
    h.app->begin_frame();
    h.app->render();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(h.app->showing_fixed_layout());
  const Comparison* c = h.app->comparison();
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->fixed_texture.width, 256);  // the same texture size
  EXPECT_EQ(max_abs_diff(h.renderer->last_texture, c->fixed_texture), 0);
  EXPECT_EQ(h.renderer->last_wedges, c->fixed_param->num_wedges());
  EXPECT_NE(h.app->status_line().find("FIXED layout"), std::string::npos);
  // L again: the adaptive layout and its texture are sent again.
  h.app->on_key('L', true, {});
  h.app->render();
  EXPECT_FALSE(h.app->showing_fixed_layout());
  EXPECT_EQ(h.renderer->last_faces, h.app->mesh()->num_faces());
  EXPECT_EQ(h.renderer->last_wedges, h.app->param()->num_wedges());
  EXPECT_EQ(max_abs_diff(h.renderer->last_texture, *h.app->texture()), 0);
  // Painting returns to the adaptive layout.
  h.app->on_key('L', true, {});
  h.drag(160, 120, 200, 120);
  EXPECT_FALSE(h.app->view().fixed_layout);
}

// ---- the library's options, and the same result as adaptex paint ------------------------------

TEST(StudioApp, AdaptsByDefaultWithTheLibrarysDefaultMethod) {
  App app(std::make_unique<NullRenderer>(), {});
  const PaintSessionOptions& o = app.session_options();
  const AdaptOptions lib;
  EXPECT_EQ(o.adapt.mode, lib.mode);
  EXPECT_EQ(o.adapt.mode, AdaptMode::DensityFlow);
  EXPECT_EQ(o.adapt.thesis.alpha, lib.thesis.alpha);
  EXPECT_EQ(o.adapt.thesis.beta, lib.thesis.beta);
  EXPECT_EQ(o.adapt.thesis.geometry_scale, lib.thesis.geometry_scale);
  EXPECT_EQ(o.adapt.thesis.fine_grid, lib.thesis.fine_grid);
  EXPECT_EQ(o.adapt.refine.enabled, lib.refine.enabled);
  EXPECT_EQ(o.texture_size, PaintSessionOptions{}.texture_size);
  EXPECT_EQ(o.padding, PaintSessionOptions{}.padding);
  EXPECT_EQ(o.schedule, ReparamSchedule::EachStroke);
}

TEST(StudioApp, EveryReparameterizationStartsFromTheInitialLayout) {
  Harness h({}, 128, "builtin:sphere", AdaptMode::DensityFlow);
  const Parameterization initial = *h.app->param();
  h.app->brush().radius = 0.03;
  h.app->brush().hardness = 0.9;
  h.drag(150, 150, 250, 150);
  ASSERT_TRUE(h.app->wait_idle(300));
  ASSERT_NE(h.app->adapt_maps(), nullptr);
  const Parameterization first = *h.app->param();
  const auto first_mesh = std::make_shared<const TriMesh>(*h.app->mesh());  // refined or not
  h.app->brush().color = Vec3(0.1, 0.1, 0.9);
  h.drag(200, 100, 200, 200);
  ASSERT_TRUE(h.app->wait_idle(300));
  // The layout is one re-parameterization of the whole history from the initial layout ...
  const auto sphere = std::make_shared<const TriMesh>(shapes::sphere(64, 32, 1.0));  // builtin:sphere
  const SessionOutcome fresh = paint_history(sphere, initial, h.app->history().to_file(), h.app->session_options(), {});
  EXPECT_EQ(h.app->mesh()->faces, fresh.mesh->faces);
  EXPECT_EQ(h.app->param()->uv, fresh.param->uv);
  EXPECT_EQ(max_abs_diff(*h.app->texture(), fresh.canvas->texture()), 0);
  // ... which is also what PaintSession's each-stroke schedule gives after these strokes ...
  PaintSessionOptions each = h.app->session_options();
  each.schedule = ReparamSchedule::EachStroke;
  each.min_gain_db = 0;  // a cycle after every stroke (none skipped): each layout is end mode's
  PaintSession session(*sphere, initial, each, h.app->history().background());
  for (const Stroke& s : h.app->history().strokes()) session.add_stroke(s);
  EXPECT_EQ(h.app->param()->uv, session.param().uv);
  EXPECT_EQ(max_abs_diff(*h.app->texture(), session.texture()), 0);
  // ... which adapted (it is not the initial layout), and is not the first layout warped again.
  EXPECT_NE(h.app->param()->uv, initial.uv);
  const SessionOutcome composed =
      paint_history(first_mesh, first, h.app->history().to_file(), h.app->session_options(), {});
  EXPECT_NE(composed.param->uv, fresh.param->uv);
  // The refined mesh is shaded with the sphere's smooth normals (not flat inside each input face).
  ASSERT_GT(h.app->mesh()->num_faces(), sphere->num_faces());
  h.app->render();
  const TriMesh& refined = *h.app->mesh();
  ASSERT_EQ(h.renderer->last_normals.size(), refined.positions.size());
  double worst = 0;
  for (size_t v = 0; v < refined.positions.size(); ++v)
    worst = std::max(worst, (h.renderer->last_normals[v] - refined.positions[v].normalized()).norm());
  EXPECT_LT(worst, 0.02);
  // The layout is a function of the history: undo gives back the first stroke's layout and mesh.
  h.app->undo();
  ASSERT_TRUE(h.app->wait_idle(300));
  EXPECT_EQ(h.app->mesh()->faces, first_mesh->faces);
  EXPECT_EQ(h.app->param()->uv, first.uv);
  EXPECT_EQ(max_abs_diff(*h.app->texture(), replay_texture(*h.app)), 0);
}

TEST(StudioApp, AdaptationWhilePaintingKeepsOneSessionAndSettlesOnEndModesLayout) {
  Harness h({}, 128, "builtin:sphere", AdaptMode::DensityFlow);
  // Every cycle after a stroke stops at the gate (no layout is predicted to gain 100 dB): the layout
  // changes only when the session settles.
  h.app->session_options().min_gain_db = 100;
  const Parameterization initial = *h.app->param();
  h.app->brush().radius = 0.03;
  h.app->brush().hardness = 0.9;
  h.drag(150, 150, 250, 150);
  const LiveAdaptation* live = h.app->live_adaptation();  // started by the stroke's frame
  ASSERT_NE(live, nullptr);
  const Vec3 colours[] = {Vec3(0.1, 0.1, 0.9), Vec3(0.9, 0.2, 0.1), Vec3(0.1, 0.7, 0.2)};
  for (int k = 0; k < 3; ++k) {  // painted while the session may still adapt to the last one
    h.app->brush().color = colours[k];
    h.drag(160 + 20 * k, 100, 200 - 10 * k, 210);
  }
  // Every stroke went to the same session: fed to it, not replayed from the initial layout again.
  EXPECT_EQ(h.app->live_adaptation(), live);
  EXPECT_EQ(live->fed(), 4u);
  // Without a script asking (wait_idle), it settles by itself once no stroke has come for
  // LiveAdaptation::kSettleDelay; until then the layout is the initial one.
  const auto t0 = std::chrono::steady_clock::now();
  int frames_before = 0, adapted_before = 0;  // frames before it settled; of those, not on the initial layout
  while (!live->settled() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120)) {
    h.app->begin_frame();
    const bool settled = live->settled();  // a settled surface may already be shown
    frames_before += !settled;
    adapted_before += !settled && h.app->param()->uv != initial.uv;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(live->settled());
  EXPECT_GT(frames_before, 10);
  EXPECT_EQ(adapted_before, 0);
  EXPECT_GE(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
            0.9 * LiveAdaptation::kSettleDelay);
  ASSERT_TRUE(h.app->wait_idle(300));
  EXPECT_EQ(h.app->live_adaptation(), live);
  EXPECT_EQ(live->adapted(), 4u);
  EXPECT_GE(live->cycles(), 2);  // a gated cycle and the settle at least
  EXPECT_LE(live->cycles(), 5);  // at most one per stroke, and the settle
  // Settled: end mode's layout and texture for the history, as a rebuild from the initial layout gives.
  const auto sphere = std::make_shared<const TriMesh>(shapes::sphere(64, 32, 1.0));  // builtin:sphere
  const SessionOutcome fresh = paint_history(sphere, initial, h.app->history().to_file(), h.app->session_options(), {});
  EXPECT_EQ(h.app->mesh()->faces, fresh.mesh->faces);
  EXPECT_EQ(h.app->param()->uv, fresh.param->uv);
  EXPECT_NE(h.app->param()->uv, initial.uv);  // it adapted
  EXPECT_EQ(max_abs_diff(*h.app->texture(), fresh.canvas->texture()), 0);
  // Undo rewrites the history: a session for the new one, which settles on its end mode layout.
  h.app->undo();
  ASSERT_TRUE(h.app->wait_idle(300));
  ASSERT_NE(h.app->live_adaptation(), nullptr);
  EXPECT_EQ(h.app->live_adaptation()->fed(), 3u);
  const SessionOutcome three = paint_history(sphere, initial, h.app->history().to_file(), h.app->session_options(), {});
  EXPECT_EQ(h.app->param()->uv, three.param->uv);
  EXPECT_EQ(max_abs_diff(*h.app->texture(), three.canvas->texture()), 0);
}

TEST(StudioApp, ExportingWhileAdaptationRunsSaysSo) {
  TempDir dir;
  Harness h({}, 128, "builtin:sphere", AdaptMode::DensityFlow);
  h.app->session_options().min_gain_db = 100;  // unsettled until the session settles (gated cycles)
  h.app->brush().radius = 0.03;
  h.drag(150, 150, 250, 150);
  const LiveAdaptation* live = h.app->live_adaptation();
  ASSERT_NE(live, nullptr);
  ASSERT_FALSE(live->settled());
  h.app->clear_messages();
  h.app->export_glb(dir.path / "m.glb");
  EXPECT_TRUE(std::filesystem::exists(dir.path / "m.glb"));  // what was shown
  ASSERT_EQ(h.app->messages().size(), 2u);
  EXPECT_NE(h.app->messages().back().text.find("still running"), std::string::npos);
  ASSERT_TRUE(h.app->wait_idle(300));
  h.app->clear_messages();
  h.app->export_glb(dir.path / "m2.glb");
  ASSERT_EQ(h.app->messages().size(), 1u);  // only "exported ..."
}

TEST(StudioApp, TurningAfterEveryStrokeOffDropsTheLiveSession) {
  Harness h({}, 128, "builtin:sphere", AdaptMode::DensityFlow);
  h.app->brush().radius = 0.03;
  h.drag(150, 150, 250, 150);
  ASSERT_NE(h.app->live_adaptation(), nullptr);
  const auto serial = h.app->surface_serial();
  h.app->session_options().schedule = ReparamSchedule::End;
  h.app->session_options_changed();
  h.app->begin_frame();
  EXPECT_EQ(h.app->live_adaptation(), nullptr);
  ASSERT_TRUE(h.app->wait_idle(300));
  EXPECT_EQ(h.app->surface_serial(), serial);  // nothing it computed is swapped in
  EXPECT_EQ(max_abs_diff(*h.app->texture(), replay_texture(*h.app)), 0);
}

TEST(StudioApp, SameLayoutAndTextureAsAdaptexPaint) {
  TempDir dir;
  const auto mesh_path = dir.path / "ball.obj";
  TriMesh second = shapes::sphere(24, 12, 0.5);
  for (Vec3& p : second.positions) p += Vec3(0, 0, -2.5);  // behind the first ball: two charts
  write_obj(mesh_path, shapes::disjoint_union({shapes::sphere(48, 24, 1.0), second}), nullptr);
  // Loaded for a 512² texture, then switched to 256²: unwrapped again with the gutter of 256² (as
  // `adaptex paint --size 256` unwraps), keeping the (empty) history.
  Harness h({}, 512, mesh_path.string(), studio_session_options().adapt.mode);
  const int charts_512 = h.app->param()->num_charts;
  const std::vector<Vec2> uv_512 = h.app->param()->uv;
  h.app->session_options().texture_size = 256;
  h.app->session_options_changed();
  ASSERT_TRUE(h.app->wait_idle(120));
  ASSERT_EQ(charts_512, 2);
  EXPECT_NE(h.app->param()->uv, uv_512);
  EXPECT_FALSE(h.app->unsaved());
  EXPECT_EQ(h.app->mesh_path(), std::filesystem::absolute(mesh_path).lexically_normal().string());
  h.app->render();
  h.app->brush().radius = 0.03;
  h.drag(150, 150, 250, 160);
  ASSERT_TRUE(h.app->wait_idle(300));
  h.app->brush().color = Vec3(0.1, 0.6, 0.2);
  h.drag(190, 90, 210, 210);
  ASSERT_TRUE(h.app->wait_idle(300));
  ASSERT_NE(h.app->adapt_maps(), nullptr);  // adaptation ran after the strokes
  h.app->save_history(dir.path / "h.json");
  h.app->export_obj(dir.path / "studio");
  const auto r = test::run_cli("paint '" + mesh_path.string() + "' --strokes '" + (dir.path / "h.json").string() +
                               "' --size 256 -o '" + (dir.path / "cli").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const TexturedMesh a = read_textured_obj(dir.path / "studio" / "ball.obj");
  const TexturedMesh b = read_textured_obj(dir.path / "cli" / "ball.obj");
  EXPECT_EQ(a.mesh.faces, b.mesh.faces);
  EXPECT_EQ(a.mesh.positions, b.mesh.positions);
  EXPECT_EQ(a.param.uv, b.param.uv);
  EXPECT_EQ(a.param.uv_faces, b.param.uv_faces);
  EXPECT_EQ(max_abs_diff(read_image(dir.path / "studio" / "ball.png"), read_image(dir.path / "cli" / "ball.png")), 0);
}

TEST(StudioApp, ComparisonWithoutAdaptationFindsTheSameTextureTwice) {
  // Without adaptation the "adaptive" texture is the fixed one: the comparison paints the same
  // texture on the initial layout (same size, paper colour and seam padding, here not the default).
  Harness h({}, 128);
  h.app->session_options().padding = 7;
  h.app->session_options_changed();
  ASSERT_TRUE(h.app->wait_idle(120));
  h.app->render();
  h.app->set_background_colour(Vec3(0.2, 0.4, 0.6));
  h.app->brush().radius = 0.1;
  h.drag(100, 150, 300, 160);
  ASSERT_TRUE(h.app->wait_idle(120));
  h.app->request_compare();
  for (int k = 0; k < 2000 && !h.app->comparison(); ++k) {
    h.app->begin_frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const Comparison* c = h.app->comparison();
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->strokes, 1u);
  EXPECT_EQ(c->fixed_param, c->adaptive_param);
  EXPECT_EQ(max_abs_diff(c->fixed_texture, c->adaptive_texture), 0);
  EXPECT_EQ(max_abs_diff(c->fixed_texture, replay_texture(*h.app)), 0);
  EXPECT_EQ(c->psnr_fixed, c->psnr_adaptive);
}

// ---- never lose work -------------------------------------------------------------------------

TEST(StudioApp, QuitWithUnsavedStrokesAsksAndCancelKeepsRunning) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path;
  opt.autosave_delay = 0;
  Harness h(opt);
  EXPECT_FALSE(h.app->unsaved());
  h.drag(150, 150, 250, 150);
  EXPECT_TRUE(h.app->unsaved());
  run_frames_until_exists(*h.app, dir.path / "recovery.json");
  ASSERT_TRUE(std::filesystem::exists(dir.path / "recovery.json"));
  h.app->on_key('Q', true, Mods{false, true, false});  // Ctrl+Q
  ASSERT_TRUE(h.app->confirm());
  EXPECT_EQ(h.app->confirm()->action, Confirm::Action::Quit);
  EXPECT_FALSE(h.app->should_quit());
  h.app->confirm_cancel();
  EXPECT_FALSE(h.app->confirm());
  EXPECT_FALSE(h.app->should_quit());
  EXPECT_EQ(h.app->history().strokes().size(), 1u);
  EXPECT_TRUE(std::filesystem::exists(dir.path / "recovery.json"));
  h.app->request_quit();
  ASSERT_TRUE(h.app->confirm());
  h.app->confirm_discard();
  EXPECT_TRUE(h.app->should_quit());
  EXPECT_FALSE(std::filesystem::exists(dir.path / "recovery.json"));  // an explicit Discard removes it
}

TEST(StudioApp, OpeningAnotherMeshOrProjectWithUnsavedStrokesAsks) {
  TempDir dir;
  Harness h;
  h.drag(150, 150, 250, 150);
  h.app->request_open_mesh("builtin:torus");
  ASSERT_TRUE(h.app->confirm());
  EXPECT_EQ(h.app->confirm()->action, Confirm::Action::OpenMesh);
  EXPECT_FALSE(h.app->load_running());  // nothing happens before the answer
  ASSERT_TRUE(h.app->confirm_save(dir.path / "a.json"));
  EXPECT_TRUE(std::filesystem::exists(dir.path / "a.json"));
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_EQ(h.app->mesh_path(), "builtin:torus");
  EXPECT_TRUE(h.app->history().strokes().empty());
  EXPECT_FALSE(h.app->unsaved());

  h.drag(150, 150, 250, 150);
  ASSERT_EQ(h.app->history().strokes().size(), 1u);
  h.app->request_open_project(dir.path / "a.json");
  ASSERT_TRUE(h.app->confirm());
  EXPECT_EQ(h.app->confirm()->action, Confirm::Action::OpenProject);
  EXPECT_FALSE(h.app->confirm_save(dir.path));  // a folder: the save fails and the question stays
  ASSERT_TRUE(h.app->confirm());
  h.app->confirm_discard();
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_EQ(h.app->mesh_path(), "builtin:sphere");
  EXPECT_EQ(h.app->history().strokes().size(), 1u);  // the project's stroke
  EXPECT_FALSE(h.app->unsaved());

  h.app->request_new();  // nothing unsaved: no question
  EXPECT_FALSE(h.app->confirm());
  EXPECT_FALSE(h.app->has_model());
}

TEST(StudioApp, TextureSizeChangeKeepsTheHistoryAndAnotherMeshDoesNot) {
  Harness h;
  h.drag(150, 150, 250, 150);
  h.app->session_options().texture_size = 128;  // unwraps again for 128², keeping the stroke
  h.app->session_options_changed();
  h.app->begin_frame();
  ASSERT_TRUE(h.app->load_running());
  h.drag(200, 100, 200, 200);  // painted on the old surface while the re-unwrap runs
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_EQ(h.app->history().strokes().size(), 2u);
  EXPECT_EQ(h.app->texture()->width, 128);
  EXPECT_TRUE(h.app->unsaved());
  EXPECT_EQ(max_abs_diff(*h.app->texture(), replay_texture(*h.app)), 0);
  h.app->session_options().texture_size = 256;
  h.app->session_options_changed();
  h.app->begin_frame();
  ASSERT_TRUE(h.app->load_running());
  h.app->open_mesh("builtin:torus");  // replaces the re-unwrap: a fresh model, no strokes
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_EQ(h.app->mesh_path(), "builtin:torus");
  EXPECT_TRUE(h.app->history().strokes().empty());
}

TEST(StudioApp, SaveAsThenSaveWritesTheProjectFile) {
  TempDir dir;
  Harness h;
  h.drag(150, 150, 250, 150);
  EXPECT_FALSE(h.app->save());  // no project file yet: Save As first
  const auto path = dir.path / "p.json";
  ASSERT_TRUE(h.app->save_project(path));
  EXPECT_FALSE(h.app->unsaved());
  h.drag(200, 100, 200, 200);
  EXPECT_TRUE(h.app->unsaved());
  h.app->on_key('S', true, Mods{false, true, false});  // Ctrl+S
  EXPECT_FALSE(h.app->unsaved());
  EXPECT_EQ(read_project(path).strokes.strokes.size(), 2u);
}

// ---- recovery files ----------------------------------------------------------------------------

/// A recovery file as a session that was killed leaves it: \p n strokes on \p mesh, belonging to
/// \p project, with a texture size and a brush colour of its own.
Project crashed_session(const std::string& mesh, const std::filesystem::path& project, int n) {
  Project p;
  p.mesh_path = mesh;
  p.project_file = project.string();
  for (int k = 0; k < n; ++k) {
    Stroke s;
    s.color = Vec3(0.1, 0.2 + 0.1 * k, 0.9);
    s.radius = 0.1;
    s.dabs = {Vec3(0, 0, 1), Vec3(0.1 * (k + 1), 0, 0.99)};
    p.strokes.strokes.push_back(s);
  }
  p.session.texture_size = 128;
  p.brush.color = Vec3(0.3, 0.6, 0.1);
  return p;
}

std::string slurp(const std::filesystem::path& p) { return read_input_file(p); }

TEST(StudioRecovery, OpeningItsMeshOffersItAndRecoverKeepsProjectPathMeshAndSettings) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path / "rec";
  std::filesystem::create_directories(opt.recovery_dir);
  const Project crashed = crashed_session("builtin:sphere", dir.path / "work.adaptex", 2);
  write_project(opt.recovery_dir / "recovery.json", crashed);
  Harness h(opt, 256, "builtin:sphere");  // started with the model the strokes belong to
  const RecoveryOffer* o = h.app->recovery_offer();
  ASSERT_TRUE(o);
  EXPECT_EQ(recovery_owner(o->project), (dir.path / "work.adaptex").string());  // the project names it
  EXPECT_EQ(h.app->current_file(), "builtin:sphere");
  h.app->on_key('R', true, {});  // Recover
  EXPECT_FALSE(h.app->recovery_offer());
  ASSERT_TRUE(h.app->wait_idle(120));
  ASSERT_EQ(h.app->history().strokes().size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(h.app->history().strokes()[k].dabs, crashed.strokes.strokes[k].dabs);
    EXPECT_EQ(h.app->history().strokes()[k].color, crashed.strokes.strokes[k].color);
  }
  EXPECT_EQ(h.app->project_path(), dir.path / "work.adaptex");  // the project file is kept
  EXPECT_EQ(h.app->mesh_path(), "builtin:sphere");
  EXPECT_EQ(h.app->session_options().texture_size, 128);  // and the settings
  EXPECT_EQ(h.app->texture()->width, 128);
  EXPECT_EQ(h.app->brush().color, Vec3(0.3, 0.6, 0.1));
  EXPECT_TRUE(h.app->unsaved());
  // Save (Ctrl+S) writes the project file the strokes belong to, and the recovery file goes.
  h.app->on_key('S', true, Mods{false, true, false});
  EXPECT_EQ(read_project(dir.path / "work.adaptex").strokes.strokes.size(), 2u);
  EXPECT_FALSE(h.app->unsaved());
  EXPECT_FALSE(std::filesystem::exists(opt.recovery_dir / "recovery.json"));
}

TEST(StudioRecovery, AnotherMeshStillOffersItNamingItsFileAndRecoverOpensThatFile) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path;
  write_project(dir.path / "recovery.json", crashed_session("builtin:sphere", {}, 1));
  Harness h(opt, 256, "builtin:torus");
  const RecoveryOffer* o = h.app->recovery_offer();
  ASSERT_TRUE(o);
  EXPECT_EQ(recovery_owner(o->project), "builtin:sphere");  // no project: the mesh names it
  EXPECT_EQ(h.app->current_file(), "builtin:torus");
  h.app->accept_recovery();  // nothing unsaved on the torus: no question first
  EXPECT_FALSE(h.app->confirm());
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_EQ(h.app->mesh_path(), "builtin:sphere");
  EXPECT_EQ(h.app->history().strokes().size(), 1u);
  EXPECT_TRUE(h.app->project_path().empty());
  EXPECT_TRUE(h.app->unsaved());
}

TEST(StudioRecovery, RecoverAfterUnsavedWorkAsksFirstAndDiscardDeletesOnlyWhenAsked) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path;
  write_project(dir.path / "recovery.json", crashed_session("builtin:torus", {}, 1));
  Harness h(opt, 256, "builtin:sphere");
  h.drag(150, 150, 250, 150);  // unsaved work of this session
  ASSERT_TRUE(h.app->recovery_offer());
  h.app->accept_recovery();
  ASSERT_TRUE(h.app->confirm());  // Save / Discard / Cancel for the sphere's stroke first
  EXPECT_EQ(h.app->confirm()->action, Confirm::Action::Recover);
  h.app->on_key(keys::Escape, true, {});  // Cancel: nothing recovered, still offered
  EXPECT_FALSE(h.app->confirm());
  ASSERT_TRUE(h.app->recovery_offer());
  EXPECT_EQ(h.app->mesh_path(), "builtin:sphere");
  h.app->on_key('D', true, {});  // Discard the recovery file
  EXPECT_FALSE(h.app->recovery_offer());
  EXPECT_FALSE(std::filesystem::exists(dir.path / "recovery.json"));
  EXPECT_EQ(h.app->history().strokes().size(), 1u);  // this session's stroke is untouched
}

TEST(StudioRecovery, LaterKeepsTheFileAndOpeningOrDroppingItsMeshAsksAgain) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path / "rec";
  opt.autosave_delay = 0;
  std::filesystem::create_directories(opt.recovery_dir);
  const auto mesh = dir.path / "ball.obj";
  write_obj(mesh, shapes::sphere(24, 12), nullptr);
  write_project(opt.recovery_dir / "recovery.json", crashed_session(mesh.string(), {}, 3));
  const std::string before = slurp(opt.recovery_dir / "recovery.json");
  Harness h(opt, 256, "builtin:sphere");
  ASSERT_TRUE(h.app->recovery_offer());
  h.app->on_key(keys::Escape, true, {});  // Later
  EXPECT_FALSE(h.app->recovery_offer());
  // This session's own work is autosaved beside it, never over it.
  h.drag(150, 150, 250, 150);
  run_frames_until_exists(*h.app, opt.recovery_dir / "recovery-2.json");
  EXPECT_TRUE(std::filesystem::exists(opt.recovery_dir / "recovery-2.json"));
  EXPECT_EQ(slurp(opt.recovery_dir / "recovery.json"), before);
  h.app->request_new();
  ASSERT_TRUE(h.app->confirm());
  h.app->confirm_discard();
  EXPECT_FALSE(std::filesystem::exists(opt.recovery_dir / "recovery-2.json"));  // its own file only
  EXPECT_EQ(slurp(opt.recovery_dir / "recovery.json"), before);
  // Dropping the mesh the strokes belong to on the window asks again.
  h.app->on_drop({mesh.string()});
  ASSERT_TRUE(h.app->recovery_offer());
  EXPECT_EQ(h.app->recovery_offer()->project.mesh_path, mesh.string());
  EXPECT_EQ(h.app->current_file(), mesh.string());
  h.app->accept_recovery();
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_EQ(h.app->history().strokes().size(), 3u);
  EXPECT_EQ(h.app->mesh_path(), mesh.string());
}

TEST(StudioRecovery, RecoverNoLeavesTheFileUntouchedAndAutosavesBesideIt) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path;
  opt.recover = RecoverMode::No;
  write_project(dir.path / "recovery.json", crashed_session("builtin:sphere", {}, 2));
  const std::string before = slurp(dir.path / "recovery.json");
  {
    Harness h(opt, 256, "builtin:sphere");
    h.app->recover_at_start();
    EXPECT_FALSE(h.app->recovery_offer());
    EXPECT_TRUE(h.app->history().strokes().empty());
    h.drag(150, 150, 250, 150);
  }  // ends with an unsaved stroke: kept in its own file
  EXPECT_EQ(slurp(dir.path / "recovery.json"), before);
  ASSERT_TRUE(std::filesystem::exists(dir.path / "recovery-2.json"));
  EXPECT_EQ(read_project(dir.path / "recovery-2.json").strokes.strokes.size(), 1u);
  // Both are offered next time, the newest first.
  opt.recover = RecoverMode::Ask;
  Harness g(opt, 256, "");
  ASSERT_TRUE(g.app->recovery_offer());
  EXPECT_EQ(g.app->recovery_offer()->file, dir.path / "recovery-2.json");
  g.app->defer_recovery();
  ASSERT_TRUE(g.app->recovery_offer());
  EXPECT_EQ(g.app->recovery_offer()->file, dir.path / "recovery.json");
}

TEST(StudioRecovery, RecoverYesTakesTheNewestAtStart) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path;
  opt.recover = RecoverMode::Yes;
  write_project(dir.path / "recovery.json", crashed_session("builtin:torus", dir.path / "t.adaptex", 2));
  Harness h(opt, 256, "");
  h.app->recover_at_start();
  EXPECT_FALSE(h.app->recovery_offer());
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_EQ(h.app->mesh_path(), "builtin:torus");
  EXPECT_EQ(h.app->history().strokes().size(), 2u);
  EXPECT_EQ(h.app->project_path(), dir.path / "t.adaptex");
}

TEST(StudioRecovery, ARunningSessionsFileIsNeverOfferedAndTwoSessionsUseTwoFiles) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path;
  opt.autosave_delay = 0;
  Harness a(opt);
  a.drag(150, 150, 250, 150);
  run_frames_until_exists(*a.app, dir.path / "recovery.json");
  ASSERT_TRUE(std::filesystem::exists(dir.path / "recovery.json"));
  Harness b(opt);  // another window while the first one runs
  EXPECT_FALSE(b.app->recovery_offer());
  b.drag(150, 150, 250, 150);
  b.drag(150, 120, 250, 120);
  run_frames_until_exists(*b.app, dir.path / "recovery-2.json");
  ASSERT_TRUE(std::filesystem::exists(dir.path / "recovery-2.json"));
  a.app->begin_frame();
  EXPECT_EQ(read_project(dir.path / "recovery.json").strokes.strokes.size(), 1u);
}

TEST(StudioRecovery, AnUnreadableRecoveryFileIsKeptAsideNotOfferedEveryTime) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path;
  std::ofstream(dir.path / "recovery.json") << "{\"format\": \"adaptex.studio-proj";
  Harness h(opt, 256, "");
  EXPECT_FALSE(h.app->recovery_offer());
  EXPECT_TRUE(std::filesystem::exists(dir.path / "recovery.json.unreadable"));
  EXPECT_FALSE(std::filesystem::exists(dir.path / "recovery.json"));
}

TEST(StudioFiles, SaveAsAndExportSuggestTheMeshStemInTheLastFolderUsed) {
  TempDir dir;
  Harness h(AppOptions{}, 256, "");
  const auto mesh = dir.path / "models" / "ball.obj";
  std::filesystem::create_directories(mesh.parent_path());
  write_obj(mesh, shapes::sphere(24, 12), nullptr);
  h.app->open_mesh(mesh.string());
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_EQ(h.app->suggested_path(FileKind::SaveProject), mesh.parent_path() / "ball.adaptex");
  EXPECT_EQ(h.app->suggested_path(FileKind::ExportGlb), mesh.parent_path() / "ball.glb");
  std::filesystem::create_directories(dir.path / "out");
  h.app->export_glb(dir.path / "out" / "first.glb");
  EXPECT_EQ(h.app->last_folder(), dir.path / "out");
  EXPECT_EQ(h.app->suggested_path(FileKind::ExportGlb), dir.path / "out" / "ball.glb");
  EXPECT_EQ(h.app->suggested_path(FileKind::SaveProject), dir.path / "out" / "ball.adaptex");
  ASSERT_TRUE(h.app->save_project(dir.path / "p.adaptex"));
  EXPECT_EQ(h.app->suggested_path(FileKind::SaveProject), dir.path / "p.adaptex");  // the project file
  // A dropped .adaptex file is a project.
  h.app->request_new();
  h.app->on_drop({(dir.path / "p.adaptex").string()});
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_EQ(h.app->mesh_path(), mesh.string());
  EXPECT_EQ(h.app->project_path(), dir.path / "p.adaptex");
}

TEST(StudioCamera, WheelZoomsTowardsThePointUnderTheCursor) {
  Harness h;
  const double x = 250, y = 120;  // off-centre, on the sphere
  h.app->on_cursor(x, y);
  const auto before = h.app->pick(x, y);
  ASSERT_TRUE(before);
  const double d0 = h.app->camera().distance;
  for (int k = 0; k < 3; ++k) h.app->on_scroll(1);
  EXPECT_LT(h.app->camera().distance, d0 * 0.7);
  const Vec3 s = h.app->camera().project(before->point);
  EXPECT_NEAR(s.x(), x, 1e-4);  // the point stays under the cursor
  EXPECT_NEAR(s.y(), y, 1e-4);
  const auto after = h.app->pick(x, y);
  ASSERT_TRUE(after);
  EXPECT_LT((after->point - before->point).norm(), 1e-6);
  // Off the model: towards the point at the target's depth, which stays under the cursor too.
  const Vec3 p = h.app->camera().point_at_target_depth(5, 5);
  h.app->on_cursor(5, 5);
  h.app->on_scroll(-2);
  const Vec3 q = h.app->camera().project(p);
  EXPECT_NEAR(q.x(), 5, 1e-4);
  EXPECT_NEAR(q.y(), 5, 1e-4);
}

// ---- layered material -------------------------------------------------------------------------

MaterialStroke roughness_stroke(double value, const Vec3& at) {
  MaterialStroke m;
  m.channels = channel_bit(Channel::Roughness);
  m.value[channel_offset(Channel::Roughness)] = value;
  m.radius = 0.2;
  m.dabs = {at};
  return m;
}

TEST(StudioMaterial, LayerEditsAndStrokesUndoAndRedoExactly) {
  MaterialDocument d;
  ASSERT_EQ(d.num_layers(), 1);
  const std::string empty = material_strokes_json(d.file());
  d.add_stroke(roughness_stroke(0.1, Vec3(1, 0, 0)));
  d.add_layer("");
  EXPECT_EQ(d.num_layers(), 2);
  EXPECT_EQ(d.active(), 1);
  EXPECT_EQ(d.file().layers[1].name, "Layer 2");
  d.add_stroke(roughness_stroke(0.9, Vec3(0, 1, 0)));
  d.set_blend(1, BlendMode::Multiply);
  d.set_visible(1, false);
  d.set_opacity(1, 0.7);
  d.set_opacity(1, 0.5, true);  // a drag: one step
  d.set_opacity(1, 0.4, true);
  d.move_layer(1, 0);
  const std::string full = material_strokes_json(d.file());
  EXPECT_EQ(d.file().layers[0].name, "Layer 2");
  EXPECT_EQ(d.file().layers[0].blend, BlendMode::Multiply);
  EXPECT_FALSE(d.file().layers[0].visible);
  EXPECT_EQ(d.file().layers[0].opacity, 0.4);
  EXPECT_EQ(d.file().layers[1].strokes.size(), 1u);
  // Bad edits change nothing.
  EXPECT_THROW(d.set_opacity(0, 1.5), InvalidInputError);
  EXPECT_THROW(d.delete_layer(7), InvalidInputError);
  EXPECT_THROW(d.add_stroke(roughness_stroke(2.0, Vec3(0, 0, 1))), InvalidInputError);
  EXPECT_EQ(material_strokes_json(d.file()), full);
  int undone = 0;
  while (d.undo()) ++undone;
  EXPECT_EQ(undone, 7);  // 2 strokes, add, blend, visible, opacity (the drag continued it), move
  EXPECT_EQ(material_strokes_json(d.file()), empty);
  while (d.redo()) {
  }
  EXPECT_EQ(material_strokes_json(d.file()), full);
  d.delete_layer(0);
  EXPECT_EQ(d.num_layers(), 1);
  EXPECT_THROW(d.delete_layer(0), InvalidInputError);  // the last layer stays
}

/// The base colour the studio shows is the library's composite of its document on its layout.
void expect_view_is_the_composite(App& app) {
  ASSERT_TRUE(app.wait_idle(300));
  MaterialPaintOptions o;
  o.size = app.session_options().texture_size;
  o.padding = app.session_options().padding;
  const MaterialTextures t = paint_material(*app.mesh(), *app.param(), app.material_file(), o);
  EXPECT_EQ(max_abs_diff(*app.texture(), t.base_color), 0);
}

TEST(StudioMaterial, TheHistoryBecomesLayerOneAndTheBrushPaintsItsChannelsOnTheActiveLayer) {
  Harness h({}, 128);
  h.app->brush().radius = 0.3;
  h.drag(150, 150, 250, 150);  // base colour, one layer: the history
  ASSERT_TRUE(h.app->wait_idle(120));
  EXPECT_FALSE(h.app->layered());
  EXPECT_EQ(h.app->material_file().layers.size(), 1u);
  ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) { d.add_layer(""); }));
  ASSERT_TRUE(h.app->layered());
  EXPECT_TRUE(h.app->history().strokes().empty());
  const MaterialStrokeFile& f = h.app->material()->file();
  ASSERT_EQ(f.layers.size(), 2u);
  ASSERT_EQ(f.layers[0].strokes.size(), 1u);
  EXPECT_EQ(f.layers[0].strokes[0].channels, channel_bit(Channel::BaseColor));
  expect_view_is_the_composite(*h.app);
  // Roughness only on layer 2: the view's base colour does not change.
  const ImageRGBA8 before = *h.app->texture();
  h.app->brush().channels = channel_bit(Channel::Roughness);
  h.app->brush().roughness = 0.05;
  h.drag(150, 120, 250, 180);
  ASSERT_EQ(h.app->material()->file().layers[1].strokes.size(), 1u);
  const MaterialStroke& r = h.app->material()->file().layers[1].strokes[0];
  EXPECT_EQ(r.channels, channel_bit(Channel::Roughness));
  EXPECT_EQ(r.value[channel_offset(Channel::Roughness)], 0.05);
  expect_view_is_the_composite(*h.app);
  EXPECT_EQ(max_abs_diff(*h.app->texture(), before), 0);
  // Blue multiplied on layer 2 darkens the view; hiding layer 2 shows layer 1 alone again.
  h.app->brush().channels = channel_bit(Channel::BaseColor) | channel_bit(Channel::Roughness);
  h.app->brush().color = Vec3(0.1, 0.2, 0.9);
  ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) { d.set_blend(1, BlendMode::Multiply); }));
  h.drag(140, 150, 260, 150);
  expect_view_is_the_composite(*h.app);
  EXPECT_GT(max_abs_diff(*h.app->texture(), before), 100);
  ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) { d.set_visible(1, false); }));
  expect_view_is_the_composite(*h.app);
  EXPECT_EQ(max_abs_diff(*h.app->texture(), before), 0);
  h.app->undo();  // layer 2 visible again
  expect_view_is_the_composite(*h.app);
  EXPECT_GT(max_abs_diff(*h.app->texture(), before), 100);
  EXPECT_TRUE(h.app->unsaved());
}

TEST(StudioMaterial, StrokesGoToTheRunningMaterialSessionAndOtherEditsStartAnother) {
  Harness h({}, 128, "builtin:sphere", AdaptMode::DensityFlow);
  h.app->brush().radius = 0.2;
  h.app->brush().channels = channel_bit(Channel::BaseColor) | channel_bit(Channel::Roughness);
  h.app->brush().roughness = 0.1;
  ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) { d.add_layer(""); }));
  ASSERT_TRUE(h.app->wait_idle(300));
  ASSERT_NE(h.app->live_material(), nullptr);
  const int started = h.app->material_sessions_started();
  const int settles = h.app->live_material()->settles();
  for (int k = 0; k < 3; ++k) h.drag(140, 120 + 20 * k, 260, 130 + 20 * k);
  // The session composites the strokes incrementally (no settle yet): every channel of the surface
  // shown is the library's composite of the whole document on that surface's layout.
  MaterialPaintOptions o;
  o.size = 128;
  o.padding = h.app->session_options().padding;
  bool shown = false;
  for (int k = 0; k < 1500 && !shown; ++k) {
    h.app->begin_frame();
    const Surface* s = h.app->surface();
    if (s->material && !s->settled) {
      const MaterialTextures t = paint_material(*s->mesh, *s->param, h.app->material_file(), o);
      shown = max_abs_diff(s->material->base_color, t.base_color) == 0 &&
              max_abs_diff(s->material->roughness, t.roughness) == 0 && max_abs_diff(*h.app->texture(), t.base_color) == 0;
    }
    if (!shown) std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_TRUE(shown);
  EXPECT_EQ(h.app->live_material()->settles(), settles);
  EXPECT_EQ(h.app->material_sessions_started(), started);  // fed, not restarted
  // After the pause it settles on paint_material_history(): the export's textures.
  ASSERT_TRUE(h.app->wait_idle(300));
  EXPECT_TRUE(h.app->surface()->settled);
  EXPECT_GT(h.app->live_material()->settles(), settles);
  EXPECT_EQ(h.app->material_sessions_started(), started);
  expect_view_is_the_composite(*h.app);
  h.app->undo();  // rewrites the history: a new session
  EXPECT_EQ(h.app->material_sessions_started(), started + 1);
  expect_view_is_the_composite(*h.app);
  EXPECT_EQ(h.app->material()->file().layers[1].strokes.size(), 2u);
  // A stroke on a mask is fed too.
  ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) { d.add_mask(1, 1.0); }));
  ASSERT_TRUE(h.app->wait_idle(300));
  const int masked = h.app->material_sessions_started();
  h.app->brush().on_mask = true;
  h.app->brush().mask_value = 0;
  h.drag(150, 110, 250, 190);
  EXPECT_EQ(h.app->material_sessions_started(), masked);
  ASSERT_EQ(h.app->material()->file().layers[1].mask->strokes.size(), 1u);
  expect_view_is_the_composite(*h.app);
}

TEST(StudioMaterial, ProjectsAndRecoveryKeepTheLayersAndOldProjectsOpenAsOneLayer) {
  TempDir dir;
  AppOptions opt;
  opt.recovery_dir = dir.path;
  opt.autosave_delay = 0.1;
  std::string saved;
  {
    Harness h(opt, 128);
    h.app->brush().radius = 0.3;
    h.drag(150, 150, 250, 150);
    ASSERT_TRUE(h.app->wait_idle(120));
    ASSERT_TRUE(h.app->save_project(dir.path / "v1.adaptex"));  // a single-layer project: version 1
    h.app->brush().channels = channel_bit(Channel::Metallic);  // another channel: layered from here
    h.drag(150, 120, 250, 180);
    ASSERT_TRUE(h.app->layered());
    ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) {
      d.add_layer("Scratches");
      d.set_opacity(1, 0.6);
    }));
    h.app->brush().channels = channel_bit(Channel::Height);
    h.drag(160, 140, 240, 160);
    ASSERT_TRUE(h.app->save_project(dir.path / "m.adaptex"));
    EXPECT_FALSE(h.app->unsaved());
    saved = material_strokes_json(h.app->material()->file());
    h.app->brush().channels = channel_bit(Channel::BaseColor);
    h.drag(150, 200, 250, 200);  // unsaved: goes to the recovery file
    run_frames_until_exists(*h.app, dir.path / "recovery.json");
    ASSERT_TRUE(std::filesystem::exists(dir.path / "recovery.json"));
  }
  {
    Harness g({}, 128, "");
    g.app->open_project(dir.path / "m.adaptex");
    ASSERT_TRUE(g.app->wait_idle(120));
    ASSERT_TRUE(g.app->layered());
    EXPECT_EQ(material_strokes_json(g.app->material()->file()), saved);
    EXPECT_EQ(g.app->material()->active(), 1);
    EXPECT_EQ(g.app->brush().channels, channel_bit(Channel::Height));
    EXPECT_FALSE(g.app->unsaved());
    expect_view_is_the_composite(*g.app);
    g.app->open_project(dir.path / "v1.adaptex");
    ASSERT_TRUE(g.app->wait_idle(120));
    EXPECT_FALSE(g.app->layered());
    EXPECT_EQ(g.app->history().strokes().size(), 1u);
    EXPECT_EQ(g.app->material_file().layers.size(), 1u);
  }
  Harness r(opt, 128, "");
  ASSERT_TRUE(r.app->recovery_offer());
  r.app->accept_recovery();
  ASSERT_TRUE(r.app->wait_idle(120));
  ASSERT_TRUE(r.app->layered());
  EXPECT_EQ(r.app->material()->file().layers[1].strokes.size(), 2u);  // height, then the unsaved stroke
  EXPECT_TRUE(r.app->unsaved());
}

TEST(StudioMaterial, ExportIsAdaptexPaintsForTheSavedVersion2File) {
  TempDir dir;
  const auto mesh_path = dir.path / "ball.obj";
  write_obj(mesh_path, shapes::sphere(32, 16, 1.0), nullptr);
  Harness h({}, 256, mesh_path.string(), studio_session_options().adapt.mode);
  h.app->brush().radius = 0.05;
  h.drag(150, 150, 250, 160);
  ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) { d.add_layer(""); }));
  h.app->brush().channels = channel_bit(Channel::Roughness) | channel_bit(Channel::Height);
  h.drag(190, 90, 210, 210);
  ASSERT_TRUE(h.app->wait_idle(300));
  h.app->save_history(dir.path / "m.json");
  h.app->export_glb(dir.path / "studio.glb");
  h.app->export_obj(dir.path / "studio");
  const auto r = test::run_cli("paint '" + mesh_path.string() + "' --strokes '" + (dir.path / "m.json").string() +
                               "' --size 256 -o '" + (dir.path / "cli").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_input_file(dir.path / "studio.glb"), read_input_file(dir.path / "cli" / "ball.glb"));
  for (const char* f : {"ball.obj", "ball.png", "ball_roughness.png", "ball_metallic.png", "ball_normal.png",
                        "ball_height.png"})
    EXPECT_EQ(read_input_file(dir.path / "studio" / f), read_input_file(dir.path / "cli" / f)) << f;
}


TEST(StudioMaterial, QuitWaitsForAQueuedExportAndASecondQuitLeavesIt) {
  TempDir dir;
  const auto mesh_path = dir.path / "ball.obj";
  write_obj(mesh_path, shapes::sphere(32, 16, 1.0), nullptr);
  Harness h({}, 256, mesh_path.string(), studio_session_options().adapt.mode);
  h.app->brush().radius = 0.05;
  ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) { d.add_layer(""); }));
  h.app->brush().channels = channel_bit(Channel::Roughness) | channel_bit(Channel::Height);
  h.drag(190, 90, 210, 210);
  ASSERT_FALSE(h.app->idle());
  h.app->export_glb(dir.path / "a.glb");
  ASSERT_TRUE(h.app->exporting());
  h.app->request_quit();
  ASSERT_TRUE(h.app->confirm());  // the unsaved strokes are asked about first
  h.app->confirm_discard();
  EXPECT_FALSE(h.app->should_quit());  // the export is written first
  EXPECT_TRUE(h.app->exporting());
  for (const auto t0 = std::chrono::steady_clock::now();
       !h.app->should_quit() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(300);) {
    h.app->begin_frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_TRUE(h.app->should_quit());
  EXPECT_FALSE(h.app->exporting());
  EXPECT_TRUE(std::filesystem::exists(dir.path / "a.glb"));

  // A second close while waiting quits at once, and the dropped export is not written.
  Harness g({}, 256, mesh_path.string(), studio_session_options().adapt.mode);
  g.app->brush().radius = 0.05;
  ASSERT_TRUE(g.app->edit_material([](MaterialDocument& d) { d.add_layer(""); }));
  g.drag(190, 90, 210, 210);
  g.app->export_glb(dir.path / "b.glb");
  g.app->request_quit();
  g.app->confirm_discard();
  EXPECT_FALSE(g.app->should_quit());
  g.app->request_quit();
  EXPECT_TRUE(g.app->should_quit());
  EXPECT_FALSE(g.app->confirm());
  EXPECT_FALSE(std::filesystem::exists(dir.path / "b.glb"));
}

TEST(StudioMaterial, ExportBeforeTheSettleWaitsForTheWorkerAndWritesWhatAdaptexPaintWrites) {
  TempDir dir;
  const auto mesh_path = dir.path / "ball.obj";
  write_obj(mesh_path, shapes::sphere(32, 16, 1.0), nullptr);
  Harness h({}, 256, mesh_path.string(), studio_session_options().adapt.mode);
  h.app->brush().radius = 0.05;
  h.app->brush().channels = channel_bit(Channel::BaseColor) | channel_bit(Channel::Roughness);
  ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) { d.add_layer(""); }));
  h.drag(150, 150, 250, 160);
  ASSERT_TRUE(h.app->wait_idle(300));
  const int settles = h.app->live_material()->settles();
  h.app->brush().channels = channel_bit(Channel::Roughness) | channel_bit(Channel::Height);
  h.drag(190, 90, 210, 210);  // fed to the session, which would settle after the pause
  ASSERT_FALSE(h.app->idle());  // the surface shown is not the settled one of this document
  // Exports now return at once: nothing is computed or written on this thread, they wait for the
  // worker's settle (asked for now). The same file asked again is written once.
  h.app->clear_messages();
  h.app->export_glb(dir.path / "studio.glb");
  h.app->export_obj(dir.path / "studio");
  h.app->export_glb(dir.path / "studio.glb");
  EXPECT_TRUE(h.app->exporting());
  EXPECT_FALSE(std::filesystem::exists(dir.path / "studio.glb"));
  EXPECT_FALSE(std::filesystem::exists(dir.path / "studio"));
  EXPECT_EQ(h.app->live_material()->settles(), settles);
  ASSERT_EQ(h.app->messages().size(), 3u);
  EXPECT_NE(h.app->messages().back().text.find("waiting for the final layout"), std::string::npos);
  const auto p = h.app->progress();
  ASSERT_TRUE(p);
  EXPECT_EQ(p->first.rfind("Exporting... waiting for the final layout", 0), 0u) << p->first;
  // A stroke during the wait is composited first; the export is of the document with it.
  h.drag(140, 200, 260, 190);
  EXPECT_TRUE(h.app->exporting());
  int frames = 0;
  for (const auto t0 = std::chrono::steady_clock::now();
       h.app->exporting() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(300); ++frames) {
    EXPECT_FALSE(std::filesystem::exists(dir.path / "studio.glb"));  // until the settled result is shown
    h.app->begin_frame();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_FALSE(h.app->exporting());
  EXPECT_GT(frames, 1);
  EXPECT_TRUE(h.app->surface()->settled);
  EXPECT_GT(h.app->live_material()->settles(), settles);
  EXPECT_EQ(h.app->messages().size(), 5u);  // 3 waiting, then "exported" GLB and OBJ
  for (const Message& m : h.app->messages()) EXPECT_FALSE(m.error) << m.text;
  // The files are `adaptex paint`'s for the saved document, and what an export after the settle writes.
  h.app->save_history(dir.path / "m.json");
  h.app->export_glb(dir.path / "settled.glb");
  EXPECT_FALSE(h.app->exporting());
  const auto r = test::run_cli("paint '" + mesh_path.string() + "' --strokes '" + (dir.path / "m.json").string() +
                               "' --size 256 -o '" + (dir.path / "cli").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_input_file(dir.path / "studio.glb"), read_input_file(dir.path / "cli" / "ball.glb"));
  EXPECT_EQ(read_input_file(dir.path / "settled.glb"), read_input_file(dir.path / "cli" / "ball.glb"));
  for (const char* f : {"ball.obj", "ball.png", "ball_roughness.png", "ball_metallic.png", "ball_normal.png",
                        "ball_height.png"})
    EXPECT_EQ(read_input_file(dir.path / "studio" / f), read_input_file(dir.path / "cli" / f)) << f;
  EXPECT_EQ(h.app->material()->file().layers[1].strokes.size(), 3u);  // the stroke during the wait included
}

TEST(StudioMaterial, MasksAndFillsAreUndoableEditsOfTheDocument) {
  MaterialDocument d;
  d.add_stroke(roughness_stroke(0.1, Vec3(1, 0, 0)));
  const std::string before = material_strokes_json(d.file());
  MaterialStroke fill;
  fill.type = MaterialStroke::Type::Fill;
  fill.channels = channel_bit(Channel::Metallic);
  fill.value[channel_offset(Channel::Metallic)] = 0.8;
  d.add_stroke(fill);
  EXPECT_THROW(d.add_mask_stroke(roughness_stroke(0, Vec3(0, 0, 1))), InvalidInputError);  // no mask yet
  d.add_mask(0, 1);
  EXPECT_THROW(d.add_mask(0, 1), InvalidInputError);
  MaterialStroke m = roughness_stroke(0.5, Vec3(0, 1, 0));
  m.channels = 0;
  m.mask_value = 0.25;
  d.add_mask_stroke(m);
  m.mask_value = 2;  // out of [0,1]: refused, nothing changes
  EXPECT_THROW(d.add_mask_stroke(m), InvalidInputError);
  MaterialStroke mask_fill = fill;
  mask_fill.channels = 0;
  mask_fill.mask_value = 0;
  d.add_mask_stroke(mask_fill);
  const MaterialLayer& l = d.file().layers[0];
  ASSERT_TRUE(l.mask.has_value());
  ASSERT_EQ(l.mask->strokes.size(), 2u);
  EXPECT_EQ(l.mask->strokes[0].mask_value, 0.25);
  EXPECT_EQ(l.mask->strokes[1].type, MaterialStroke::Type::Fill);
  ASSERT_EQ(l.strokes.size(), 2u);
  EXPECT_EQ(l.strokes[1].type, MaterialStroke::Type::Fill);
  // The file written and read back is the document (the v2 file holds masks and fills).
  const std::string full = material_strokes_json(d.file());
  EXPECT_EQ(material_strokes_json(parse_material_strokes(full, "m.json", ".")), full);
  d.remove_mask(0);
  EXPECT_FALSE(d.file().layers[0].mask.has_value());
  ASSERT_TRUE(d.undo());  // the mask comes back with its strokes
  EXPECT_EQ(material_strokes_json(d.file()), full);
  for (int k = 0; k < 4; ++k) ASSERT_TRUE(d.undo());  // mask fill, mask stroke, add mask, fill
  EXPECT_EQ(material_strokes_json(d.file()), before);
}

TEST(StudioMaterial, TheBrushPaintsTheMaskAndFillsTheLayerAndTheMask) {
  Harness h({}, 128);
  h.app->brush().radius = 0.3;
  h.app->brush().channels = channel_bit(Channel::BaseColor);
  h.app->brush().color = Vec3(0.9, 0.1, 0.1);
  ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) { d.add_layer(""); }));
  h.app->brush().color = Vec3(0.1, 0.2, 0.9);
  ASSERT_TRUE(h.app->fill_active(false));  // layer 2 all blue
  ASSERT_FALSE(h.app->fill_active(true));  // no mask: refused with a message
  ASSERT_TRUE(h.app->edit_material([](MaterialDocument& d) { d.add_mask(1, 1); }));
  h.app->brush().on_mask = true;
  h.app->brush().mask_value = 0;
  EXPECT_TRUE(h.app->painting_mask());
  h.drag(150, 150, 250, 150);  // hides layer 2 along the drag
  const MaterialLayer& l = h.app->material()->file().layers[1];
  ASSERT_EQ(l.strokes.size(), 1u);
  EXPECT_EQ(l.strokes[0].type, MaterialStroke::Type::Fill);
  EXPECT_EQ(l.strokes[0].channels, channel_bit(Channel::BaseColor));
  ASSERT_TRUE(l.mask.has_value());
  ASSERT_EQ(l.mask->strokes.size(), 1u);
  EXPECT_EQ(l.mask->strokes[0].type, MaterialStroke::Type::Brush);
  EXPECT_EQ(l.mask->strokes[0].mask_value, 0);
  EXPECT_GT(l.mask->strokes[0].dabs.size(), 2u);
  expect_view_is_the_composite(*h.app);
  const ImageRGBA8 masked = *h.app->texture();
  h.app->brush().mask_value = 0.5;
  ASSERT_TRUE(h.app->fill_active(true));
  EXPECT_EQ(h.app->material()->file().layers[1].mask->strokes.size(), 2u);
  expect_view_is_the_composite(*h.app);
  EXPECT_GT(max_abs_diff(*h.app->texture(), masked), 50);
  h.app->undo();
  expect_view_is_the_composite(*h.app);
  EXPECT_EQ(max_abs_diff(*h.app->texture(), masked), 0);
}

TEST(StudioMaterial, PenPressureGoesIntoTheDabsAndTheCurvesIntoTheStroke) {
  Harness h({}, 128);
  h.app->brush().radius = 0.3;
  h.app->brush().channels = channel_bit(Channel::Roughness);
  h.drag(150, 150, 250, 150);  // a mouse: pressure 1, no pressures written
  ASSERT_TRUE(h.app->layered());
  const auto& strokes = h.app->material()->file().layers[0].strokes;
  ASSERT_EQ(strokes.size(), 1u);
  EXPECT_TRUE(strokes[0].pressure.empty());
  EXPECT_TRUE(strokes[0].radius_curve.points.empty());
  h.app->brush().radius_curve.points = {Vec2(0, 0.2), Vec2(0.5, 0.6), Vec2(1, 1)};
  h.app->brush().opacity_curve.points = {Vec2(0, 0), Vec2(1, 1)};
  h.app->set_pen_pressure(0.35);
  h.drag(150, 120, 250, 180);
  const auto& all = h.app->material()->file().layers[0].strokes;
  ASSERT_EQ(all.size(), 2u);
  const MaterialStroke& s = all[1];
  ASSERT_EQ(s.pressure.size(), s.dabs.size());
  for (double p : s.pressure) EXPECT_EQ(p, 0.35);
  EXPECT_EQ(s.radius_curve.points, h.app->brush().radius_curve.points);
  // In the file: [x, y, z, p] dabs and the "pressure" object; read back equal.
  const std::string text = material_strokes_json(h.app->material()->file());
  EXPECT_NE(text.find("\"pressure\": {\"radius\": [[0, 0.2], [0.5, 0.6], [1, 1]], \"opacity\": [[0, 0], [1, 1]]}"),
            std::string::npos)
      << text;
  const MaterialStrokeFile back = parse_material_strokes(text, "m.json", ".");
  EXPECT_EQ(back.layers[0].strokes[1].pressure, s.pressure);
  EXPECT_DOUBLE_EQ(back.layers[0].strokes[1].radius_curve(0.35), 0.2 + 0.35 / 0.5 * 0.4);
  // Pressure curves need the layered document (a version 1 stroke has none): the first stroke with
  // them makes the single base-colour layer a layered material.
  Harness g({}, 128);
  g.app->brush().radius = 0.3;
  g.app->brush().opacity_curve.points = {Vec2(0, 0.5), Vec2(1, 1)};
  g.app->set_pen_pressure(0.5);
  g.drag(150, 150, 250, 150);
  ASSERT_TRUE(g.app->layered());
  ASSERT_EQ(g.app->material()->file().layers[0].strokes.size(), 1u);
  EXPECT_EQ(g.app->material()->file().layers[0].strokes[0].opacity_curve.points.size(), 2u);
}


TEST(StudioBrushPreset, SavesAndLoadsTheBrushAndRefusesBadFilesWithOneLine) {
  TempDir dir;
  BrushSettings b;
  b.channels = channel_bit(Channel::BaseColor) | channel_bit(Channel::Height);
  b.color = Vec3(0.25, 0.5, 0.75);
  b.height = 0.9;
  b.pixel_radius = 42;
  b.hardness = 0.3;
  b.opacity = 0.6;
  b.spacing = 0.5;
  b.mask_value = 0.25;
  b.radius_curve.points = {Vec2(0, 0.2), Vec2(0.5, 0.6), Vec2(1, 1)};
  write_brush_preset(dir.path / "p.json", b);
  const BrushSettings r = read_brush_preset(dir.path / "p.json", BrushSettings{});
  EXPECT_EQ(r.channels, b.channels);
  EXPECT_EQ(r.color, b.color);
  EXPECT_EQ(r.height, 0.9);
  EXPECT_EQ(r.pixel_radius, 42);
  EXPECT_TRUE(r.screen_space);
  EXPECT_EQ(r.hardness, 0.3);
  EXPECT_EQ(r.opacity, 0.6);
  EXPECT_EQ(r.spacing, 0.5);
  EXPECT_EQ(r.mask_value, 0.25);
  EXPECT_EQ(r.radius_curve.points, b.radius_curve.points);
  EXPECT_TRUE(r.opacity_curve.points.empty());
  EXPECT_EQ(brush_preset_json(r), brush_preset_json(b));
  const auto error = [](const std::string& text) {
    try {
      (void)parse_brush_preset(text, "p.json", BrushSettings{});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string head = R"({"format": "adaptex.brush-preset", "version": 1, "brush": )";
  EXPECT_EQ(error(head + R"({"hardness": 1.5}})"), "p.json: brush: \"hardness\" must be in [0, 1] (got 1.5)");
  EXPECT_EQ(error(head + R"({"pressure": {"radius": [[0, 1], [0.5, 1]]}}})"),
            "p.json: brush: \"pressure.radius\" must start at pressure 0 and end at pressure 1");
  EXPECT_EQ(error(head + R"({"channels": {"roughnes": 0.5}}})"), "p.json: brush: unknown brush channel \"roughnes\"");
  EXPECT_EQ(error(head + R"({"radius_px": "big"}})"), "p.json: brush: \"radius_px\" must be a number (got string)");
  EXPECT_EQ(error(head + R"({"opacity": 1}, "extra": 1})"), "p.json: unknown field \"extra\"");
  EXPECT_EQ(error(R"({"format": "adaptex.strokes", "version": 1})"),
            "p.json: \"format\" must be \"adaptex.brush-preset\" (not a brush preset)");
  EXPECT_EQ(error("{").find('\n'), std::string::npos);
  EXPECT_EQ(error("{").rfind("p.json: not valid JSON", 0), 0u);
  // The App: a bad file leaves the brush as it was, with one error message.
  Harness h({}, 64);
  h.app->brush().opacity = 0.4;
  std::ofstream(dir.path / "bad.json") << head + R"({"opacity": 7}})";
  EXPECT_FALSE(h.app->load_brush_preset(dir.path / "bad.json"));
  EXPECT_EQ(h.app->brush().opacity, 0.4);
  ASSERT_FALSE(h.app->messages().empty());
  EXPECT_TRUE(h.app->messages().back().error);
  EXPECT_TRUE(h.app->load_brush_preset(dir.path / "p.json"));
  EXPECT_EQ(h.app->brush().opacity, 0.6);
}

TEST(StudioMaterial, TheEyedropperPicksTheCompositedValuesOfTheCheckedChannels) {
  Harness h({}, 128);
  h.app->brush().radius = 0.3;
  h.app->brush().channels = channel_bit(Channel::Roughness) | channel_bit(Channel::Metallic);
  h.app->brush().roughness = 0.05;
  h.app->brush().metallic = 0.7;
  h.drag(150, 150, 250, 150);
  ASSERT_TRUE(h.app->layered());
  ASSERT_TRUE(h.app->wait_idle(120));
  h.app->brush().roughness = 0.9;
  h.app->brush().metallic = 0.1;
  h.app->brush().color = Vec3(0, 0, 0);
  h.app->brush().channels = channel_bit(Channel::Roughness);  // picks roughness only
  h.app->brush().tool = Tool::Eyedropper;
  h.click(200, 150);
  EXPECT_NEAR(h.app->brush().roughness, 0.05, 1e-9);  // the middle of the stroke: fully covered
  EXPECT_EQ(h.app->brush().metallic, 0.1);
  EXPECT_EQ(h.app->brush().color, Vec3(0, 0, 0));
  h.app->brush().channels = channel_bit(Channel::Metallic) | channel_bit(Channel::BaseColor);
  h.click(200, 150);
  EXPECT_NEAR(h.app->brush().metallic, 0.7, 1e-9);
  EXPECT_EQ(h.app->brush().color, Vec3(1, 1, 1));  // the white background
}


TEST(StudioTablet, PressureIsTheNormalisedValuatorAmongThePackedValues) {
  // Valuators 0 (x), 1 (y) and 2 (pressure, range 0..65535) set; values packed in order.
  unsigned char mask[2] = {0b00000111, 0};
  const double values[] = {100, 200, 16383.75};
  EXPECT_DOUBLE_EQ(valuator_pressure(mask, 2, values, 2, 0, 65535, 1), 0.25);
  // Valuator 1 not set: the pressure is the second packed value.
  mask[0] = 0b00000101;
  const double packed[] = {100, 65535};
  EXPECT_DOUBLE_EQ(valuator_pressure(mask, 2, packed, 2, 0, 65535, 1), 1.0);
  // The pressure not in the event: unchanged; out of range: clamped; a valuator past the mask: unchanged.
  mask[0] = 0b00000011;
  EXPECT_DOUBLE_EQ(valuator_pressure(mask, 2, values, 2, 0, 65535, 0.4), 0.4);
  mask[0] = 0b00000100;
  const double over[] = {70000};
  EXPECT_DOUBLE_EQ(valuator_pressure(mask, 2, over, 2, 0, 65535, 0.4), 1.0);
  EXPECT_DOUBLE_EQ(valuator_pressure(mask, 2, over, 20, 0, 65535, 0.4), 0.4);
  // A range of 1..2048 (some drivers): the minimum is pressure 0.
  const double low[] = {1};
  EXPECT_DOUBLE_EQ(valuator_pressure(mask, 2, low, 2, 1, 2048, 0.4), 0.0);
}


TEST(StudioBrushPreset, ProjectsKeepTheMaskValueAndThePressureCurves) {
  TempDir dir;
  Project p;
  p.mesh_path = "builtin:sphere";
  p.brush.mask_value = 0.3;
  p.brush.on_mask = true;
  p.brush.radius_curve.points = {Vec2(0, 0.1), Vec2(0.5, 0.4), Vec2(1, 1)};
  write_project(dir.path / "p.adaptex", p);
  const Project r = read_project(dir.path / "p.adaptex");
  EXPECT_EQ(r.brush.mask_value, 0.3);
  EXPECT_TRUE(r.brush.on_mask);
  EXPECT_EQ(r.brush.radius_curve.points, p.brush.radius_curve.points);
  EXPECT_TRUE(r.brush.opacity_curve.points.empty());
  // A broken curve in a project: one line naming the file and the field.
  std::string text = read_input_file(dir.path / "p.adaptex");
  const size_t at = text.find("0.1", text.find("\"pressure\""));
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 3, "1.5");
  std::ofstream(dir.path / "bad.adaptex") << text;
  try {
    (void)read_project(dir.path / "bad.adaptex");
    ADD_FAILURE() << "a pressure factor of 1.5 was read";
  } catch (const InvalidInputError& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir.path / "bad.adaptex").string() + ": brush: \"pressure.radius[0][1]\" must be in [0, 1] (got 1.5)");
  }
}


/// Loads a green disc on a transparent 32 x 32 square (the image's alpha is the stamp's shape) as the
/// decal image and turns stamping on with a brush 20 pixels in radius (a disc of radius 14/32 * 40 = 17.5).
void load_disc_stamp(Harness& h, const TempDir& dir) {
  ImageRGBA8 img(32, 32, {0, 0, 0, 0});
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      if (std::hypot(x - 15.5, y - 15.5) < 14) {
        std::uint8_t* t = img.texel(x, y);
        t[0] = 20, t[1] = 200, t[2] = 40, t[3] = 255;
      }
  write_png(dir.path / "disc.png", img);
  h.app->load_decal(dir.path / "disc.png");
  ASSERT_TRUE(h.app->decal_image());
  h.app->brush().stamp = true;
  h.app->brush().screen_space = true;
  h.app->brush().pixel_radius = 20;
}

TEST(StudioMaterial, AStampPlacesTheDecalImageAtTheCursorAsTallAsTheBrush) {
  TempDir dir;
  Harness h({}, 128);
  load_disc_stamp(h, dir);
  ASSERT_TRUE(h.app->stencil());
  const Stencil stencil = *h.app->stencil();
  const ImageRGBA8 before = *h.app->texture();
  h.click(150, 150);
  ASSERT_TRUE(h.app->wait_idle(60));
  ASSERT_EQ(h.app->history().strokes().size(), 1u);
  EXPECT_EQ(h.app->history().strokes()[0].type, Stroke::Type::Decal);
  EXPECT_EQ(h.app->stencil()->centre, stencil.centre);  // the stencil stays where it was
  const auto colour_at = [&](double x, double y) {
    const auto hit = h.app->pick(x, y);
    EXPECT_TRUE(hit);
    return hit ? h.app->sample_colour(*hit) : Vec3(-1, -1, -1);
  };
  EXPECT_LT((colour_at(150, 150) - Vec3(20, 200, 40) / 255.0).norm(), 0.05);  // the disc's centre
  EXPECT_LT((colour_at(150, 162) - Vec3(20, 200, 40) / 255.0).norm(), 0.05);  // inside its radius
  EXPECT_LT((colour_at(150, 185) - Vec3(1, 1, 1)).norm(), 0.05);              // past the brush: untouched
  EXPECT_LT((colour_at(150 + 19, 150 + 19) - Vec3(1, 1, 1)).norm(), 0.05);    // the square's corner: alpha 0
  EXPECT_GT(max_abs_diff(before, *h.app->texture()), 100);
}

TEST(StudioMaterial, AStampPaintsTheBrushsHeightAndRoughnessWithTheImagesCoverage) {
  TempDir dir;
  Harness h({}, 128);
  load_disc_stamp(h, dir);
  h.app->brush().channels = channel_bit(Channel::Height) | channel_bit(Channel::Roughness);
  h.app->brush().height = 0.9;
  h.app->brush().roughness = 0.1;
  h.click(150, 150);
  ASSERT_TRUE(h.app->wait_idle(60));
  ASSERT_TRUE(h.app->layered());  // a channel other than base colour: a layered material
  const auto material_at = [&](double x, double y) {
    const auto hit = h.app->pick(x, y);
    EXPECT_TRUE(hit);
    return hit ? evaluate_material(*h.app->mesh(), h.app->material_file(), {SurfacePoint{hit->face, hit->b0, hit->b1}})[0]
               : MaterialValue{};
  };
  const std::vector<MaterialStroke>& strokes = h.app->material()->file().layers[h.app->material()->active()].strokes;
  ASSERT_EQ(strokes.size(), 1u);
  EXPECT_EQ(strokes[0].type, MaterialStroke::Type::Decal);
  EXPECT_EQ(strokes[0].channels, channel_bit(Channel::Height) | channel_bit(Channel::Roughness));
  MaterialValue v = material_at(150, 150);  // the disc's centre: height and roughness, base colour untouched
  EXPECT_NEAR(v[channel_offset(Channel::Height)], 0.9, 1e-6);
  EXPECT_NEAR(v[channel_offset(Channel::Roughness)], 0.1, 1e-6);
  EXPECT_EQ(Vec3(v[0], v[1], v[2]), Vec3(1, 1, 1));
  v = material_at(150 + 19, 150 + 19);  // the square's corner: alpha 0
  EXPECT_EQ(v[channel_offset(Channel::Height)], 0.5);
  EXPECT_EQ(v[channel_offset(Channel::Roughness)], 0.5);
  // With base colour checked too: the image's colour and the brush's height.
  h.app->brush().channels = channel_bit(Channel::BaseColor) | channel_bit(Channel::Height);
  h.click(250, 150);
  ASSERT_TRUE(h.app->wait_idle(60));
  v = material_at(250, 150);
  EXPECT_LT((Vec3(v[0], v[1], v[2]) - Vec3(20, 200, 40) / 255.0).norm(), 0.02);
  EXPECT_NEAR(v[channel_offset(Channel::Height)], 0.9, 1e-6);
  EXPECT_NEAR(v[channel_offset(Channel::Roughness)], 0.5, 1e-6);
  // The saved version 2 file holds the stamps' channels.
  h.app->save_material_strokes(dir.path / "m.json");
  const MaterialStrokeFile saved = read_material_strokes(dir.path / "m.json");
  const MaterialStroke& last = saved.layers[h.app->material()->active()].strokes.back();
  EXPECT_EQ(last.channels, channel_bit(Channel::BaseColor) | channel_bit(Channel::Height));
  EXPECT_TRUE(last.image_color);
  EXPECT_EQ(last.value[channel_offset(Channel::Height)], 0.9);
  // No channel checked: nothing is stamped, a message says why.
  h.app->brush().channels = 0;
  h.click(200, 120);
  EXPECT_EQ(h.app->material()->file().layers[h.app->material()->active()].strokes.size(), 2u);
  // A projected decal (P) paints the image's colour on the layer, whatever the brush's channels.
  h.app->project_decal(1.0);
  ASSERT_TRUE(h.app->wait_idle(60));
  const auto& layer = h.app->material()->file().layers[h.app->material()->active()];
  ASSERT_EQ(layer.strokes.size(), 3u);
  EXPECT_EQ(layer.strokes[2].channels, channel_bit(Channel::BaseColor));
  EXPECT_TRUE(layer.strokes[2].image_color);
}

}  // namespace
}  // namespace adaptex::studio
