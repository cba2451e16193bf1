#pragma once
/// \file shrink_print.h
/// What `adaptex shrink` and `adaptex reparam` (its default) print about a shrink.
#include <nlohmann/json.hpp>
#include <string>

#include "adaptex/adapt/shrink.h"
#include "adaptex/adapt/shrink_report.h"
#include "cli_common.h"

namespace adaptex::cli {

/// Prints "SLOT: psnr X dB, downsized Y dB, gain Z dB" for every map, then the face counts before and
/// after, on stdout.
void print_shrink_summary(const ShrinkResult& r, const std::vector<std::string>& slots);

/// A progress callback printing one line per phase ("shrink: pack") on stderr unless quiet.
ProgressCallback shrink_progress(const Context& ctx, const std::string& prefix);

}  // namespace adaptex::cli
