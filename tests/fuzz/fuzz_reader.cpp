// libFuzzer target: one input format per build (ADAPTEX_FUZZ_EXTENSION and the ADAPTEX_FUZZ_* flags, see
// CMakeLists.txt). The bytes go through the same code as the CLI after its file checks: the in-memory
// entry points that the path-based readers call once they have read the file (read_mesh_from_memory
// with the CLI's validation and repair, parse_strokes and parse_material_strokes, read_image_from_memory for PNG, JPEG and TGA,
// parse_mtl for material files; fuzz_obj and fuzz_gltf also run read_textured_asset_from_memory). The studio's project
// reader has no in-memory entry point, so fuzz_project writes each input to a file and calls
// read_project. With ADAPTEX_FUZZ_VIA_FILE=1 in the environment every target does that (writes the
// input to a file, calls the path-based reader: read_mesh, read_strokes, read_image), the harness of
// before the in-memory entry points; set TMPDIR=/dev/shm for it, or each run waits on the disk.
// Every adaptex::Error is an accepted outcome; anything else (a crash, a sanitizer report, another
// exception, a timeout or running out of memory) is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/io/asset_io.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/input_file.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/strokes.h"
#if ADAPTEX_FUZZ_PROJECT
#include "settings.h"
#endif
#if ADAPTEX_FUZZ_BRUSH_PRESET
#include "brush_preset.h"
#endif

namespace {

/// The file each input stands for (written only in file mode; its folder is the base of relative paths).
const std::filesystem::path& input_path() {
  static const std::filesystem::path path = [] {
    const auto dir = std::filesystem::temp_directory_path() / ("adaptex-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir / ("input" + std::string(ADAPTEX_FUZZ_EXTENSION));
  }();
  return path;
}

bool via_file() {
#if ADAPTEX_FUZZ_PROJECT
  return true;
#else
  static const bool file = [] {
    const char* v = std::getenv("ADAPTEX_FUZZ_VIA_FILE");
    return v && std::string(v) == "1";
  }();
  return file;
#endif
}

[[maybe_unused]] adaptex::ReadOptions mesh_options() {
  adaptex::ReadOptions options;
  options.repair = true;  // the repair code paths too
  return options;
}

void read_file(const std::filesystem::path& path) {
#if ADAPTEX_FUZZ_STROKES
  try {
    (void)adaptex::read_strokes(path);
  } catch (const adaptex::Error&) {
  }
  (void)adaptex::read_material_strokes(path);  // version 2 (and 1) on the same bytes
#elif ADAPTEX_FUZZ_PNG
  (void)adaptex::read_image(path);
#elif ADAPTEX_FUZZ_MTL
  (void)adaptex::parse_mtl(adaptex::read_input_file(path), path);
#elif ADAPTEX_FUZZ_PROJECT
  (void)adaptex::studio::read_project(path);
#elif ADAPTEX_FUZZ_BRUSH_PRESET
  (void)adaptex::studio::read_brush_preset(path, adaptex::studio::BrushSettings{});
#else
  (void)adaptex::read_mesh(path, mesh_options());
#endif
}

void read_memory([[maybe_unused]] const std::string& bytes, [[maybe_unused]] const std::filesystem::path& path) {
#if ADAPTEX_FUZZ_STROKES
  try {
    (void)adaptex::parse_strokes(bytes, path.string(), path.parent_path());
  } catch (const adaptex::Error&) {
  }
  (void)adaptex::parse_material_strokes(bytes, path.string(), path.parent_path());
#elif ADAPTEX_FUZZ_PNG
  (void)adaptex::read_image_from_memory(bytes, path.string());
#elif ADAPTEX_FUZZ_MTL
  std::vector<std::string> warnings;
  (void)adaptex::parse_mtl(bytes, path, &warnings);
#elif ADAPTEX_FUZZ_PROJECT
  // not reached: via_file()
#elif ADAPTEX_FUZZ_BRUSH_PRESET
  (void)adaptex::studio::parse_brush_preset(bytes, path.string(), adaptex::studio::BrushSettings{});
#else
  try {
    (void)adaptex::read_mesh_from_memory(bytes, ADAPTEX_FUZZ_EXTENSION, path, mesh_options());
  } catch (const adaptex::Error&) {
  }
#if ADAPTEX_FUZZ_ASSET
  // The textured asset reader on the same bytes: UVs, materials and embedded images.
  adaptex::AssetReadOptions options;
  options.mesh = mesh_options();
  (void)adaptex::read_textured_asset_from_memory(bytes, ADAPTEX_FUZZ_EXTENSION, path, options);
#endif
#endif
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& path = input_path();
  try {
    if (via_file()) {
      {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
      }
      read_file(path);
    } else {
      read_memory(std::string(reinterpret_cast<const char*>(data), size), path);
    }
  } catch (const adaptex::Error&) {
    // A clean rejection: the CLI prints the message and exits 2.
  }
  return 0;
}
