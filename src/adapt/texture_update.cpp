// Texture update after a re-parameterization (thesis §3.7.3): resample and replay.
#include "adaptex/adapt/texture_update.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/paint/padding.h"

namespace adaptex {

ImageRGBA8 resample_texture(const Parameterization& old_param, const ImageRGBA8& old_texture,
                            const TexelMap& new_map, int padding, std::array<std::uint8_t, 4> outside) {
  if (old_texture.empty()) throw InvalidInputError("resample_texture: empty old texture");
  if (new_map.width <= 0 || new_map.height <= 0) throw InvalidInputError("resample_texture: empty texel map");
  const int F = static_cast<int>(old_param.uv_faces.size());
  for (int t : new_map.inside)
    if (new_map.face[t] < 0 || new_map.face[t] >= F)
      throw InvalidInputError("resample_texture: the texel map covers face " + std::to_string(new_map.face[t]) +
                              ", the old parameterization has " + std::to_string(F) +
                              " faces (the two layouts must be of the same mesh)");
  ImageRGBA8 out(new_map.width, new_map.height, outside);
  tbb::parallel_for(size_t(0), new_map.inside.size(), [&](size_t k) {
    const int t = new_map.inside[k];
    const int f = new_map.face[t];
    const auto& b = new_map.bary[t];
    const Face& w = old_param.uv_faces[f];
    // Same face, same barycentrics, old UVs: the old texture coordinate of the same surface point.
    const Vec2 uv = b.x() * old_param.uv[w[0]] + b.y() * old_param.uv[w[1]] +
                    (1.0 - b.x() - b.y()) * old_param.uv[w[2]];
    const Vec3 c = sample_bilinear(old_texture, uv.x(), uv.y());
    std::uint8_t* px = out.data.data() + static_cast<size_t>(t) * 4;
    for (int ch = 0; ch < 3; ++ch)
      px[ch] = static_cast<std::uint8_t>(std::lround(std::clamp(c[ch], 0.0, 1.0) * 255.0));
    px[3] = 255;
  });
  if (padding > 0) apply_seam_padding(out, build_seam_padding(new_map, padding));
  return out;
}

ImageRGBA8 update_texture(TextureUpdate mode, Painter& new_painter, const StrokeFile& history,
                          const Parameterization& old_param, const ImageRGBA8& old_texture, int padding,
                          const ProgressCallback& progress) {
  if (mode == TextureUpdate::Replay) {
    if (!progress) {
      new_painter.paint_all(history);
      return new_painter.texture();
    }
    StrokeFile none;  // paint_all's background, without strokes
    none.background = history.background;
    new_painter.paint_all(none);
    const size_t n = history.strokes.size();
    for (size_t k = 0; k < n; ++k) {
      report_progress(progress, "texture", double(k) / double(n));
      new_painter.paint_stroke(history.strokes[k]);
    }
    return new_painter.texture();
  }
  auto to8 = [](double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
  const Vec3& bg = history.background;
  return resample_texture(old_param, old_texture, new_painter.texel_map(), padding,
                          {to8(bg[0]), to8(bg[1]), to8(bg[2]), 0});
}

ImageRGBA8 composite_over_base(const ImageRGBA8& base, const ImageRGBA8& over_black, const ImageRGBA8& over_white,
                               const TexelMap& map, int padding) {
  auto same = [&](const ImageRGBA8& i) { return i.width == map.width && i.height == map.height; };
  if (!same(base) || !same(over_black) || !same(over_white))
    throw InvalidInputError("composite_over_base: the textures and the texel map differ in size");
  ImageRGBA8 out = base;
  for (int t : map.inside)
    for (int c = 0; c < 3; ++c) {
      const size_t k = static_cast<size_t>(t) * 4 + c;
      const double S = over_black.data[k] / 255.0, T = std::max(0.0, over_white.data[k] / 255.0 - S);
      out.data[k] = static_cast<std::uint8_t>(std::lround(std::clamp(out.data[k] / 255.0 * T + S, 0.0, 1.0) * 255));
    }
  apply_seam_padding(out, build_seam_padding(map, padding));
  return out;
}

Painter replay_texture(const TriMesh& mesh, const Parameterization& new_param, const StrokeFile& history,
                       const PainterOptions& options) {
  Painter p(mesh, new_param, options, history.background);
  p.paint_all(history);
  return p;
}

template <>
std::span<const EnumName<TextureUpdate>> enum_names<TextureUpdate>() {
  static constexpr EnumName<TextureUpdate> names[] = {{TextureUpdate::Replay, "replay"},
                                                      {TextureUpdate::Resample, "resample"}};
  return names;
}

}  // namespace adaptex
