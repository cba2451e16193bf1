#pragma once
/// \file shrink_report.h
/// JSON of a shrink's report (report.json of `adaptex shrink` / `adaptex reparam`, the Python module).
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "adaptex/adapt/shrink.h"

namespace adaptex {

/// The figures of \p r: PSNR of the result and of plain downsizing (first map and per map, named by
/// \p slots, parallel to r.maps), the candidates, islands, faces, flips and shared texels before and after.
nlohmann::ordered_json shrink_report_json(const ShrinkResult& r, const std::vector<std::string>& slots);

}  // namespace adaptex
