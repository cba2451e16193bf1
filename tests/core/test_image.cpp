#include <gtest/gtest.h>

#include "adaptex/core/image.h"

using namespace adaptex;

TEST(Image, BilinearHitsTexelCentresAndClampsToEdge) {
  ImageRGBA8 img(2, 2);
  img.texel(0, 0)[0] = 0;
  img.texel(1, 0)[0] = 255;
  img.texel(0, 1)[0] = 255;
  img.texel(1, 1)[0] = 255;
  EXPECT_NEAR(sample_bilinear(img, 0.25, 0.25).x(), 0.0, 1e-12);  // centre of texel (0,0)
  EXPECT_NEAR(sample_bilinear(img, 0.75, 0.25).x(), 1.0, 1e-12);
  EXPECT_NEAR(sample_bilinear(img, 0.5, 0.25).x(), 0.5, 1e-12);   // halfway between centres
  EXPECT_NEAR(sample_bilinear(img, 0.0, 0.0).x(), 0.0, 1e-12);    // clamp: edge = first centre
  EXPECT_NEAR(sample_bilinear(img, 0.5, 0.5).x(), 0.75, 1e-12);
}

// bilinear_tap(): the per-axis footprint sample_bilinear() uses, so a lookup from taps gives its
// values exactly, inside, between texels, at and past the edges (clamp).
TEST(Image, BilinearTapsReproduceSampleBilinear) {
  adaptex::ImageF img(7, 5);
  for (size_t k = 0; k < img.data.size(); ++k) img.data[k] = static_cast<float>((k * 37) % 11) * 0.25f;
  for (double u = -0.2; u <= 1.2; u += 0.0371)
    for (double v = -0.2; v <= 1.2; v += 0.0413) {
      const adaptex::BilinearTap x = adaptex::bilinear_tap(img.width, u), y = adaptex::bilinear_tap(img.height, v);
      ASSERT_TRUE(x.i0 >= 0 && x.i1 < img.width && y.i0 >= 0 && y.i1 < img.height);
      const double a = img.at(x.i0, y.i0), b = img.at(x.i1, y.i0), d = img.at(x.i0, y.i1), e = img.at(x.i1, y.i1);
      const double bottom = a + (b - a) * x.f, top = d + (e - d) * x.f;
      EXPECT_EQ(bottom + (top - bottom) * y.f, adaptex::sample_bilinear(img, u, v)) << u << " " << v;
    }
  // A texel centre reads that texel.
  const adaptex::BilinearTap c = adaptex::bilinear_tap(7, 3.5 / 7);
  EXPECT_EQ(c.i0, 3);
  EXPECT_EQ(c.f, 0.0);
}
