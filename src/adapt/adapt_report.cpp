// JSON of re-parameterization reports.
#include "adaptex/adapt/adapt_report.h"

#include <cmath>
#include <nlohmann/json.hpp>

namespace adaptex {

nlohmann::ordered_json adapt_report_json(const AdaptReport& r) {
  nlohmann::ordered_json j{{"mode", to_string(r.mode)},
                     {"accepted", r.accepted},
                     {"skipped", r.skipped},
                     {"damping", r.damping},
                     {"global_damping", r.global_damping},
                     {"locally_damped_wedges", r.locally_damped},
                     {"l2_before", r.l2_before},
                     {"l2_after", r.l2_after},
                     {"coarse_iterations", r.coarse_iterations},
                     {"fine_iterations", r.fine_iterations},
                     {"remap_checks", r.remap_checks},
                     {"flipped_after", r.flipped_after},
                     {"degenerate_after", r.degenerate_after},
                     {"signal_fraction", r.signal_fraction},
                     {"predicted_gain_db", r.predicted_gain_db},
                     {"gain_over_held_db", r.gain_over_held_db},
                     {"flow_tangled_cells", r.flow_tangled_cells},
                     {"flow_inverted_cells", r.flow_inverted_cells},
                     {"flow_steps", r.flow_steps},
                     {"flow_advected_points", r.flow_advected_points},
                     {"polish_sweeps", r.polish_sweeps},
                     {"polish_gain_db", r.polish_error_before > 0 && r.polish_error_after > 0
                                            ? 10 * std::log10(r.polish_error_before / r.polish_error_after)
                                            : 0.0},
                     {"polish_warm_lattices", r.polish_warm_lattices},
                     {"faces_before", r.faces_before},
                     {"faces_after", r.faces_after},
                     {"time_ms",
                      {{"importance", 1e3 * r.time_importance},
                       {"stretch_map", 1e3 * r.time_stretch_map},
                       {"ls2", 1e3 * r.time_ls2},
                       {"coarse", 1e3 * r.time_coarse},
                       {"fine", 1e3 * r.time_fine},
                       {"density", 1e3 * r.time_density},
                       {"flow", 1e3 * r.time_flow},
                       {"polish", 1e3 * r.time_polish},
                       {"refine", 1e3 * r.time_refine},
                       {"remap", 1e3 * r.time_remap},
                       {"texel_map", 1e3 * r.time_texel_map},
                       {"texture_update", 1e3 * r.time_texture_update},
                       {"safeguard", 1e3 * r.time_safeguard},
                       {"total", 1e3 * r.time_total}}}};
  if (r.error_before >= 0) {
    j["mse_before"] = r.error_before;
    j["mse_after"] = r.error_after;
  }
  return j;
}

void to_json(nlohmann::json& j, const AdaptReport& report) { j = nlohmann::json(adapt_report_json(report)); }

nlohmann::json adapt_reports_json(const std::vector<AdaptReport>& reports) {
  nlohmann::json arr = nlohmann::json::array();
  double total = 0;
  int accepted = 0, skipped = 0;
  for (const auto& r : reports) {
    arr.push_back(r);
    total += r.time_total;
    accepted += r.accepted ? 1 : 0;
    skipped += r.skipped ? 1 : 0;
  }
  return {{"count", reports.size()},
          {"accepted", accepted},
          {"skipped", skipped},
          {"total_ms", 1e3 * total},
          {"reports", arr}};
}

}  // namespace adaptex
