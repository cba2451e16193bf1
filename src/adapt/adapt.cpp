// Signal-adaptive re-parameterization, thesis §3.5–§3.8 (two-stage framework: §3.8).
#include "adaptex/adapt/adapt.h"

#include <chrono>
#include <cmath>
#include <string>

#include "adaptex/adapt/stretch_map.h"
#include "adaptex/core/errors.h"
#include "adaptex/param/stretch.h"

namespace adaptex {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
void validate(const AdaptOptions& o) {
  if (o.coarse_grid < 1 || o.fine_grid < 1)
    throw InvalidInputError("grid sizes must be >= 1 cell, got " + std::to_string(o.coarse_grid) + "," +
                            std::to_string(o.fine_grid));
  if (o.coarse_grid > 4096 || o.fine_grid > 4096)
    throw InvalidInputError("grid sizes must be <= 4096 cells per side");
  if (!(o.alpha >= 0) || !(o.beta >= 0) || !std::isfinite(o.alpha) || !std::isfinite(o.beta))
    throw InvalidInputError("alpha and beta must be finite and >= 0");
  if (!(o.min_weight > 0 && o.min_weight <= 1)) throw InvalidInputError("min_weight must be in (0, 1]");
  if (!(o.epsilon_texels >= 0) || o.max_iterations < 0 || o.fine_max_iterations < 0)
    throw InvalidInputError("epsilon must be >= 0 and max_iterations >= 0");
}
}  // namespace

std::vector<const GridWarp*> AdaptResult::warps() const {
  std::vector<const GridWarp*> w;
  if (coarse.n > 0) w.push_back(&coarse);
  if (fine.n > 0) w.push_back(&fine);
  return w;
}

const char* to_string(AdaptMode mode) {
  switch (mode) {
    case AdaptMode::None: return "none";
    case AdaptMode::Single: return "single";
    case AdaptMode::TwoStage: return "two-stage";
  }
  return "?";
}

AdaptMode parse_adapt_mode(const std::string& name) {
  if (name == "none") return AdaptMode::None;
  if (name == "single") return AdaptMode::Single;
  if (name == "two-stage" || name == "two_stage" || name == "twostage") return AdaptMode::TwoStage;
  throw InvalidInputError("unknown adapt mode '" + name + "' (expected none, single or two-stage)");
}

AdaptResult adapt_parameterization(const TriMesh& mesh, const Parameterization& current,
                                   const ImageRGBA8& texture, const TexelMap& current_map,
                                   const AdaptOptions& o) {
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
  rep.l2_before = measure_stretch(mesh, current).l2;
  if (o.mode == AdaptMode::None) {
    res.param = current;
    rep.l2_after = rep.l2_before;
    rep.damping = 0;
    rep.time_total = seconds_since(t_start);
    return res;
  }
  auto t0 = std::chrono::steady_clock::now();
  report_progress(o.progress, "importance", 0);
  res.importance = compute_importance(texture, &current_map, o.importance);
  size_t with_signal = 0;
  for (int t : current_map.inside)
    if (res.importance.data[t] > 1.0f / 512.0f) ++with_signal;
  rep.signal_fraction = current_map.inside.empty() ? 0.0 : double(with_signal) / current_map.inside.size();
  rep.time_importance = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  report_progress(o.progress, "stretch", 0);
  if (o.use_geometry_stretch) res.stretch = compute_stretch_map(mesh, current, current_map);
  rep.time_stretch_map = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  report_progress(o.progress, "ls2", 0);
  Ls2Options lo;
  lo.alpha = o.alpha;
  lo.beta = o.beta;
  lo.min_weight = o.min_weight;
  lo.geometry_scale = o.geometry_scale;
  res.ls2 = compute_ls2(res.importance, res.stretch, lo);
  rep.time_ls2 = seconds_since(t0);

  const int T = std::max(texture.width, texture.height);
  RelaxOptions ro;
  ro.ring = o.ring;
  ro.slide_boundary = o.slide_boundary;
  ro.epsilon = o.epsilon_texels / T;
  ro.max_iterations = o.max_iterations;
  ro.progress = o.progress;
  if (o.mode == AdaptMode::TwoStage) {
    t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "coarse", 0);
    res.coarse = GridWarp::uniform(o.coarse_grid);
    rep.coarse_iterations = relax_grid(res.coarse, pool_for_grid(res.ls2, o.coarse_grid, o.pool), ro).iterations;
    rep.time_coarse = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "fine", 0);
    // The fine stage works in the domain already warped by the coarse stage: its weight field is the
    // L_s² of the content now at each place (pulled back through the coarse warp).
    const ImageF pooled = pool_for_grid(res.ls2, o.fine_grid, o.pool);
    const ImageF field = pull_back_field(pooled, res.coarse, std::max(pooled.width, pooled.height));
    res.fine = GridWarp::uniform(o.fine_grid);
    RelaxOptions fo = ro;
    fo.max_iterations = o.fine_max_iterations;
    rep.fine_iterations = relax_grid(res.fine, field, fo).iterations;
    rep.time_fine = seconds_since(t0);
  } else {
    t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "fine", 0);
    res.fine = GridWarp::uniform(o.fine_grid);
    rep.fine_iterations = relax_grid(res.fine, pool_for_grid(res.ls2, o.fine_grid, o.pool), ro).iterations;
    rep.time_fine = seconds_since(t0);
  }

  t0 = std::chrono::steady_clock::now();
  report_progress(o.progress, "remap", 0);
  SafeRemapResult sr = safe_remap(current, res.warps(), o.remap);
  rep.remap_checks = sr.checks;
  rep.damping = sr.mean_damping;
  rep.global_damping = sr.damping;
  rep.locally_damped = sr.locally_damped;
  res.param = std::move(sr.param);
  rep.l2_after = measure_stretch(mesh, res.param).l2;
  if (o.geometry_safeguard && with_signal == 0 && !(rep.l2_after < rep.l2_before) && rep.damping > 0) {
    // No signal: the only goal is lower L2 stretch. Try half the warp, else keep the input.
    std::vector<GridWarp> half;
    for (const GridWarp* w : res.warps()) half.push_back(w->blended(0.5 * rep.damping));
    std::vector<const GridWarp*> ptrs;
    for (auto& w : half) ptrs.push_back(&w);
    SafeRemapResult h = safe_remap(current, ptrs, o.remap);
    rep.remap_checks += h.checks;
    const double l2h = measure_stretch(mesh, h.param).l2;
    if (l2h < rep.l2_before) {
      res.param = std::move(h.param);
      rep.damping = 0.5 * rep.damping * h.mean_damping;
      rep.l2_after = l2h;
    } else {
      res.param = current;
      rep.damping = 0;
      rep.l2_after = rep.l2_before;
      rep.accepted = false;
    }
  }
  rep.time_remap = seconds_since(t0);
  rep.time_total = seconds_since(t_start);
  return res;
}

}  // namespace adaptex
