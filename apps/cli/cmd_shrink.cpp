// `adaptex shrink`: a textured asset (OBJ + MTL, glTF/GLB) with every map of every material made
// smaller on a repacked copy of the artist's atlas (adapt/shrink_asset.h). Writes NAME.obj/.mtl,
// the maps (NAME.png + NAME_SLOT.png for one material; NAME_MATERIAL[_SLOT].png for several), NAME.glb
// and report.json into OUTDIR, all or nothing.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "adaptex/adapt/shrink_asset.h"
#include "adaptex/adapt/shrink_report.h"
#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/io/asset_io.h"
#include "adaptex/paint/export.h"
#include "cli_common.h"
#include "shrink_output.h"
#include "shrink_print.h"

namespace adaptex::cli {

namespace {

struct ShrinkArgs {
  std::string mesh, outdir, name;
  int size = 0;
  double factor = 0;
  std::string candidate;
  double max_face_growth = ShrinkOptions{}.max_face_growth;
  bool no_refine = false;
};

/// One material on every face: the outputs of the one-material export (NAME.png, NAME_SLOT.png).
bool one_material(const TexturedAsset& asset, const AssetShrinkResult& res) {
  return res.groups.size() == 1 && res.groups[0].materials.size() == 1 &&
         static_cast<int>(res.groups[0].faces.size()) == asset.mesh.num_faces();
}

/// "shrink: FILE: F faces, M map(s) WxH -> NxN" per group (the group's materials named when several).
/// A --size above a group's base colour map is warned of; above every group's, it is an error.
/// \throw InvalidInputError when --size would enlarge every map.
void print_plan(const Context& ctx, const ShrinkArgs& a, const TexturedAsset& asset, const AssetShrinkOptions& opt) {
  const std::vector<MaterialGroupShrink> groups = material_groups(asset);
  int largest = 0;
  for (const MaterialGroupShrink& g : groups)
    for (const GroupMapRef& r : g.refs)
      if (r.map == 0) {
        const ImageRGBA8& img = asset.materials[r.material].find(r.slot)->image;
        largest = std::max({largest, img.width, img.height});
      }
  if (a.size > largest)
    throw InvalidInputError(a.mesh + ": --size " + std::to_string(a.size) + " is larger than every base colour map (the largest is " +
                            std::to_string(largest) + " texels wide): shrink only makes maps smaller (reparam --size can enlarge)");
  for (const MaterialGroupShrink& g : groups) {
    const TextureMap* first = nullptr;
    std::string names;
    for (int m : g.materials) names += (names.empty() ? "" : "+") + asset.materials[m].name;
    const auto faces = groups.size() == 1 && g.materials.size() == 1 ? asset.mesh.num_faces() : std::count_if(asset.face_material.begin(), asset.face_material.end(), [&](int m) {
      return std::find(g.materials.begin(), g.materials.end(), m) != g.materials.end();
    });
    for (const GroupMapRef& r : g.refs)
      if (r.map == 0) first = asset.materials[r.material].find(r.slot);
    const ImageRGBA8& img = first->image;
    const int n = shrink_output_size(opt, img);
    if (n > std::max(img.width, img.height))
      ctx.warn(a.mesh + ": " + (groups.size() > 1 ? "material " + names + ": " : "") + "--size " + std::to_string(n) +
               " enlarges its " + std::to_string(img.width) + "x" + std::to_string(img.height) + " maps (more texels, no more detail)");
    ctx.info("shrink: " + a.mesh + ": " + (groups.size() > 1 ? "material " + names + ": " : "") +
             std::to_string(faces) + " faces, " + std::to_string(g.slots.size()) + " map(s) " +
             std::to_string(img.width) + "x" + std::to_string(img.height) + " -> " + std::to_string(n) + "x" +
             std::to_string(n));
  }
}

void run_shrink(const ShrinkArgs& a, const Context& ctx) {
  const auto t_start = std::chrono::steady_clock::now();
  if (a.size > 0 && a.factor > 0) throw InvalidInputError("give --size or --factor, not both");
  if (a.size <= 0 && !(a.factor >= 1)) throw InvalidInputError("give --size N (>= 8) or --factor K (>= 1)");
  const std::string name =
      a.name.empty() ? sanitize_export_name(std::filesystem::path(a.mesh).stem().string()) : a.name;
  check_export_name(name);
  AssetReadOptions ro;
  ro.mesh.repair = true;  // the shrink never needs a manifold mesh
  const TexturedAsset asset = read_textured_asset(a.mesh, ro);
  AssetShrinkOptions opt;
  opt.size = a.size;
  opt.factor = a.factor;
  opt.progress = shrink_progress(ctx, "shrink");
  opt.shrink.force_candidate = a.candidate;
  opt.shrink.max_face_growth = a.no_refine ? 0.0 : a.max_face_growth;
  print_plan(ctx, a, asset, opt);
  const AssetShrinkResult res = shrink_textured_asset(asset, opt);
  const bool one = one_material(asset, res);
  ExportOptions eo;
  eo.mtl_clamp = true;  // the layout ends at the square's border: no renderer may wrap
  AtomicOutput out;
  const std::vector<std::string> names = output_material_names(asset);
  std::vector<std::vector<std::pair<std::string, std::string>>> files(asset.materials.size());
  if (one) {
    const MaterialGroupShrink& g = res.groups[0];
    files[g.materials[0]].emplace_back(g.slots[0], name + ".png");
    for (size_t m = 1; m < g.slots.size(); ++m) {
      eo.maps.push_back({g.slots[m], g.result.maps[m]});
      files[g.materials[0]].emplace_back(g.slots[m], name + "_" + g.slots[m] + ".png");
    }
    export_textured_mesh(out, a.outdir, name, asset.mesh, res.param, g.result.maps[0], eo);
  } else {
    const ExportMaterials set = shrink_export_materials(asset, res, names, name);
    files = material_files(asset, set);
    export_textured_materials(out, a.outdir, name, asset.mesh, res.param, set, eo);
  }
  nlohmann::ordered_json j;
  j["input"] = a.mesh;
  j["faces"] = asset.mesh.num_faces();
  j["size"] = {res.groups[0].size, res.groups[0].size};
  if (one) j["shrink"] = shrink_report_json(res.groups[0].result, res.groups[0].slots);
  j["psnr"] = res.psnr;
  j["psnr_downsized"] = res.psnr_downsized;
  if (!one) j["psnr_weighting"] = "3-D area of each material group (mean of the groups' MSE, base colour)";
  j["materials"] = materials_report(asset, res, names, files);
  j["time_total_ms"] = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  write_text(out, std::filesystem::path(a.outdir) / "report.json", j.dump(2) + "\n");
  out.commit();
  print_asset_summary(asset, res, one);
  ctx.info("shrink: " + (one ? res.groups[0].result.chosen + ", " : "") + "wrote " +
           (std::filesystem::path(a.outdir) / name).string() + ".{obj,mtl,png,glb} and report.json");
}

}  // namespace

void add_shrink_command(CLI::App& app, Context& ctx) {
  auto a = std::make_shared<ShrinkArgs>();
  auto* sub = app.add_subcommand(
      "shrink", "Make every map of every material of a textured asset smaller on a repacked copy of its own atlas (docs/shrink.md)");
  sub->add_option("mesh", a->mesh, "OBJ (+ MTL) or glTF/GLB with texture coordinates and texture maps")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("-o,--output", a->outdir, "Output directory")->required();
  sub->add_option("--size", a->size, "Output width = height of every map of every material")->check(CLI::Range(8, adaptex::kMaxTextureSize));
  sub->add_option("--factor", a->factor, "Or: K times fewer texels than each material's base colour map (each side / sqrt(K))");
  sub->add_option("--candidate", a->candidate,
                  "Output this candidate (downsized, artist, repacked, budget, island_warp, warped, warped_islands) instead of the best");
  sub->add_option("--max-face-growth", a->max_face_growth,
                  "Largest share of faces the new layout may add (0.1 = 10 %; the shrink adds none)")
      ->check(cli::kFiniteNonNegative)
      ->capture_default_str();
  sub->add_flag("--no-refine", a->no_refine, "Keep the input's faces exactly (--max-face-growth 0)");
  sub->add_option("--name", a->name, "Base name of the output files (default: the mesh file's stem)");
  sub->callback([a, &ctx] { run_shrink(*a, ctx); });
}

}  // namespace adaptex::cli
