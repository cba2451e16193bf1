#pragma once
/// \file input_file.h
/// Reading an input file (mesh, image, stroke file, project) into memory with bounded resources:
/// only regular files (no devices, FIFOs, sockets or directories, so /dev/zero cannot hang a reader),
/// at most kMaxInputFileBytes (core/limits.h).
#include <cstdint>
#include <filesystem>
#include <string>

namespace adaptex {

/// Whole file as bytes.
/// \pre none (every problem is reported by an exception).
/// \throw IoError missing, a directory or another non-regular file, larger than kMaxInputFileBytes,
/// unreadable or empty. The message names the file and says what is wrong.
std::string read_input_file(const std::filesystem::path& path);

/// The checks read_input_file() makes on the bytes themselves, for input already in memory (the
/// read_*_from_memory() entry points): not empty, at most kMaxInputFileBytes.
/// \pre none.
/// \throw IoError \p size is 0 or larger than kMaxInputFileBytes; the message names \p name.
void check_input_size(std::uint64_t size, const std::string& name);

}  // namespace adaptex
