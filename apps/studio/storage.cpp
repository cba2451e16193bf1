/// \file storage.cpp
/// Project file, unsaved-work tracking, recent files and the recovery file (see storage.h).
#include "storage.h"

#include <algorithm>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"

namespace adaptex::studio {

namespace {
std::filesystem::path offered_path(const std::filesystem::path& dir) { return dir / "recovery.offered.json"; }
}  // namespace

ProjectStore::ProjectStore(std::filesystem::path config_dir, std::filesystem::path recovery_dir,
                           double autosave_delay, Sink sink)
    : config_dir_(std::move(config_dir)),
      recovery_dir_(std::move(recovery_dir)),
      autosave_delay_(autosave_delay),
      sink_(std::move(sink)) {
  load_config();
  if (recovery_dir_.empty()) return;
  std::error_code ec;
  const auto rec = recovery_path(), offered = offered_path(recovery_dir_);
  if (std::filesystem::exists(rec)) std::filesystem::rename(rec, offered, ec);
  if (std::filesystem::exists(offered)) {
    pending_recovery_ = offered;
    std::cout << "adaptex-studio: recovery file found: " << offered.string() << std::endl;
  }
}

ProjectStore::~ProjectStore() { wait_autosave(); }

// ---- recent files ------------------------------------------------------------------------------

void ProjectStore::load_config() {
  if (config_dir_.empty()) return;
  std::ifstream in(config_dir_ / "studio.json");
  if (!in) return;
  try {
    const auto j = nlohmann::json::parse(in);
    for (const auto& r : j.value("recent", nlohmann::json::array())) recent_.push_back(r.get<std::string>());
  } catch (const std::exception&) {
    sink_("ignoring a corrupt config file " + (config_dir_ / "studio.json").string(), true);
  }
}

void ProjectStore::save_config() const {
  if (config_dir_.empty()) return;
  try {
    AtomicOutput out;
    const auto tmp = out.add(config_dir_ / "studio.json");
    {
      std::ofstream o(tmp);
      o << nlohmann::json{{"recent", recent_}}.dump(1) << "\n";
    }
    out.commit();
  } catch (const std::exception&) {
    // The recent-files list is a convenience: a read-only config folder is not an error.
  }
}

void ProjectStore::add_recent(const std::string& path) {
  recent_.erase(std::remove(recent_.begin(), recent_.end(), path), recent_.end());
  recent_.insert(recent_.begin(), path);
  if (recent_.size() > 10) recent_.resize(10);
  save_config();
}

// ---- project file and unsaved work ---------------------------------------------------------------

void ProjectStore::mark_clean(std::uint64_t version, const std::filesystem::path& project_path) {
  clean_version_ = version;
  project_path_ = project_path;
}

bool ProjectStore::unsaved(std::uint64_t version, bool has_strokes) const {
  return version != clean_version_ && (has_strokes || !project_path_.empty());
}

bool ProjectStore::save(const std::filesystem::path& path, const Project& project, std::uint64_t version) {
  try {
    write_project(path, project);
  } catch (const std::exception& e) {
    sink_(e.what(), true);
    return false;
  }
  project_path_ = path;
  clean_version_ = version;
  remove_recovery_files();
  sink_("saved project " + path.string(), false);
  return true;
}

void ProjectStore::discard(std::uint64_t version) {
  clean_version_ = version;
  remove_recovery_files();
}

// ---- recovery ------------------------------------------------------------------------------------

std::filesystem::path ProjectStore::recovery_path() const { return recovery_dir_ / "recovery.json"; }

Project ProjectStore::accept_recovery() {
  if (!pending_recovery_) throw InvalidInputError("no recovery file to accept");
  const auto path = *pending_recovery_;
  pending_recovery_.reset();
  try {
    Project p = read_project(path);
    offered_taken_ = true;
    return p;
  } catch (const std::exception&) {
    std::error_code ec;
    std::filesystem::remove(path, ec);  // unreadable: it would be offered at every start
    throw;
  }
}

void ProjectStore::discard_recovery() {
  if (!pending_recovery_) return;
  std::error_code ec;
  std::filesystem::remove(*pending_recovery_, ec);
  pending_recovery_.reset();
}

void ProjectStore::wait_autosave() {
  if (!autosave_job_) return;
  try {
    autosave_job_->take();  // joins
  } catch (const std::exception& e) {
    sink_(std::string("autosave failed: ") + e.what(), true);
  }
  autosave_job_.reset();
}

void ProjectStore::remove_recovery_files() {
  if (recovery_dir_.empty()) return;
  wait_autosave();
  std::error_code ec;
  std::filesystem::remove(recovery_path(), ec);
  if (offered_taken_) std::filesystem::remove(offered_path(recovery_dir_), ec);
  offered_taken_ = false;
  recovery_version_ = ~0ull;
}

void ProjectStore::autosave_tick(std::uint64_t version, bool unsaved, bool can_write,
                                 const std::function<Project()>& snapshot) {
  if (recovery_dir_.empty()) return;
  if (autosave_job_ && !autosave_job_->ready()) return;
  if (autosave_job_) {
    wait_autosave();
    std::error_code ec;
    // This session's recovery file now holds the recovered work too.
    if (offered_taken_ && std::filesystem::exists(recovery_path())) {
      std::filesystem::remove(offered_path(recovery_dir_), ec);
      offered_taken_ = false;
    }
  }
  if (!unsaved || version == recovery_version_ || !can_write) return;
  const auto now = Clock::now();
  if (!change_time_) change_time_ = now;
  const bool due = *change_time_ == Clock::time_point{} ||
                   std::chrono::duration<double>(now - *change_time_).count() >= autosave_delay_;
  if (!due) return;
  recovery_version_ = version;
  change_time_.reset();
  autosave_job_ = std::make_unique<Job<int>>([p = snapshot(), path = recovery_path()](Job<int>&) {
    write_project(path, p);
    return 0;
  });
}

void ProjectStore::finish(bool unsaved, const std::function<Project()>& snapshot) {
  wait_autosave();
  if (recovery_dir_.empty()) return;
  if (!unsaved) return remove_recovery_files();
  try {
    write_project(recovery_path(), snapshot());
    std::cout << "adaptex-studio: unsaved strokes kept in " << recovery_path().string() << std::endl;
    std::error_code ec;
    if (offered_taken_) std::filesystem::remove(offered_path(recovery_dir_), ec);
  } catch (const std::exception& e) {
    std::cerr << "adaptex-studio: error: could not write the recovery file: " << e.what() << std::endl;
  }
}

}  // namespace adaptex::studio
