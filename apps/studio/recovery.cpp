/// \file recovery.cpp
/// Recovery files, their locks and the orphans left by sessions that did not end cleanly (see recovery.h).
#include "recovery.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <iostream>

#include "adaptex/core/errors.h"

namespace adaptex::studio {

namespace {
/// recovery.json, recovery-N.json, and recovery.offered.json (written by earlier versions).
/// Hand-written rather than std::regex, which trips GCC 12's -Wmaybe-uninitialized under sanitizers.
bool is_recovery_name(const std::string& name) {
  const std::string head = "recovery", tail = ".json";
  if (name.size() < head.size() + tail.size() || name.compare(0, head.size(), head) != 0 ||
      name.compare(name.size() - tail.size(), tail.size(), tail) != 0)
    return false;
  const std::string mid = name.substr(head.size(), name.size() - head.size() - tail.size());
  if (mid.empty() || mid == ".offered") return true;
  if (mid[0] != '-' || mid.size() < 2 || mid.size() > 7) return false;
  return std::all_of(mid.begin() + 1, mid.end(), [](char c) { return c >= '0' && c <= '9'; });
}
std::filesystem::path lock_path(const std::filesystem::path& file) {
  std::string name(1, '.');  // appended, not "." + name: GCC 12's -Wrestrict misfires on the latter
  name += file.filename().string();
  name += ".lock";
  return file.parent_path() / name;
}
std::filesystem::path slot_name(const std::filesystem::path& dir, int n) {
  return dir / (n == 1 ? std::string("recovery.json") : "recovery-" + std::to_string(n) + ".json");
}
}  // namespace

std::string recovery_owner(const Project& p) {
  return p.project_file.empty() ? p.mesh_path : p.project_file;
}

std::string strokes_text(size_t n) { return std::to_string(n) + (n == 1 ? " stroke" : " strokes"); }

// ---- FileLock ------------------------------------------------------------------------------------

std::optional<FileLock> FileLock::try_lock(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return std::nullopt;
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    return std::nullopt;
  }
  return FileLock(fd);
}

FileLock& FileLock::operator=(FileLock&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(o.fd_, -1);
  }
  return *this;
}

FileLock::~FileLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the last descriptor releases the flock
}

// ---- RecoveryFiles -------------------------------------------------------------------------------

RecoveryFiles::RecoveryFiles(std::filesystem::path dir, Sink sink) : sink_(std::move(sink)) {
  if (dir.empty()) return;
  std::error_code ec;
  dir_ = std::filesystem::absolute(dir, ec).lexically_normal();  // messages name whole paths
  if (ec) dir_ = dir;
  scan();
}

RecoveryFiles::~RecoveryFiles() = default;

