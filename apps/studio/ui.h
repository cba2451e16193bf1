#pragma once
/// \file ui.h
/// The Dear ImGui panels of adaptex-studio (File, Brush, View, Adapt, Inspect, status line,
/// progress + Cancel) and its modal pop-ups (unsaved strokes, recovery, file dialogs, errors). Only
/// UI-local state lives here; everything else is read from and changed through the App.
/// Every frame draws the ordinary windows first and then at most one modal, chosen by priority
/// (which_modal): a question of the App, then a file dialog, then an error.
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>

#include "adaptex/core/image.h"
#include "app.h"
#include "file_browser.h"
#include "native_dialog.h"
#include "overlay.h"

namespace adaptex::studio {

class StudioUi {
 public:
  /// Builds this frame's panels (between ImGui::NewFrame and ImGui::Render).
  void draw(App& app);
  /// Opens the Inspect panel showing \p mode (0 texture, 1 texture + UV, 2 importance, 3 stretch,
  /// 4 L_s^2, 5 fixed vs adaptive, 6 density).
  void show_inspect(int mode) {
    show_inspect_ = true;
    inspect_mode_ = mode;
  }

 private:
  /// Which path field takes the keyboard next frame (the File menu's "..." items).
  enum class Focus { None, OpenPath, ProjectPath, DecalPath };
  /// Default width of the side panel: 30% of the window within these bounds (its right edge can be
  /// dragged wider, up to 60% of the window).
  static constexpr float kMinPanelWidth = 300, kPanelWidth = 380, kMaterialWidth = 290;

  /// File / Edit / View / Help. \return its height
  float menu_bar(App& app);
  void side_panel(App& app, float top);
  /// The F1 window: every shortcut (input.h shortcuts()).
  void help_window(App& app);
  /// A path field as wide as the panel allows beside its \p button. \return the button or Enter
  /// was pressed with a path
  bool path_row(const char* id, const char* hint, std::string& path, const char* button, Focus focus = Focus::None);
  void save(App& app);
  /// \p field shows \p suggestion as long as the user has not edited it (\p shown: the last one shown).
  static void follow_suggestion(std::string& field, std::string& shown, const std::string& suggestion);
  /// Asks for a file: the desktop's dialog (native_dialog.h), else the in-app browser.
  void choose(App& app, FileKind kind);
  /// Does what \p kind asked for with the chosen \p path.
  void act(App& app, FileKind kind, const std::string& path);
  /// The in-app browser while a request is open.
  void browser_window(App& app);
  void file_panel(App& app);
  void brush_panel(App& app);
  /// The Material window (right of the view): the layer panel and the brush's channels.
  void material_window(App& app, float top);
  void layers_panel(App& app);
  void channels_panel(App& app);
  /// ADAPTEX_STUDIO_UI_TRACE=1: prints "ui: ID at X Y" (the last widget's centre) when it moves, so
  /// that scripted tests click widgets where they are.
  void trace(const char* id);
  void stencil_controls(App& app);
  void view_panel(App& app);
  void pbr_checkbox(ViewSettings& v);
  void adapt_panel(App& app);
  void inspect_window(App& app, float top);
  /// Plain-words legend (colour bar and meaning) of the map shown in Inspect.
  void inspect_legend(const AdaptMaps* maps) const;
  /// The modal shown this frame, by priority.
  enum class Modal { None, Confirm, Recovery, Native, Browser, Error };
  Modal which_modal(const App& app) const;
  /// Draws the one modal of this frame (after every other window) and closes one no longer wanted.
  void modal(App& app);
  /// New messages: errors for the Error pop-up, the others for the toast.
  void collect_messages(App& app);
  /// Loading progress with Cancel (not modal).
  void working_window(App& app);
  void error_prompt(App& app);
  /// Recover / Discard / Later for a recovery file left by a session that did not exit cleanly.
  void recovery_prompt(App& app);
  /// Shown while the desktop's file dialog is open (the app keeps drawing): Cancel closes it.
  void native_wait(App& app);
  /// The last message that is not an error (saved, exported, ...), for a few seconds.
  void toast(App& app);
  /// Save / Discard / Cancel before an action that would drop unsaved strokes.
  void confirm_prompt(App& app);
  void status_bar(App& app);

  std::string open_path_, project_path_, export_dir_ = "export",
              glb_path_, screenshot_path_ = "screenshot.png", decal_path_;
  bool show_inspect_ = false;
  int inspect_mode_ = 1;       // 0 texture, 1 texture + UV wireframe, 2 importance, 3 stretch, 4 L_s^2
  bool inspect_grid_ = true;
  std::uint64_t inspect_key_ = ~0ull;  // what the uploaded inspect image shows
  int inspect_frames_ = 0;
  void* inspect_tex_ = nullptr;
  bool show_material_ = false, shown_layered_ = false;  // the Material window; the document was layered
  bool trace_ = std::getenv("ADAPTEX_STUDIO_UI_TRACE") != nullptr;
  std::string preset_path_;  // the brush preset file (brush_panel.h)
  std::map<std::string, std::pair<int, int>> traced_;
  void* compare_tex_[2] = {nullptr, nullptr};
  ImageRGBA8 inspect_img_;
  size_t shown_messages_ = 0;
  std::string error_text_, toast_text_;
  double toast_until_ = 0;
  std::string open_modal_;  // the modal drawn last frame (empty: none)
  NativeDialog native_;
  // The last suggestions shown in project_path_ and glb_path_ (follow_suggestion).
  std::string suggested_project_, suggested_glb_;
  Overlay overlay_;
  Focus focus_ = Focus::None;
  std::optional<FileRequest> browser_;  // the in-app browser's open request
  std::string browser_dir_, browser_name_;
  bool browser_ready_ = false;  // its Name field has had the keyboard
};

}  // namespace adaptex::studio
