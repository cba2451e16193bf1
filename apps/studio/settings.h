#pragma once
/// \file settings.h
/// Brush and view settings of adaptex-studio, the library's session options it paints with, and the
/// project file that stores them with the stroke history and the mesh reference (JSON, atomic).
#include <filesystem>
#include <optional>
#include <string>

#include "adaptex/adapt/session.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/strokes.h"
#include "camera.h"

namespace adaptex::studio {

enum class Tool { Brush, Eraser, Eyedropper };
enum class MouseButton { Left = 0, Right = 1, Middle = 2 };

/// Modifier keys held during an event.
struct Mods {
  bool shift = false, ctrl = false, alt = false;
};

/// Key codes: printable keys use their upper-case ASCII code (as GLFW does).
namespace keys {
constexpr int Escape = 256, Enter = 257, Delete = 261, Home = 268, F1 = 290, KeypadEnter = 335;
}

struct BrushSettings {
  Tool tool = Tool::Brush;
  Vec3 color = Vec3(0.85, 0.10, 0.10);
  bool screen_space = true;  ///< The radius is pixels on the screen (as Blender / Substance); else world.
  double pixel_radius = 25;  ///< Screen-space radius in window pixels (at the depth of the surface).
  double radius = 0.02;   ///< World-space radius as a fraction of the model's bounding-box diagonal.
  double hardness = 0.5;  ///< Stroke-file hardness h.
  double opacity = 1.0;
  double spacing = 0.25;  ///< Dab spacing as a fraction of the radius.
  int symmetry_axis = -1; ///< -1 none, 0 = X, 1 = Y, 2 = Z (mirror plane through the box centre).
  /// Channels a stroke paints (Channel bits; base colour only: the single-layer history). The values:
  /// color, and these three (alpha is not painted by the studio's brush).
  unsigned channels = channel_bit(Channel::BaseColor);
  double roughness = 0.2, metallic = 1.0, height = 0.75;
  /// Strokes paint the active layer's mask (when it has one) with mask_value, not its channels.
  bool on_mask = false;
  double mask_value = 0;  ///< In [0,1]: 0 hides the layer where painted, 1 shows it.
  /// With a decal image loaded: a click stamps the image centred at the cursor, as tall as the brush's
  /// diameter on the screen, at the brush's opacity (a decal stroke painting the brush's channels: base
  /// colour from the image, the others at the brush's values), instead of painting dabs.
  bool stamp = false;
  /// Pen pressure -> factor of the radius / the opacity (written to each stroke's "pressure").
  PressureCurve radius_curve, opacity_curve;
};

struct ViewSettings {
  bool wireframe = false;
  bool checker = false;       ///< Texel-density checker on the model (C): one square = a block of texels.
  bool fixed_layout = false;  ///< Show the fixed (initial) layout instead of the adaptive one (L).
  bool pbr = false;           ///< Lit material preview (V): roughness, metallic and the height's normal.
  bool show_help = false;     ///< The shortcuts window (F1).
  Vec3 background = Vec3(0.22, 0.22, 0.25);
  bool show_ui = true;
};

/// The options the studio paints and re-parameterizes with: the library's PaintSessionOptions with
/// every library default (adapt.mode = the library's default method, density-flow), except
/// schedule = EachStroke: an interactive session adapts after every stroke, in one each-stroke session
/// kept while painting (live_adaptation.h), which settles on `adaptex paint --reparam end`'s layout for
/// the history once painting pauses (End: only when asked, "Re-parameterize now", paint_history()).
/// Every layout is computed from the initial layout, so warps never compose.
PaintSessionOptions studio_session_options();
/// The options as the project file writes them, as one string: equal keys, equal sessions.
std::string session_options_key(const PaintSessionOptions& options);

/// Everything a project file holds.
struct Project {
  std::string mesh_path;  ///< Absolute path of the mesh (or "builtin:NAME").
  StrokeFile strokes;     ///< The stroke history (decal image paths absolute).
  BrushSettings brush;
  ViewSettings view;
  PaintSessionOptions session = studio_session_options();  ///< Texture size and adaptation.
  /// `"layout": "unwrap"`: the model was unwrapped afresh; `"atlas"`: painted on its own UV atlas and
  /// texture when it has them. Projects written before the key existed were unwrapped: true.
  bool unwrap = false;
  std::optional<Camera> camera;
  /// `"adapted_strokes": N`: the layout was adapted (*Re-parameterize now*, without the each-stroke
  /// schedule) to the first N strokes, the rest painted on it; reopening adapts to them again. Absent
  /// (older projects, the each-stroke schedule, which adapts to the whole history): not adapted.
  std::optional<size_t> adapted_strokes;
  /// `"material"` (project version 2): the layered material (a stroke file of version 2) with
  /// `"active_layer"`; absent: the document is `strokes`, one base-colour layer.
  std::optional<MaterialStrokeFile> material;
  int active_layer = 0;
  /// Recovery files only: the project file the strokes belong to (empty: never saved as a project).
  std::string project_file;
};

/// Writes a project file atomically ("format": "adaptex.studio-project", version 1, or 2 with a
/// material). The mesh and decal images inside the project file's folder are written relative to it
/// (the folder can be moved whole), files elsewhere as absolute paths. \throw OutputError
void write_project(const std::filesystem::path& path, const Project& project);
/// Reads a project file; relative mesh and decal image paths are resolved against its folder, so the
/// Project holds absolute paths. \throw IoError unreadable / not JSON; InvalidInputError bad content
Project read_project(const std::filesystem::path& path);

}  // namespace adaptex::studio
