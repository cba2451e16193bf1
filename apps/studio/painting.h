#pragma once
/// \file painting.h
/// The painting state of adaptex-studio: the stroke history (undo / redo), the loaded model, the
/// surface being painted, the open stroke, picking on the surface, and what the renderer still has
/// to upload. Dabs are painted on the UI thread at once; rebuilt surfaces from background jobs are
/// swapped in here with the strokes that were finished (or are open) meanwhile painted on top.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "history.h"
#include "renderer.h"
#include "surface.h"

namespace adaptex::studio {

class Painting {
 public:
  StrokeHistory& history() { return history_; }
  const StrokeHistory& history() const { return history_; }
  const std::shared_ptr<const Model>& model() const { return model_; }
  const Surface* surface() const { return surface_.get(); }

  /// A newly loaded model with its first surface; the history becomes \p strokes on \p background.
  void set_model(std::shared_ptr<const Model> model, std::unique_ptr<Surface> surface, std::vector<Stroke> strokes,
                 const Vec3& background);
  /// No model (File > New): empty history, nothing to draw.
  void clear();
  /// Swaps in \p s if it is still for this model, history generation and \p texture_size: the strokes
  /// finished since it was started, then the open stroke, are painted on it first. \return swapped
  bool accept_rebuilt(std::unique_ptr<Surface> s, int texture_size);
  /// Paints history strokes missing from the canvas (pure appends: redo, decals, replays).
  void catch_up();
  /// The canvas must be rebuilt (history rewritten, or another texture size).
  bool stale(int texture_size) const;
  /// The canvas shows exactly the history.
  bool in_sync() const;
  /// The surface uses the model's initial layout (never re-parameterized).
  bool on_initial_layout() const;

  bool stroke_open() const { return stroke_open_; }
  const Stroke& open_stroke() const { return current_; }
  /// Opens a stroke with \p style (no dabs yet). \pre a surface exists
  void begin_stroke(const Stroke& style);
  /// Paints one dab at \p h (and its mirror across the box centre when \p symmetry_axis >= 0, found
  /// by casting the mirrored \p ray). \pre stroke_open()
  void add_dab(const Hit& h, const Ray& ray, int symmetry_axis);
  /// Closes the open stroke. \return true if it had dabs and was recorded in the history.
  bool end_stroke();
  /// Closes the open stroke without recording it (a layered material records it in its document).
  /// \return the stroke (no dabs: nothing was painted)
  Stroke take_stroke();
  /// Swaps in a layered material's surface \p s if it is for this model and \p texture_size (any
  /// document version: s->generation); the open stroke is painted on it first. \return swapped
  bool accept_material(std::unique_ptr<Surface> s, int texture_size);
  /// The last painted dab of the open stroke, if any.
  std::optional<Vec3> last_dab() const { return last_dab_; }
  /// Records a whole stroke (decal); painted by catch_up().
  void push(Stroke s) { history_.push(std::move(s)); }
  bool undo();
  bool redo();

  /// The visible front-facing surface along \p ray.
  std::optional<Hit> pick(const Ray& ray) const;
  /// The front-facing hit of \p ray mirrored across the box centre on \p axis (not \p h itself).
  std::optional<Hit> mirror_hit(const Ray& ray, const Hit& h, int axis) const;
  /// Painted colour at a hit (bilinear texture sample).
  Vec3 sample_colour(const Hit& h) const;

  /// Uploads the mesh / texture changes since the last call.
  void upload(Renderer& renderer);
  /// The renderer shows something else (the fixed layout): the next upload() sends everything.
  void invalidate_uploads() { mesh_upload_ = texture_full_upload_ = surface_ != nullptr; }
  /// Changes whenever a new surface is swapped in.
  std::uint64_t serial() const { return serial_; }

 private:
  void swap_surface(std::unique_ptr<Surface> s);

  StrokeHistory history_;
  std::shared_ptr<const Model> model_;
  std::unique_ptr<Surface> surface_;
  bool stroke_open_ = false;
  Stroke current_;
  std::optional<Vec3> last_dab_;
  std::array<int, 4> dirty_{0, 0, -1, -1};
  bool texture_full_upload_ = false, mesh_upload_ = false;
  std::uint64_t serial_ = 0;
};

}  // namespace adaptex::studio
