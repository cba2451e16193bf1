#pragma once
/// \file debug_maps.h
/// Debug pictures of one re-parameterization (`--debug-maps DIR`).
#include <filesystem>
#include <string>

#include "adaptex/adapt/adapt.h"

namespace adaptex {

/// Writes the maps and grids of \p result into \p dir with file prefix \p prefix: importance (or the
/// error map of density-flow), stretch, ls2, density (grey levels, log scale) and every warp grid drawn
/// over the L_s² or density map (thesis Figs. 3.8, 3.9). \throw IoError
void write_debug_maps(const std::filesystem::path& dir, const std::string& prefix, const AdaptResult& result);

}  // namespace adaptex
