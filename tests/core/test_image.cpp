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
