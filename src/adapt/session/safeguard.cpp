// PaintSession: the safeguard: samples, the exact signal there, the error before and after a cycle.
#include "session_impl.h"

#include <chrono>

#include "adaptex/paint/point_transfer.h"
#include "adaptex/core/timer.h"

namespace adaptex {

void PaintSession::Impl::ensure_samples() {
  if (samples.empty()) samples = sample_surface(mesh, opt.safeguard_samples, opt.safeguard_seed);
  if (refined && refined_samples.size() != samples.size()) {  // refined without a safeguard run
    refined_samples = sample_surface(*refined, opt.safeguard_samples, opt.safeguard_seed);
    refined_moved = false;
  }
}

bool PaintSession::Impl::are_samples(const std::vector<SurfacePoint>& pts) const {
  return &pts == &samples || (&pts == &refined_samples && refined_moved);
}

const std::vector<Vec3>* PaintSession::Impl::cached_signal(const std::vector<SurfacePoint>& pts) {
  if (!are_samples(pts) || samples.empty()) return nullptr;
  if (!signal_cache) signal_cache = std::make_unique<PointSignalCache>(mesh, samples, history.background);
  signal_cache->update(history);
  return signal_cache->has_decals() ? nullptr : &signal_cache->values();
}

std::vector<Vec3> PaintSession::Impl::exact_signal(const std::vector<SurfacePoint>& src, const TriMesh& m,
                               const std::vector<SurfacePoint>& pts) {
  if (const std::vector<Vec3>* c = cached_signal(src)) return *c;
  return StrokeSignal(m, history).evaluate(pts);
}

SafeguardPoints PaintSession::Impl::prepare_safeguard(const AdaptResult& res, const TriMesh& cand_mesh, AdaptReport& rep) {
  SafeguardPoints sg;
  const std::vector<SurfacePoint>& src_pts = base_param ? samples : current_samples();
  if (res.refined_mesh && !src_pts.empty())
    sg.moved = transfer_points(src_pts, source_mesh(), cand_mesh, res.parent_face);
  if (!res.refined_mesh) sg.kept = &src_pts;
  sg.from_samples = are_samples(src_pts);
  sg.exact = exact_signal(src_pts, cand_mesh, sg.points());
  const bool initial = path_independent();
  const std::vector<SurfacePoint>& ref_pts = initial ? samples : current_samples();
  // Without refinement the candidate's points are the reference's: evaluate the signal once.
  const std::vector<Vec3> ref_exact = sg.kept == &ref_pts ? std::vector<Vec3>{}
                                                          : exact_signal(ref_pts, initial ? mesh : current_mesh(), ref_pts);
  rep.error_before = reconstruction_mse(initial ? *base_param : *param, initial ? base_painter->texture() : texture(),
                                        ref_pts, sg.kept == &ref_pts ? sg.exact : ref_exact);
  return sg;
}

bool PaintSession::Impl::judge(Candidate& c, AdaptResult& res, const SafeguardPoints& sg, const AdaptOptions& ao,
           const TriMesh& cand_mesh) {
  AdaptReport& rep = res.report;
  auto t0 = std::chrono::steady_clock::now();
  rep.error_after = reconstruction_mse(*c.param, c.texture, sg.points(), sg.exact);
  // The margin guards the fixed layout against an adapted one that only the estimate finds better.
  // End mode asked again (or resample mode) once the current layout is adapted: any better candidate
  // replaces it.
  const bool against_fixed = path_independent() || !adapted;
  const double limit = rep.error_before * (1.0 - (against_fixed ? opt.safeguard_margin : 0.0));
  rep.time_safeguard += seconds_since(t0);
  if (rep.error_after < limit) return true;
  Candidate half = make_candidate(res, 0.5, ao, cand_mesh);
  t0 = std::chrono::steady_clock::now();
  const double eh = reconstruction_mse(*half.param, half.texture, sg.points(), sg.exact);
  rep.time_safeguard += seconds_since(t0);
  if (!(eh < limit)) return false;
  c = std::move(half);
  rep.error_after = eh;
  rep.damping *= 0.5;
  return true;
}

double PaintSession::Impl::current_error() {
  if (history.strokes.empty()) return 0;
  if (opt.safeguard_samples == 0) return -1;
  ensure_samples();
  const std::vector<SurfacePoint>& pts = current_samples();
  return reconstruction_mse(*param, texture(), pts, exact_signal(pts, current_mesh(), pts));
}

}  // namespace adaptex
