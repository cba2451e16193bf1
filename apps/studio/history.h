#pragma once
/// \file history.h
/// The stroke history of a studio session: the exact record of what was painted (the stroke-file
/// contract), with unlimited undo / redo. Undo removes the last stroke; the texture is then rebuilt
/// by replaying the remaining strokes (history-based undo: no texture snapshots).
#include <cstdint>
#include <vector>

#include "adaptex/paint/strokes.h"

namespace adaptex::studio {

class StrokeHistory {
 public:
  /// Strokes currently in effect, in painting order.
  const std::vector<Stroke>& strokes() const { return strokes_; }
  const Vec3& background() const { return background_; }
  void set_background(const Vec3& bg);

  /// Appends a finished stroke (clears the redo stack).
  void push(Stroke s);
  /// Removes the last stroke onto the redo stack. \return false if there is nothing to undo.
  bool undo();
  /// Re-applies the last undone stroke. \return false if there is nothing to redo.
  bool redo();
  bool can_undo() const { return !strokes_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  /// Replaces everything (project load, recovery); clears the redo stack.
  void reset(std::vector<Stroke> strokes, const Vec3& background);

  /// Incremented by every change.
  std::uint64_t version() const { return version_; }
  /// Incremented by every change that is not a pure append (undo, redo, reset, background):
  /// a texture built from an older rewrite generation must be rebuilt, not extended.
  std::uint64_t generation() const { return generation_; }
  /// The history as a stroke file.
  StrokeFile to_file() const;
  /// Total number of dabs over all strokes.
  size_t num_dabs() const;

 private:
  std::vector<Stroke> strokes_, redo_;
  Vec3 background_ = Vec3(1, 1, 1);
  std::uint64_t version_ = 0, generation_ = 0;
};

}  // namespace adaptex::studio
