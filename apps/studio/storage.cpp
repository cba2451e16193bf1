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

ProjectStore::ProjectStore(std::filesystem::path config_dir, std::filesystem::path recovery_dir,
                           double autosave_delay, Sink sink)
    : config_dir_(std::move(config_dir)),
      autosave_delay_(autosave_delay),
      sink_(std::move(sink)),
      recovery_(std::move(recovery_dir), sink_) {
  load_config();
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
    last_folder_ = j.value("last_folder", std::string());
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
      o << nlohmann::json{{"recent", recent_}, {"last_folder", last_folder_.string()}}.dump(1) << "\n";
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

void ProjectStore::set_last_folder(const std::filesystem::path& folder) {
  if (folder.empty() || folder == last_folder_) return;
  last_folder_ = folder;
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

bool ProjectStore::wait_autosave() {
  if (!autosave_job_) return true;
  bool ok = true;
  try {
    autosave_job_->take();  // joins
  } catch (const std::exception& e) {
    sink_(std::string("autosave failed: ") + e.what(), true);
    ok = false;
  }
  autosave_job_.reset();
  return ok;
}

void ProjectStore::remove_recovery_files() {
  wait_autosave();
  recovery_.remove_own();
  recovery_version_ = ~0ull;
}

void ProjectStore::autosave_tick(std::uint64_t version, bool unsaved, bool can_write,
                                 const std::function<Project()>& snapshot) {
  if (!recovery_.enabled()) return;
  if (autosave_job_ && !autosave_job_->ready()) return;
  if (autosave_job_ && wait_autosave()) recovery_.own_written();  // it holds the taken work too
  if (!unsaved || version == recovery_version_ || !can_write) return;
  const auto now = Clock::now();
  if (!change_time_) change_time_ = now;
  const bool due = *change_time_ == Clock::time_point{} ||
                   std::chrono::duration<double>(now - *change_time_).count() >= autosave_delay_;
  if (!due) return;
  const std::filesystem::path path = recovery_.own_path();
  if (path.empty()) return;
  recovery_version_ = version;
  change_time_.reset();
  autosave_job_ = std::make_unique<Job<int>>([p = snapshot(), path](Job<int>&) {
    write_project(path, p);
    return 0;
  });
}

void ProjectStore::finish(bool unsaved, const std::function<Project()>& snapshot) {
  wait_autosave();
  if (!recovery_.enabled()) return;
  if (!unsaved) return remove_recovery_files();
  const std::filesystem::path path = recovery_.own_path();
  if (path.empty()) return;
  try {
    write_project(path, snapshot());
    recovery_.own_written();
    std::cout << "adaptex-studio: unsaved strokes kept in " << path.string() << std::endl;
  } catch (const std::exception& e) {
    std::cerr << "adaptex-studio: error: could not write the recovery file: " << e.what() << std::endl;
  }
}

}  // namespace adaptex::studio
