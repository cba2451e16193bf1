// Direct tests of the texture update after a re-parameterization (adapt/texture_update.h, thesis
// §3.7.3): resample_texture() carries the surface signal from one layout to another, replay_texture()
// is exactly a fresh painting of the history on the new layout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "adaptex/adapt/texture_update.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/texel_map.h"
#include "adaptex/param/unwrap.h"

namespace adaptex {
namespace {

/// A smooth signal on the surface: each channel is linear in one coordinate (sphere of radius 1).
std::array<double, 3> signal(const Vec3f& p) {
  return {255.0 * (p.x() + 1) / 2, 255.0 * (p.y() + 1) / 2, 255.0 * (p.z() + 1) / 2};
}

/// The texture of \p map showing signal() at every covered texel; an uncovered texel takes the value
/// of the nearest covered texel of its row (so bilinear sampling at chart borders stays close).
ImageRGBA8 signal_texture(const TexelMap& map) {
  ImageRGBA8 img(map.width, map.height, {0, 0, 0, 255});
  for (int j = 0; j < map.height; ++j) {
    std::vector<int> covered;
    for (int i = 0; i < map.width; ++i)
      if (map.face[map.index(i, j)] >= 0) covered.push_back(i);
    if (covered.empty()) continue;
    for (int i = 0; i < map.width; ++i) {
      const auto it = std::lower_bound(covered.begin(), covered.end(), i);
      int src = it == covered.end() ? covered.back() : *it;
      if (it != covered.begin() && i - *(it - 1) < src - i) src = *(it - 1);
      const auto c = signal(map.position[map.index(src, j)]);
      for (int ch = 0; ch < 3; ++ch) img.texel(i, j)[ch] = static_cast<std::uint8_t>(std::lround(c[ch]));
    }
  }
  return img;
}

/// The 90th percentile over the covered texels of \p map of the largest channel error of \p img
/// against signal().
double p90_error(const TexelMap& map, const ImageRGBA8& img) {
  std::vector<double> err;
  for (int t : map.inside) {
    const auto c = signal(map.position[t]);
    const std::uint8_t* px = img.data.data() + static_cast<size_t>(t) * 4;
    double e = 0;
    for (int ch = 0; ch < 3; ++ch) e = std::max(e, std::abs(px[ch] - c[ch]));
    err.push_back(e);
  }
  std::nth_element(err.begin(), err.begin() + err.size() * 9 / 10, err.end());
  return err[err.size() * 9 / 10];
}

struct TwoLayouts : ::testing::Test {
  // Two unit spheres (two charts, so the packed layouts leave texels outside every chart).
  TriMesh mesh = shapes::disjoint_union({shapes::sphere(40, 20), shapes::sphere(24, 12)});
  Parameterization old_param = unwrap(mesh).param;
  Parameterization new_param = [this] {
    UnwrapOptions o;  // another layout of the same faces: other weights, no stretch minimization
    o.weights = EmbeddingWeights::ShapePreserving;
    o.yoshizawa_max_iterations = 0;
    return unwrap(mesh, o).param;
  }();
  static constexpr int N = 256;
};

TEST_F(TwoLayouts, TheLayoutsDiffer) {
  ASSERT_EQ(old_param.uv_faces.size(), new_param.uv_faces.size());
  double moved = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      moved = std::max(moved, (old_param.uv[old_param.uv_faces[f][k]] - new_param.uv[new_param.uv_faces[f][k]]).norm());
  EXPECT_GT(moved, 0.05);
}

TEST_F(TwoLayouts, ResampleCarriesTheSurfaceSignalToTheNewLayout) {
  const TexelMap old_map = build_texel_map(mesh, old_param, N, N);
  const TexelMap new_map = build_texel_map(mesh, new_param, N, N);
  const ImageRGBA8 old_tex = signal_texture(old_map);
  ASSERT_LE(p90_error(old_map, old_tex), 0.5);
  const ImageRGBA8 out = resample_texture(old_param, old_tex, new_map, 0, {1, 2, 3, 4});
  ASSERT_EQ(out.width, N);
  ASSERT_EQ(out.height, N);
  const double e = p90_error(new_map, out);
  // Reading the old texture at the *new* UVs (the mistake resampling exists to avoid) is far off.
  const double wrong = p90_error(new_map, old_tex);
  std::printf("resample: 90th-percentile error %.2f levels (old texture read at the new UVs: %.2f)\n", e, wrong);
  EXPECT_LE(e, 3.0);
  EXPECT_GT(wrong, 10 * std::max(e, 1.0));
  // Texels outside the new charts get the outside colour (no padding asked).
  int outside = 0;
  for (int t = 0; t < N * N; ++t) {
    if (new_map.face[t] >= 0) continue;
    ++outside;
    const std::uint8_t* px = out.data.data() + static_cast<size_t>(t) * 4;
    ASSERT_EQ(std::vector<int>(px, px + 4), (std::vector<int>{1, 2, 3, 4})) << t;
  }
  EXPECT_GT(outside, 0);
}

TEST_F(TwoLayouts, ResampleOntoTheSameLayoutKeepsEveryCoveredTexel) {
  PainterOptions po;
  po.width = po.height = 128;
  Painter painter(mesh, old_param, po);
  GenerateOptions go;
  go.count = 6;
  painter.paint_all(generate_strokes(mesh, go));
  const ImageRGBA8 tex = painter.texture();
  const TexelMap& map = painter.texel_map();
  const ImageRGBA8 out = resample_texture(old_param, tex, map, 0);
  // Texel centres map to themselves: bilinear sampling at a texel centre returns that texel.
  int differ = 0;
  for (int t : map.inside)
    for (int ch = 0; ch < 4; ++ch) differ += std::abs(out.data[4 * t + ch] - tex.data[4 * t + ch]) > 1;
  EXPECT_EQ(differ, 0);
  // With padding, the texels next to the charts are filled too (from the charts, not the outside colour).
  const ImageRGBA8 padded = resample_texture(old_param, tex, map, 2, {1, 2, 3, 4});
  int filled = 0;
  for (int t = 0; t < 128 * 128; ++t)
    filled += map.face[t] < 0 && padded.data[4 * t + 3] == 255 && padded.data[4 * t] != 1;
  EXPECT_GT(filled, 0);
}

TEST_F(TwoLayouts, ResampleRejectsEmptyInputs) {
  const TexelMap map = build_texel_map(mesh, new_param, 16, 16);
  EXPECT_THROW(resample_texture(old_param, ImageRGBA8(), map, 0), InvalidInputError);
  EXPECT_THROW(resample_texture(old_param, ImageRGBA8(4, 4), TexelMap(), 0), InvalidInputError);
  // A layout of another mesh (fewer faces than the map covers): an error, not silently blank texels.
  Parameterization fewer = old_param;
  fewer.uv_faces.resize(fewer.uv_faces.size() / 2);
  EXPECT_THROW(resample_texture(fewer, ImageRGBA8(4, 4), map, 0), InvalidInputError);
}

TEST_F(TwoLayouts, ReplayIsAFreshPaintingOfTheHistoryOnTheNewLayout) {
  GenerateOptions go;
  go.count = 8;
  go.seed = 3;
  const StrokeFile history = generate_strokes(mesh, go);
  PainterOptions po;
  po.width = po.height = 128;
  Painter replayed = replay_texture(mesh, new_param, history, po);
  Painter fresh(mesh, new_param, po, history.background);
  fresh.paint_all(history);
  EXPECT_EQ(replayed.texture().data, fresh.texture().data);
  // It is the new layout's texture, not the old one's.
  Painter on_old(mesh, old_param, po, history.background);
  on_old.paint_all(history);
  EXPECT_NE(replayed.texture().data, on_old.texture().data);
  // The strokes were painted: the texture is not just the background.
  StrokeFile nothing;
  nothing.background = history.background;
  Painter blank = replay_texture(mesh, new_param, nothing, po);
  EXPECT_NE(replayed.texture().data, blank.texture().data);
  for (int t : blank.texel_map().inside)
    for (int ch = 0; ch < 3; ++ch)
      ASSERT_EQ(blank.texture().data[4 * t + ch], std::lround(history.background[ch] * 255)) << t;
}

}  // namespace
}  // namespace adaptex