void RecoveryFiles::scan() {
  std::error_code ec;
  std::vector<std::pair<std::filesystem::file_time_type, std::filesystem::path>> found;
  for (std::filesystem::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    std::error_code e2;
    if (is_recovery_name(it->path().filename().string()) && it->is_regular_file(e2))
      found.emplace_back(it->last_write_time(e2), it->path());
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  const auto now = std::filesystem::file_time_type::clock::now();
  for (const auto& [time, file] : found) {
    std::optional<FileLock> lock = FileLock::try_lock(lock_path(file));
    if (!lock) continue;  // a running session's own file (or an orphan another starting session offers)
    std::error_code e2;
    if (!std::filesystem::exists(file, e2)) continue;  // its session ended cleanly meanwhile
    try {
      RecoveryOffer offer{file, read_project(file), std::chrono::duration<double>(now - time).count()};
      std::cout << "adaptex-studio: recovery file found: " << file.string() << " (unsaved: "
                << strokes_text(offer.project.strokes.strokes.size()) << " on " << recovery_owner(offer.project) << ")"
                << std::endl;
      pending_.push_back({std::move(offer), std::move(*lock)});
    } catch (const std::exception& e) {
      // Unreadable (truncated by a full disk, edited by hand): kept aside, not offered at every start.
      const std::filesystem::path aside = file.string() + ".unreadable";
      std::filesystem::rename(file, aside, e2);
      sink_("recovery file " + file.string() + " cannot be read (" + e.what() + "): kept as " + aside.string(),
            false);
    }
  }
}

std::vector<const RecoveryOffer*> RecoveryFiles::all_offers() const {
  std::vector<const RecoveryOffer*> out;
  for (const auto* list : {&pending_, &deferred_})
    for (const Orphan& o : *list) out.push_back(&o.offer);
  return out;
}

std::optional<RecoveryFiles::Orphan> RecoveryFiles::pop(const std::filesystem::path& file) {
  for (auto* list : {&pending_, &deferred_}) {
    auto it = std::find_if(list->begin(), list->end(), [&](const Orphan& o) { return o.offer.file == file; });
    if (it == list->end()) continue;
    Orphan o = std::move(*it);
    list->erase(it);
    return o;
  }
  return std::nullopt;
}

Project RecoveryFiles::take(std::filesystem::path file) {
  std::optional<Orphan> o = pop(file);
  if (!o) throw InvalidInputError(file.string() + ": not a recovery file of this session");
  if (own_.empty()) {  // adopted: the next autosave writes this session's work (the recovered included) there
    own_ = o->offer.file;
    own_lock_ = std::move(o->lock);
  } else {
    taken_.push_back(o->offer.file);
  }
  return std::move(o->offer.project);
}

void RecoveryFiles::discard(std::filesystem::path file) {
  if (!pop(file)) return;
  std::error_code ec;
  std::filesystem::remove(file, ec);
}

void RecoveryFiles::defer(std::filesystem::path file) {
  if (std::optional<Orphan> o = pop(file)) deferred_.push_back(std::move(*o));
}

void RecoveryFiles::reoffer(const std::string& mesh, const std::filesystem::path& project) {
  const auto mine = [&](const Orphan& o) {
    const Project& p = o.offer.project;
    return (!mesh.empty() && p.mesh_path == mesh) ||
           (!project.empty() && !p.project_file.empty() && p.project_file == project.string());
  };
  std::vector<Orphan> first, rest;
  for (auto* list : {&pending_, &deferred_})
    for (auto it = list->begin(); it != list->end();) {
      if (!mine(*it) && list == &deferred_) {
        ++it;
        continue;
      }
      (mine(*it) ? first : rest).push_back(std::move(*it));
      it = list->erase(it);
    }
  for (Orphan& o : rest) first.push_back(std::move(o));
  pending_ = std::move(first);
}

std::vector<RecoveryOffer> RecoveryFiles::leave_all() {
  std::vector<RecoveryOffer> out;
  for (auto* list : {&pending_, &deferred_}) {
    for (Orphan& o : *list) out.push_back(std::move(o.offer));
    list->clear();  // unlocked
  }
  return out;
}

std::filesystem::path RecoveryFiles::own_path() {
  if (!own_.empty() || dir_.empty()) return own_;
  for (int n = 1; n <= 1000; ++n) {
    const std::filesystem::path file = slot_name(dir_, n);
    std::optional<FileLock> lock = FileLock::try_lock(lock_path(file));
    std::error_code ec;
    if (!lock || std::filesystem::exists(file, ec)) continue;  // a running session's, or an orphan
    own_ = file;
    own_lock_ = std::move(lock);
    return own_;
  }
  sink_("no free recovery file name in " + dir_.string() + ": this session is not autosaved", true);
  dir_.clear();
  return own_;
}

void RecoveryFiles::own_written() {
  std::error_code ec;
  for (const auto& f : taken_) std::filesystem::remove(f, ec);
  taken_.clear();
}

void RecoveryFiles::remove_own() {
  std::error_code ec;
  if (!own_.empty()) std::filesystem::remove(own_, ec);
  own_written();
}

}  // namespace adaptex::studio
