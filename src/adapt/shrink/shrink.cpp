/// \file shrink.cpp
/// shrink_textured_mesh(): islands -> error model -> budget -> repack -> texels -> the best candidate.
#include "adaptex/adapt/shrink.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
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
      opt.error_samples < 1000 || opt.eval_samples < 1000)
    throw InvalidInputError("shrink: bad options (overlap_share >= 0, max_scale_ratio >= 1, gutter in [0,16], samples >= 1000)");
}

bool inside_unit_square(const Parameterization& p) {
  for (const Vec2& q : p.uv)
    if (q.x() < 0 || q.x() > 1 || q.y() < 0 || q.y() > 1) return false;
  return true;
}

/// A candidate layout with its first map.
struct Built {
  ShrinkCandidate info;
  Parameterization param;
  ImageRGBA8 first;
  double lambda = 0;  ///< Repacked: the common factor the packing reached (scales · λ).
};

/// Everything the candidates share.
struct Context {
  const TriMesh& mesh;
  const std::vector<ShrinkMap>& maps;
  const ShrinkOptions& opt;
  Parameterization layout;        // shifted input layout
  std::vector<int> face_island;
  int islands = 0;
  EvalSet eval;
};

Built repacked(const Context& cx, const std::string& name, const std::vector<double>& scales) {
  Built b;
  b.info.name = name;
  double fill = 0;
  const std::vector<IslandPlacement> pl = pack_islands(cx.layout, cx.face_island, cx.islands, scales, cx.opt.size,
                                                       cx.opt.gutter, cx.opt.rotate, &fill);
  if (pl.empty()) {
    b.info.valid = false;
    return b;
  }
  b.lambda = pl[0].sigma / (cx.opt.size * scales[0]);
  b.param = apply_placements(cx.layout, cx.face_island, pl, cx.opt.size);
  b.first = transfer_texels(cx.mesh, cx.layout, cx.maps[0].image, b.param, cx.opt.size);
  b.info.psnr = eval_psnr(cx.eval, b.param, b.first);
  b.info.fill = fill;
  return b;
}

}  // namespace

