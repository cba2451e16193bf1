#pragma once
/// \file file_browser.h
/// What a file dialog of adaptex-studio asks for (FileRequest: open a mesh, a project, an image; save
/// a project, a GLB, a screenshot; choose an export folder) and the in-app browser used where no
/// native dialog is available: a folder's entries, folders first, files filtered by extension.
#include <filesystem>
#include <string>
#include <vector>

namespace adaptex::studio {

/// What a dialog is for.
enum class FileKind {
  OpenMesh, OpenProject, SaveProject, ExportGlb, ExportObjFolder, LoadImage, Screenshot, LoadBrushPreset, SaveBrushPreset
};

/// A dialog's title, whether it saves, whether it picks a folder, and the extensions it shows.
struct FileRequest {
  FileKind kind = FileKind::OpenMesh;
  const char* title = "";
  bool save = false;                    ///< Save: the file may not exist yet (a name is typed).
  bool folder = false;                  ///< Picks a folder (export OBJ).
  std::vector<std::string> extensions;  ///< Lower case with the dot (".obj"); empty: all files.
};

/// The request of \p kind (mesh formats: those the library reads).
FileRequest file_request(FileKind kind);

/// One entry of a folder listing.
struct BrowserEntry {
  std::string name;
  bool folder = false;
};

/// The entries of \p dir: sub-folders, then files whose extension (any case) is in \p extensions (all
/// files when empty), each group sorted case-insensitively; hidden entries (a leading dot) are left
/// out. An unreadable folder gives an empty list.
std::vector<BrowserEntry> list_folder(const std::filesystem::path& dir, const std::vector<std::string>& extensions);

}  // namespace adaptex::studio
