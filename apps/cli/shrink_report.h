#pragma once
/// \file shrink_report.h
/// The report of an atlas-preserving shrink (`adaptex shrink`, `adaptex reparam`'s default): the
/// JSON of report.json and the lines printed on stdout.
#include <nlohmann/json.hpp>
#include <string>

#include "adaptex/adapt/shrink.h"
#include "cli_common.h"

namespace adaptex::cli {

/// report.json fields of \p r (slots name the maps, parallel to r.maps).
nlohmann::ordered_json shrink_report_json(const ShrinkResult& r, const std::vector<std::string>& slots);

/// Prints "psnr: X dB (downsized: Y dB, gain Z dB)" for every map on stdout.
void print_shrink_summary(const ShrinkResult& r, const std::vector<std::string>& slots);

/// A progress callback printing one line per phase ("shrink: pack") on stderr unless quiet.
ProgressCallback shrink_progress(const Context& ctx, const std::string& prefix);

}  // namespace adaptex::cli
