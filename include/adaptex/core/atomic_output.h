#pragma once
/// \file atomic_output.h
/// All-or-nothing output: files are written under temporary names and renamed into place only by
/// commit(); if the object is destroyed without commit() (an error was thrown), every temporary is
/// removed, so a failed command leaves no partial output behind.
#include <filesystem>
#include <string>
#include <vector>

namespace adaptex {

class AtomicOutput {
 public:
  AtomicOutput() = default;
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;
  ~AtomicOutput();

  /// Registers \p final_path and returns the temporary path to write it to (same directory).
  /// Creates missing parent directories (and removes them again if nothing is committed).
  std::filesystem::path add(const std::filesystem::path& final_path);
  /// Renames every temporary into place. \throw OutputError if a rename fails.
  void commit();
  /// The final paths registered so far, in the order add() was called.
  std::vector<std::filesystem::path> final_paths() const;

 private:
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> files_;  // (tmp, final)
  std::vector<std::filesystem::path> created_dirs_;
  bool committed_ = false;
};

}  // namespace adaptex
