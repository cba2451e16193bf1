#pragma once
/// \file input.h
/// Mouse and keyboard state of adaptex-studio: which drag a button press starts (paint, orbit, pan,
/// eyedropper), whether the UI owns the mouse / keyboard this frame, and the keyboard shortcuts as
/// commands. The App executes what it returns.
#include <vector>

#include "settings.h"
#include "stencil.h"

namespace adaptex::studio {

/// What a mouse drag does (Stencil: a right drag while a decal stencil is shown, see stencil.h).
enum class Drag { None, Paint, Orbit, Pan, Eyedrop, Stencil };

/// A keyboard shortcut's meaning.
enum class Command {
  None, Undo, Redo, Quit, Save, Frame, SmallerBrush, LargerBrush, ResizeBrush, Brush, Eraser, Eyedropper,
  Wireframe, ProjectStencil, Checker, FixedLayout, Help, OpenMeshDialog, PbrPreview
};

/// One shortcut for the menus and the F1 help: its keys and what it does.
struct Shortcut {
  const char* keys;
  const char* what;
};
/// Every keyboard and mouse shortcut, in the order the help lists them.
const std::vector<Shortcut>& shortcuts();

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
  /// another drag runs). \p tool decides what a left drag does; with a \p stencil shown a right
  /// drag edits it (Shift: scale, Ctrl: rotate, else move) instead of orbiting.
  Drag press(MouseButton b, Mods mods, Tool tool, bool stencil = false);
  /// What the running Stencil drag does.
  StencilEdit stencil_edit() const { return stencil_edit_; }
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
  StencilEdit stencil_edit_ = StencilEdit::Move;
  Mods mods_;
};

}  // namespace adaptex::studio
