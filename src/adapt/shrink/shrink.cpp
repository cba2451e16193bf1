/// \file shrink.cpp
/// shrink_textured_mesh(): islands -> error model -> budget -> repack -> texels -> the best candidate.
#include "adaptex/adapt/shrink.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "adaptex/adapt/adapt.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/paint/asset_eval.h"
#include "adaptex/paint/texel_map.h"
#include "shrink_internal.h"

namespace adaptex {

using namespace shrink_detail;

namespace {

void check_inputs(const TriMesh& mesh, const Parameterization& param, const std::vector<ShrinkMap>& maps,
                  const ShrinkOptions& opt) {
  if (maps.empty()) throw InvalidInputError("shrink: no texture map");
  for (const ShrinkMap& m : maps)
    if (m.image.empty()) throw InvalidInputError("shrink: map '" + m.slot + "' is empty");
  if (opt.size < 8 || opt.size > kMaxTextureSize)
    throw InvalidInputError("shrink: size must be in [8, " + std::to_string(kMaxTextureSize) + "]");
  if (param.uv_faces.size() != mesh.faces.size()) throw InvalidInputError("shrink: the layout does not match the mesh");
  for (const Face& t : param.uv_faces)
    for (int w : t)
      if (w < 0 || w >= param.num_wedges()) throw InvalidInputError("shrink: a UV index is out of range");
  for (const Vec2& p : param.uv)
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) throw InvalidInputError("shrink: a texture coordinate is not finite");
  if (!(opt.overlap_share >= 0) || !(opt.max_scale_ratio >= 1) || opt.gutter < 0 || opt.gutter > 16 ||
      opt.error_samples < 1000 || opt.eval_samples < 1000 || !(opt.max_face_growth >= 0) ||
      !(opt.island_warp_ratio >= 1) || !std::isfinite(opt.island_warp_ratio) ||
      !std::isfinite(opt.max_face_growth))
    throw InvalidInputError(
        "shrink: bad options (overlap_share >= 0, max_scale_ratio >= 1, island_warp_ratio >= 1, gutter in [0,16], "
        "samples >= 1000, max_face_growth >= 0)");
  const auto& names = {"",         "downsized", "artist",      "repacked",
                       "budget",   "island_warp", "warped", "warped_islands"};
  if (std::find(names.begin(), names.end(), opt.force_candidate) == names.end())
    throw InvalidInputError("shrink: unknown candidate '" + opt.force_candidate +
                            "' (downsized, artist, repacked, budget, island_warp, warped, warped_islands)");
}

/// A candidate layout with its first map.
struct Built {
  ShrinkCandidate info;
  Parameterization param;
  ImageRGBA8 first;
  double lambda = 0;  ///< Repacked: the common factor the packing reached (scales · λ).
  double fill_hint = 0;  ///< Repacked: the fill its packing started from.
};

/// Everything the candidates share.
struct Context {
  const TriMesh& mesh;
  const Parameterization& param;  // the input layout (the texels' source)
  const std::vector<ShrinkMap>& maps;
  const ShrinkOptions& opt;
  Parameterization layout;        // the input layout with every chart shifted into [0,1)² (packing)
  std::vector<int> face_island;
  int islands = 0;
  SampleSet samples;              // the measure's samples, the originals' colours at them

