// The asset measure (paint/asset_eval.h): surface PSNR against a reference textured mesh, box
// downsizing, and the texel count a baseline needs for equal quality. Meshes and textures built in code.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/asset_eval.h"

using namespace adaptex;

namespace {

/// plane(n) with one wedge per vertex at its (x, y): UVs in [0,1]^2, one chart.
Parameterization planar_uv(const TriMesh& m) {
  Parameterization p;
  for (const Vec3& x : m.positions) p.uv.emplace_back(x.x(), x.y());
  p.uv_faces = m.faces;
  for (int v = 0; v < m.num_vertices(); ++v) p.wedge_vertex.push_back(v);
  p.face_chart.assign(m.faces.size(), 0);
  p.num_charts = 1;
  return p;
}

/// Random RGB in [lo, hi], alpha 255.
ImageRGBA8 noise(int w, int h, int lo, int hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> d(lo, hi);
  ImageRGBA8 img(w, h);
  for (size_t i = 0; i < img.data.size(); ++i) img.data[i] = static_cast<std::uint8_t>(i % 4 == 3 ? 255 : d(rng));
  return img;
}

/// Every face split into four at its edge midpoints (a conforming refinement), UVs interpolated.
void split4(const TriMesh& m, const Parameterization& p, TriMesh& out, Parameterization& out_p, FaceData<int>& parent) {
  out = {};
  out_p = {};
  parent.clear();
  for (int f = 0; f < m.num_faces(); ++f) {
    const Face& t = m.faces[f];
    const Face& w = p.uv_faces[f];
    Vec3 x[6];
    Vec2 u[6];
    for (int k = 0; k < 3; ++k) {
      x[k] = m.positions[t[k]];
      u[k] = p.uv[w[k]];
      x[3 + k] = 0.5 * (m.positions[t[k]] + m.positions[t[(k + 1) % 3]]);
      u[3 + k] = 0.5 * (p.uv[w[k]] + p.uv[w[(k + 1) % 3]]);
    }
    const int base = out.num_vertices();
    for (int k = 0; k < 6; ++k) {
      out.positions.push_back(x[k]);
      out_p.uv.push_back(u[k]);
      out_p.wedge_vertex.push_back(base + k);
    }
    for (const Face& c : {Face{0, 3, 5}, Face{3, 1, 4}, Face{5, 4, 2}, Face{3, 4, 5}}) {
      const Face g{base + c[0], base + c[1], base + c[2]};
      out.faces.push_back(g);
      out_p.uv_faces.push_back(g);
      out_p.face_chart.push_back(0);
      parent.push_back(f);
    }
  }
  out_p.num_charts = 1;
}

}  // namespace

TEST(SurfacePsnr, IdenticalTextureAndLayoutIsExact) {
  const TriMesh m = shapes::plane(6);
  const Parameterization p = planar_uv(m);
  const ImageRGBA8 tex = noise(32, 32, 0, 255, 1);
  const SurfacePsnr r = surface_psnr(m, p, tex, m, p, tex);
  EXPECT_EQ(r.mse, 0.0);
  EXPECT_EQ(r.psnr, 200.0);
  EXPECT_EQ(r.samples, 200000);
}

TEST(SurfacePsnr, ConstantOffsetGivesTheExactPsnr) {
  const TriMesh m = shapes::plane(6);
  const Parameterization p = planar_uv(m);
  const ImageRGBA8 ref = noise(32, 32, 0, 200, 2);
  for (const int k : {1, 5, 40}) {
    ImageRGBA8 test = ref;
    for (size_t i = 0; i < test.data.size(); ++i)
      if (i % 4 != 3) test.data[i] = static_cast<std::uint8_t>(test.data[i] + k);
    const SurfacePsnr r = surface_psnr(m, p, ref, m, p, test);
    EXPECT_NEAR(r.mse, (k / 255.0) * (k / 255.0), 1e-12) << k;
    EXPECT_NEAR(r.psnr, 20.0 * std::log10(255.0 / k), 1e-6) << k;
  }
}

TEST(SurfacePsnr, AlphaIsIgnored) {
  const TriMesh m = shapes::plane(4);
  const Parameterization p = planar_uv(m);
  const ImageRGBA8 ref = noise(16, 16, 0, 255, 3);
  ImageRGBA8 test = ref;
  for (size_t i = 3; i < test.data.size(); i += 4) test.data[i] = 0;
  EXPECT_EQ(surface_psnr(m, p, ref, m, p, test).psnr, 200.0);
}

