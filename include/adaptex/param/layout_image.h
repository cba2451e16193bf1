#pragma once
/// \file layout_image.h
/// Picture of a UV layout (the `unwrap --layout` PNG, thesis Figure 3.8 "geometry stretch map"):
/// every UV triangle filled with a colour ramp by a per-face value (normally its L2 stretch), with
/// the triangle edges drawn on top.
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/parameterization.h"

namespace adaptex {

/// Settings of render_layout().
struct LayoutImageOptions {
  int size = 1024;            ///< Width and height in pixels.
  /// Values at the ends of the ramp (blue at \p low, through green and yellow, red at \p high).
  /// high <= low (the default): the 1st and 99th percentiles of the finite values.
  double low = 0.0, high = 0.0;
  /// Draw the triangle edges (skipped automatically when the mean UV triangle covers fewer than
  /// 6 pixels, where they would hide the colours).
  bool wireframe = true;
};

/// Rasterizes the layout: image row 0 is v = 0 (ImageRGBA8 convention). Pixels outside every
/// triangle are white; triangles with a non-finite value are magenta.
/// \param face_value F values, parallel to param.uv_faces
/// \throw InvalidInputError size out of [1, kMaxTextureSize] (core/limits.h) or face_value of the wrong size
ImageRGBA8 render_layout(const Parameterization& param, const std::vector<double>& face_value,
                         const LayoutImageOptions& options = {});

}  // namespace adaptex
