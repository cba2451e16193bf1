// PaintSession: its layouts (current, initial, resample base + segment) and the candidates that replace them.
#include "session_impl.h"

#include <chrono>

#include "adaptex/adapt/texture_update.h"
#include "adaptex/core/timer.h"

namespace adaptex {

const ImageRGBA8& PaintSession::Impl::texture() {
  if (!resampled) return painter->texture();
  if (!segment || segment->empty) return base;
  if (composite_dirty) {
    composite = composite_over_base(base, segment->black.texture(), segment->white.texture(), painter->texel_map(),
                                    opt.padding);
    composite_dirty = false;
  }
  return composite;
}

void PaintSession::Impl::new_segment() {
  const PainterOptions po = painter_options();
  segment = std::make_unique<Segment>(Segment{Painter(current_mesh(), *param, po, Vec3(0, 0, 0)),
                                              Painter(current_mesh(), *param, po, Vec3(1, 1, 1)), true});
}

void PaintSession::Impl::paint(const Stroke& s) {
  if (base_painter) base_painter->paint_stroke(s);
  painter->paint_stroke(s);  // keeps the painter's own (replay-exact) texture for the history too
  if (resampled) {
    segment->black.paint_stroke(s);
    segment->white.paint_stroke(s);
    segment->empty = false;
    composite_dirty = true;
  }
}

Candidate PaintSession::Impl::make_candidate(AdaptResult& res, double t, const AdaptOptions& ao, const TriMesh& cand_mesh) {
  AdaptReport& rep = res.report;
  Candidate c;
  if (t == 1.0) {
    c.param = std::make_unique<Parameterization>(res.param);
  } else {
    const Parameterization start = res.start_layout(source_param());
    c.param = std::make_unique<Parameterization>(
        safe_remap_layout(start, res.warp->warp_layout(start, t * rep.damping), ao.remap).param);
  }
  auto tm = std::chrono::steady_clock::now();
  c.painter = std::make_unique<Painter>(cand_mesh, *c.param, painter_options(), history.background);
  rep.time_texel_map += seconds_since(tm);
  tm = std::chrono::steady_clock::now();
  // Resample: the visible texture is the resampled one; the new painter only provides the texel map
  // (and the segment painters paint the strokes that follow).
  c.from_cache = uses_surface_cache() && &source_mesh() == &mesh;
  if (c.from_cache)
    c.texture = texture_from_cache(*c.painter, cand_mesh, res.refined_mesh ? &res.parent_face : nullptr);
  else
    c.texture = update_texture(opt.update, *c.painter, history, *param, texture(), opt.padding, ao.progress);
  rep.time_texture_update += seconds_since(tm);
  return c;
}

void PaintSession::Impl::adopt(Candidate&& c, AdaptResult& res, SafeguardPoints&& sg) {
  adapted = true;
  held_from_cache = c.from_cache;
  if (path_independent()) method->hold(&res);
  res.param = *c.param;
  painter = std::move(c.painter);  // references *c.param and the candidate's mesh: keep both alive
  param = std::move(c.param);
  if (res.refined_mesh) {
    refined_moved = sg.from_samples && !sg.moved.empty();
    refined_samples = std::move(sg.moved);
    refined = res.refined_mesh;
  } else if (base_param) {
    refined.reset();  // each-stroke: an unrefined candidate lives on the input mesh
    refined_samples.clear();
    refined_moved = false;
  }
  if (opt.update == TextureUpdate::Resample) {
    resampled = true;
    base = std::move(c.texture);
    new_segment();
    composite_dirty = true;
  }
}

void PaintSession::Impl::return_to_initial() {
  method->hold(nullptr);
  held_error = held_best = -1;
  if (!adapted) return;
  param = std::make_unique<Parameterization>(*base_param);
  held_from_cache = uses_surface_cache();
  if (held_from_cache) {
    painter = std::make_unique<Painter>(mesh, *param, painter_options(), history.background);
    texture_from_cache(*painter, mesh, nullptr);
  } else {
    painter = std::make_unique<Painter>(replay_texture(mesh, *param, history, painter_options()));
  }
  refined.reset();
  refined_samples.clear();
  refined_moved = false;
  adapted = false;
}

void PaintSession::Impl::keep(AdaptResult& res) {
  if (path_independent()) return_to_initial();
  AdaptReport& rep = res.report;
  rep.accepted = false;
  rep.damping = 0;
  rep.l2_after = rep.l2_before;
  rep.faces_after = current_mesh().num_faces();
  res.param = *param;
  res.refined_mesh = refined;
  res.refined_layout.reset();
  res.parent_face.clear();
}

}  // namespace adaptex
