/// \file overlay.cpp
/// Stencil preview and brush circles over the 3-D view (see overlay.h).
#include "overlay.h"

#include <imgui.h>

namespace adaptex::studio {

namespace {
ImVec2 im(const Vec2& p) { return ImVec2(float(p.x()), float(p.y())); }

/// Identifies the pixels of an image cheaply (size and a few texels): a new decal is uploaded again.
std::uint64_t image_key(const ImageRGBA8& img) {
  std::uint64_t k = std::uint64_t(img.width) * 1000003u + std::uint64_t(img.height);
  const size_t step = std::max<size_t>(1, img.data.size() / 61);
  for (size_t i = 0; i < img.data.size(); i += step) k = k * 1099511628211ull + img.data[i];
  return k;
}
}  // namespace

void Overlay::draw(App& app) {
  draw_stencil(app);
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  for (const ScreenCircle& c : app.brush_cursors()) {
    const float r = float(c.radius);
    dl->AddCircle(im(c.centre), r, IM_COL32(0, 0, 0, 255), 64, 5.f);        // dark on both sides ...
    dl->AddCircle(im(c.centre), r, IM_COL32(255, 255, 255, 255), 64, 1.5f);  // ... of a light ring
  }
}

void Overlay::draw_stencil(App& app) {
  const auto& st = app.stencil();
  const auto& img = app.decal_image();
  if (!st || !img) return;
  const std::uint64_t key = image_key(*img);
  if (uploaded_ != &*img || key != uploaded_key_) {
    stencil_tex_ = app.renderer().ui_image(3, *img);
    uploaded_ = &*img;
    uploaded_key_ = key;
  }
  const auto c = st->corners(app.camera());
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  // ImageRGBA8 row 0 (v = 0, the image's bottom) is the first row uploaded: ImGui's uv y = 0.
  if (stencil_tex_)
    dl->AddImageQuad(stencil_tex_, im(c[0]), im(c[1]), im(c[2]), im(c[3]), ImVec2(0, 0), ImVec2(1, 0), ImVec2(1, 1),
                     ImVec2(0, 1), IM_COL32(255, 255, 255, 110));
  for (int k = 0; k < 4; ++k) dl->AddLine(im(c[size_t(k)]), im(c[size_t((k + 1) % 4)]), IM_COL32(0, 0, 0, 200), 3.f);
  for (int k = 0; k < 4; ++k)
    dl->AddLine(im(c[size_t(k)]), im(c[size_t((k + 1) % 4)]), IM_COL32(255, 220, 60, 255), 1.f);
}

}  // namespace adaptex::studio
