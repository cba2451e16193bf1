// render_layout (param/layout_image.h): the image size is bounded by the library's texture limit.
#include <gtest/gtest.h>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/shapes.h"
#include "adaptex/param/layout_image.h"
#include "adaptex/param/unwrap.h"

namespace adaptex {
namespace {

TEST(LayoutImage, SizeIsBoundedByTheTextureLimit) {
  const TriMesh mesh = shapes::icosphere(1);
  const Parameterization param = unwrap(mesh).param;
  const std::vector<double> value(param.uv_faces.size(), 1.0);
  LayoutImageOptions o;
  o.size = 64;
  const ImageRGBA8 img = render_layout(param, value, o);
  EXPECT_EQ(img.width, 64);
  EXPECT_EQ(img.height, 64);
  o.size = kMaxTextureSize + 1;  // 8193² RGBA would be 268 MB: refused before allocating
  EXPECT_THROW(render_layout(param, value, o), InvalidInputError);
  o.size = 0;
  EXPECT_THROW(render_layout(param, value, o), InvalidInputError);
}

}  // namespace
}  // namespace adaptex