  /// PSNR of the first map on a quarter of the evaluation's samples (ranking the candidates).
  double rank_psnr(const Parameterization& p, const ImageRGBA8& img) const { return samples.psnr(0, p, img, 4); }
  /// The candidate of layout \p p with draft-fitted texels, ranked.
  Built fitted(const std::string& name, Parameterization p) const {
    Built b;
    b.info.name = name;
    b.param = std::move(p);
    b.first = fit_maps(mesh, param, maps, 1, b.param, opt.size, true)[0];
    b.info.psnr = rank_psnr(b.param, b.first);
    return b;
  }
};

/// The islands of \p layout (the shifted input layout, or a warp of it) packed at \p scales, fitted.
Built repacked(const Context& cx, const std::string& name, const std::vector<double>& scales, double fill_hint,
               const Parameterization& layout) {
  double fill = 0;
  const std::vector<IslandPlacement> pl = pack_islands(layout, cx.face_island, cx.islands, scales, cx.opt.size,
                                                       cx.opt.gutter, cx.opt.rotate, fill_hint, &fill);
  if (pl.empty()) {
    Built b;
    b.info.name = name;
    b.info.valid = false;
    return b;
  }
  Built b = cx.fitted(name, apply_placements(layout, cx.face_island, pl, cx.opt.size));
  b.lambda = pl[0].sigma / (cx.opt.size * scales[0]);
  b.fill_hint = fill_hint;
  b.info.fill = fill;
  return b;
}

/// The budgeted candidate: island scales from the error model for the area the uniform packing
/// reached (\p uniform), packed, then allocated again for the area that packing reached. \p curves
/// and \p chosen receive the error model and the candidate's scales.
Built budgeted(const Context& cx, const Built& uniform, const std::vector<double>& area, double* predicted_gain,
               ErrorCurves* curves_out, std::vector<double>* chosen_scales) {
  const ShrinkOptions& o = cx.opt;
  // The spacings the two allocations below can read: the uniform one's, times the packing's factor
  // (within the ratio either way), within max_scale_ratio.
  const double h_uniform = 1.0 / (o.size * uniform.lambda);
  const size_t stride = static_cast<size_t>(std::max(1LL, o.eval_samples / o.error_samples));
  ErrorCurves& curves = *curves_out;
  curves = island_error_curves(cx.samples, stride, cx.param, cx.face_island, cx.islands, cx.maps,
                                                 h_uniform / (2 * o.max_scale_ratio), h_uniform * 2 * o.max_scale_ratio);
  double budget = 0;
  for (double a : area) budget += a * uniform.lambda * uniform.lambda;
  report_progress(o.progress, "pack", 0.5);
  std::vector<double> scales = allocate_island_scales(curves, area, budget, o.size, o.max_scale_ratio);
  Built bud = repacked(cx, "budget", scales, uniform.info.fill, cx.layout);
  // The error model's gain of the chosen budget layout over the uniform repack.
  const auto finish = [&](const std::vector<double>& chosen) {
    double e_uni = 0, e_bud = 0;
    for (int i = 0; i < cx.islands; ++i) {
      e_uni += curves.weight[i] * island_error(curves, i, 1.0 / (o.size * uniform.lambda));
      e_bud += curves.weight[i] * island_error(curves, i, 1.0 / (o.size * chosen[i] * bud.lambda));
    }
    if (e_uni > 0 && e_bud > 0) *predicted_gain = 10 * std::log10(e_uni / e_bud);
    *chosen_scales = chosen;
    return std::move(bud);
  };
  if (!bud.info.valid) return bud;
  // Allocated again for the area the packing reached, unless it reached about the area it was given.
  if (std::abs(bud.lambda - 1.0) < 0.02) return finish(scales);
  std::vector<double> scales2 = allocate_island_scales(curves, area, budget * bud.lambda * bud.lambda, o.size,
                                                       o.max_scale_ratio);
  Built bud2 = repacked(cx, "budget", scales2, bud.info.fill, cx.layout);
  if (bud2.info.valid && bud2.info.psnr > bud.info.psnr) {
    bud = std::move(bud2);
    scales = scales2;
  }
  return finish(scales);
}

/// The budgeted islands, each warped inside itself towards its detail (warp_islands), packed at the
/// budget's scales; the best (ranked) of the full-strength warp, a gentle one (density ratio
/// kGentleWarpRatio: on smooth paint a strong squeeze costs more than the edge model predicts) and,
/// with island_warp_measured, the full-strength warp whose cells' areas follow their own measured error
/// curves. Valid only if no face flips.
Built island_warped(const Context& cx, const Built& budget, const ErrorCurves& curves,
                    const std::vector<double>& scales) {
  constexpr double kGentleWarpRatio = 1.5;
  std::vector<double> texels(scales.size()), blend;
  for (size_t i = 0; i < scales.size(); ++i) texels[i] = cx.opt.size * scales[i] * budget.lambda;
  struct Rung {
    double ratio;
    bool measured;
  };
  const double full = cx.opt.island_warp_ratio;
  std::vector<Rung> rungs{{full, false}};
  if (full > kGentleWarpRatio) rungs.push_back({kGentleWarpRatio, false});
  if (cx.opt.island_warp_measured) {
    rungs.push_back({full, true});
    if (full > kGentleWarpRatio) rungs.push_back({kGentleWarpRatio, true});
  }
  Built best;
  best.info.name = "island_warp";
  best.info.valid = false;
  for (const Rung& r : rungs) {
    const Parameterization layout =
        warp_islands(cx.samples, curves, cx.layout, cx.face_island, cx.islands, texels, {}, r.ratio, r.measured, &blend);
    Built b = repacked(cx, "island_warp", scales, budget.fill_hint, layout);
    if (b.info.valid && layout_stats(cx.mesh, cx.param, b.param, cx.param.face_chart, cx.opt.size).flipped > 0)
      b.info.valid = false;
    if (b.info.valid && (!best.info.valid || b.info.psnr > best.info.psnr)) best = std::move(b);
  }
  return best;
}

/// Output texels per input UV unit of every face of \p p (size² square): sqrt of its area against the
/// input's; faces without input area take the size.
std::vector<double> face_texels(const Context& cx, const Parameterization& p) {
  std::vector<double> t(p.uv_faces.size(), cx.opt.size);
  const auto area = [](const Parameterization& q, const Face& f) {
    return std::abs((q.uv[f[1]] - q.uv[f[0]]).x() * (q.uv[f[2]] - q.uv[f[0]]).y() -
                    (q.uv[f[1]] - q.uv[f[0]]).y() * (q.uv[f[2]] - q.uv[f[0]]).x());
  };
  const double tiny = 1e-6 / (static_cast<double>(cx.opt.size) * cx.opt.size);  // a degenerate face
  for (size_t f = 0; f < t.size(); ++f) {
    const double a_in = area(cx.param, cx.param.uv_faces[f]), a_out = area(p, p.uv_faces[f]);
    if (a_in > tiny && a_out > tiny) t[f] = cx.opt.size * std::sqrt(a_out / a_in);
  }
  return t;
}

/// \p start (a layout of the output square, here the whole-layout warp) with every island warped in
/// place, inside its own bounding box, towards its detail at its faces' own texel spacing, gently
/// (density ratio kGentleWarpRatio: \p start is already adapted), halved towards \p start until no face
/// flips and no more texels are covered by two islands than in \p start (else not a candidate).
Built warped_in_place(const Context& cx, const std::string& name, const Parameterization& start,
                      const ErrorCurves& curves) {
  constexpr double kGentleWarpRatio = 1.5;
  constexpr int kHalvings = 3;
  const std::vector<double> texels(cx.islands, cx.opt.size), per_face = face_texels(cx, start);
  const long shared = shared_island_texels(start, cx.face_island, cx.islands, cx.opt.size);
  std::vector<double> blend;
  const Parameterization full = warp_islands(cx.samples, curves, start, cx.face_island, cx.islands, texels, per_face,
                                             std::min(kGentleWarpRatio, cx.opt.island_warp_ratio), false, &blend);
  Parameterization p = full;
  for (int k = 0; k <= kHalvings; ++k) {
    const double t = std::ldexp(1.0, -k);
    for (size_t w = 0; w < p.uv.size(); ++w) p.uv[w] = start.uv[w] + t * (full.uv[w] - start.uv[w]);
    if (layout_stats(cx.mesh, cx.param, p, cx.param.face_chart, cx.opt.size).flipped == 0 &&
        shared_island_texels(p, cx.face_island, cx.islands, cx.opt.size) <= shared)
      return cx.fitted(name, std::move(p));
  }
  Built none;
  none.info.name = name;
  none.info.valid = false;
  return none;
}

/// The density-flow warp of the whole layout (adapt.h, no refinement: the input's faces), for layouts
/// whose charts share no texels (it moves charts apart). Valid only if no face flips or degenerates.
Built warped(const Context& cx, const ShrinkLayoutStats& input_at_size) {
  Built b;
  b.info.name = "warped";
  b.info.valid = false;
  const ImageRGBA8& tex = cx.maps[0].image;
  // The flow warps the unit square: UVs just outside it are clamped onto it (a flip shows below).
  Parameterization start = cx.param;
  for (Vec2& p : start.uv) p = p.cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1));
  AdaptOptions ao;
  ao.refine.enabled = false;
  ao.progress = cx.opt.progress;
  const AdaptResult r =
      adapt_parameterization(cx.mesh, start, tex, build_texel_map(cx.mesh, start, tex.width, tex.height), ao);
  if (r.refined_mesh || !r.report.accepted) return b;
  const ShrinkLayoutStats st = layout_stats(cx.mesh, cx.param, r.param, cx.param.face_chart, cx.opt.size);
  if (st.flipped > 0 || st.degenerate > input_at_size.degenerate) return b;
  b = cx.fitted("warped", r.param);
  return b;
}

}  // namespace

