#pragma once
/// \file recovery.h
/// The recovery files of adaptex-studio in one folder. Every running session autosaves its unsaved work
/// to a file of its own (recovery.json, else recovery-2.json, recovery-3.json, ...) and holds it locked
/// (flock on a hidden ".NAME.lock" beside it) for as long as it runs. A recovery file that no running
/// session holds was left by one that did not end cleanly (a crash, kill -9, a power cut): an orphan,
/// offered at the next start. An orphan is never overwritten: it is removed only once taken (its work is
/// then this session's, and removed when this session has autosaved, saved or discarded it) or
/// explicitly discarded.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "settings.h"

namespace adaptex::studio {

/// A recovery file left by a session that did not end cleanly.
struct RecoveryOffer {
  std::filesystem::path file;  ///< The recovery file.
  Project project;             ///< Its content: the mesh, the project file, the strokes and the settings.
  /// The file's age in seconds when it was found.
  double age_seconds = 0;
};

/// The project file or mesh a recovery belongs to, as the user would name it: the project file when
/// there is one, else the mesh.
std::string recovery_owner(const Project& p);
/// "1 stroke", "3 strokes".
std::string strokes_text(size_t n);

/// An exclusive flock on a file (created if missing), released on destruction.
class FileLock {
 public:
  /// \return the lock, or nullopt when another open file (any process) holds it or it cannot be created
  static std::optional<FileLock> try_lock(const std::filesystem::path& path);
  FileLock(FileLock&& o) noexcept : fd_(std::exchange(o.fd_, -1)) {}
  FileLock& operator=(FileLock&& o) noexcept;
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock();

 private:
  explicit FileLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

/// take(), discard() and defer() take the file by value: callers pass next_offer()->file, which they
/// remove from the lists.
class RecoveryFiles {
 public:
  /// Reports a line for the user (text, is_error).
  using Sink = std::function<void(const std::string&, bool)>;

  /// Finds the orphans in \p dir (newest first) and locks them, so that no other session offers them
  /// meanwhile. An unreadable one is renamed to NAME.unreadable (reported through \p sink), not offered
  /// at every start. \p dir empty: no recovery files at all.
  RecoveryFiles(std::filesystem::path dir, Sink sink);
  ~RecoveryFiles();
  RecoveryFiles(const RecoveryFiles&) = delete;
  RecoveryFiles& operator=(const RecoveryFiles&) = delete;

  bool enabled() const { return !dir_.empty(); }
  /// The orphan to ask about next (null: none).
  const RecoveryOffer* next_offer() const { return pending_.empty() ? nullptr : &pending_.front().offer; }
  /// Every orphan not yet answered, the deferred ones included.
  std::vector<const RecoveryOffer*> all_offers() const;
  /// Takes the orphan \p file: its work becomes this session's. \return its content
  /// \pre \p file is an offer (pending or deferred) \throw InvalidInputError when it is not
  Project take(std::filesystem::path file);
  /// Deletes the orphan \p file (no-op if it is not an offer).
  void discard(std::filesystem::path file);
  /// Keeps the orphan \p file for later: not asked again in this session unless its mesh or project
  /// is opened (reoffer), offered again at the next start.
  void defer(std::filesystem::path file);
  /// Orphans that belong to \p mesh or \p project (deferred ones too) are asked about next.
  void reoffer(const std::string& mesh, const std::filesystem::path& project);
  /// Leaves every orphan untouched and unlocked (`--recover no`). \return what was left
  std::vector<RecoveryOffer> leave_all();

  /// This session's own recovery file (claimed at the first call: the first free name). Empty when
  /// recovery is off or no name could be locked.
  std::filesystem::path own_path();
  /// This session's own recovery file if claimed, else empty.
  const std::filesystem::path& claimed_path() const { return own_; }
  /// The own file now holds all of this session's work: the taken orphans are removed.
  void own_written();
  /// Removes the own file and the taken orphans (the work was saved or discarded, or there is none).
  void remove_own();

 private:
  struct Orphan {
    RecoveryOffer offer;
    FileLock lock;
  };
  void scan();
  /// Removes \p file from the pending and deferred lists. \return it, or nullopt
  std::optional<Orphan> pop(const std::filesystem::path& file);

  std::filesystem::path dir_;
  Sink sink_;
  std::vector<Orphan> pending_, deferred_;
  std::filesystem::path own_;
  std::optional<FileLock> own_lock_;
  std::vector<std::filesystem::path> taken_;  // orphans whose work is this session's, not yet in own_
};

}  // namespace adaptex::studio
