/// \file native_dialog.cpp
/// GTK 3 file dialogs (see native_dialog.h); without ADAPTEX_STUDIO_GTK none is available.
#include "native_dialog.h"

#include <cctype>
#include <cstdlib>
#include <cstring>

#ifdef ADAPTEX_STUDIO_GTK
#include <gtk/gtk.h>
#endif

namespace adaptex::studio {

#ifdef ADAPTEX_STUDIO_GTK
namespace {
/// Lets GTK finish closing its windows (the dialog disappears before the app draws again).
void drain_gtk_events() {
  while (gtk_events_pending()) gtk_main_iteration();
}
}  // namespace

bool native_dialogs_available() {
  static const bool ok = [] {
    const char* mode = std::getenv("ADAPTEX_STUDIO_DIALOG");
    if (mode && std::strcmp(mode, "builtin") == 0) return false;
    return gtk_init_check(nullptr, nullptr) != 0;
  }();
  return ok;
}

std::optional<std::string> run_native_dialog(const FileRequest& r, const std::string& folder) {
  const GtkFileChooserAction action = r.folder ? GTK_FILE_CHOOSER_ACTION_SELECT_FOLDER
                                      : r.save ? GTK_FILE_CHOOSER_ACTION_SAVE
                                               : GTK_FILE_CHOOSER_ACTION_OPEN;
  GtkFileChooserNative* d =
      gtk_file_chooser_native_new(r.title, nullptr, action, r.save ? "_Save" : "_Open", "_Cancel");
  GtkFileChooser* fc = GTK_FILE_CHOOSER(d);
  gtk_file_chooser_set_do_overwrite_confirmation(fc, TRUE);
  if (!folder.empty()) gtk_file_chooser_set_current_folder(fc, folder.c_str());
  if (!r.extensions.empty()) {
    GtkFileFilter* f = gtk_file_filter_new();
    gtk_file_filter_set_name(f, r.title);
    for (const std::string& e : r.extensions) {
      std::string pattern(1, '*');  // any case: "*.[pP][nN][gG]"
      for (char c : e) {
        if (c == '.') {
          pattern.push_back(c);
          continue;
        }
        pattern.push_back('[');
        pattern.push_back(char(std::tolower(static_cast<unsigned char>(c))));
        pattern.push_back(char(std::toupper(static_cast<unsigned char>(c))));
        pattern.push_back(']');
      }
      gtk_file_filter_add_pattern(f, pattern.c_str());
    }
    gtk_file_chooser_add_filter(fc, f);  // the chooser takes the filter
  }
  std::optional<std::string> out;
  if (gtk_native_dialog_run(GTK_NATIVE_DIALOG(d)) == GTK_RESPONSE_ACCEPT) {
    if (char* name = gtk_file_chooser_get_filename(fc)) {
      out = name;
      g_free(name);
    }
  }
  g_object_unref(d);
  drain_gtk_events();
  return out;
}
#else
bool native_dialogs_available() { return false; }
std::optional<std::string> run_native_dialog(const FileRequest&, const std::string&) { return std::nullopt; }
#endif

}  // namespace adaptex::studio
