/// \file input_file.cpp
/// read_input_file(): the one place where adaptex reads an input file into memory (regular files only,
/// size capped by kMaxInputFileBytes).
#include "adaptex/io/input_file.h"

#include <fstream>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"

namespace adaptex {

std::string read_input_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw IoError(name + ": cannot read: file does not exist");
  if (std::filesystem::is_directory(status)) throw IoError(name + ": cannot read: is a directory");
  if (!std::filesystem::is_regular_file(status))
    throw IoError(name + ": cannot read: not a regular file (a device, FIFO or socket); only regular files are read");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw IoError(name + ": cannot read: cannot get the file size (" + ec.message() + ")");
  if (size > kMaxInputFileBytes) check_input_size(size, name);  // before allocating anything
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(name + ": cannot read: cannot open the file (permissions?)");
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw IoError(name + ": cannot read: I/O error while reading");
  check_input_size(text.size(), name);
  return text;
}

void check_input_size(std::uint64_t size, const std::string& name) {
  if (size == 0) throw IoError(name + ": cannot read: file is empty (0 bytes)");
  if (size > kMaxInputFileBytes)
    throw IoError(name + ": cannot read: file is " + std::to_string(size) + " bytes, more than the " +
                  std::to_string(kMaxInputFileBytes) + "-byte limit for input files");
}

}  // namespace adaptex
