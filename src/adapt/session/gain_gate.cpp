// PaintSession: the gain gate of each-stroke mode (PaintSessionOptions::min_gain_db).
#include "session_impl.h"

#include <chrono>
#include <cmath>

#include "adaptex/core/timer.h"
#include "adaptex/param/stretch.h"

namespace adaptex {

std::optional<PaintSession::Impl::Model> PaintSession::Impl::model_now(const AdaptOptions& ao, bool measure) {
  if (!fixed_layout() || history.strokes.empty()) return std::nullopt;
  const auto t0 = std::chrono::steady_clock::now();
  const std::optional<GainModel> g =
      method->predict_gain(WarpInput{mesh, *base_param, base_painter->texture(), base_painter->texel_map(), &history, ao});
  if (!g) return std::nullopt;
  Model m{*g};
  const double best = g->least_error;
  const double now = measure && held_error > 0 && held_best > 0 && best > 0 ? current_error() : -1;
  const double held = now > 0 ? now : g->held_error;
  const double reachable = now > 0 ? held_error * best / held_best : best;
  m.gain_over_held_db = held > 0 && reachable > 0 ? 10 * std::log10(held / reachable) : 0.0;
  m.seconds = seconds_since(t0);
  return m;
}

const AdaptReport& PaintSession::Impl::skip(const AdaptOptions& ao, const Model& m, std::chrono::steady_clock::time_point t_all) {
  AdaptReport rep;
  rep.mode = ao.mode;
  rep.skipped = true;
  rep.accepted = false;
  rep.damping = 0;
  rep.signal_fraction = m.gain.signal_fraction;
  rep.predicted_gain_db = m.gain.predicted_gain_db;
  rep.gain_over_held_db = m.gain_over_held_db;
  rep.faces_before = rep.faces_after = current_mesh().num_faces();
  if (held_l2 < 0) held_l2 = measure_stretch(current_mesh(), *param).l2;
  rep.l2_before = rep.l2_after = held_l2;
  rep.time_density = m.seconds;
  rep.time_total = seconds_since(t_all);
  pending = true;
  reports.push_back(rep);
  return reports.back();
}

}  // namespace adaptex
