#pragma once
/// \file debug_maps.h
/// Debug pictures of one re-parameterization (`--debug-maps DIR`).
#include <filesystem>
#include <string>

#include "adaptex/adapt/adapt.h"

namespace adaptex {

/// Writes \p result's maps and warp grids as PNGs \p dir/\p prefix* (thesis Figs. 3.8, 3.9). \throw IoError
void write_debug_maps(const std::filesystem::path& dir, const std::string& prefix, const AdaptResult& result);

}  // namespace adaptex
