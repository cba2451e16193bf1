// unwrap_options_for_texture (param/unwrap.h): the gutter is the seam padding in texels of the texture.
#include <gtest/gtest.h>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/param/unwrap.h"

namespace adaptex {
namespace {

TEST(UnwrapOptions, GutterIsThePaddingInTexelsOfTheTexture) {
  UnwrapOptions base;
  base.charts = ChartMode::Single;
  const UnwrapOptions o = unwrap_options_for_texture(256, 4, base);
  EXPECT_EQ(o.gutter_texture_size, 256);
  EXPECT_DOUBLE_EQ(o.gutter_texels, 4.0);
  EXPECT_EQ(o.charts, ChartMode::Single);  // the rest of base is kept
  EXPECT_DOUBLE_EQ(unwrap_options_for_texture(256, 0).gutter_texels, 2.0);   // at least 2 texels
  EXPECT_DOUBLE_EQ(unwrap_options_for_texture(16, 8).gutter_texels, 3.2);    // at most a fifth
  EXPECT_THROW(unwrap_options_for_texture(0, 4), InvalidInputError);
  EXPECT_EQ(unwrap_options_for_texture(kMaxTextureSize, 4).gutter_texture_size, kMaxTextureSize);
  EXPECT_THROW(unwrap_options_for_texture(kMaxTextureSize + 1, 4), InvalidInputError);
  EXPECT_THROW(unwrap_options_for_texture(256, -1), InvalidInputError);
}

}  // namespace
}  // namespace adaptex
