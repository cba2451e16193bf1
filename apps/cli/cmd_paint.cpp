// `adaptex paint MESH --strokes S.json [--size N] [--adapt none] -o OUTDIR`: unwrap, paint the stroke
// file exactly into an N x N texture, export OBJ/MTL/PNG/GLB and report.json (docs/export.md; the
// --adapt family of flags: docs/adaptive.md). All outputs are committed together or not at all.
#include <cmath>
#include <memory>
#include <sstream>

#include "adaptex/core/errors.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/adapt/material_adapt.h"
#include "adaptex/paint/export.h"
#include "adaptex/paint/material_paint.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/strokes.h"
#include "cli_common.h"
#include "paint_common.h"
#include "session_options.h"

namespace adaptex::cli {

namespace {

struct PaintCommand {
  std::filesystem::path mesh, strokes, outdir;
  std::string name;
  bool repair = false;
  bool no_refine = false;
  PaintRunOptions run;
  std::string grid;  // raw --grid text
  double alpha = std::nan(""), beta = std::nan("");
  double min_gain = std::nan("");
  bool grid_given = false, alpha_given = false, beta_given = false;  // the option was on the command line
  bool min_gain_given = false;
  bool layers = false;  // --layers: every layer of a version 2 file as PNGs besides the material
};

/// Checks every option before any work is done (so a bad option never costs an unwrap).
void validate(PaintCommand& c, const Context& ctx) {
  AdaptSettings& a = c.run.adapt;
  a.refine = !c.no_refine;
  if (c.grid_given) a.grid = parse_grid(c.grid);  // --grid "" is an error, not the default
  if (c.alpha_given) {  // --alpha nan is an error, not the default
    if (!std::isfinite(c.alpha) || c.alpha < 0) throw InvalidInputError("--alpha must be a finite number >= 0");
    a.alpha = c.alpha;
  }
  if (c.beta_given) {
    if (!std::isfinite(c.beta) || c.beta < 0) throw InvalidInputError("--beta must be a finite number >= 0");
    a.beta = c.beta;
  }
  if (c.min_gain_given) {  // --min-gain nan is an error, not the default
    if (!std::isfinite(c.min_gain) || c.min_gain < 0)
      throw InvalidInputError("--min-gain must be a finite number of dB >= 0");
    a.min_gain = c.min_gain;
  }
  const AdaptMode mode = parse_adapt_mode(a.mode);
  if (mode == AdaptMode::TwoStage && a.grid.size() == 1)
    throw InvalidInputError("--grid: two-stage needs two sizes (coarse,fine), e.g. 16,256");
  if (mode == AdaptMode::Single && a.grid.size() == 2)
    throw InvalidInputError("--grid: single-stage needs one size, e.g. 256");
  if (mode == AdaptMode::None && (!a.grid.empty() || a.alpha || a.beta || !a.debug_maps.empty()))
    ctx.warn("--grid/--alpha/--beta/--debug-maps have no effect with --adapt none");
  if (mode == AdaptMode::DensityFlow && !a.grid.empty()) ctx.warn("--grid has no effect with --adapt density-flow");
  if (c.min_gain_given && (parse_reparam_schedule(a.reparam) != ReparamSchedule::EachStroke ||
                           mode != AdaptMode::DensityFlow || parse_texture_update(a.update) != TextureUpdate::Replay))
    ctx.warn("--min-gain has an effect only with --reparam each-stroke, --adapt density-flow and --update replay");
  // Let the session validate the combination now, before any work is done.
  (void)make_session_options(c.run.size, c.run.padding, a.mode, a.grid, a.alpha.value_or(-1.0),
                             a.beta.value_or(-1.0), a.reparam, a.update, a.debug_maps);
  if (c.name.empty())
    c.name = sanitize_export_name(c.mesh.stem().string());
  else
    check_export_name(c.name);
}

/// Every layer of \p material alone on the final layout, as NAME_layerI_CHANNEL.png (RGB = the layer's
/// value, A = its coverage) and NAME_layerI_mask.png (I from 1, bottom layer first); returns their
/// names per layer with its name, visibility, opacity and blend mode (docs/export.md).
nlohmann::json write_layer_pngs(AtomicOutput& out, const PaintCommand& c, const MaterialAdaptResult& run,
                                const MaterialStrokeFile& material, const MaterialPaintOptions& paint) {
  const std::vector<LayerTextures> layers = paint_material_layers(run.mesh, run.param, material, paint);
  nlohmann::json files = nlohmann::json::array();
  for (size_t l = 0; l < layers.size(); ++l) {
    const MaterialLayer& ml = material.layers[l];
    const std::string stem = c.name + "_layer" + std::to_string(l + 1) + "_";
    nlohmann::json channels = nlohmann::json::object();
    for (const auto& [ch, img] : layers[l].channels) {
      const std::string file = stem + channel_name(ch) + ".png";
      write_png(out.add(c.outdir / file), img);
      channels[channel_name(ch)] = file;
    }
    nlohmann::json entry = {{"name", ml.name}, {"visible", ml.visible}, {"opacity", ml.opacity},
                            {"blend", blend_mode_name(ml.blend)}, {"channels", channels}, {"mask", nullptr}};
    if (layers[l].mask) {
      write_png(out.add(c.outdir / (stem + "mask.png")), *layers[l].mask);
      entry["mask"] = stem + "mask.png";
    }
    files.push_back(entry);
  }
  return files;
}

/// A layered material (stroke file version 2) on the unwrap's layout adapted once to the material's
/// summed error model (adapt/material_adapt.h): base colour, roughness, metallic, height and the
/// derived normal map, exported as a glTF metallic-roughness material and an OBJ/MTL with map_Kd,
/// map_Pr, map_Pm and norm; the height map is written beside them, named in the MTL by a comment only
/// (Blender's OBJ importer reads `bump` as a normal map; docs/export.md).
void run_paint_material(PaintCommand& c, const TriMesh& mesh, const MaterialStrokeFile& material,
                        const ReadReport& rr, double time_read, const Context& ctx) {
  Stopwatch total, sw;
  if (c.run.adapt.mode != "none" && c.run.adapt.mode != "density-flow")
    throw InvalidInputError("--adapt " + c.run.adapt.mode + ": a layered material (stroke file version 2) adapts with "
                            "density-flow or none");
  const UnwrapResult ur = unwrap(mesh, paint_unwrap_options(c.run, phase_printer(ctx, "unwrap")));
  const double time_unwrap = sw.lap();
  const AdaptSettings& a = c.run.adapt;
  if (a.reparam != "end")
    ctx.info("paint: a layered material adapts once, after every stroke (--reparam end)");
  ctx.info("paint: " + std::to_string(material.layers.size()) + " layers at " + std::to_string(c.run.size) + "x" +
           std::to_string(c.run.size) + (a.mode == "none" ? std::string() : ", adapt " + a.mode));
  MaterialAdaptOptions mo;
  mo.paint.size = c.run.size;
  mo.paint.padding = c.run.padding;
  mo.adapt = make_session_options(c.run.size, c.run.padding, a.mode, a.grid, a.alpha.value_or(-1.0),
                                  a.beta.value_or(-1.0), a.reparam, a.update, a.debug_maps)
                 .adapt;
  mo.adapt.refine.enabled = a.refine;
  mo.adapt.progress = phase_printer(ctx, "adapt");
  const MaterialAdaptResult run = adapt_material(mesh, ur.param, material, mo);
  const MaterialTextures& tex = run.textures;
  const double time_paint = sw.lap();
  AtomicOutput out;
  const ExportedFiles files = export_material_textures(out, c.outdir, c.name, run.mesh, run.param, tex);
  const nlohmann::json layer_files = c.layers ? write_layer_pngs(out, c, run, material, mo.paint) : nlohmann::json();
  const double time_export = sw.lap();
  nlohmann::json layers = nlohmann::json::array();
  size_t strokes = 0;
  for (const MaterialLayer& l : material.layers) {
    layers.push_back({{"name", l.name}, {"strokes", l.strokes.size()}, {"blend", blend_mode_name(l.blend)},
                      {"mask", l.mask.has_value()}, {"visible", l.visible}, {"opacity", l.opacity}});
    strokes += l.strokes.size();
  }
  nlohmann::json report = {
      {"command", "paint"},
      {"input", {{"mesh", c.mesh.string()}, {"strokes", c.strokes.string()}, {"format", rr.format}, {"version", 2}}},
      {"mesh", {{"vertices", run.mesh.num_vertices()}, {"faces", run.mesh.num_faces()}, {"input_faces", mesh.num_faces()},
                {"charts", run.param.num_charts}}},
      {"texture", {{"width", c.run.size}, {"height", c.run.size}, {"padding", c.run.padding}}},
      {"material", {{"layers", layers}, {"strokes", strokes}, {"dabs", material.num_dabs()},
                    {"height_scale", tex.height_scale}}},
      {"adapt", {{"mode", a.mode}, {"adapted", run.adapted}, {"error_fixed", run.error_fixed},
                 {"error_adapted", run.error_adapted}, {"report", nlohmann::json::parse(adapt_report_json(run.report).dump())}}},
      {"files", {{"obj", files.obj.filename().string()}, {"mtl", files.mtl.filename().string()},
                 {"png", files.png.filename().string()}, {"glb", files.glb.filename().string()},
                 {"maps", {c.name + "_roughness.png", c.name + "_metallic.png", c.name + "_normal.png",
                           c.name + "_height.png"}}}},
      {"times_s", {{"read", time_read}, {"unwrap", time_unwrap}, {"paint", time_paint}, {"export", time_export},
                   {"total", time_read + total.lap()}}}};
  if (c.layers) report["files"]["layers"] = layer_files;
  write_text(out, c.outdir / "report.json", report.dump(2) + "\n");
  out.commit();
  std::cout << "wrote " << (c.outdir / c.name).string() << ".{obj,mtl,png,glb}, its roughness, metallic, normal and "
            << "height maps, " << (c.layers ? std::to_string(layer_files.size()) + " layers as PNGs, " : std::string())
            << "and " << (c.outdir / "report.json").string() << " (" << c.run.size << "x" << c.run.size
            << ", " << material.layers.size() << " layers, " << strokes << " strokes, unwrap " << time_unwrap
            << " s, paint " << time_paint << " s)\n";
}

void run_paint(PaintCommand& c, const Context& ctx) {
  validate(c, ctx);
  Stopwatch total, sw;
  ReadOptions ro;
  ro.repair = c.repair;
  ReadReport rr;
  const TriMesh mesh = read_mesh(c.mesh, ro, &rr);
  for (const std::string& w : rr.warnings) ctx.warn(w);
  AnyStrokeFile any = read_any_strokes(c.strokes);
  if (const MaterialStrokeFile* material = std::get_if<MaterialStrokeFile>(&any)) {
    for (const std::string& w : material->warnings) ctx.warn(w);
    return run_paint_material(c, mesh, *material, rr, sw.lap(), ctx);
  }
  if (c.layers)
    throw InvalidInputError(c.strokes.string() + ": --layers needs a stroke file of version 2 (a version 1 file is one "
                            "base-colour layer: NAME.png is that layer)");
  const StrokeFile strokes = std::get<StrokeFile>(std::move(any));
  for (const std::string& w : strokes.warnings) ctx.warn(w);
  const double time_read = sw.lap();
  ctx.info("read: " + c.mesh.filename().string() + " (" + std::to_string(mesh.num_vertices()) +
           " vertices, " + std::to_string(mesh.num_faces()) + " faces), " +
           std::to_string(strokes.strokes.size()) + " strokes");

  const PaintRun run = unwrap_and_paint(mesh, strokes, c.run, ctx);
  sw.lap();

  AtomicOutput out;
  const ExportedFiles files = export_textured_mesh(out, c.outdir, c.name, run.mesh, run.param, run.texture);
  const double time_export = sw.lap();
  nlohmann::json report = paint_report(run.mesh, strokes, run, c.run, files);
  report["mesh"]["input_faces"] = mesh.num_faces();
  report["command"] = "paint";
  report["input"] = {{"mesh", c.mesh.string()}, {"strokes", c.strokes.string()}, {"format", rr.format}};
  report["times_s"] = {{"read", time_read},
                       {"unwrap", run.time_unwrap},
                       {"paint", run.time_paint},
                       {"export", time_export},
                       {"total", total.lap()}};
  write_text(out, c.outdir / "report.json", report.dump(2) + "\n");
  out.commit();
  std::cout << "wrote " << (c.outdir / c.name).string() << ".{obj,mtl,png,glb} and "
            << (c.outdir / "report.json").string() << " (" << run.texture.width << "x"
            << run.texture.height << ", " << strokes.strokes.size() << " strokes, unwrap "
            << run.time_unwrap << " s, paint " << run.time_paint << " s)\n";
}

}  // namespace

void add_paint_command(CLI::App& app, Context& ctx) {
  auto cmd = std::make_shared<PaintCommand>();
  auto* sub = app.add_subcommand(
      "paint", "Unwrap a mesh, paint a stroke file into its texture, export OBJ/MTL/PNG/GLB + report.json");
  sub->add_option("mesh", cmd->mesh, "Input mesh (OBJ, OFF, PLY, STL, glTF/GLB)")->required();
  sub->add_option("--strokes", cmd->strokes, "Stroke file (adaptex.strokes JSON, see docs/strokes.md)")
      ->required();
  sub->add_option("-o,--output", cmd->outdir, "Output directory (created if missing)")->required();
  add_size_option(sub, cmd->run.size);
  sub->add_option("--padding", cmd->run.padding, "Seam padding in texels (dilation of the charts)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  sub->add_option("--name", cmd->name, "Base name of the output files (default: the mesh file's stem)");
  sub->add_flag("--layers", cmd->layers,
                "Stroke file version 2: also write every layer alone as PNGs (NAME_layerI_CHANNEL.png, "
                "NAME_layerI_mask.png)");
  sub->add_flag("--repair", cmd->repair, "Split non-manifold vertices / drop duplicate faces on reading");
  sub->add_option("--adapt", cmd->run.adapt.mode, "Signal-adaptive re-parameterization: " + adapt_methods_help())
      ->check(CLI::IsMember(adapt_method_names()))
      ->capture_default_str();
  sub->add_flag("--no-refine", cmd->no_refine,
                "Keep the input's vertices (density-flow refines triangles too large for the warp)");
  sub->add_option("--grid", cmd->grid, "Relaxation grid size(s): coarse,fine for two-stage (e.g. 16,256)")
      ->each([cmd](const std::string&) { cmd->grid_given = true; });
  sub->add_option("--alpha", cmd->alpha, "L_s^2 weight of the geometric stretch")
      ->each([cmd](const std::string&) { cmd->alpha_given = true; });
  sub->add_option("--beta", cmd->beta, "L_s^2 weight of the signal stretch")
      ->each([cmd](const std::string&) { cmd->beta_given = true; });
  sub->add_option("--reparam", cmd->run.adapt.reparam, "When to re-parameterize: each-stroke | end")
      ->check(CLI::IsMember(enum_choices<ReparamSchedule>()))
      ->capture_default_str();
  sub->add_option("--min-gain", cmd->min_gain,
                  "each-stroke: re-parameterize only when the error model predicts at least this PSNR gain "
                  "(dB) over the held layout; 0 = after every stroke (default " +
                      std::to_string(PaintSessionOptions{}.min_gain_db).substr(0, 4) + ")")
      ->each([cmd](const std::string&) { cmd->min_gain_given = true; });
  sub->add_option("--update", cmd->run.adapt.update, "Texture update after re-parameterizing: replay | resample")
      ->check(CLI::IsMember(enum_choices<TextureUpdate>()))
      ->capture_default_str();
  sub->add_option("--debug-maps", cmd->run.adapt.debug_maps,
                  "Write the importance / stretch / L_s^2 / grid pictures to this directory");
  sub->callback([cmd, &ctx] { run_paint(*cmd, ctx); });
}

}  // namespace adaptex::cli
