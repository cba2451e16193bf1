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
    return Command::None;
  }
  switch (key) {
    case 'F': return Command::Frame;
    case '[': return Command::SmallerBrush;
    case ']': return Command::LargerBrush;
    case 'B': return Command::Brush;
    case 'E': return Command::Eraser;
    case 'I': return Command::Eyedropper;
    case 'W': return Command::Wireframe;
    default: return Command::None;
  }
}

Drag InputState::press(MouseButton b, Mods mods, Tool tool) {
  mods_ = mods;
  if (drag_ != Drag::None || ui_mouse_) return Drag::None;  // one drag at a time; the UI owns its clicks
  down_[static_cast<int>(b)] = true;
  if (b == MouseButton::Left)
    drag_ = mods.alt ? Drag::Orbit : tool == Tool::Eyedropper ? Drag::Eyedrop : Drag::Paint;
  else if (b == MouseButton::Right)
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
