#pragma once
// The thesis' methods (§3.5–§3.8), registered in method.cpp; internal to the adapt library.
#include <memory>

#include "adaptex/adapt/method.h"
#include "adaptex/adapt/relax.h"

namespace adaptex {

std::unique_ptr<AdaptMethod> make_single_method();     ///< §3.7: one relaxed grid (single_method.cpp)
std::unique_ptr<AdaptMethod> make_two_stage_method();  ///< §3.8: coarse then fine (two_stage_method.cpp)

/// Importance (§3.5), geometry stretch (§3.5) and L_s² (§3.6) into \p result, with their times and
/// signal_fraction in result.report. Shared by both methods.
void compute_thesis_weights(const WarpInput& input, AdaptResult& result);
/// Relaxation settings of the thesis methods from input.options (ε in texels of the texture).
RelaxOptions thesis_relax_options(const WarpInput& input);

}  // namespace adaptex
