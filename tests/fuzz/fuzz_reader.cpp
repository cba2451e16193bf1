// libFuzzer target: one input format per build (ADAPTEX_FUZZ_FORMAT, see CMakeLists.txt). The bytes are
// written to a file with the format's extension and read through the same entry point as the CLI
// (read_mesh with its validation, read_strokes, read_image, studio's read_project). Every adaptex::Error
// is an accepted outcome; anything else (a crash, a sanitizer report, another exception, a timeout or
// running out of memory) is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/strokes.h"
#if ADAPTEX_FUZZ_PROJECT
#include "settings.h"
#endif

namespace {

const std::filesystem::path& input_path() {
  static const std::filesystem::path path = [] {
    const auto dir = std::filesystem::temp_directory_path() / ("adaptex-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return dir / ("input" + std::string(ADAPTEX_FUZZ_EXTENSION));
  }();
  return path;
}

void read_input(const std::filesystem::path& path) {
#if ADAPTEX_FUZZ_STROKES
  (void)adaptex::read_strokes(path);
#elif ADAPTEX_FUZZ_PNG
  (void)adaptex::read_image(path);
#elif ADAPTEX_FUZZ_PROJECT
  (void)adaptex::studio::read_project(path);
#else
  adaptex::ReadOptions options;
  options.repair = true;  // the repair code paths too
  (void)adaptex::read_mesh(path, options);
#endif
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& path = input_path();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    read_input(path);
  } catch (const adaptex::Error&) {
    // A clean rejection: the CLI prints the message and exits 2.
  }
  return 0;
}
