/// \file file_browser.cpp
/// File requests and the in-app browser's folder listing (see file_browser.h).
#include "file_browser.h"

#include <algorithm>
#include <cctype>

namespace adaptex::studio {

namespace {
std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}
}  // namespace

FileRequest file_request(FileKind kind) {
  switch (kind) {
    case FileKind::OpenMesh:
      return {kind, "Open mesh", false, false, {".obj", ".off", ".ply", ".stl", ".gltf", ".glb"}};
    case FileKind::OpenProject: return {kind, "Open project", false, false, {".adaptex", ".json"}};
    case FileKind::SaveProject: return {kind, "Save project as", true, false, {".adaptex", ".json"}};
    case FileKind::ExportGlb: return {kind, "Export GLB", true, false, {".glb"}};
    case FileKind::ExportObjFolder: return {kind, "Export OBJ + MTL + PNG into folder", false, true, {}};
    case FileKind::LoadImage: return {kind, "Load decal image", false, false, {".png", ".jpg", ".jpeg"}};
    case FileKind::Screenshot: return {kind, "Save screenshot", true, false, {".png"}};
    case FileKind::LoadBrushPreset: return {kind, "Load brush preset", false, false, {".json"}};
    case FileKind::SaveBrushPreset: return {kind, "Save brush preset as", true, false, {".json"}};
  }
  return {};
}

std::vector<BrowserEntry> list_folder(const std::filesystem::path& dir, const std::vector<std::string>& extensions) {
  std::vector<BrowserEntry> out;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;
    std::error_code e2;
    const bool folder = it->is_directory(e2);
    const std::string ext = lower(it->path().extension().string());
    if (!folder && !extensions.empty() && std::find(extensions.begin(), extensions.end(), ext) == extensions.end())
      continue;
    out.push_back({name, folder});
  }
  std::sort(out.begin(), out.end(), [](const BrowserEntry& a, const BrowserEntry& b) {
    if (a.folder != b.folder) return a.folder;
    return lower(a.name) < lower(b.name);
  });
  return out;
}

}  // namespace adaptex::studio
