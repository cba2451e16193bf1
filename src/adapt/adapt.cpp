// Signal-adaptive re-parameterization: the framework around the methods (method.h):
// validation, the method's warp, refinement, the flip-free remap and the geometry safeguard.
#include "adaptex/adapt/adapt.h"

#include <chrono>
#include <cmath>
#include <string>

#include "adaptex/adapt/refine.h"
#include "adaptex/adapt/method.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/timer.h"
#include "adaptex/param/stretch.h"

namespace adaptex {

namespace {
void validate(const AdaptOptions& o) {
  check_polish_options(o.density_flow.polish);
  if (o.thesis.coarse_grid < 1 || o.thesis.fine_grid < 1)
    throw InvalidInputError("grid sizes must be >= 1 cell, got " + std::to_string(o.thesis.coarse_grid) + "," +
                            std::to_string(o.thesis.fine_grid));
  if (o.thesis.coarse_grid > kMaxGridCells || o.thesis.fine_grid > kMaxGridCells)
    throw InvalidInputError("grid sizes must be <= " + std::to_string(kMaxGridCells) + " cells per side");
  if (!(o.thesis.alpha >= 0) || !(o.thesis.beta >= 0) || !std::isfinite(o.thesis.alpha) || !std::isfinite(o.thesis.beta))
    throw InvalidInputError("alpha and beta must be finite and >= 0");
  if (!(o.thesis.min_weight > 0 && o.thesis.min_weight <= 1)) throw InvalidInputError("min_weight must be in (0, 1]");
  if (!(o.thesis.epsilon_texels >= 0) || o.thesis.max_iterations < 0 || o.thesis.fine_max_iterations < 0)
    throw InvalidInputError("epsilon must be >= 0 and max_iterations >= 0");
  if (!(o.density_flow.chart_gutter_texels >= 0 && o.density_flow.chart_gutter_texels <= 64))
    throw InvalidInputError("chart_gutter_texels must be in [0, 64]");
  if (!(o.refine.tolerance_texels > 0) || o.refine.max_levels < 0 || !(o.refine.max_face_factor >= 1))
    throw InvalidInputError("refinement: tolerance must be > 0, levels >= 0 and the face factor >= 1");
}

/// Refines the mesh where the warp bends or flips its triangles (refine.h); on success the result's
/// refined_mesh, refined_layout (old UV domain) and parent_face are set.
void refine_under_warp(const TriMesh& mesh, const Parameterization& current, int texture_size,
                       const AdaptOptions& o, AdaptResult& res) {
  const UvWarp& warp = *res.warp;
  RefineOptions ro;
  ro.tolerance = o.refine.tolerance_texels / texture_size;
  ro.max_levels = o.refine.max_levels;
  ro.max_faces = static_cast<long>(o.refine.max_face_factor * mesh.num_faces());
  RefineResult rr = refine_for_warp(mesh, current, [&warp](const Vec2& p) { return warp.apply(p); }, ro);
  if (rr.added_faces == 0) return;
  res.refined_mesh = std::make_shared<const TriMesh>(std::move(rr.mesh));
  res.refined_layout = std::make_shared<const Parameterization>(std::move(rr.param));
  res.parent_face = std::move(rr.parent_face);
}
}  // namespace

std::vector<const GridWarp*> AdaptResult::warps() const {
  std::vector<const GridWarp*> w;
  if (warp)
    for (const GridWarp& g : warp->lattices())
      if (g.n > 0) w.push_back(&g);
  return w;
}

Parameterization AdaptResult::start_layout(const Parameterization& input) const {
  const Parameterization& layout = refined_layout ? *refined_layout : input;
  return warp ? warp->start_layout(layout) : layout;
}

namespace {
/// The adaptation around \p method's warp (null for None): validation, the warp, refinement, the
/// flip-free remap and the geometry safeguard.
AdaptResult run(AdaptMethod* method, const WarpInput& in) {
  const TriMesh& mesh = in.mesh;
  const Parameterization& current = in.param;
  const ImageRGBA8& texture = in.texture;
  const TexelMap& current_map = in.map;
  const AdaptOptions& o = in.options;
  validate(o);
  if (current.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("parameterization has " + std::to_string(current.uv_faces.size()) +
                            " faces, mesh has " + std::to_string(mesh.faces.size()));
  if (texture.empty()) throw InvalidInputError("adapt_parameterization: empty texture");
  if (current_map.width != texture.width || current_map.height != texture.height)
    throw InvalidInputError("adapt_parameterization: texel map size differs from the texture size");
  const auto t_start = std::chrono::steady_clock::now();
  AdaptResult res;
  AdaptReport& rep = res.report;
  rep.mode = o.mode;
  rep.faces_before = rep.faces_after = mesh.num_faces();
  rep.l2_before = measure_stretch(mesh, current).l2;
  if (!method) {
    res.param = current;
    rep.l2_after = rep.l2_before;
    rep.damping = 0;
    rep.time_total = seconds_since(t_start);
    return res;
  }
  method->compute(in, res);

  // Refinement: where the warp varies faster than the triangles, split them (same surface).
  if (o.refine.enabled && method->wants_refinement()) {
    const auto t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "refine", 0);
    refine_under_warp(mesh, current, std::max(texture.width, texture.height), o, res);
    rep.time_refine = seconds_since(t0);
  }
  const TriMesh& out_mesh = res.refined_mesh ? *res.refined_mesh : mesh;
  rep.faces_after = out_mesh.num_faces();

  const auto t0 = std::chrono::steady_clock::now();
  report_progress(o.progress, "remap", 0);
  // Re-packed charts (multi-chart density-flow) move first (an exact similarity per chart); the
  // warp's map acts on the moved charts.
  const Parameterization src = res.start_layout(current);
  SafeRemapResult sr = safe_remap_layout(src, res.warp->warp_layout(src), o.remap);
  rep.remap_checks = sr.checks;
  rep.damping = sr.mean_damping;
  rep.global_damping = sr.damping;
  rep.locally_damped = sr.locally_damped;
  res.param = std::move(sr.param);
  rep.l2_after = measure_stretch(out_mesh, res.param).l2;
  if (o.geometry_safeguard && rep.signal_fraction == 0 && !(rep.l2_after < rep.l2_before) && rep.damping > 0) {
    // No signal: the only goal is lower L2 stretch. Try half the warp, else keep the input.
    SafeRemapResult h = safe_remap_layout(src, res.warp->warp_layout(src, 0.5 * rep.damping), o.remap);
    rep.remap_checks += h.checks;
    const double l2h = measure_stretch(out_mesh, h.param).l2;
    if (l2h < rep.l2_before) {
      res.param = std::move(h.param);
      rep.damping = 0.5 * rep.damping * h.mean_damping;
      rep.l2_after = l2h;
    } else {  // the warp stays in the result (pictures); nothing else of it
      res.param = current;
      res.refined_mesh.reset();
      res.refined_layout.reset();
      res.parent_face.clear();
      rep.faces_after = mesh.num_faces();
      rep.damping = 0;
      rep.l2_after = rep.l2_before;
      rep.accepted = false;
    }
  }
  rep.time_remap = seconds_since(t0);
  rep.time_total = seconds_since(t_start);
  return res;
}
}  // namespace

AdaptResult adapt_parameterization(const TriMesh& mesh, const Parameterization& current, const ImageRGBA8& texture,
                                   const TexelMap& current_map, const AdaptOptions& options,
                                   const StrokeFile* history) {
  const WarpInput in{mesh, current, texture, current_map, history, options};
  if (options.mode == AdaptMode::None) return run(nullptr, in);
  const std::unique_ptr<AdaptMethod> method = make_adapt_method(options.mode);
  return run(method.get(), in);
}

AdaptResult adapt_parameterization(const TriMesh& mesh, const Parameterization& current, const ImageRGBA8& texture,
                                   const TexelMap& current_map, const ErrorDensity& model, const AdaptOptions& options) {
  const WarpInput in{mesh, current, texture, current_map, nullptr, options, &model};
  if (options.mode == AdaptMode::None) return run(nullptr, in);
  const std::unique_ptr<AdaptMethod> method = make_adapt_method(options.mode);
  return run(method.get(), in);
}

AdaptResult adapt_with(AdaptMethod& method, const WarpInput& input) { return run(&method, input); }

}  // namespace adaptex