TEST(SurfacePsnr, TheTestLayoutIsLookedUpAtItsOwnUvs) {
  // A mirrored layout (u -> 1 - u) with the mirrored texture renders the same colours at every point:
  // texel i of the mirror has its centre at 1 - (i + 0.5) / W, so the bilinear lookups agree exactly.
  const TriMesh m = shapes::plane(5);
  const Parameterization p = planar_uv(m);
  Parameterization mirrored = p;
  for (Vec2& uv : mirrored.uv) uv.x() = 1.0 - uv.x();
  const ImageRGBA8 ref = noise(24, 24, 0, 255, 4);
  ImageRGBA8 flipped(24, 24);
  for (int j = 0; j < 24; ++j)
    for (int i = 0; i < 24; ++i)
      for (int c = 0; c < 4; ++c) flipped.texel(23 - i, j)[c] = ref.texel(i, j)[c];
  EXPECT_GT(surface_psnr(m, p, ref, m, mirrored, flipped).psnr, 120.0);
  // The same layout with the unmirrored texture is far off (random texels): the layout matters.
  EXPECT_LT(surface_psnr(m, p, ref, m, mirrored, ref).psnr, 20.0);
}

TEST(SurfacePsnr, RefinedMeshIsJudgedAtTheSameSurfacePoints) {
  const TriMesh m = shapes::plane(4);
  const Parameterization p = planar_uv(m);
  TriMesh fine;
  Parameterization fine_p;
  FaceData<int> parent;
  split4(m, p, fine, fine_p, parent);
  const ImageRGBA8 tex = noise(16, 16, 0, 255, 5);
  EXPECT_GT(surface_psnr(m, p, tex, fine, fine_p, tex, parent).psnr, 120.0);
  // Without the parent map the face counts differ: an error, not a wrong figure.
  EXPECT_THROW(surface_psnr(m, p, tex, fine, fine_p, tex), InvalidInputError);
  // A wrong parent map (every child on face 0) carries the points to other places: large error.
  const FaceData<int> wrong(parent.size(), 0);
  EXPECT_LT(surface_psnr(m, p, tex, fine, fine_p, tex, wrong).psnr, 20.0);
}

TEST(SurfacePsnr, DeterministicForASeedAndKeepsSampleErrors) {
  const TriMesh m = shapes::sphere(12, 8);
  Parameterization p;  // UV from the position's (x, y): overlapping halves, still a valid lookup
  for (const Vec3& x : m.positions) p.uv.emplace_back(0.5 + 0.5 * x.x(), 0.5 + 0.5 * x.y());
  p.uv_faces = m.faces;
  for (int v = 0; v < m.num_vertices(); ++v) p.wedge_vertex.push_back(v);
  p.face_chart.assign(m.faces.size(), 0);
  p.num_charts = 1;
  const ImageRGBA8 ref = noise(32, 32, 0, 255, 6), test = noise(32, 32, 0, 255, 7);
  SurfacePsnrOptions o;
  o.samples = 5000;
  o.keep_sample_errors = true;
  const SurfacePsnr a = surface_psnr(m, p, ref, m, p, test, {}, o), b = surface_psnr(m, p, ref, m, p, test, {}, o);
  EXPECT_EQ(a.mse, b.mse);
  ASSERT_EQ(a.sample_errors.size(), 5000u);
  ASSERT_EQ(a.points.size(), 5000u);
  double sum = 0, mx = 0;
  for (float e : a.sample_errors) sum += e, mx = std::max<double>(mx, e);
  EXPECT_NEAR(sum / 5000.0, a.mse, 1e-6 * a.mse);
  EXPECT_NEAR(mx, a.max_error, 1e-6 * a.max_error);
  o.seed = 2;
  EXPECT_NE(surface_psnr(m, p, ref, m, p, test, {}, o).mse, a.mse);
}

