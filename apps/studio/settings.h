#pragma once
/// \file settings.h
/// Brush, view and adaptation settings of adaptex-studio, and the project file that stores them
/// with the stroke history and the mesh reference (JSON, written atomically).
#include <filesystem>
#include <optional>
#include <string>

#include "adaptex/paint/strokes.h"
#include "camera.h"

namespace adaptex::studio {

enum class Tool { Brush, Eraser, Eyedropper };
enum class AdaptMode { None, Single, TwoStage, DensityFlow };  // names: adaptex::to_string(adaptex::AdaptMode)
enum class MouseButton { Left = 0, Right = 1, Middle = 2 };

/// Modifier keys held during an event.
struct Mods {
  bool shift = false, ctrl = false, alt = false;
};

/// Key codes: printable keys use their upper-case ASCII code (as GLFW does).
namespace keys {
constexpr int Escape = 256, Delete = 261;
}

struct BrushSettings {
  Tool tool = Tool::Brush;
  Vec3 color = Vec3(0.85, 0.10, 0.10);
  double radius = 0.02;   ///< Brush radius as a fraction of the model's bounding-box diagonal.
  double hardness = 0.5;  ///< Stroke-file hardness h.
  double opacity = 1.0;
  double spacing = 0.25;  ///< Dab spacing as a fraction of the radius.
  int symmetry_axis = -1; ///< -1 none, 0 = X, 1 = Y, 2 = Z (mirror plane through the box centre).
};

struct ViewSettings {
  bool wireframe = false;
  Vec3 background = Vec3(0.22, 0.22, 0.25);
  bool show_ui = true;
};

struct AdaptSettings {
  AdaptMode mode = AdaptMode::None;
  double alpha = 0.5, beta = 0.5;  ///< L_s^2 weights (adapt area defaults).
  int coarse_grid = 16, fine_grid = 256;
  int texture_size = 1024;         ///< Texture width = height in texels.
};

/// Everything a project file holds.
struct Project {
  std::string mesh_path;  ///< Absolute path of the mesh (or "builtin:NAME").
  StrokeFile strokes;     ///< The stroke history (decal image paths absolute).
  BrushSettings brush;
  ViewSettings view;
  AdaptSettings adapt;
  std::optional<Camera> camera;
};

/// Writes a project file atomically ("format": "adaptex.studio-project", version 1). \throw OutputError
void write_project(const std::filesystem::path& path, const Project& project);
/// Reads a project file. \throw IoError unreadable / not JSON; InvalidInputError bad content
Project read_project(const std::filesystem::path& path);

}  // namespace adaptex::studio
