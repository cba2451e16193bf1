#pragma once
/// \file renderer.h
/// Rendering interface of adaptex-studio. The App talks only to this interface; GlRenderer draws
/// with OpenGL 3.3, NullRenderer records the calls so the app logic is testable without a GPU.
#include <array>
#include <string>
#include <vector>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "camera.h"

namespace adaptex::studio {

/// Side of one checker square in texels (FrameView::checker).
inline constexpr int kCheckerTexels = 16;

/// What one frame of the 3-D view shows.
struct FrameView {
  Camera camera;
  bool has_mesh = false;
  bool wireframe = false;
  Vec3 background = Vec3(0.22, 0.22, 0.25);
  /// Texel-density checker over the texture: squares of kCheckerTexels x kCheckerTexels texels, so
  /// smaller squares on the model mean more texels there.
  bool checker = false;
  /// Lit material preview: the base colour shaded with the roughness, metallic and normal maps
  /// (set_material_maps()) under a sky/ground environment and one key light (GGX, metallic workflow).
  bool pbr = false;
};

class Renderer {
 public:
  virtual ~Renderer() = default;
  /// Uploads the geometry (one vertex per UV wedge, triangles = param.uv_faces) with the vertex
  /// normals \p normals (size V), or vertex_normals(mesh) (paint/tangent_frame.h) when null.
  virtual void set_mesh(const TriMesh& mesh, const Parameterization& param, const std::vector<Vec3>* normals) = 0;
  /// Uploads the whole texture.
  virtual void set_texture(const ImageRGBA8& tex) = 0;
  /// Uploads the texel rectangle (i0, j0, i1, j1), inclusive, of \p tex.
  virtual void update_texture(const ImageRGBA8& tex, const std::array<int, 4>& rect) = 0;
  /// Uploads a layered material's maps for the lit preview: the glTF metallic-roughness packing
  /// (G = roughness, B = metallic) and the tangent-space normal map (MaterialTextures), on the layout of
  /// the last set_mesh(); empty images: a plain dielectric (roughness 0.5, metallic 0, flat normal).
  virtual void set_material_maps(const ImageRGBA8& metallic_roughness, const ImageRGBA8& normal) = 0;
  /// Draws the 3-D view into the current framebuffer.
  virtual void draw(const FrameView& view) = 0;
  /// Reads the framebuffer back (rows bottom-up, like ImageRGBA8).
  virtual ImageRGBA8 read_pixels(int width, int height) = 0;
  /// Uploads a picture for the UI (inspect panel); \return an ImGui texture id (nullptr if none).
  virtual void* ui_image(int slot, const ImageRGBA8& img) = 0;
};

/// Records what was asked of it; draws nothing.
class NullRenderer : public Renderer {
 public:
  void set_mesh(const TriMesh& mesh, const Parameterization& param, const std::vector<Vec3>* normals) override {
    ++mesh_uploads;
    last_normals = normals ? *normals : std::vector<Vec3>();
    last_faces = mesh.num_faces();
    last_wedges = param.num_wedges();
  }
  void set_texture(const ImageRGBA8& tex) override {
    ++texture_uploads;
    last_texture = tex;
  }
  void update_texture(const ImageRGBA8& tex, const std::array<int, 4>& rect) override {
    ++texture_updates;
    last_rect = rect;
    last_texture = tex;
  }
  void set_material_maps(const ImageRGBA8& metallic_roughness, const ImageRGBA8& normal) override {
    ++material_uploads;
    last_metallic_roughness = metallic_roughness;
    last_normal_map = normal;
  }
  void draw(const FrameView& view) override {
    ++draws;
    last_view = view;
  }
  ImageRGBA8 read_pixels(int width, int height) override { return ImageRGBA8(width, height, {0, 0, 0, 255}); }
  void* ui_image(int, const ImageRGBA8&) override { return nullptr; }

  int mesh_uploads = 0, texture_uploads = 0, texture_updates = 0, material_uploads = 0, draws = 0;
  int last_faces = 0, last_wedges = 0;
  std::array<int, 4> last_rect{0, 0, -1, -1};
  ImageRGBA8 last_texture, last_metallic_roughness, last_normal_map;
  std::vector<Vec3> last_normals;  ///< Empty when the renderer was to compute them.
  FrameView last_view;
};

}  // namespace adaptex::studio
