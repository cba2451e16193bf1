/// \file input.cpp
/// Mouse drags and keyboard shortcuts (see input.h).
#include "input.h"

namespace adaptex::studio {

Command key_command(int key, Mods mods) {
  if (mods.ctrl) {
    if (key == 'Z') return mods.shift ? Command::Redo : Command::Undo;
    if (key == 'Y') return Command::Redo;
    if (key == 'Q') return Command::Quit;
    if (key == 'S') return Command::Save;
    if (key == 'O') return Command::OpenMeshDialog;
    return Command::None;
  }
  switch (key) {
    case keys::F1: return Command::Help;
    case keys::Home: return Command::Frame;
    case 'F': return Command::ResizeBrush;
    case 'P': return Command::ProjectStencil;
    case 'C': return Command::Checker;
    case 'V': return Command::PbrPreview;
    case 'L': return Command::FixedLayout;
    case '[': return Command::SmallerBrush;
    case ']': return Command::LargerBrush;
    case 'B': return Command::Brush;
    case 'E': return Command::Eraser;
    case 'I': return Command::Eyedropper;
    case 'W': return Command::Wireframe;
    default: return Command::None;
  }
}

const std::vector<Shortcut>& shortcuts() {
  static const std::vector<Shortcut> list = {
      {"Left drag", "paint (with the eyedropper: pick a colour)"},
      {"Middle drag, Alt + left drag", "orbit"},
      {"Right drag", "orbit; with a stencil shown: move the stencil"},
      {"Shift + right drag", "scale the stencil"},
      {"Ctrl + right drag", "rotate the stencil"},
      {"Shift + middle drag", "pan"},
      {"Wheel", "zoom"},
      {"[  ]", "smaller / larger brush"},
      {"F", "resize the brush with the mouse; click or F to keep, Esc or right click to cancel"},
      {"B / E / I", "brush / eraser / eyedropper"},
      {"P", "project the stencil onto the model"},
      {"C", "texel-density checker on the model"},
      {"V", "lit material preview (roughness, metallic, normal from height)"},
      {"L", "show the fixed layout (hold the same texture size) instead of the adaptive one"},
      {"W", "wireframe"},
      {"Home", "frame the model"},
      {"Ctrl+Z, Ctrl+Shift+Z / Ctrl+Y", "undo, redo"},
      {"Ctrl+O", "open a mesh (file dialog)"},
      {"Ctrl+S", "save the project"},
      {"Ctrl+Q", "quit (asks when strokes are unsaved)"},
      {"F1", "this help"},
  };
  return list;
}

Drag InputState::press(MouseButton b, Mods mods, Tool tool, bool stencil) {
  mods_ = mods;
  if (drag_ != Drag::None || ui_mouse_) return Drag::None;  // one drag at a time; the UI owns its clicks
  down_[static_cast<int>(b)] = true;
  if (b == MouseButton::Left)
    drag_ = mods.alt ? Drag::Orbit : tool == Tool::Eyedropper ? Drag::Eyedrop : Drag::Paint;
  else if (b == MouseButton::Right && stencil) {
    drag_ = Drag::Stencil;
    stencil_edit_ = mods.ctrl ? StencilEdit::Rotate : mods.shift ? StencilEdit::Scale : StencilEdit::Move;
  } else if (b == MouseButton::Right)
    drag_ = Drag::Orbit;
  else
    drag_ = mods.shift ? Drag::Pan : Drag::Orbit;
  return drag_;
}

Drag InputState::release(MouseButton b, Mods mods) {
  mods_ = mods;
  down_[static_cast<int>(b)] = false;
  if (down_[0] || down_[1] || down_[2]) return Drag::None;  // only the buttons of the drag are ever down
  const Drag ended = drag_;
  drag_ = Drag::None;
  return ended;
}

std::pair<double, double> InputState::move(double x, double y) {
  const std::pair<double, double> d{x - x_, y - y_};
  x_ = x;
  y_ = y;
  return d;
}

}  // namespace adaptex::studio
