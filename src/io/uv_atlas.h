#pragma once
/// \file uv_atlas.h
/// Internal to the io area: the UV tile handling of read_textured_asset() (uv_atlas.cpp). Not installed.
#include <string>

#include "adaptex/io/asset_io.h"

namespace adaptex::io_detail {

/// analyze_uvs() without the texel usage (covered_fraction, shared_fraction stay 0).
UvReport count_uvs(const TriMesh& mesh, const Parameterization& param);

/// True when \p path names one tile of a UDIM texture set: a "<UDIM>", "<UVTILE>" or "%(UDIM)d"
/// token, or a tile number 1001-1199 just before the extension ("skin.1001.png", "skin_1002.tga").
bool is_udim_path(const std::string& path);

/// Moves every chart that lies inside one integer UV tile [i, i+1] x [j, j+1] (give or take
/// options.uv_tolerance) by (-i, -j) into [0,1]^2, and clamps the coordinates within the tolerance
/// outside it; counts both in \p report (wrapped_charts, clamped_uvs). With
/// options.keep_straddling_charts, a chart crossing a tile border is left as it is (straddling_charts). \p udim_map, when not empty, is a map path
/// named like a UDIM tile (is_udim_path()).
/// \pre param.face_chart set, every UV finite
/// \throw InvalidInputError a chart crosses a tile border by more than the tolerance (unless kept); the charts lie in
/// more than one tile and \p udim_map is set (UDIM). The message names \p name.
void wrap_uv_charts(Parameterization& param, const AssetReadOptions& options, const std::string& name,
                    const std::string& udim_map, UvReport& report);

}  // namespace adaptex::io_detail
