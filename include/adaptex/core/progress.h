#pragma once
/// \file progress.h
/// Progress / cancel callback (after xatlas): long operations call it with the name of the current
/// phase and a fraction in [0,1]. Returning false cancels: the operation throws CancelledError.
#include <functional>
#include <string_view>

#include "adaptex/core/errors.h"

namespace adaptex {

/// \param phase short name of the running phase ("cut", "floater", "yoshizawa", ...)
/// \param fraction progress of that phase in [0,1]
/// \return false to cancel the operation
using ProgressCallback = std::function<bool(std::string_view phase, double fraction)>;

/// Calls \p cb if set. \throw CancelledError if it returns false.
inline void report_progress(const ProgressCallback& cb, std::string_view phase, double fraction) {
  if (cb && !cb(phase, fraction)) throw CancelledError();
}

}  // namespace adaptex
