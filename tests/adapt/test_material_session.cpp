// The each-stroke session of layered materials (adapt/material_session.h) and its per-layer point
// cache (paint/material_point_cache.h): the cache equals the exact evaluation stroke by stroke, the
// session's textures equal paint_material()'s on the layout it holds, the held layout is never worse
// than the initial one on the check's samples, and strokes after an adopted layout reach its textures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "adaptex/adapt/material_session.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/material_point_cache.h"
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
  EXPECT_TRUE(s.history().layers[0].strokes.empty());
  o.adapt.mode = AdaptMode::Single;
  EXPECT_THROW(MaterialPaintSession(mesh, param, three_layers(), o), InvalidInputError);
}

}  // namespace
}  // namespace adaptex
