#pragma once
/// \file input.h
/// Mouse and keyboard state of adaptex-studio: which drag a button press starts (paint, orbit, pan,
/// eyedropper), whether the UI owns the mouse / keyboard this frame, and the keyboard shortcuts as
/// commands. The App executes what it returns.
#include "settings.h"

namespace adaptex::studio {

/// What a mouse drag does.
enum class Drag { None, Paint, Orbit, Pan, Eyedrop };

/// A keyboard shortcut's meaning.
enum class Command {
  None, Undo, Redo, Quit, Save, Frame, SmallerBrush, LargerBrush, Brush, Eraser, Eyedropper, Wireframe
};

/// The shortcut of \p key with \p mods (keys::* and upper-case ASCII codes).
Command key_command(int key, Mods mods);

class InputState {
 public:
  /// What the UI wants (ImGui io.WantCaptureMouse / WantCaptureKeyboard / WantTextInput of the last
  /// frame).
  void set_ui_capture(bool mouse, bool keyboard, bool text) {
    ui_mouse_ = mouse;
    ui_keyboard_ = keyboard;
    ui_text_ = text;
  }
  bool ui_mouse() const { return ui_mouse_; }
  bool ui_keyboard() const { return ui_keyboard_; }
  bool ui_text() const { return ui_text_; }  ///< A text field has the keyboard.

  /// A button press: \return the drag it starts (None: ignored, e.g. the UI owns the click or
  /// another drag runs). \p tool decides what a left drag does.
  Drag press(MouseButton b, Mods mods, Tool tool);
  /// A button release: \return the drag that ended (None if buttons are still held or none ran).
  Drag release(MouseButton b, Mods mods);
  /// Moves the cursor; \return the motion since the last position.
  std::pair<double, double> move(double x, double y);

  Drag drag() const { return drag_; }
  double x() const { return x_; }
  double y() const { return y_; }
  const Mods& mods() const { return mods_; }
  void set_mods(Mods m) { mods_ = m; }

 private:
  bool ui_mouse_ = false, ui_keyboard_ = false, ui_text_ = false;
  double x_ = 0, y_ = 0;
  bool down_[3] = {false, false, false};
  Drag drag_ = Drag::None;
  Mods mods_;
};

}  // namespace adaptex::studio
