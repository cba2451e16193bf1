#pragma once
/// \file gl_renderer.h
/// OpenGL 3.3 core implementation of Renderer: lit textured mesh (base colour, or the lit material), wireframe overlay, brush cursor
/// circles. Needs a current GL context (created by the window layer) for its whole life.
#include <map>
#include <memory>

#include "renderer.h"

namespace adaptex::studio {

class GlRenderer : public Renderer {
 public:
  GlRenderer();
  ~GlRenderer() override;
  void set_mesh(const TriMesh& mesh, const Parameterization& param, const std::vector<Vec3>* normals) override;
  void set_texture(const ImageRGBA8& tex) override;
  void update_texture(const ImageRGBA8& tex, const std::array<int, 4>& rect) override;
  void set_material_maps(const ImageRGBA8& metallic_roughness, const ImageRGBA8& normal) override;
  void draw(const FrameView& view) override;
  ImageRGBA8 read_pixels(int width, int height) override;
  void* ui_image(int slot, const ImageRGBA8& img) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex::studio
