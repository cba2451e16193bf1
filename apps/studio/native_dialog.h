#pragma once
/// \file native_dialog.h
/// The desktop's own file dialog (GTK 3's GtkFileChooserNative: the XDG desktop portal where one
/// runs, else GTK's dialog), when adaptex-studio was built with GTK 3 and a display is there.
/// ADAPTEX_STUDIO_DIALOG=builtin in the environment turns it off (the in-app browser is used).
/// The dialog does not block: the app keeps drawing its frames and pumps GTK's events (poll()) while
/// it is open.
#include <optional>
#include <string>

#include "file_browser.h"

namespace adaptex::studio {

/// True if NativeDialog can show a dialog (GTK 3 built in and initialised, not turned off).
bool native_dialogs_available();

/// One open desktop file dialog at a time.
class NativeDialog {
 public:
  NativeDialog() = default;
  ~NativeDialog();
  NativeDialog(const NativeDialog&) = delete;
  NativeDialog& operator=(const NativeDialog&) = delete;

  /// Shows the dialog for \p request in \p folder, proposing the file name \p name (save dialogs).
  /// \pre native_dialogs_available() and !is_open()
  void open(const FileRequest& request, const std::string& folder, const std::string& name);
  bool is_open() const { return dialog_ != nullptr; }
  /// The request of the open dialog. \pre is_open()
  const FileRequest& request() const { return request_; }
  /// Handles the desktop's pending events (call once a frame). \return once answered: the chosen
  /// path, or an empty string when cancelled; then the dialog is closed
  std::optional<std::string> poll();
  /// Closes the dialog without a choice.
  void cancel();

 private:
  void* dialog_ = nullptr;  // GtkFileChooserNative*
  FileRequest request_;
  int response_ = 0;      // the GTK response once answered (0: not yet)
  std::string chosen_;
};

}  // namespace adaptex::studio