TEST(SurfacePsnr, BadInputIsAnError) {
  const TriMesh m = shapes::plane(2);
  const Parameterization p = planar_uv(m);
  const ImageRGBA8 tex = noise(4, 4, 0, 255, 8);
  EXPECT_THROW(surface_psnr(m, p, ImageRGBA8{}, m, p, tex), InvalidInputError);
  EXPECT_THROW(surface_psnr(m, p, tex, m, p, ImageRGBA8{}), InvalidInputError);
  SurfacePsnrOptions o;
  o.samples = 0;
  EXPECT_THROW(surface_psnr(m, p, tex, m, p, tex, {}, o), InvalidInputError);
  Parameterization short_p = p;
  short_p.uv_faces.pop_back();
  EXPECT_THROW(surface_psnr(m, p, tex, m, short_p, tex), InvalidInputError);
}

TEST(BoxDownsize, IntegerFactorAveragesBlocks) {
  const ImageRGBA8 img = noise(8, 6, 0, 255, 9);
  const ImageRGBA8 out = box_downsize(img, 4, 3);
  ASSERT_EQ(out.width, 4);
  ASSERT_EQ(out.height, 3);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 4; ++c) {
        const double mean = (img.texel(2 * i, 2 * j)[c] + img.texel(2 * i + 1, 2 * j)[c] +
                             img.texel(2 * i, 2 * j + 1)[c] + img.texel(2 * i + 1, 2 * j + 1)[c]) / 4.0;
        EXPECT_NEAR(out.texel(i, j)[c], mean, 0.5 + 1e-9) << i << "," << j << "," << c;
      }
}

TEST(BoxDownsize, FractionalFootprintsAreAreaWeighted) {
  ImageRGBA8 img(3, 1);
  const int v[3] = {0, 90, 240};
  for (int i = 0; i < 3; ++i)
    for (int c = 0; c < 4; ++c) img.texel(i, 0)[c] = static_cast<std::uint8_t>(v[i]);
  const ImageRGBA8 out = box_downsize(img, 2, 1);
  // Output 0 covers source [0, 1.5): (0 + 0.5 * 90) / 1.5 = 30; output 1 covers [1.5, 3): (45 + 240) / 1.5 = 190.
  EXPECT_EQ(out.texel(0, 0)[0], 30);
  EXPECT_EQ(out.texel(1, 0)[0], 190);
  EXPECT_EQ(out.texel(1, 0)[3], 190);  // alpha averaged like the colours
}

TEST(BoxDownsize, SameSizeIsTheIdentityAndBadSizesThrow) {
  const ImageRGBA8 img = noise(7, 5, 0, 255, 10);
  EXPECT_EQ(box_downsize(img, 7, 5).data, img.data);
  EXPECT_THROW(box_downsize(img, 0, 5), InvalidInputError);
  EXPECT_THROW(box_downsize(ImageRGBA8{}, 2, 2), InvalidInputError);
}

TEST(TexelsToMatch, InterpolatesPsnrLinearlyInLogTexels) {
  const std::vector<double> t{1024, 4096, 16384}, psnr{30, 33, 36};
  EXPECT_DOUBLE_EQ(texels_to_match(t, psnr, 33).texels, 4096);
  EXPECT_NEAR(texels_to_match(t, psnr, 34.5).texels, 8192, 1e-6);
  const TexelMatch above = texels_to_match(t, psnr, 39);
  EXPECT_TRUE(above.above_range);
  EXPECT_NEAR(above.texels, 65536, 1e-6);
  const TexelMatch below = texels_to_match(t, psnr, 27);
  EXPECT_TRUE(below.below_range);
  EXPECT_NEAR(below.texels, 256, 1e-9);
  // Order of the points does not matter.
  EXPECT_NEAR(texels_to_match({16384, 1024, 4096}, {36, 30, 33}, 34.5).texels, 8192, 1e-6);
}

TEST(TexelsToMatch, ALossIsFlatAndAFlatEndNeverReaches) {
  // 4096 lost PSNR: counted as 30 (flat), so 31.5 lies half way from 4096 to 16384 in log2.
  EXPECT_NEAR(texels_to_match({1024, 4096, 16384}, {30, 29, 33}, 31.5).texels, 8192, 1e-6);
  EXPECT_TRUE(std::isinf(texels_to_match({1024, 4096}, {30, 30}, 31).texels));
  EXPECT_THROW(texels_to_match({1024}, {30}, 30), InvalidInputError);
  EXPECT_THROW(texels_to_match({1024, 0}, {30, 31}, 30), InvalidInputError);
}
