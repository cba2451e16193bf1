// Every channel of a material's textures judged on surface samples (paint/material_eval.h): the
// shading normal's error falls as the normal map resolves a smooth groove, a normal map with the
// wrong sign of slope is judged far worse, the weighted sum follows the error model's weights, a layout's
// frame terms given give the same normal map and error, and the generated detail cases paint only their
// own channel.
#include <gtest/gtest.h>

#include <cmath>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/material_eval.h"
#include "adaptex/paint/material_generate.h"
#include "adaptex/paint/material_signal.h"
#include "adaptex/paint/texel_map.h"
#include "brush_test_util.h"

namespace adaptex {
namespace {

/// A soft groove (hardness 0, height only) across the unit plane over a flat base colour.
MaterialStrokeFile groove() {
  return parse_material_strokes(R"({"format": "adaptex.strokes", "version": 2, "height_scale": 0.05, "layers": [
    {"strokes": [{"type": "fill", "channels": {"base_color": [0.6, 0.5, 0.4]}},
                 {"channels": {"height": 0.1}, "radius": 0.12, "hardness": 0,
                  "dabs": [[0.2, 0.3, 0], [0.4, 0.45, 0], [0.6, 0.55, 0], [0.8, 0.7, 0]]}]}]})",
                                "groove.json", ".");
}

struct GrooveOnPlane : ::testing::Test {
  const TriMesh mesh = shapes::plane(16);
  const Parameterization param = test::planar_param(mesh, 0.9, 0.05);
  const MaterialStrokeFile file = groove();
  MaterialEvalOptions eo = [] {
    MaterialEvalOptions o;
    o.samples = 50000;
    return o;
  }();
  MaterialError judge(int size) const {
    MaterialPaintOptions po;
    po.size = size;
    po.padding = 2;
    return evaluate_material_textures(mesh, param, paint_material(mesh, param, file, po), file, eo);
  }
};

TEST_F(GrooveOnPlane, NormalErrorFallsAsTheNormalMapResolvesTheGroove) {
  const MaterialError coarse = judge(32), fine = judge(128);
  EXPECT_GT(coarse.normal, 1e-5);  // the groove tilts the normal: 32² does not hold it exactly
  EXPECT_LT(fine.normal, coarse.normal / 4);
  // The other channels have no detail: only 8-bit rounding of flat values (< (0.5/255)²).
  for (const MaterialError& e : {coarse, fine}) {
    EXPECT_LT(e.base_color, 4e-6);
    EXPECT_LT(e.roughness, 4e-6);
    EXPECT_LT(e.metallic, 4e-6);
    EXPECT_LT(e.alpha, 4e-6);
  }
}

TEST_F(GrooveOnPlane, AWrongSignOfSlopeIsJudgedFarWorse) {
  MaterialPaintOptions po;
  po.size = 128;
  po.padding = 2;
  MaterialTextures tex = paint_material(mesh, param, file, po);
  const double right = evaluate_material_textures(mesh, param, tex, file, eo).normal;
  for (size_t t = 0; t < tex.normal.data.size(); t += 4)
    for (int c = 0; c < 2; ++c) tex.normal.data[t + c] = static_cast<std::uint8_t>(255 - tex.normal.data[t + c]);
  const double wrong = evaluate_material_textures(mesh, param, tex, file, eo).normal;
  EXPECT_GT(wrong, 10 * right);
}

TEST_F(GrooveOnPlane, WeightedErrorSumsTheChannelsWithTheModelsWeights) {
  const MaterialError e = judge(32);
  // Lambert: 4 · mean square of the base colour (flat here).
  EXPECT_NEAR(e.normal_weight, 4 * (0.36 + 0.25 + 0.16) / 3, 1e-9);
  EXPECT_NEAR(e.weighted,
              e.base_color + 0.25 * (e.alpha + e.roughness + e.metallic) / 3 + e.normal_weight * e.normal, 1e-15);
  EXPECT_GT(e.normal_weight * e.normal, 0.5 * e.weighted);  // the groove dominates
  EXPECT_EQ(psnr_from_mse(0), 200.0);  // exact: the convention of evaluate_texture()
  EXPECT_NEAR(psnr_from_mse(1e-3), 30, 1e-12);
}

// A session passes a layout's frame terms (height_normal_terms()) to its normal map and its check:
// the same bytes and the same error as computing them there; terms of another mesh are refused.
TEST_F(GrooveOnPlane, TheLayoutsFrameTermsGivenShadeAndJudgeTheSame) {
  const TexelMap map = build_texel_map(mesh, param, 64, 64);
  const std::vector<MaterialValue> at_texels = evaluate_material(mesh, file, texel_points(map));
  const HeightNormalTerms terms = height_normal_terms(mesh, param);
  MaterialTextures own, given;
  material_textures_from_values(mesh, param, map, at_texels, file.background, 2, 0.05, own);
  material_textures_from_values(mesh, param, map, at_texels, file.background, 2, 0.05, given, kAllChannels, &terms);
  EXPECT_EQ(given.normal.data, own.normal.data);
  int tilted = 0;  // the groove's texels: normals away from (0, 0, 1)
  for (size_t t = 0; t < own.normal.data.size(); t += 4) tilted += own.normal.data[t] != 128 || own.normal.data[t + 1] != 128;
  EXPECT_GT(tilted, 100);
  const MaterialEvalPoints pts = material_eval_points(mesh, true, eo);
  const std::vector<MaterialValue> exact = evaluate_material(mesh, file, pts.probes);
  const MaterialError a = evaluate_material_textures(mesh, param, own, pts, exact, eo);
  const MaterialError b = evaluate_material_textures(mesh, param, own, pts, exact, eo, &terms);
  EXPECT_GT(a.normal, 0);
  EXPECT_EQ(b.normal, a.normal);
  EXPECT_EQ(b.weighted, a.weighted);
  const TriMesh small = shapes::plane(4);
  const HeightNormalTerms other = height_normal_terms(small, test::planar_param(small, 0.9, 0.05));
  EXPECT_THROW(evaluate_material_textures(mesh, param, own, pts, exact, eo, &other), InvalidInputError);
  MaterialTextures wrong;
  EXPECT_THROW(material_textures_from_values(mesh, param, map, at_texels, file.background, 2, 0.05, wrong, kAllChannels,
                                             &other),
               InvalidInputError);
}

TEST(MaterialDetail, EachCasePaintsOnlyItsOwnChannel) {
  const TriMesh mesh = shapes::plane(24);
  const std::vector<SurfacePoint> pts = sample_surface(mesh, 20000, 3);
  for (const MaterialDetail d : {MaterialDetail::RoughnessScratches, MaterialDetail::HeightEngravings}) {
    const MaterialStrokeFile file = generate_material_detail(mesh, d, 4);
    EXPECT_EQ(file.num_dabs(), generate_material_detail(mesh, d, 4).num_dabs());  // reproducible
    ASSERT_EQ(file.layers.size(), 2u);
    const std::vector<MaterialValue> v = evaluate_material(mesh, file, pts);
    const int detail = d == MaterialDetail::RoughnessScratches ? 4 : 6;
    int varied = 0;
    for (const MaterialValue& x : v) {
      for (int c = 0; c < kMaterialComponents; ++c)
        ASSERT_TRUE(c == detail || x[c] == v[0][c]) << "component " << c;  // flat everywhere else
      varied += x[detail] != v[0][detail];
    }
    EXPECT_GT(varied, 0) << "the strokes paint their channel";
  }
}

}  // namespace
}  // namespace adaptex
