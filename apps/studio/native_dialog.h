#pragma once
/// \file native_dialog.h
/// The desktop's own file dialog (GTK 3's GtkFileChooserNative: the XDG desktop portal where one
/// runs, else GTK's dialog), when adaptex-studio was built with GTK 3 and a display is there.
/// ADAPTEX_STUDIO_DIALOG=builtin in the environment turns it off (the in-app browser is used).
#include <optional>
#include <string>

#include "file_browser.h"

namespace adaptex::studio {

/// True if run_native_dialog() can show a dialog (GTK 3 built in and initialised, not turned off).
bool native_dialogs_available();

/// Shows the dialog for \p request starting in \p folder and waits for it (the app's window does not
/// redraw meanwhile). \return the chosen path, or nullopt when cancelled
/// \pre native_dialogs_available()
std::optional<std::string> run_native_dialog(const FileRequest& request, const std::string& folder);

}  // namespace adaptex::studio
