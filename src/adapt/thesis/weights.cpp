// Thesis §3.5–§3.7: the weights the relaxation methods share (importance, stretch map, L_s²).
#include <chrono>

#include "adaptex/adapt/importance.h"
#include "adaptex/adapt/ls2.h"
#include "adaptex/adapt/stretch_map.h"
#include "adaptex/core/timer.h"
#include "thesis_methods.h"

namespace adaptex {

RelaxOptions thesis_relax_options(const WarpInput& in) {
  const AdaptOptions& o = in.options;
  RelaxOptions ro;
  ro.ring = o.thesis.ring;
  ro.slide_boundary = o.thesis.slide_boundary;
  ro.epsilon = o.thesis.epsilon_texels / std::max(in.texture.width, in.texture.height);
  ro.max_iterations = o.thesis.max_iterations;
  ro.progress = o.progress;
  return ro;
}

void compute_thesis_weights(const WarpInput& in, AdaptResult& res) {
  const AdaptOptions& o = in.options;
  AdaptReport& rep = res.report;
  auto t0 = std::chrono::steady_clock::now();
  report_progress(o.progress, "importance", 0);
  res.importance = compute_importance(in.texture, &in.map, o.thesis.importance);
  size_t with_signal = 0;
  for (int t : in.map.inside)
    if (res.importance.data[t] > 1.0f / 512.0f) ++with_signal;
  rep.signal_fraction = in.map.inside.empty() ? 0.0 : double(with_signal) / in.map.inside.size();
  rep.time_importance = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  report_progress(o.progress, "stretch", 0);
  if (o.thesis.use_geometry_stretch) res.stretch = compute_stretch_map(in.mesh, in.param, in.map);
  rep.time_stretch_map = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  report_progress(o.progress, "ls2", 0);
  Ls2Options lo;
  lo.alpha = o.thesis.alpha;
  lo.beta = o.thesis.beta;
  lo.min_weight = o.thesis.min_weight;
  lo.geometry_scale = o.thesis.geometry_scale;
  res.ls2 = compute_ls2(res.importance, res.stretch, lo);
  rep.time_ls2 = seconds_since(t0);
}

}  // namespace adaptex
