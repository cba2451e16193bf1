// Texel saving factor (paint/texel_saving.h): inverse of none's PSNR, piecewise linear in log2 N.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "adaptex/core/errors.h"
#include "adaptex/paint/texel_saving.h"

using namespace adaptex;

TEST(TexelSaving, GridPointsGiveTheirAreas) {
  const std::array<double, 3> none{24.0, 27.0, 31.0};
  EXPECT_DOUBLE_EQ(texel_saving_factor(24.0, none).factor, 1.0);
  EXPECT_DOUBLE_EQ(texel_saving_factor(27.0, none).factor, 4.0);
  EXPECT_DOUBLE_EQ(texel_saving_factor(31.0, none).factor, 16.0);
  EXPECT_FALSE(texel_saving_factor(31.0, none).above_range);
}

TEST(TexelSaving, LinearInLog2SizeBetweenGridPoints) {
  const std::array<double, 3> none{24.0, 27.0, 31.0};
  // Half way from N to 2N in dB is N' = sqrt(2) N: area factor 2.
  EXPECT_NEAR(texel_saving_factor(25.5, none).factor, 2.0, 1e-12);
  // A quarter of the way from 2N to 4N: N' = 2^1.25 N, factor 4^1.25.
  EXPECT_NEAR(texel_saving_factor(28.0, none).factor, std::pow(4.0, 1.25), 1e-12);
}

TEST(TexelSaving, ExtrapolatesBelowWithTheFirstSlopeAndClamps) {
  const std::array<double, 3> none{24.0, 28.0, 31.0};
  const TexelSaving a = texel_saving_factor(23.0, none);  // x = -1/4 with the 4 dB slope (not the 3 dB one)
  EXPECT_NEAR(a.factor, std::pow(4.0, -0.25), 1e-12);
  EXPECT_FALSE(a.clamped);
  const TexelSaving b = texel_saving_factor(10.0, none);
  EXPECT_DOUBLE_EQ(b.factor, 0.25);
  EXPECT_TRUE(b.clamped);
  EXPECT_LT(a.factor, 1.0);
}

TEST(TexelSaving, ExtrapolatesAboveWithTheLastSlopeAndMarksIt) {
  const std::array<double, 3> none{24.0, 28.0, 30.0};
  const TexelSaving r = texel_saving_factor(31.0, none);  // x = 2 + 1/2 with the 2 dB slope
  EXPECT_TRUE(r.above_range);
  EXPECT_NEAR(r.factor, 32.0, 1e-9);
}

TEST(TexelSaving, LosslessLevelCountsAsEqual) {
  const std::array<double, 3> none{52.0, 58.0, 63.0};
  const TexelSaving same = texel_saving_factor(51.0, none);
  EXPECT_TRUE(same.lossless);
  EXPECT_DOUBLE_EQ(same.factor, 1.0);
  // Worse than none, but both >= 50 dB: not "below 1" either.
  EXPECT_FALSE(worse_than_none(51.0, 52.0));
  // The method reaching 50 dB is matched by none reaching 50 dB (not 55).
  const std::array<double, 3> low{45.0, 55.0, 60.0};
  EXPECT_NEAR(texel_saving_factor(70.0, low).factor, std::pow(4.0, 0.5), 1e-12);
  EXPECT_FALSE(texel_saving_factor(70.0, low).above_range);
  // Below 50 dB against none above it: a real loss.
  EXPECT_LT(texel_saving_factor(49.0, none).factor, 1.0);
  EXPECT_TRUE(worse_than_none(49.0, 52.0));
}

TEST(TexelSaving, WorseThanNoneUsesTheTolerance) {
  EXPECT_FALSE(worse_than_none(29.95, 30.0));
  EXPECT_TRUE(worse_than_none(29.85, 30.0));
  EXPECT_FALSE(worse_than_none(31.0, 30.0));
}

TEST(TexelSaving, NonMonotoneNoneIsFlatAndBadInputThrows) {
  // none lost PSNR from 2N to 4N: the curve is flat there, so anything above 2N's is above range.
  const std::array<double, 3> none{40.0, 46.0, 45.0};
  const TexelSaving r = texel_saving_factor(47.0, none);
  EXPECT_TRUE(r.above_range);
  EXPECT_DOUBLE_EQ(r.factor, 16.0);
  EXPECT_NEAR(texel_saving_factor(43.0, none).factor, 2.0, 1e-12);
  EXPECT_THROW(texel_saving_factor(std::numeric_limits<double>::quiet_NaN(), none), InvalidInputError);
  TexelSavingOptions o;
  o.min_factor = 0;
  EXPECT_THROW(texel_saving_factor(30.0, none, o), InvalidInputError);
}
