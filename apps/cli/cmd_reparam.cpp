// `adaptex reparam`: re-parameterize an existing textured mesh (OBJ with UVs + its texture) by the
// signal of the texture (thesis §3.5–§3.8), in resample mode (§3.7.3): what a user with an old asset
// runs. Writes NAME.obj/.mtl/.png/.glb and report.json into OUTDIR, all or nothing.
#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/session.h"
#include "adaptex/adapt/shrink.h"
#include "adaptex/adapt/texture_update.h"
#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/export.h"
#include "adaptex/paint/texel_map.h"
#include "adaptex/param/stretch.h"
#include "cli_common.h"
#include "session_options.h"
#include "shrink_print.h"

namespace adaptex::cli {

namespace {

/// `--adapt` value of the atlas-preserving shrink (adapt/shrink.h), the default.
constexpr const char* kShrinkMode = "shrink";

struct ReparamArgs {
  std::string mesh, texture, outdir, name, grid, mode = kShrinkMode, debug_maps;
  std::string candidate;  // --candidate (shrink)
  bool no_refine = false;
  double max_face_growth = ShrinkOptions{}.max_face_growth;
  bool max_face_growth_given = false;  // --max-face-growth was on the command line
  bool grid_given = false;  // --grid was on the command line
  double alpha = AdaptOptions{}.thesis.alpha, beta = AdaptOptions{}.thesis.beta;
  int size = 0, padding = 4;
};

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// The re-parameterization settings of \p a, checked before any file is read. \throw InvalidInputError
AdaptOptions reparam_options(const ReparamArgs& a) {
  AdaptOptions opt;
  try {
    // The shrink takes none of these settings, but they are checked all the same.
    opt.mode = a.mode == kShrinkMode ? AdaptMode::DensityFlow : parse_adapt_mode(a.mode);
  } catch (const InvalidInputError&) {
    opt.mode = AdaptMode::None;
  }
  if (opt.mode == AdaptMode::None)
    throw InvalidInputError("--adapt must be shrink, " + or_list(adapt_method_names(false)) + " (got '" + a.mode + "')");
  opt.refine.enabled = !a.no_refine;
  // density-flow's refinement keeps its own face budget unless the user bounds the growth.
  if (a.max_face_growth_given) opt.refine.max_face_factor = 1.0 + a.max_face_growth;
  opt.thesis.alpha = a.alpha;
  opt.thesis.beta = a.beta;
  if (a.grid_given) set_grid(opt, parse_grid(a.grid));  // --grid "" is an error, not the default
  const ThesisOptions& t = opt.thesis;
  if (!(t.alpha >= 0) || !(t.beta >= 0) || !std::isfinite(t.alpha) || !std::isfinite(t.beta))
    throw InvalidInputError("--alpha and --beta must be finite numbers >= 0");
  check_export_name(a.name.empty() ? "mesh" : a.name);
  return opt;
}

/// report.json of `adaptex reparam` (without the total time).
nlohmann::ordered_json reparam_report(const ReparamArgs& a, const TexturedMesh& tm, const TriMesh& out_mesh,
                                      const AdaptResult& res, int W, int H, double time_old_map,
                                      const StretchStats& st) {
  nlohmann::ordered_json j;
  j["input"] = a.mesh;
  j["texture"] = a.texture;
  j["faces"] = tm.mesh.num_faces();
  j["faces_out"] = out_mesh.num_faces();
  j["charts"] = tm.param.num_charts;
  j["size"] = {W, H};
  j["update"] = "resample";
  nlohmann::json rj = res.report;
  rj["time_ms"]["old_texel_map"] = 1e3 * time_old_map;
  j["adapt"] = rj;
  const StretchStats st0 = measure_stretch(tm.mesh, tm.param);
  j["flipped_before"] = st0.flipped;  // mirrored charts of the input keep their orientation
  j["flipped"] = st.flipped;
  j["degenerate"] = st.degenerate;
  return j;
}

/// The default: the artist's charts kept, repacked by the texture's error model (adapt/shrink.h).
void run_reparam_shrink(const ReparamArgs& a, const Context& ctx) {
  const auto t_start = Clock::now();
  // The shrink never needs a manifold mesh: non-manifold edges are split, not refused.
  ReadOptions ro;
  ro.repair = true;
  const TexturedMesh tm = read_textured_obj(a.mesh, ro);
  std::vector<ShrinkMap> maps(1);
  maps[0].slot = "base_color";
  maps[0].image = read_image(a.texture);
  ctx.info("reparam: " + a.mesh + ": " + std::to_string(tm.mesh.num_faces()) + " faces, texture " +
           std::to_string(maps[0].image.width) + "x" + std::to_string(maps[0].image.height));
  ShrinkOptions opt;
  opt.size = a.size > 0 ? a.size : std::max(maps[0].image.width, maps[0].image.height);
  opt.progress = shrink_progress(ctx, "reparam");
  opt.force_candidate = a.candidate;
  opt.max_face_growth = a.no_refine ? 0.0 : a.max_face_growth;
  const ShrinkResult res = shrink_textured_mesh(tm.mesh, tm.param, maps, opt);
  AtomicOutput out;
  const std::string name = a.name.empty() ? sanitize_export_name(std::filesystem::path(a.mesh).stem().string()) : a.name;
  ExportOptions eo;
  eo.mtl_clamp = true;  // the layout ends at the square's border: no renderer may wrap
  export_textured_mesh(out, a.outdir, name, tm.mesh, res.param, res.maps[0], eo);
  if (!a.debug_maps.empty()) {  // the layouts before and after, drawn over their textures
    write_png(out.add(std::filesystem::path(a.debug_maps) / (name + "_layout_before.png")),
              draw_uv_layout(tm.param, &maps[0].image, 1024));
    write_png(out.add(std::filesystem::path(a.debug_maps) / (name + "_layout_after.png")),
              draw_uv_layout(res.param, &res.maps[0], 1024));
  }
  nlohmann::ordered_json j;
  j["input"] = a.mesh;
  j["texture"] = a.texture;
  j["faces"] = tm.mesh.num_faces();
  j["faces_out"] = tm.mesh.num_faces();
  j["size"] = {opt.size, opt.size};
  j["update"] = "fit";
  j["shrink"] = shrink_report_json(res, {"base_color"});
  j["psnr"] = res.psnr;
  j["psnr_downsized"] = res.psnr_downsized;
  j["flipped"] = res.after.flipped;
  j["degenerate"] = res.after.degenerate;
  j["time_total_ms"] = 1e3 * since(t_start);
  write_text(out, std::filesystem::path(a.outdir) / "report.json", j.dump(2) + "\n");
  out.commit();
  print_shrink_summary(res, {"base_color"});
  ctx.info("reparam: shrink (" + res.chosen + "), wrote " + (std::filesystem::path(a.outdir) / name).string() +
           ".{obj,mtl,png,glb} and report.json");
}

void run_reparam(const ReparamArgs& a, const Context& ctx) {
  const auto t_start = Clock::now();
  const AdaptOptions opt = reparam_options(a);
  if (a.mode == kShrinkMode) return run_reparam_shrink(a, ctx);

  const TexturedMesh tm = read_textured_obj(a.mesh);
  const ImageRGBA8 tex = read_image(a.texture);
  ctx.info("reparam: " + a.mesh + ": " + std::to_string(tm.mesh.num_faces()) + " faces, texture " +
           std::to_string(tex.width) + "x" + std::to_string(tex.height));
  auto t0 = Clock::now();
  const TexelMap old_map = build_texel_map(tm.mesh, tm.param, tex.width, tex.height);
  const double time_old_map = since(t0);
  AdaptResult res = adapt_parameterization(tm.mesh, tm.param, tex, old_map, opt);
  const int W = a.size > 0 ? a.size : tex.width, H = a.size > 0 ? a.size : tex.height;
  t0 = Clock::now();
  // With refinement the layout belongs to the refined mesh (same surface); its old-domain layout
  // tells where each refined face's texels were in the input texture.
  const TriMesh& out_mesh = res.refined_mesh ? *res.refined_mesh : tm.mesh;
  const Parameterization& old_layout = res.refined_mesh ? *res.refined_layout : tm.param;
  const TexelMap new_map = build_texel_map(out_mesh, res.param, W, H);
  res.report.time_texel_map = since(t0);
  t0 = Clock::now();
  const ImageRGBA8 new_tex = resample_texture(old_layout, tex, new_map, a.padding);
  res.report.time_texture_update = since(t0);
  const StretchStats st = measure_stretch(out_mesh, res.param);

  AtomicOutput out;
  const std::string name = a.name.empty() ? sanitize_export_name(std::filesystem::path(a.mesh).stem().string()) : a.name;
  export_textured_mesh(out, a.outdir, name, out_mesh, res.param, new_tex);
  if (!a.debug_maps.empty()) {
    // Written inside OUTDIR's commit when it is below OUTDIR; otherwise directly.
    write_debug_maps(a.debug_maps, name, res);
  }
  nlohmann::ordered_json j = reparam_report(a, tm, out_mesh, res, W, H, time_old_map, st);
  j["time_total_ms"] = 1e3 * since(t_start);
  write_text(out, std::filesystem::path(a.outdir) / "report.json", j.dump(2) + "\n");
  out.commit();
  std::ostringstream line;
  line.precision(4);
  line << "reparam: " << to_string(opt.mode) << ", L2 stretch " << res.report.l2_before << " -> "
       << res.report.l2_after << ", damping " << res.report.damping << ", " << st.flipped << " flipped, "
       << 1e3 * res.report.time_total << " ms; wrote " << (std::filesystem::path(a.outdir) / name).string()
       << ".{obj,mtl,png,glb} and report.json";
  ctx.info(line.str());
}

}  // namespace

void add_reparam_command(CLI::App& app, Context& ctx) {
  auto a = std::make_shared<ReparamArgs>();
  auto* sub = app.add_subcommand(
      "reparam", "Re-parameterize a textured mesh by its texture's signal (thesis §3.5-3.8, resample mode)");
  sub->add_option("mesh", a->mesh, "OBJ with texture coordinates (vt, f v/vt)")->required()->check(CLI::ExistingFile);
  sub->add_option("texture", a->texture, "Its texture image (PNG, ...)")->required()->check(CLI::ExistingFile);
  sub->add_option("-o,--output", a->outdir, "Output directory")->required();
  sub->add_option("--adapt", a->mode,
                  "shrink (keep the artist's charts, repack them by the texture's detail) | " +
                      adapt_methods_help(false))
      ->capture_default_str();
  sub->add_flag("--no-refine", a->no_refine,
                "Keep the input's vertices (density-flow refines triangles too large for the warp)");
  sub->add_option("--max-face-growth", a->max_face_growth,
                  "Largest share of faces refinement may add (0.1 = 10 %; shrink adds none; density-flow: "
                  "default its own budget)")
      ->check(cli::kFiniteNonNegative)
      ->each([a](const std::string&) { a->max_face_growth_given = true; });
  sub->add_option("--grid", a->grid, "Grid cells per side: FINE or COARSE,FINE (default 16,256)")
      ->each([a](const std::string&) { a->grid_given = true; });
  sub->add_option("--alpha", a->alpha, "L_s^2 weight of the geometry stretch where there is signal")->capture_default_str();
  sub->add_option("--beta", a->beta, "L_s^2 weight of the signal stretch E_h")->capture_default_str();
  sub->add_option("--size", a->size, "Output texture width = height (default: the input texture's size)")
      ->check(CLI::Range(1, adaptex::kMaxTextureSize));
  sub->add_option("--padding", a->padding, "Seam padding in texels")->check(CLI::Range(0, 64))->capture_default_str();
  sub->add_option("--candidate", a->candidate,
                  "shrink: output this candidate (downsized, artist, repacked, budget, island_warp, warped, warped_islands) instead of the best");
  sub->add_option("--name", a->name, "Base name of the output files (default: the mesh file's stem)");
  sub->add_option("--debug-maps", a->debug_maps,
                  "Also write importance / stretch / L_s^2 / grid PNGs here (shrink: the layouts before and after)");
  sub->callback([a, &ctx] { run_reparam(*a, ctx); });
}

}  // namespace adaptex::cli
