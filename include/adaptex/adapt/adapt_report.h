#pragma once
/// \file adapt_report.h
/// JSON of re-parameterization reports (report.json of `adaptex paint` / `adaptex reparam`).
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "adaptex/adapt/adapt.h"

namespace adaptex {

/// JSON of one report (phase times in ms, stretch before/after, damping, iterations, accepted), its
/// keys in the pipeline's order (report.json sorts them: to_json()).
nlohmann::ordered_json adapt_report_json(const AdaptReport& report);
/// adapt_report_json() as nlohmann::json (keys sorted).
void to_json(nlohmann::json& j, const AdaptReport& report);
/// JSON array of reports plus totals: {"count", "accepted", "skipped", "total_ms", "reports": [...]}.
nlohmann::json adapt_reports_json(const std::vector<AdaptReport>& reports);

}  // namespace adaptex
