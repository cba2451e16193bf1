#pragma once
/// \file input_file.h
/// Reading an input file (mesh, image, stroke file, project) into memory with bounded resources:
/// only regular files (no devices, FIFOs, sockets or directories, so /dev/zero cannot hang a reader),
/// at most kMaxInputFileBytes (core/limits.h).
#include <filesystem>
#include <string>

namespace adaptex {

/// Whole file as bytes.
/// \pre none (every problem is reported by an exception).
/// \throw IoError missing, a directory or another non-regular file, larger than kMaxInputFileBytes,
/// unreadable or empty. The message names the file and says what is wrong.
std::string read_input_file(const std::filesystem::path& path);

}  // namespace adaptex