ShrinkResult shrink_textured_mesh(const TriMesh& mesh, const Parameterization& param,
                                  const std::vector<ShrinkMap>& maps, const ShrinkOptions& options) {
  const auto t_start = std::chrono::steady_clock::now();
  check_inputs(mesh, param, maps, options);
  const int N = options.size;
  const int R = std::clamp(maps[0].image.width, 64, 2048);
  report_progress(options.progress, "islands", 0);
  const UvIslands isl = find_uv_islands(param, R, options.overlap_share);
  Context cx{mesh, maps, options, shifted_layout(param, isl), {}, isl.num_islands, {}};
  cx.face_island.resize(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) cx.face_island[f] = isl.chart_island[isl.face_chart[f]];
  ShrinkResult res;
  res.charts = isl.num_charts;
  res.islands = isl.num_islands;
  res.faces_before = res.faces_after = mesh.num_faces();
  res.before = layout_stats(param, param, isl.face_chart, R);
  report_progress(options.progress, "evaluate", 0);
  cx.eval = make_eval_set(mesh, cx.layout, maps[0].image, options.eval_samples, options.seed);

  std::vector<Built> cands;
  {  // The user's baseline: the artist's UVs, every map box-downsized.
    Built b;
    b.info.name = "downsized";
    b.param = param;
    b.first = box_resize(maps[0].image, N, N);
    b.info.psnr = eval_psnr(cx.eval, param, b.first);
    b.info.valid = inside_unit_square(param);
    res.psnr_downsized = b.info.psnr;
    cands.push_back(std::move(b));
  }
  if (inside_unit_square(cx.layout)) {
    Built b;
    b.info.name = "artist";
    b.param = cx.layout;
    b.first = transfer_texels(mesh, cx.layout, maps[0].image, b.param, N);
    b.info.psnr = eval_psnr(cx.eval, b.param, b.first);
    cands.push_back(std::move(b));
  }
  report_progress(options.progress, "pack", 0);
  if (!isl.tiling) {
    const std::vector<double> area = island_areas(cx.layout, cx.face_island, cx.islands, R);
    Built uni = repacked(cx, "repacked", std::vector<double>(cx.islands, 1.0));
    if (options.budget && uni.info.valid) {
      report_progress(options.progress, "error model", 0);
      const ErrorCurves curves = island_error_curves(mesh, cx.layout, cx.face_island, cx.islands, maps,
                                                     options.error_samples, options.seed + 1);
      const double lambda = uni.lambda;
      double budget = 0;
      for (double a : area) budget += a * lambda * lambda;
      report_progress(options.progress, "pack", 0.5);
      std::vector<double> scales = allocate_island_scales(curves, area, budget, N, options.max_scale_ratio);
      if (std::getenv("SHRINK_DEBUG"))
        for (int i = 0; i < cx.islands; ++i) {
          std::fprintf(stderr, "island %d w %.3f area %.4f scale %.3f lambda %.3f:", i, curves.weight[i], area[i], scales[i], lambda);
          for (double e : curves.error[i]) std::fprintf(stderr, " %.2g", e);
          std::fprintf(stderr, "\n");
        }
      Built bud = repacked(cx, "budget", scales);
      if (bud.info.valid) {
        // Second round: the budget the packing actually reached.
        const double f = bud.lambda;
        std::vector<double> scales2 = allocate_island_scales(curves, area, budget * f * f, N, options.max_scale_ratio);
        Built bud2 = repacked(cx, "budget", scales2);
        if (bud2.info.valid && bud2.info.psnr > bud.info.psnr) {
          bud = std::move(bud2);
          scales = scales2;
        }
        double e_uni = 0, e_bud = 0;
        const double fb = bud.lambda;
        for (int i = 0; i < cx.islands; ++i) {
          e_uni += curves.weight[i] * island_error(curves, i, 1.0 / (N * lambda));
          e_bud += curves.weight[i] * island_error(curves, i, 1.0 / (N * scales[i] * fb));
        }
        if (e_uni > 0 && e_bud > 0) res.predicted_gain_db = 10 * std::log10(e_uni / e_bud);
      }
      cands.push_back(std::move(bud));
    }
    cands.push_back(std::move(uni));
  }
  // The best valid candidate by measured PSNR.
  size_t best = cands.size();
  for (size_t c = 0; c < cands.size(); ++c) {
    res.candidates.push_back(cands[c].info);
    if (cands[c].info.valid && (best == cands.size() || cands[c].info.psnr > cands[best].info.psnr)) best = c;
  }
  if (best == cands.size()) best = 0;  // nothing valid (wrapping UVs that could not be repacked): downsizing
  for (size_t c = 0; c < cands.size(); ++c)
    if (cands[c].info.valid && cands[c].info.name == options.force_candidate) best = c;
  Built& chosen = cands[best];
  res.chosen = chosen.info.name;
  res.psnr = chosen.info.psnr;
  res.param = chosen.param;
  report_progress(options.progress, "texels", 0);
  for (size_t m = 0; m < maps.size(); ++m) {
    if (m == 0) {
      res.maps.push_back(chosen.first);
    } else if (res.chosen == "downsized") {
      res.maps.push_back(box_resize(maps[m].image, N, N));
    } else {
      res.maps.push_back(transfer_texels(mesh, cx.layout, maps[m].image, res.param, N));
    }
    report_progress(options.progress, "texels", static_cast<double>(m + 1) / maps.size());
  }
  for (size_t m = 0; m < maps.size(); ++m) {
    const EvalSet ev = m == 0 ? EvalSet{} : make_eval_set(mesh, cx.layout, maps[m].image, options.eval_samples, options.seed);
    const EvalSet& e = m == 0 ? cx.eval : ev;
    res.map_psnr.push_back(eval_psnr(e, res.param, res.maps[m]));
    res.map_psnr_downsized.push_back(eval_psnr(e, param, box_resize(maps[m].image, N, N)));
  }
  res.after = layout_stats(param, res.param, isl.face_chart, N);
  res.time_total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return res;
}

}  // namespace adaptex
