#pragma once
/// \file shrink_print.h
/// What `adaptex shrink` and `adaptex reparam` (its default) print about a shrink.
#include <nlohmann/json.hpp>
#include <string>

#include "adaptex/adapt/shrink.h"
#include "adaptex/adapt/shrink_asset.h"
#include "adaptex/adapt/shrink_report.h"
#include "cli_common.h"

namespace adaptex::cli {

/// Prints "SLOT: psnr X dB, downsized Y dB, gain Z dB" for every map, then the face counts before and
/// after, on stdout; every line starts with \p prefix.
void print_shrink_summary(const ShrinkResult& r, const std::vector<std::string>& slots, const std::string& prefix = "");

/// print_shrink_summary() of an asset's shrink: of its group when \p one_material, else of every group
/// ("MATERIAL: ..." lines) and the overall area-weighted PSNRs.
void print_asset_summary(const TexturedAsset& asset, const AssetShrinkResult& res, bool one_material);

/// A progress callback printing one line per phase ("shrink: pack") on stderr unless quiet.
ProgressCallback shrink_progress(const Context& ctx, const std::string& prefix);

}  // namespace adaptex::cli