MapKind map_kind_of_slot(const std::string& slot) {
  if (slot == "normal") return MapKind::Normal;
  for (const char* data : {"metallic_roughness", "roughness", "metallic", "occlusion", "bump", "specular"})
    if (slot == data) return MapKind::Data;
  return MapKind::Color;
}

ShrinkResult shrink_textured_mesh(const TriMesh& mesh, const Parameterization& input,
                                  const std::vector<ShrinkMap>& maps, const ShrinkOptions& options) {
  const auto t_start = std::chrono::steady_clock::now();
  check_inputs(mesh, input, maps, options);
  const int N = options.size;
  const int R = std::clamp(maps[0].image.width, 64, 2048);
  report_progress(options.progress, "islands", 0);
  const UvIslands isl = find_uv_islands(input, R, options.overlap_share);
  // Charts in another UV tile move by their integer offset into [0,1]²: the texels a repeating lookup
  // read, now read by the clamped output too. The input itself when no chart moves.
  const bool moved = std::any_of(isl.chart_shift.begin(), isl.chart_shift.end(),
                                 [](const Vec2& s) { return s != Vec2::Zero(); });
  Parameterization unit;
  if (moved) {
    unit = input;
    unit.uv = shifted_layout(input, isl).uv;
  }
  const Parameterization& param = moved ? unit : input;
  Context cx{mesh,   param, maps, options, shifted_layout(input, isl), {}, isl.num_islands,
             SampleSet(mesh, param, maps, options.eval_samples, options.seed)};
  cx.face_island.resize(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) cx.face_island[f] = isl.chart_island[isl.face_chart[f]];
  ShrinkResult res;
  res.charts = isl.num_charts;
  res.islands = isl.num_islands;
  res.faces_before = res.faces_after = mesh.num_faces();
  res.before = layout_stats(mesh, param, param, isl.face_chart, R);

  report_progress(options.progress, "evaluate", 0);
  std::vector<Built> cands;
  {  // The user's baseline: the artist's UVs, every map box-downsized.
    Built b;
    b.info.name = "downsized";
    b.param = param;
    b.first = box_downsize(maps[0].image, N, N);
    b.info.psnr = cx.rank_psnr(param, b.first);
    cands.push_back(std::move(b));
  }
  cands.push_back(cx.fitted("artist", param));
  report_progress(options.progress, "pack", 0);
  ErrorCurves curves;  // the error model, when a budget was made
  if (!isl.tiling) {
    const std::vector<double> area = island_areas(cx.layout, cx.face_island, cx.islands, R);
    Built uni = repacked(cx, "repacked", std::vector<double>(cx.islands, 1.0), 0.75, cx.layout);
    bool uni_added = false;
    if (options.budget && uni.info.valid) {
      report_progress(options.progress, "error model", 0);
      std::vector<double> scales;
      cands.push_back(budgeted(cx, uni, area, &res.predicted_gain_db, &curves, &scales));
      if (options.island_warp && cands.back().info.valid) {  // warp the better of the two rigid layouts
        report_progress(options.progress, "warp", 0);
        const bool from_uniform = uni.info.psnr > cands.back().info.psnr;
        if (from_uniform) scales.assign(cx.islands, 1.0);
        Built iw = island_warped(cx, from_uniform ? uni : cands.back(), curves, scales);
        cands.push_back(std::move(uni));
        uni_added = true;
        cands.push_back(std::move(iw));  // after the rigid layouts: a warp that changes nothing ties, and loses
      }
    }
    if (!uni_added) cands.push_back(std::move(uni));
  }
  if (options.warp && isl.num_islands == isl.num_charts) {
    report_progress(options.progress, "warp", 0);
    cands.push_back(warped(cx, layout_stats(mesh, param, param, isl.face_chart, N)));
  }
  if (options.island_warp && !curves.spacing.empty() && cands.back().info.name == "warped" && cands.back().info.valid)
    cands.push_back(warped_in_place(cx, "warped_islands", cands.back().param, curves));
  // The best valid candidate by measured PSNR (downsizing is always valid: the floor).
  size_t best = 0;
  for (size_t c = 0; c < cands.size(); ++c) {
    res.candidates.push_back(cands[c].info);
    if (cands[c].info.valid && cands[c].info.psnr > cands[best].info.psnr) best = c;
  }
  for (size_t c = 0; c < cands.size(); ++c)
    if (cands[c].info.valid && cands[c].info.name == options.force_candidate) best = c;
  // The chosen layout's maps, fitted in full, measured against downsizing on every sample.
  report_progress(options.progress, "texels", 0);
  const std::vector<ImageRGBA8> downsized = [&] {
    std::vector<ImageRGBA8> d;
    for (const ShrinkMap& m : maps) d.push_back(box_downsize(m.image, N, N));
    return d;
  }();
  auto measure = [&](size_t m, const Parameterization& p, const ImageRGBA8& img) { return cx.samples.psnr(m, p, img); };
  for (size_t m = 0; m < maps.size(); ++m) res.map_psnr_downsized.push_back(measure(m, param, downsized[m]));
  res.psnr_downsized = res.map_psnr_downsized[0];
  res.chosen = cands[best].info.name;
  res.param = cands[best].param;
  res.lifted_faces = lift_degenerate_faces(res.param, param, N);  // before the texels are fitted to it
  if (res.chosen != "downsized") {
    res.maps = fit_maps(mesh, param, maps, maps.size(), res.param, N, false, options.progress);
    report_progress(options.progress, "evaluate", 0.5);
    for (size_t m = 0; m < maps.size(); ++m) res.map_psnr.push_back(measure(m, res.param, res.maps[m]));
    if (res.map_psnr[0] < res.psnr_downsized && options.force_candidate.empty()) {  // the floor
      res.chosen = "downsized";
      res.param = param;
      res.lifted_faces = lift_degenerate_faces(res.param, param, N);
    }
  }
  if (res.chosen == "downsized") {
    res.maps = downsized;
    res.map_psnr = res.map_psnr_downsized;
  }
  res.psnr = res.map_psnr[0];
  res.after = layout_stats(mesh, param, res.param, isl.face_chart, N);
  res.time_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return res;
}

}  // namespace adaptex
