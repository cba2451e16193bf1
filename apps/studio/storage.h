#pragma once
/// \file storage.h
/// Where adaptex-studio keeps work: the project file (Save / Save As), whether the history has
/// unsaved changes, the recent-files list and the last folder used, and this session's recovery file
/// (recovery.h: autosaved in the background, removed only after a successful save or an explicit
/// Discard; at any other exit it is written, so a quit by signal or by a script never loses strokes).
/// Recovery files left by sessions that did not end cleanly are offered (recovery.h RecoveryFiles).
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "jobs.h"
#include "recovery.h"
#include "settings.h"

namespace adaptex::studio {

class ProjectStore {
 public:
  using Clock = std::chrono::steady_clock;
  /// Receives messages for the status line / error pop-up (text, is_error).
  using Sink = std::function<void(const std::string&, bool)>;

  /// \param config_dir recent files (empty: none) \param recovery_dir recovery file (empty: no autosave)
  /// \param autosave_delay seconds after a change before the recovery file is written
  ProjectStore(std::filesystem::path config_dir, std::filesystem::path recovery_dir, double autosave_delay,
               Sink sink);
  ~ProjectStore();
  ProjectStore(const ProjectStore&) = delete;
  ProjectStore& operator=(const ProjectStore&) = delete;

  const std::vector<std::string>& recent() const { return recent_; }
  void add_recent(const std::string& path);
  /// The folder of the last file opened, saved or exported (kept in the config; empty: none yet).
  const std::filesystem::path& last_folder() const { return last_folder_; }
  void set_last_folder(const std::filesystem::path& folder);

  /// The project file of this session (empty: never saved or opened as a project).
  const std::filesystem::path& project_path() const { return project_path_; }
  /// The history at \p version is what \p project_path holds (empty: no project file); \p project_path
  /// empty and \p version current also means "nothing to save" (a freshly opened mesh).
  void mark_clean(std::uint64_t version, const std::filesystem::path& project_path);
  /// Work that would be lost: the history changed since mark_clean / save and has strokes (or
  /// belongs to a project file).
  bool unsaved(std::uint64_t version, bool has_strokes) const;
  /// Writes \p project to \p path atomically; on success the path becomes the project path, the
  /// history \p version counts as saved and the recovery files are removed. \return success
  bool save(const std::filesystem::path& path, const Project& project, std::uint64_t version);
  /// Drops the unsaved work at \p version: the recovery files are removed (File > Discard).
  void discard(std::uint64_t version);

  /// This session's recovery file (empty until the first autosave, or without recovery).
  const std::filesystem::path& recovery_path() const { return recovery_.claimed_path(); }
  /// Recovery files left by sessions that did not end cleanly.
  RecoveryFiles& recovery() { return recovery_; }
  const RecoveryFiles& recovery() const { return recovery_; }

  /// Every frame: writes the recovery file in the background when the unsaved history at \p version
  /// has not been written and the autosave delay has passed since the change. \p snapshot is called
  /// only then. \p can_write false (a stroke is open) postpones it.
  void autosave_tick(std::uint64_t version, bool unsaved, bool can_write, const std::function<Project()>& snapshot);
  /// Autosave as soon as possible (a stroke just ended).
  void autosave_soon() { change_time_ = Clock::time_point{}; }
  /// At exit: with unsaved work the recovery file is written now; without, it is removed.
  void finish(bool unsaved, const std::function<Project()>& snapshot);

 private:
  void load_config();
  void save_config() const;
  /// Waits for a running autosave. \return false if it failed (reported)
  bool wait_autosave();
  void remove_recovery_files();

  std::filesystem::path config_dir_;
  double autosave_delay_;
  Sink sink_;
  std::vector<std::string> recent_;
  std::filesystem::path last_folder_;
  std::filesystem::path project_path_;
  std::uint64_t clean_version_ = 0;
  RecoveryFiles recovery_;
  std::uint64_t recovery_version_ = ~0ull;  // history version in the recovery file
  std::optional<Clock::time_point> change_time_;
  std::unique_ptr<Job<int>> autosave_job_;
};

}  // namespace adaptex::studio
