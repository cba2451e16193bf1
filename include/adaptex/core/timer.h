#pragma once
/// \file timer.h
/// Wall-clock timing of the phases reported in the JSON reports and progress lines.
#include <chrono>

namespace adaptex {

/// Seconds of wall-clock time (std::chrono::steady_clock) elapsed since \p t0.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace adaptex
