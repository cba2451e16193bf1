#pragma once
/// \file backend.h
/// The one place where adaptex-studio calls the adaptex library (mesh reading, unwrapping, painting,
/// stroke files, export). The app and its tests use only these functions, so a library part plugs in
/// (or is replaced) here without touching the app logic.
#include <array>
#include <filesystem>
#include <memory>
#include <string>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/progress.h"
#include "adaptex/paint/strokes.h"

namespace adaptex::studio {

/// Reads a mesh file, or a built-in shape named "builtin:sphere", "builtin:torus",
/// "builtin:trefoil", "builtin:plane", "builtin:icosphere".
/// \throw IoError, InvalidInputError, TopologyError (one-line messages naming the file)
TriMesh load_mesh(const std::string& path);

/// Initial parameterization (library unwrap()). \throw CancelledError when \p progress returns false
Parameterization unwrap_mesh(const TriMesh& mesh, const ProgressCallback& progress);

/// A paintable texture on one parameterization (wraps the library's Painter).
class Canvas {
 public:
  /// \pre mesh and param outlive the canvas and do not change
  Canvas(const TriMesh& mesh, const Parameterization& param, int width, int height, const Vec3& background);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  void paint_stroke(const Stroke& stroke);
  void begin_stroke(const Stroke& style);
  /// \return touched texel rectangle (i0, j0, i1, j1), inclusive; empty if i1 < i0
  std::array<int, 4> add_dab(const Vec3& centre);
  void end_stroke();
  const ImageRGBA8& texture();
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int width_, height_;
};

/// Reads a stroke file (strict). \throw IoError, InvalidInputError
StrokeFile load_strokes(const std::filesystem::path& path);
/// Writes a stroke file atomically. \throw IoError
void save_strokes(const std::filesystem::path& path, const StrokeFile& file);
/// Writes OBJ + MTL + PNG into \p dir as NAME.obj/.mtl/.png, atomically. \throw IoError
void export_obj(const std::filesystem::path& dir, const std::string& name, const TriMesh& mesh,
                const Parameterization& param, const ImageRGBA8& texture);
/// Writes a binary glTF with the texture embedded, atomically. \throw IoError
void export_glb(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization& param,
                const ImageRGBA8& texture);
/// Writes a PNG atomically. \throw IoError
void save_png(const std::filesystem::path& path, const ImageRGBA8& img);
/// Reads an image (decals). \throw IoError
ImageRGBA8 load_image(const std::filesystem::path& path);

/// Which library parts the studio is built against (shown in the About box; "fallback" = a simple
/// stand-in inside the studio until the library part lands).
std::string backend_summary();

}  // namespace adaptex::studio

namespace adaptex::studio {

/// Settings of one adaptive re-parameterization step (mirrors the adapt area's options).
struct AdaptRequest {
  int mode = 0;  ///< 1 = single stage, 2 = two-stage.
  double alpha = 0.5, beta = 0.5;
  int coarse_grid = 16, fine_grid = 256;
  int texture_size = 1024;
};

/// What an adaptive step returns to the studio (maps for the Inspect panel, phase times).
struct AdaptOutcome {
  Parameterization param;
  std::vector<std::pair<std::string, double>> phase_ms;
  ImageF importance, stretch, ls2;      ///< Maps over the old domain (may be empty).
  std::vector<Vec2> grid;               ///< Optimized fine grid points, row-major (may be empty).
  int grid_n = 0;                       ///< Grid points per side.
};

/// True when the library's adaptive re-parameterization is linked in.
bool adapt_available();
/// Runs one adaptive re-parameterization of \p param from \p texture / \p strokes.
/// \throw Error when not available; CancelledError when \p progress returns false
AdaptOutcome adapt_step(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                        const StrokeFile& strokes, const AdaptRequest& request, const ProgressCallback& progress);

}  // namespace adaptex::studio
