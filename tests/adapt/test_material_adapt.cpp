// Layered materials adapted by one summed error model (adapt/material_adapt.h, docs/error_model.md
// "Materials"): a channel's detail draws texels whichever channel carries it, a channel without
// detail adds nothing, and the adapted layout reconstructs the material better than the fixed one.
#include <gtest/gtest.h>

#include "adaptex/adapt/material_adapt.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/material_strokes.h"
#include "../paint/brush_test_util.h"

namespace adaptex {
namespace {

/// Thin hard scratches in the corner x, y < 0.3 of the unit plane, painting \p channels.
MaterialStrokeFile corner_scratches(const std::string& channels, bool flat_metal_layer = false,
                                    const std::string& hardness = "0.9") {
  std::string strokes;
  for (int k = 0; k < 8; ++k) {
    const double y = 0.03 + 0.03 * k;
    strokes += std::string(k ? "," : "") + R"({"channels": )" + channels +
               R"(, "radius": 0.006, "hardness": )" + hardness + R"(, "dabs": [[0.02, )" + std::to_string(y) + ", 0], [0.1, " +
               std::to_string(y + 0.01) + ", 0], [0.2, " + std::to_string(y) + ", 0], [0.28, " +
               std::to_string(y + 0.005) + ", 0]]}";
  }
  std::string layers = R"({"strokes": [)" + strokes + "]}";
  if (flat_metal_layer) layers += R"(, {"strokes": [{"type": "fill", "channels": {"metallic": 1}}]})";
  return parse_material_strokes(R"({"format": "adaptex.strokes", "version": 2, "layers": [)" + layers + "]}", "m.json",
                                ".");
}

/// Mean density of the cells of the corner x, y < 0.3 over the mean elsewhere.
double corner_ratio(const ImageF& d) {
  double in = 0, out = 0;
  int n_in = 0, n_out = 0;
  for (int j = 0; j < d.height; ++j)
    for (int i = 0; i < d.width; ++i) {
      const bool corner = (i + 0.5) / d.width < 0.3 && (j + 0.5) / d.height < 0.3;
      (corner ? in : out) += d.at(i, j);
      (corner ? n_in : n_out) += 1;
    }
  return (in / n_in) / (out / n_out);
}

ErrorDensity model_of(const TriMesh& mesh, const Parameterization& param, const MaterialStrokeFile& file) {
  MaterialPaintOptions po;
  po.size = 128;
  const MaterialTextures tex = paint_material(mesh, param, file, po);
  ErrorDensityOptions eo;
  eo.cells = 32;
  const TexelMap map = build_texel_map(mesh, param, 128, 128);
  return compute_error_density(mesh, param, map, material_error_planes(mesh, param, map, file, tex, 0.25), eo);
}

TEST(MaterialAdapt, DetailInAnyChannelDrawsTexels) {
  const TriMesh mesh = shapes::plane(24);
  const Parameterization param = test::planar_param(mesh);
  for (const std::string channels : {R"({"roughness": 0.05})", R"({"metallic": 1})", R"({"height": 0.1})",
                                     R"({"base_color": [0.1, 0.1, 0.1]})"}) {
    const ErrorDensity m = model_of(mesh, param, corner_scratches(channels));
    EXPECT_GT(corner_ratio(m.density), 3.0) << channels;
    EXPECT_GT(m.predicted_gain_db, 0.5) << channels;
  }
}

TEST(MaterialAdapt, AChannelWithoutDetailAddsNothing) {
  const TriMesh mesh = shapes::plane(24);
  const Parameterization param = test::planar_param(mesh);
  const ErrorDensity a = model_of(mesh, param, corner_scratches(R"({"roughness": 0.05})"));
  const ErrorDensity b = model_of(mesh, param, corner_scratches(R"({"roughness": 0.05})", true));
  ASSERT_EQ(a.density.data.size(), b.density.data.size());
  double worst = 0;
  for (size_t k = 0; k < a.density.data.size(); ++k) worst = std::max(worst, double(std::abs(a.density.data[k] - b.density.data[k])));
  EXPECT_LT(worst, 1e-6);
}

TEST(MaterialAdapt, AdaptedLayoutReconstructsTheMaterialBetter) {
  const TriMesh mesh = shapes::plane(24);
  const Parameterization param = test::planar_param(mesh, 0.9, 0.05);
  MaterialAdaptOptions o;
  o.paint.size = 128;
  o.check_samples = 50000;
  // Grooves with a profile (hardness 0): every channel is judged, the height through its normal, and
  // the normal of a hard step narrower than a texel gets worse in L2 as texels sharpen it.
  const MaterialAdaptResult r =
      adapt_material(mesh, param, corner_scratches(R"({"roughness": 0.05, "height": 0.2})", false, "0"), o);
  EXPECT_TRUE(r.adapted);
  EXPECT_LT(r.error_adapted, 0.5 * r.error_fixed);
  EXPECT_EQ(r.textures.base_color.width, 128);
  EXPECT_EQ(r.param.uv_faces.size(), r.mesh.faces.size());
  MaterialAdaptOptions none = o;
  none.adapt.mode = AdaptMode::None;
  const MaterialAdaptResult f = adapt_material(mesh, param, corner_scratches(R"({"roughness": 0.05})"), none);
  EXPECT_FALSE(f.adapted);
  EXPECT_EQ(f.param.uv, param.uv);
  MaterialAdaptOptions thesis = o;
  thesis.adapt.mode = AdaptMode::Single;
  EXPECT_THROW(adapt_material(mesh, param, corner_scratches(R"({"roughness": 0.05})"), thesis), InvalidInputError);
}

}  // namespace
}  // namespace adaptex
