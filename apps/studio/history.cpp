/// \file history.cpp
#include "history.h"

namespace adaptex::studio {

void StrokeHistory::set_background(const Vec3& bg) {
  if (bg == background_) return;
  background_ = bg;
  ++version_;
  ++generation_;
}

void StrokeHistory::push(Stroke s) {
  strokes_.push_back(std::move(s));
  if (!redo_.empty()) {
    redo_.clear();
  }
  ++version_;
}

bool StrokeHistory::undo() {
  if (strokes_.empty()) return false;
  redo_.push_back(std::move(strokes_.back()));
  strokes_.pop_back();
  ++version_;
  ++generation_;
  return true;
}

bool StrokeHistory::redo() {
  if (redo_.empty()) return false;
  strokes_.push_back(std::move(redo_.back()));
  redo_.pop_back();
  ++version_;  // a pure append: a texture of the current generation can be extended
  return true;
}

void StrokeHistory::reset(std::vector<Stroke> strokes, const Vec3& background) {
  strokes_ = std::move(strokes);
  redo_.clear();
  background_ = background;
  ++version_;
  ++generation_;
}

StrokeFile StrokeHistory::to_file() const {
  StrokeFile f;
  f.background = background_;
  f.strokes = strokes_;
  return f;
}

size_t StrokeHistory::num_dabs() const {
  size_t n = 0;
  for (const auto& s : strokes_) n += s.dabs.size();
  return n;
}

}  // namespace adaptex::studio
