#pragma once
/// \file backend.h
/// The one place where adaptex-studio calls the adaptex library (mesh reading, unwrapping, painting,
/// adaptive re-parameterization, stroke files, export, evaluation). The app and its tests use only
/// these functions, so a library change plugs in here without touching the app logic.
#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/core/progress.h"
#include "adaptex/paint/strokes.h"

namespace adaptex {
class PaintSession;
}

namespace adaptex::studio {

/// Reads a mesh file (adaptex::read_mesh), or a built-in shape named "builtin:sphere",
/// "builtin:torus", "builtin:trefoil", "builtin:plane", "builtin:icosphere".
/// \throw IoError, InvalidInputError, TopologyError (one-line messages naming the file)
TriMesh load_mesh(const std::string& path);

/// Initial parameterization (adaptex::unwrap). \throw CancelledError when \p progress returns false
Parameterization unwrap_mesh(const TriMesh& mesh, const ProgressCallback& progress);

/// A paintable texture on one parameterization (an adaptex::Painter, or the painter of the
/// PaintSession that produced an adapted parameterization).
class Canvas {
 public:
  /// \pre mesh and param outlive the canvas and do not change
  Canvas(const TriMesh& mesh, const Parameterization& param, int width, int height, const Vec3& background);
  /// Takes over an adaptive painting session (its painter becomes this canvas).
  explicit Canvas(std::unique_ptr<PaintSession> session);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  void paint_stroke(const Stroke& stroke);
  void begin_stroke(const Stroke& style);
  /// \return touched texel rectangle (i0, j0, i1, j1), inclusive; empty if i1 < i0
  std::array<int, 4> add_dab(const Vec3& centre);
  void end_stroke();
  const ImageRGBA8& texture();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Settings of one adaptive re-parameterization (adaptex::AdaptOptions subset).
struct AdaptRequest {
  int mode = 2;  ///< Index into adaptex::adapt_modes(): 1 single, 2 two-stage, 3 density-flow.
  double alpha = 0.5, beta = 0.95;
  int coarse_grid = 16, fine_grid = 256;
  int texture_size = 1024;
};

/// Result of adapt_and_replay(): the new parameterization with the history replayed on it, the maps
/// for the Inspect panel and the phase times for the status line.
struct AdaptOutcome {
  std::shared_ptr<const Parameterization> param;
  std::unique_ptr<Canvas> canvas;
  std::vector<std::pair<std::string, double>> phase_ms;
  ImageF importance, stretch, ls2;
  GridWarp coarse, fine;
  bool accepted = true;  ///< false: the "never worse" safeguard kept the previous parameterization.
  double damping = 1;
};

/// Paints \p history on \p current, re-parameterizes once (adaptex::PaintSession with its safeguard)
/// and replays the history onto the new parameterization.
/// \throw CancelledError when \p progress returns false; InvalidInputError bad settings
AdaptOutcome adapt_and_replay(const TriMesh& mesh, const Parameterization& current, const StrokeFile& history,
                              const AdaptRequest& request, const ProgressCallback& progress);

/// PSNR (dB) of \p texture on \p param against the exact signal of \p history (adaptex eval).
double texture_psnr(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture,
                    const StrokeFile& history, long long samples = 200000);

/// Reads a stroke file (strict, adaptex::read_strokes). \throw IoError, InvalidInputError
StrokeFile load_strokes(const std::filesystem::path& path);
/// Writes a stroke file atomically (adaptex::write_strokes). \throw OutputError
void save_strokes(const std::filesystem::path& path, const StrokeFile& file);
/// Writes OBJ + MTL + PNG into \p dir as NAME.obj/.mtl/.png, atomically. \throw OutputError
void export_obj(const std::filesystem::path& dir, const std::string& name, const TriMesh& mesh,
                const Parameterization& param, const ImageRGBA8& texture);
/// Writes a binary glTF with the texture embedded, atomically. \throw OutputError
void export_glb(const std::filesystem::path& path, const TriMesh& mesh, const Parameterization& param,
                const ImageRGBA8& texture);
/// Writes a PNG atomically. \throw OutputError
void save_png(const std::filesystem::path& path, const ImageRGBA8& img);
/// Reads an image (decals). \throw IoError
ImageRGBA8 load_image(const std::filesystem::path& path);

}  // namespace adaptex::studio
