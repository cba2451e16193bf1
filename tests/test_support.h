#pragma once
/// \file test_support.h
/// Helpers shared by the test programs: the shared-mesh folder (tests skip when it is absent),
/// running the CLI, temporary directories.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace adaptex::test {

/// ../shared/meshes, or $ADAPTEX_SHARED/meshes; nullopt when absent.
inline std::optional<std::filesystem::path> shared_meshes_dir() {
  std::filesystem::path dir = ADAPTEX_SHARED_DIR;
  if (const char* env = std::getenv("ADAPTEX_SHARED")) dir = env;
  dir /= "meshes";
  if (std::filesystem::is_directory(dir)) return dir;
  return std::nullopt;
}

/// The shared meshes (every file in ../shared/meshes that is a mesh), sorted by name.
inline std::vector<std::filesystem::path> shared_meshes() {
  std::vector<std::filesystem::path> out;
  if (auto dir = shared_meshes_dir())
    for (auto& e : std::filesystem::directory_iterator(*dir)) {
      const auto ext = e.path().extension().string();
      if (ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".stl") out.push_back(e.path());
    }
  std::sort(out.begin(), out.end());
  return out;
}

#define ADAPTEX_REQUIRE_SHARED()                                                         \
  do {                                                                                   \
    if (!::adaptex::test::shared_meshes_dir())                                           \
      GTEST_SKIP() << "shared meshes folder not found (" ADAPTEX_SHARED_DIR "/meshes); " \
                      "skipping the shared-mesh test";                                   \
  } while (0)

/// A fresh empty directory under the system temp dir, removed at destruction.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() /
           ("adaptex-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  static int& counter() {
    static int c = 0;
    return c;
  }
};

/// Result of running the CLI.
struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

/// Runs the adaptex CLI with \p args (shell-quoted by the caller where needed). \p shell_prefix is put
/// before the command (e.g. "ulimit -v 2097152; timeout 30 ").
CliResult run_cli(const std::string& args, const std::string& shell_prefix = "");

}  // namespace adaptex::test
