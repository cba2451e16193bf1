/// \file shrink_report.cpp
#include "adaptex/adapt/shrink_report.h"

#include <nlohmann/json.hpp>

namespace adaptex {

namespace {
nlohmann::ordered_json stats_json(const ShrinkLayoutStats& s) {
  nlohmann::ordered_json j;
  j["flipped"] = s.flipped;
  j["degenerate"] = s.degenerate;
  j["shared_fraction"] = s.shared_fraction;
  j["shared_surface"] = s.shared_surface;
  return j;
}
}  // namespace

nlohmann::ordered_json shrink_report_json(const ShrinkResult& r, const std::vector<std::string>& slots) {
  nlohmann::ordered_json j;
  j["method"] = "shrink";
  j["chosen"] = r.chosen;
  j["psnr"] = r.psnr;
  j["psnr_downsized"] = r.psnr_downsized;
  j["gain_db"] = r.psnr - r.psnr_downsized;
  nlohmann::ordered_json maps = nlohmann::ordered_json::array();
  for (size_t m = 0; m < r.maps.size(); ++m) {
    nlohmann::ordered_json jm;
    jm["slot"] = m < slots.size() ? slots[m] : std::string("map") + std::to_string(m);
    jm["psnr"] = r.map_psnr[m];
    jm["psnr_downsized"] = r.map_psnr_downsized[m];
    maps.push_back(jm);
  }
  j["maps"] = maps;
  nlohmann::ordered_json cands = nlohmann::ordered_json::array();
  for (const ShrinkCandidate& c : r.candidates) {
    nlohmann::ordered_json jc;
    jc["name"] = c.name;
    jc["valid"] = c.valid;
    if (c.valid) jc["psnr"] = c.psnr;
    jc["fill"] = c.fill;
    cands.push_back(jc);
  }
  j["candidates"] = cands;
  j["size"] = r.maps.empty() ? 0 : r.maps[0].width;
  j["predicted_budget_gain_db"] = r.predicted_gain_db;
  j["charts"] = r.charts;
  j["islands"] = r.islands;
  j["faces_before"] = r.faces_before;
  j["faces_after"] = r.faces_after;
  j["face_growth"] = r.faces_before ? static_cast<double>(r.faces_after) / r.faces_before - 1.0 : 0.0;
  j["lifted_faces"] = r.lifted_faces;
  j["before"] = stats_json(r.before);
  j["after"] = stats_json(r.after);
  j["flipped"] = r.after.flipped;
  j["time_shrink_ms"] = 1e3 * r.time_total;
  return j;
}

}  // namespace adaptex
