#pragma once
/// \file overlay.h
/// What adaptex-studio draws over the 3-D view and under its panels (Dear ImGui's background draw
/// list): the decal stencil's semi-transparent preview with its outline, and the brush circles in two
/// tones (dark outside, light inside: visible on any paint). The App decides what is shown (none of
/// the brush circles while the mouse is over a panel).
#include <cstdint>
#include <string>

#include "app.h"

namespace adaptex::studio {

class Overlay {
 public:
  /// Adds this frame's stencil and brush circles (between ImGui::NewFrame and ImGui::Render).
  void draw(App& app);

 private:
  void draw_stencil(App& app);
  void* stencil_tex_ = nullptr;
  const ImageRGBA8* uploaded_ = nullptr;  // the decal image in stencil_tex_ ...
  std::uint64_t uploaded_key_ = 0;        // ... and its size and first texels
};

}  // namespace adaptex::studio
