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
/// Lets GTK handle what is pending (the dialog's input and drawing), without waiting.
void pump_gtk_events() {
  while (gtk_events_pending()) gtk_main_iteration_do(FALSE);
}

/// "*.[pP][nN][gG]": \p ext in any case.
std::string any_case_pattern(const std::string& ext) {
  std::string pattern(1, '*');
  for (char c : ext) {
    if (c == '.') {
      pattern.push_back(c);
      continue;
    }
    pattern.push_back('[');
    pattern.push_back(char(std::tolower(static_cast<unsigned char>(c))));
    pattern.push_back(char(std::toupper(static_cast<unsigned char>(c))));
    pattern.push_back(']');
  }
  return pattern;
}

struct Answer {
  int* response;
  std::string* chosen;
};

void on_response(GtkNativeDialog* d, gint response, gpointer data) {
  auto* a = static_cast<Answer*>(data);
  *a->response = response == GTK_RESPONSE_ACCEPT ? 1 : -1;
  if (response != GTK_RESPONSE_ACCEPT) return;
  if (char* name = gtk_file_chooser_get_filename(GTK_FILE_CHOOSER(d))) {
    *a->chosen = name;
    g_free(name);
  }
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

void NativeDialog::open(const FileRequest& r, const std::string& folder, const std::string& name) {
  cancel();
  request_ = r;
  response_ = 0;
  chosen_.clear();
  const GtkFileChooserAction action = r.folder ? GTK_FILE_CHOOSER_ACTION_SELECT_FOLDER
                                      : r.save ? GTK_FILE_CHOOSER_ACTION_SAVE
                                               : GTK_FILE_CHOOSER_ACTION_OPEN;
  GtkFileChooserNative* d =
      gtk_file_chooser_native_new(r.title, nullptr, action, r.save ? "_Save" : "_Open", "_Cancel");
  GtkFileChooser* fc = GTK_FILE_CHOOSER(d);
  gtk_file_chooser_set_do_overwrite_confirmation(fc, TRUE);
  if (!folder.empty()) gtk_file_chooser_set_current_folder(fc, folder.c_str());
  if (r.save && !name.empty()) gtk_file_chooser_set_current_name(fc, name.c_str());
  if (!r.extensions.empty()) {
    GtkFileFilter* f = gtk_file_filter_new();
    gtk_file_filter_set_name(f, r.title);
    for (const std::string& e : r.extensions) gtk_file_filter_add_pattern(f, any_case_pattern(e).c_str());
    gtk_file_chooser_add_filter(fc, f);  // the chooser takes the filter
  }
  // The answer is written here by the "response" signal, during a later poll(); the Answer lives
  // as long as the dialog (freed with it).
  auto* answer = new Answer{&response_, &chosen_};
  g_signal_connect_data(d, "response", G_CALLBACK(on_response), answer,
                        [](gpointer data, GClosure*) { delete static_cast<Answer*>(data); }, GConnectFlags(0));
  gtk_native_dialog_set_modal(GTK_NATIVE_DIALOG(d), TRUE);
  gtk_native_dialog_show(GTK_NATIVE_DIALOG(d));
  dialog_ = d;
  pump_gtk_events();
}

std::optional<std::string> NativeDialog::poll() {
  if (!dialog_) return std::nullopt;
  pump_gtk_events();
  if (response_ == 0) return std::nullopt;
  std::string out = response_ > 0 ? chosen_ : std::string();
  cancel();
  return out;
}

void NativeDialog::cancel() {
  if (!dialog_) return;
  auto* d = static_cast<GtkFileChooserNative*>(dialog_);
  dialog_ = nullptr;
  gtk_native_dialog_destroy(GTK_NATIVE_DIALOG(d));
  g_object_unref(d);
  pump_gtk_events();  // the dialog disappears before the app draws again
}

NativeDialog::~NativeDialog() { cancel(); }
#else
bool native_dialogs_available() { return false; }
void NativeDialog::open(const FileRequest&, const std::string&, const std::string&) {}
std::optional<std::string> NativeDialog::poll() { return std::nullopt; }
void NativeDialog::cancel() {}
NativeDialog::~NativeDialog() = default;
#endif

}  // namespace adaptex::studio
