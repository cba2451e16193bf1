// The reports of unwrap, the reader, evaluate and the stretch as JSON (report_json.h).
#include "adaptex/adapt/report_json.h"

#include <nlohmann/json.hpp>

namespace adaptex {

nlohmann::ordered_json unwrap_report_json(const UnwrapReport& r) {
  nlohmann::ordered_json j;
  j["components"] = r.num_components;
  j["genus"] = r.genus;
  j["boundary_loops"] = r.boundary_loops;
  j["charts"] = r.num_charts;
  j["cut_length"] = r.cut_length;
  j["augmentations"] = r.augmentations;
  j["yoshizawa_iterations"] = r.yoshizawa_iterations;
  j["floater_l2"] = r.floater_l2;
  j["floater_linf"] = r.floater_linf;
  j["final_l2"] = r.final_l2;
  j["final_linf"] = r.final_linf;
  j["coverage"] = r.coverage;
  j["effective_texel_share"] = r.effective_texel_share;
  j["gutter"] = r.gutter;
  j["requested_gutter"] = r.requested_gutter;
  j["time"] = {{"cut", r.time_cut},         {"segment", r.time_segment}, {"floater", r.time_floater},
               {"yoshizawa", r.time_yoshizawa}, {"augment", r.time_augment},
               {"layouts", r.time_layouts},     {"pack", r.time_pack},
               {"total", r.time_total}};
  return j;
}

nlohmann::ordered_json read_report_json(const ReadReport& r) {
  return {{"dropped_degenerate_faces", r.dropped_degenerate_faces},
          {"dropped_unreferenced_vertices", r.dropped_unreferenced_vertices},
          {"dropped_duplicate_faces", r.dropped_duplicate_faces},
          {"split_nonmanifold_vertices", r.split_nonmanifold_vertices},
          {"split_pinched_vertices", r.split_pinched_vertices},
          {"flipped_faces", r.flipped_faces},
          {"welded_vertices", r.welded_vertices}};
}

nlohmann::ordered_json eval_result_json(const EvalResult& r) {
  return {{"mse", r.mse}, {"psnr", r.psnr}, {"samples", r.samples}, {"seed", r.seed}};
}

nlohmann::ordered_json stretch_json(const StretchStats& s) {
  return {{"l2", s.l2},
          {"linf", s.linf},
          {"area_distortion", s.area_distortion},
          {"angle_distortion", s.angle_distortion},
          {"flipped", s.flipped},
          {"degenerate", s.degenerate}};
}

}  // namespace adaptex
