// The each-stroke session of layered materials (adapt/material_session.h) and its per-layer point
// cache (paint/material_point_cache.h): the cache equals the exact evaluation stroke by stroke, the
// session's textures equal paint_material()'s on the layout it holds, the held layout is never worse
// than the initial one on the check's samples, and strokes after an adopted layout reach its textures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "adaptex/adapt/error_density.h"
#include "adaptex/adapt/material_adapt.h"
#include "adaptex/adapt/material_session.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/material_eval.h"
#include "adaptex/paint/material_point_cache.h"
#include "adaptex/paint/material_surface_cache.h"
#include "adaptex/paint/material_signal.h"
#include "../paint/brush_test_util.h"

namespace adaptex {
namespace {

MaterialStroke scratch(int k, unsigned channels, double hardness = 0.9) {
  MaterialStroke s;
  s.channels = channels;
  s.value = {0.1 + 0.1 * (k % 5), 0.2, 0.8, 1.0, 0.05 + 0.1 * (k % 3), double(k % 2), 0.2 + 0.1 * (k % 4)};
  s.radius = 0.006;
  s.hardness = hardness;
  const double y = 0.03 + 0.03 * (k % 8);
  s.dabs = {Vec3(0.02, y, 0), Vec3(0.1, y + 0.01, 0), Vec3(0.2, y, 0), Vec3(0.28, y + 0.005, 0)};
  s.pressure = {1.0, 0.6, 0.9, 0.3};
  s.radius_curve.points = {Vec2(0, 0.5), Vec2(1, 1)};
  return s;
}

constexpr unsigned kFour = (1u << 0) | (1u << 2) | (1u << 3) | (1u << 4);  // base colour, roughness, metallic, height

/// Three layers (normal, multiply with a mask, overlay at 0.7), no strokes yet.
MaterialStrokeFile three_layers() {
  MaterialStrokeFile f;
  f.layers.resize(3);
  f.layers[1].blend = BlendMode::Multiply;
  f.layers[1].mask = LayerMask{0.4, {}};
  f.layers[2].blend = BlendMode::Overlay;
  f.layers[2].opacity = 0.7;
  return f;
}

int max_byte_difference(const ImageRGBA8& a, const ImageRGBA8& b) {
  EXPECT_EQ(a.data.size(), b.data.size());
  int worst = 0;
  for (size_t k = 0; k < std::min(a.data.size(), b.data.size()); ++k) worst = std::max(worst, std::abs(a.data[k] - b.data[k]));
  return worst;
}

/// Every texture of the session against paint_material() on the session's layout: within one 8-bit
/// level (the caches keep single-precision layer state; a value at a rounding boundary may differ).
void expect_paint_material(MaterialPaintSession& s, int size) {
  MaterialPaintOptions po;
  po.size = size;
  const MaterialTextures ref = paint_material(s.mesh(), s.param(), s.history(), po);
  const MaterialTextures& got = s.textures();
  EXPECT_LE(max_byte_difference(got.base_color, ref.base_color), 1);
  EXPECT_LE(max_byte_difference(got.roughness, ref.roughness), 1);
  EXPECT_LE(max_byte_difference(got.metallic, ref.metallic), 1);
  EXPECT_LE(max_byte_difference(got.metallic_roughness, ref.metallic_roughness), 1);
  // The normal differentiates the height: one level of height moves a normal by a few levels.
  EXPECT_LE(max_byte_difference(got.normal, ref.normal), 8);
}

TEST(MaterialPointCache, EqualsTheExactMaterialStrokeByStroke) {
  const TriMesh mesh = shapes::plane(16);
  const std::vector<SurfacePoint> pts = sample_surface(mesh, 4000, 3);
  MaterialStrokeFile f = three_layers();
  MaterialPointCache cache(mesh, pts, f);
  auto add = [&](int layer, const MaterialStroke& s, bool mask) {
    (mask ? f.layers[layer].mask->strokes : f.layers[layer].strokes).push_back(s);
    cache.update(f);
    const std::vector<MaterialValue> exact = evaluate_material(mesh, f, pts);
    const std::vector<MaterialValue>& got = cache.values(f);
    double worst = 0;
    for (size_t k = 0; k < pts.size(); ++k)
      for (int c = 0; c < kMaterialComponents; ++c) worst = std::max(worst, std::abs(got[k][c] - exact[k][c]));
    EXPECT_LT(worst, 1e-5) << "after " << cache.strokes() << " strokes";
  };
  add(0, scratch(0, kFour), false);
  add(2, scratch(1, kFour, 0.2), false);
  add(1, scratch(2, 1u << 2), false);  // a lower layer after a higher one
  MaterialStroke fill;
  fill.type = MaterialStroke::Type::Fill;
  fill.channels = 1u << 3;
  fill.value[channel_offset(Channel::Metallic)] = 0.7;
  fill.opacity = 0.5;
  add(1, fill, false);
  MaterialStroke mask = scratch(3, 0);
  mask.mask_value = 1.0;
  add(1, mask, true);
  MaterialStroke erase = scratch(4, kFour);
  erase.type = MaterialStroke::Type::Erase;
  add(0, erase, false);
  // Blending settings are read when compositing: hiding a layer needs no stroke again.
  f.layers[2].visible = false;
  const std::vector<MaterialValue> exact = evaluate_material(mesh, f, pts);
  EXPECT_LT(std::abs(cache.values(f)[17][0] - exact[17][0]) + std::abs(cache.values(f)[900][4] - exact[900][4]), 1e-5);
  // reset(): other points, the same strokes, as a new cache.
  const std::vector<SurfacePoint> other = sample_surface(mesh, 500, 9);
  cache.reset(mesh, other, f);
  const std::vector<MaterialValue> e2 = evaluate_material(mesh, f, other);
  double worst = 0;
  for (size_t k = 0; k < other.size(); ++k)
    for (int c = 0; c < kMaterialComponents; ++c) worst = std::max(worst, std::abs(cache.values(f)[k][c] - e2[k][c]));
  EXPECT_LT(worst, 1e-5);
  EXPECT_EQ(cache.strokes(), 6);
}

MaterialSessionOptions small_options() {
  MaterialSessionOptions o;
  o.paint.size = 128;
  o.check_samples = 20000;
  o.adapt.density_flow.density.cells = 32;
  return o;
}

TEST(MaterialSession, TexturesEqualPaintMaterialAndTheHeldLayoutIsNeverWorse) {
  const TriMesh mesh = shapes::plane(24);
  const Parameterization param = test::planar_param(mesh, 0.9, 0.05);
  MaterialPaintSession s(mesh, param, three_layers(), small_options());
  int adapted = 0;
  for (int k = 0; k < 8; ++k) {
    s.add_stroke(k % 3 == 2 ? 2 : 0, scratch(k, k % 2 ? kFour : 1u << 2, k % 2 ? 0.9 : 0.0));
    ASSERT_EQ(s.reports().size(), static_cast<size_t>(k + 1));
    const double held = s.held_error().weighted, initial = s.initial_error().weighted;
    if (s.adapted()) {
      ++adapted;
      EXPECT_LT(held, initial * (1 - small_options().check_margin)) << "stroke " << k;
    } else {
      EXPECT_EQ(held, initial) << "stroke " << k;
    }
    expect_paint_material(s, 128);
  }
  EXPECT_GT(adapted, 0);  // the scratches are detail enough to adapt for
}

TEST(MaterialSession, ItsModelIsTheModelOfTheHistoryAfterEveryStroke) {
  // The session keeps the model's exact values, the exact height's normals (updated where the height
  // changed) and the planes' cell sums (summed again where rasters changed): its model after every
  // stroke is the one computed afresh from the file on the initial layout (up to the caches' single
  // precision and the textures' 8-bit rounding), for strokes that paint height and strokes that do not.
  const TriMesh mesh = shapes::plane(24);
  const Parameterization param = test::planar_param(mesh, 0.9, 0.05);
  MaterialSessionOptions o = small_options();
  o.min_gain_db = 0;
  MaterialPaintSession s(mesh, param, three_layers(), o);
  const TexelMap map = build_texel_map(mesh, param, 128, 128);
  for (int k = 0; k < 7; ++k) {
    s.add_stroke(k % 3 == 2 ? 2 : 0, scratch(k, k % 2 ? kFour : 1u << 2, 0.9));
    const MaterialTextures tex = paint_material(mesh, param, s.history(), o.paint);
    const ErrorDensity fresh = compute_error_density(
        mesh, param, map, material_error_planes(mesh, param, map, s.history(), tex, o.data_weight),
        o.adapt.density_flow.density);
    const AdaptReport& r = s.reports().back();
    EXPECT_NEAR(r.predicted_gain_db, fresh.predicted_gain_db, 0.01 * std::abs(fresh.predicted_gain_db) + 1e-3)
        << "stroke " << k;
    EXPECT_NEAR(r.signal_fraction, fresh.signal_fraction, 0.01) << "stroke " << k;
  }
  EXPECT_GT(s.reports().back().predicted_gain_db, 0.3);
}

TEST(MaterialSession, StrokesAfterAnAdoptedLayoutReachItsTextures) {
  const TriMesh mesh = shapes::plane(24);
  const Parameterization param = test::planar_param(mesh, 0.9, 0.05);
  MaterialStrokeFile start = three_layers();
  for (int k = 0; k < 6; ++k) start.layers[0].strokes.push_back(scratch(k, kFour, 0.0));
  MaterialSessionOptions o = small_options();
  o.min_gain_db = 100;  // every gated cycle is skipped: the held layout stays
  MaterialPaintSession s(mesh, param, start, o);
  s.reparameterize();
  ASSERT_TRUE(s.adapted());
  const Parameterization held = s.param();
  const ImageRGBA8 base_before = s.textures().base_color;
  // A roughness-only stroke elsewhere: the gate skips, the held layout's roughness changes, its base colour not.
  MaterialStroke r = scratch(0, 1u << 2);
  for (Vec3& d : r.dabs) d += Vec3(0.6, 0.6, 0);
  s.add_stroke(0, r);
  EXPECT_TRUE(s.reports().back().skipped);
  ASSERT_TRUE(s.adapted());
  EXPECT_EQ(s.param().uv, held.uv);
  EXPECT_EQ(max_byte_difference(s.textures().base_color, base_before), 0);
  expect_paint_material(s, 128);
  MaterialStroke m = scratch(1, 0);
  m.mask_value = 0;
  s.add_stroke(1, m, true);
  expect_paint_material(s, 128);
}

/// Three layers of strokes over the plane: soft and hard scratches on every channel, a mask, a
/// fill, a stroke to a lower layer after a higher one.
MaterialStrokeFile painted_layers(int strokes) {
  MaterialStrokeFile f = three_layers();
  for (int k = 0; k < strokes; ++k) {
    MaterialStroke s = scratch(k, k % 2 ? kFour : 1u << 2, k % 3 ? 0.9 : 0.0);
    s.radius = 0.02;
    for (Vec3& d : s.dabs) d.y() = 0.05 + 0.9 * std::fmod(0.37 * k, 1.0) + 0.3 * d.x() * (k % 2 ? 1 : -1);
    f.layers[k % 3].strokes.push_back(s);
  }
  MaterialStroke fill;
  fill.type = MaterialStroke::Type::Fill;
  fill.channels = 1u << 3;
  fill.value[channel_offset(Channel::Metallic)] = 0.7;
  fill.opacity = 0.5;
  f.layers[1].strokes.push_back(fill);
  MaterialStroke mask = scratch(3, 0);
  mask.radius = 0.05;
  f.layers[1].mask->strokes.push_back(mask);
  return f;
}

TEST(MaterialSession, TheInitialLayoutsIncrementalCheckEqualsTheFullOne) {
  // The check of the initial layout recomputes only the samples whose exact values or texels a
  // stroke changed (padding and the height's normals included): after every stroke it equals the
  // full evaluation bit for bit, for brush, erase, fill and mask strokes on three layers, and a stroke
  // along the chart's border.
  const TriMesh mesh = shapes::plane(24);
  const Parameterization param = test::planar_param(mesh, 0.9, 0.05);
  MaterialSessionOptions o = small_options();
  o.adapt.mode = AdaptMode::None;  // the held layout is the initial one: textures() are its textures
  MaterialEvalOptions eo;
  eo.samples = o.check_samples;
  eo.seed = o.check_seed;
  eo.data_weight = o.data_weight;
  const MaterialEvalPoints pts = material_eval_points(mesh, true, eo);
  const MaterialStrokeFile all = painted_layers(9);
  MaterialPaintSession s(mesh, param, three_layers(), o);
  MaterialErrorTracker unflagged;  // told of no change: stale after the first stroke
  int stale = 0;
  auto expect_full = [&](const std::string& what) {
    const MaterialError got = s.initial_error();
    MaterialPointCache exact(mesh, pts.probes, s.history());
    const MaterialError full = evaluate_material_textures(mesh, param, s.textures(), pts, exact.values(s.history()), eo);
    EXPECT_EQ(got.weighted, full.weighted) << what;
    EXPECT_EQ(got.base_color, full.base_color) << what;
    EXPECT_EQ(got.normal, full.normal) << what;
    EXPECT_EQ(got.roughness, full.roughness) << what;
    const std::vector<char> none_p(pts.probes.size(), 0), none_t(128 * 128, 0);
    stale += unflagged.evaluate(mesh, param, s.textures(), pts, exact.values(s.history()), none_p, none_t, eo).weighted !=
             full.weighted;
  };
  expect_full("no stroke");
  for (size_t l = 0; l < all.layers.size(); ++l)
    for (size_t k = 0; k < all.layers[l].strokes.size(); ++k) {
      MaterialStroke st = all.layers[l].strokes[k];
      if (k == 1) st.type = MaterialStroke::Type::Erase;
      s.add_stroke(static_cast<int>(l), st);
      expect_full("layer " + std::to_string(l) + ", stroke " + std::to_string(k));
    }
  s.add_stroke(1, all.layers[1].mask->strokes[0], true);
  expect_full("mask stroke");
  MaterialStroke border = scratch(5, kFour);  // along the chart's border: the samples there read padded texels
  border.radius = 0.04;
  border.dabs = {Vec3(0, 0.2, 0), Vec3(0, 0.5, 0), Vec3(0, 0.8, 0), Vec3(1, 0.3, 0), Vec3(1, 0.6, 0)};
  border.pressure.clear();
  s.add_stroke(0, border);
  expect_full("border stroke");
  EXPECT_GE(stale, 9);  // the strokes change the error: a check told of no change would be wrong
}

/// PSNR of \p got against \p ref over components [c0, c0 + n) (values in [0, 1]).
double component_psnr(const std::vector<MaterialValue>& got, const std::vector<MaterialValue>& ref, int c0, int n) {
  double s = 0;
  for (size_t k = 0; k < ref.size(); ++k)
    for (int c = c0; c < c0 + n; ++c) s += (got[k][c] - ref[k][c]) * (got[k][c] - ref[k][c]);
  return 10 * std::log10(ref.size() * n / std::max(s, 1e-30));
}

// The surface cache at the session's default density (1.5 samples per texel) against the exact
// material at the texels of a 256² layout, every channel; not exact (it interpolates).
TEST(MaterialSurfaceCache, TexelValuesAreCloseToTheExactMaterial) {
  const TriMesh mesh = shapes::plane(24);
  const Parameterization param = test::planar_param(mesh, 0.9, 0.05);
  const TexelMap map = build_texel_map(mesh, param, 256, 256);
  MaterialStrokeFile f = painted_layers(20);
  const double texel = std::sqrt(surface_area(mesh) / map.inside.size());
  MaterialSurfaceCache cache(mesh, texel / MaterialSessionOptions{}.surface_cache, f);
  EXPECT_EQ(cache.strokes(), 22);
  EXPECT_GT(cache.num_samples(), static_cast<long long>(map.inside.size()));
  auto check = [&](const char* when) {
    const std::vector<MaterialValue> got = cache.texel_values(f, map, mesh);
    const std::vector<MaterialValue> exact = evaluate_material(mesh, f, texel_points(map));
    const double colour = component_psnr(got, exact, 0, 3), rough = component_psnr(got, exact, 4, 1),
                 metal = component_psnr(got, exact, 5, 1), height = component_psnr(got, exact, 6, 1);
    std::printf("%s: cache vs exact PSNR colour %.1f, roughness %.1f, metallic %.1f, height %.1f dB\n", when, colour,
                rough, metal, height);
    for (double p : {colour, rough, metal, height}) {
      EXPECT_GT(p, 46.0) << when;  // measured 48.2 dB and more
      EXPECT_LT(p, 200.0) << when;  // not vacuous: the cache does interpolate
    }
  };
  check("20 strokes");
  // A stroke to the lowest layer, after the others, and one more to a mask: the cache follows.
  f.layers[0].strokes.push_back(scratch(5, kFour, 0.3));
  f.layers[1].mask->strokes.push_back(scratch(6, 0));
  cache.update(f);
  EXPECT_EQ(cache.strokes(), 24);
  check("24 strokes");
  // Texels located on a refinement (here the mesh itself, each face its own parent): the same values.
  const std::vector<int> parent = [&] {
    std::vector<int> p(mesh.num_faces());
    for (int k = 0; k < mesh.num_faces(); ++k) p[k] = k;
    return p;
  }();
  const std::vector<MaterialValue> direct = cache.texel_values(f, map, mesh), located = cache.texel_values(f, map, mesh, &parent);
  double worst = 0;
  for (size_t k = 0; k < direct.size(); ++k)
    for (int c = 0; c < kMaterialComponents; ++c) worst = std::max(worst, std::abs(direct[k][c] - located[k][c]));
  EXPECT_LT(worst, 1e-4);
  // "Texels" at the lattice's points of every face (n subdivisions by the longest edge, the
  // diagonal here): the exact material there, to the 16-bit storage.
  const Face& f0 = mesh.faces[0];
  const double diagonal = std::max({(mesh.positions[f0[1]] - mesh.positions[f0[0]]).norm(),
                                    (mesh.positions[f0[2]] - mesh.positions[f0[1]]).norm(),
                                    (mesh.positions[f0[0]] - mesh.positions[f0[2]]).norm()});
  const int n = static_cast<int>(std::ceil(diagonal / (texel / MaterialSessionOptions{}.surface_cache)));
  TexelMap at;
  for (int face = 0; face < mesh.num_faces(); face += 7)
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const Face& t = mesh.faces[face];
        const double b1 = double(i) / n, b2 = double(j) / n, b0 = 1 - b1 - b2;
        at.inside.push_back(static_cast<int>(at.face.size()));
        at.face.push_back(face);
        at.bary.emplace_back(float(b0), float(b1));
        at.position.push_back((b0 * mesh.positions[t[0]] + b1 * mesh.positions[t[1]] + b2 * mesh.positions[t[2]]).cast<float>());
      }
  at.width = static_cast<int>(at.face.size());
  at.height = 1;
  const std::vector<MaterialValue> on_lattice = cache.texel_values(f, at, mesh, &parent);
  const std::vector<MaterialValue> exact_there = evaluate_material(mesh, f, texel_points(at));
  worst = 0;
  for (size_t k = 0; k < on_lattice.size(); ++k)
    for (int c = 0; c < kMaterialComponents; ++c) worst = std::max(worst, std::abs(on_lattice[k][c] - exact_there[k][c]));
  EXPECT_GT(on_lattice.size(), 1000u);
  EXPECT_LT(worst, 2e-4);
  EXPECT_THROW(MaterialSurfaceCache(mesh, 0.0, f), InvalidInputError);
  EXPECT_THROW(MaterialSurfaceCache(mesh, texel / 2, f, 1000), InvalidInputError);
}

double texture_psnr(const ImageRGBA8& a, const ImageRGBA8& b, const TexelMap& map, int channels) {
  double s = 0;
  for (int t : map.inside)
    for (int c = 0; c < channels; ++c) {
      const double d = (a.data[size_t(t) * 4 + c] - b.data[size_t(t) * 4 + c]) / 255.0;
      s += d * d;
    }
  return 10 * std::log10(map.inside.size() * channels / std::max(s, 1e-30));
}

// With the surface cache on from the first stroke, the candidates' and the held layout's textures
// come from it: close to paint_material() on the held layout, and the held layout still beats the
// initial one on the check's exact samples.
TEST(MaterialSession, TexturesFromTheSurfaceCacheAreCloseToExactReplay) {
  const TriMesh mesh = shapes::plane(24);
  const Parameterization param = test::planar_param(mesh, 0.9, 0.05);
  MaterialSessionOptions o = small_options();
  o.paint.size = 256;
  o.surface_cache_coverage = 0;
  const MaterialStrokeFile all = painted_layers(12);
  MaterialStrokeFile start = all;
  for (MaterialLayer& l : start.layers) l.strokes.clear();
  MaterialPaintSession s(mesh, param, start, o);
  EXPECT_EQ(s.surface_cache_samples(), 0);
  for (int layer = 0; layer < 3; ++layer) s.add_strokes(layer, all.layers[layer].strokes);
  EXPECT_GT(s.surface_cache_samples(), 0);
  s.reparameterize();
  ASSERT_TRUE(s.adapted());
  ASSERT_TRUE(s.held_from_cache());
  EXPECT_LT(s.held_error().weighted, s.initial_error().weighted * (1 - o.check_margin));
  MaterialPaintOptions po;
  po.size = 256;
  const MaterialTextures ref = paint_material(s.mesh(), s.param(), s.history(), po);
  const MaterialTextures& got = s.textures();
  const TexelMap map = build_texel_map(s.mesh(), s.param(), 256, 256);
  const double colour = texture_psnr(got.base_color, ref.base_color, map, 3),
               mr = texture_psnr(got.metallic_roughness, ref.metallic_roughness, map, 3),
               height = texture_psnr(got.height, ref.height, map, 1), normal = texture_psnr(got.normal, ref.normal, map, 3);
  std::printf("held textures from the cache vs exact replay: PSNR base colour %.1f, metallic-roughness %.1f, height "
              "%.1f, normal %.1f dB\n", colour, mr, height, normal);
  for (double p : {colour, mr, height}) {
    EXPECT_GT(p, 47.0);  // measured 49.1 dB and more
    EXPECT_LT(p, 200.0);  // not vacuous: interpolated, not replayed
  }
  EXPECT_GT(normal, 48.0);  // measured 50.7 dB
  // What matters is the error against the exact material on the surface (the check's measure):
  // the cached textures' is within a few tenths of a dB of exact replay's.
  MaterialEvalOptions eo;
  eo.data_weight = o.data_weight;
  const double e_cached = evaluate_material_textures(s.mesh(), s.param(), got, s.history(), eo).weighted;
  const double e_exact = evaluate_material_textures(s.mesh(), s.param(), ref, s.history(), eo).weighted;
  std::printf("surface error of the held textures: cached %.3g, exact replay %.3g (%+.2f dB)\n", e_cached, e_exact,
              10 * std::log10(e_cached / e_exact));
  EXPECT_LT(std::abs(10 * std::log10(e_cached / e_exact)), 0.3);
}

TEST(MaterialSession, RefusesBadInput) {
  const TriMesh mesh = shapes::plane(8);
  const Parameterization param = test::planar_param(mesh);
  MaterialSessionOptions o = small_options();
  MaterialPaintSession s(mesh, param, three_layers(), o);
  EXPECT_THROW(s.add_stroke(3, scratch(0, kFour)), InvalidInputError);
  EXPECT_THROW(s.add_stroke(0, scratch(0, kFour), true), InvalidInputError);  // layer 0 has no mask
  MaterialStroke bad = scratch(0, kFour);
  bad.radius = -1;
  EXPECT_THROW(s.add_stroke(0, bad), InvalidInputError);
  // A stroke built in code that paints no channel, a decal too, would paint nothing: refused with
  // the parser's message, as the studio's strokes are.
  bad = scratch(0, 0);
  EXPECT_THROW(s.add_stroke(0, bad), InvalidInputError);
  MaterialStroke decal;
  decal.type = MaterialStroke::Type::Decal;
  decal.decal.type = Stroke::Type::Decal;
  decal.decal.camera.eye = Vec3(0.5, 0.5, 2);
  decal.decal.camera.target = Vec3(0.5, 0.5, 0);
  decal.decal.image = ImageRGBA8(4, 4, {255, 0, 0, 255});
  try {
    s.add_stroke(0, decal);
    ADD_FAILURE() << "a decal without channels was taken";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("material session: layer 0, stroke 0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("channel"), std::string::npos) << e.what();
  }
  decal.channels = channel_bit(Channel::BaseColor);
  EXPECT_NO_THROW(validate_material_stroke(decal, false, "")) << "the decal is valid with a channel";
  EXPECT_TRUE(s.history().layers[0].strokes.empty());
  o.adapt.mode = AdaptMode::Single;
  EXPECT_THROW(MaterialPaintSession(mesh, param, three_layers(), o), InvalidInputError);
}

}  // namespace
}  // namespace adaptex
