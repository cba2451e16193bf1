#include "adaptex/core/atomic_output.h"

#include <random>
#include <system_error>

#include "adaptex/core/errors.h"

namespace adaptex {

namespace fs = std::filesystem;

AtomicOutput::~AtomicOutput() {
  if (committed_) return;
  std::error_code ec;
  for (auto& [tmp, final_path] : files_) fs::remove(tmp, ec);
  for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) fs::remove(*it, ec);
}

fs::path AtomicOutput::add(const fs::path& final_path) {
  fs::path dir = final_path.parent_path();
  // The error_code overloads throughout: a directory that cannot even be examined (no search
  // permission on a parent) is an OutputError too, never a std::filesystem::filesystem_error.
  std::error_code ec;
  if (!dir.empty() && !fs::exists(dir, ec)) {
    // Remember every directory level we create so that a failure removes them again.
    std::vector<fs::path> missing;
    for (fs::path d = dir; !d.empty() && !fs::exists(d, ec); d = d.parent_path()) missing.push_back(d);
    fs::create_directories(dir, ec);
    if (ec) throw OutputError(dir.string() + ": cannot create directory: " + ec.message());
    created_dirs_.insert(created_dirs_.end(), missing.rbegin(), missing.rend());
  }
  static thread_local std::mt19937_64 rng{std::random_device{}()};
  fs::path tmp = final_path;
  tmp += ".tmp-" + std::to_string(rng() % 1000000000ULL);
  files_.emplace_back(tmp, final_path);
  return tmp;
}

void AtomicOutput::commit() {
  // A final path that is a directory would fail its rename after the others were renamed into place:
  // refuse before renaming anything, so that the command still leaves no partial output.
  for (auto& [tmp, final_path] : files_) {
    std::error_code ec;
    if (fs::is_directory(final_path, ec))
      throw OutputError(final_path.string() + ": cannot write: is a directory");
  }
  for (auto& [tmp, final_path] : files_) {
    std::error_code ec;
    fs::rename(tmp, final_path, ec);
    if (ec) throw OutputError(final_path.string() + ": cannot write: " + ec.message());
  }
  committed_ = true;
}

std::vector<fs::path> AtomicOutput::final_paths() const {
  std::vector<fs::path> out;
  out.reserve(files_.size());
  for (const auto& [tmp, final_path] : files_) out.push_back(final_path);
  return out;
}

}  // namespace adaptex
