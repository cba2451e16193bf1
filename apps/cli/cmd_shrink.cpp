// `adaptex shrink`: a textured asset (OBJ + MTL, glTF/GLB) with every map of its material made
// smaller on a repacked copy of the artist's atlas (adapt/shrink.h). Writes NAME.obj/.mtl/.png
// (+ NAME_SLOT.png per further map), NAME.glb and report.json into OUTDIR, all or nothing.
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "adaptex/adapt/shrink.h"
#include "adaptex/adapt/shrink_report.h"
#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/io/asset_io.h"
#include "adaptex/paint/export.h"
#include "cli_common.h"
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

/// The maps of the asset's one textured material, base colour first. \throw InvalidInputError
std::vector<ShrinkMap> asset_maps(const TexturedAsset& asset, const std::string& file) {
  const Material* textured = nullptr;
  for (const Material& m : asset.materials)
    if (!m.maps.empty()) {
      if (textured)
        throw InvalidInputError(file + ": several materials have texture maps ('" + textured->name + "', '" + m.name +
                                "'); shrink supports one textured material");
      textured = &m;
    }
  if (!textured) throw InvalidInputError(file + ": no material with a texture map");
  std::vector<ShrinkMap> maps;
  for (const TextureMap& t : textured->maps) {
    const std::string slot = map_slot_name(t.slot);
    ShrinkMap m{slot, t.image, map_kind_of_slot(slot)};
    if (t.slot == MapSlot::BaseColor)
      maps.insert(maps.begin(), std::move(m));
    else
      maps.push_back(std::move(m));
  }
  return maps;
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
  const std::vector<ShrinkMap> maps = asset_maps(asset, a.mesh);
  const ImageRGBA8& first = maps[0].image;
  ShrinkOptions opt;
  // --factor K: K times fewer texels (each side divided by sqrt(K)).
  opt.size = a.size > 0 ? a.size
                        : std::max(8, static_cast<int>(std::lround(std::max(first.width, first.height) / std::sqrt(a.factor))));
  opt.progress = shrink_progress(ctx, "shrink");
  opt.force_candidate = a.candidate;
  opt.max_face_growth = a.no_refine ? 0.0 : a.max_face_growth;
  ctx.info("shrink: " + a.mesh + ": " + std::to_string(asset.mesh.num_faces()) + " faces, " +
           std::to_string(maps.size()) + " map(s) " + std::to_string(first.width) + "x" + std::to_string(first.height) +
           " -> " + std::to_string(opt.size) + "x" + std::to_string(opt.size));
  const ShrinkResult res = shrink_textured_mesh(asset.mesh, asset.param, maps, opt);
  ExportOptions eo;
  eo.mtl_clamp = true;  // the layout ends at the square's border: no renderer may wrap
  std::vector<std::string> slots;
  for (size_t m = 0; m < maps.size(); ++m) {
    slots.push_back(maps[m].slot);
    if (m > 0) eo.maps.push_back({maps[m].slot, res.maps[m]});
  }
  AtomicOutput out;
  export_textured_mesh(out, a.outdir, name, asset.mesh, res.param, res.maps[0], eo);
  nlohmann::ordered_json j;
  j["input"] = a.mesh;
  j["faces"] = asset.mesh.num_faces();
  j["size"] = {opt.size, opt.size};
  j["shrink"] = shrink_report_json(res, slots);
  j["psnr"] = res.psnr;
  j["psnr_downsized"] = res.psnr_downsized;
  j["time_total_ms"] = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  write_text(out, std::filesystem::path(a.outdir) / "report.json", j.dump(2) + "\n");
  out.commit();
  print_shrink_summary(res, slots);
  ctx.info("shrink: " + res.chosen + ", wrote " + (std::filesystem::path(a.outdir) / name).string() +
           ".{obj,mtl,png,glb} and report.json");
}

}  // namespace

void add_shrink_command(CLI::App& app, Context& ctx) {
  auto a = std::make_shared<ShrinkArgs>();
  auto* sub = app.add_subcommand(
      "shrink", "Make every map of a textured asset smaller on a repacked copy of its own atlas (docs/shrink.md)");
  sub->add_option("mesh", a->mesh, "OBJ (+ MTL) or glTF/GLB with texture coordinates and texture maps")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("-o,--output", a->outdir, "Output directory")->required();
  sub->add_option("--size", a->size, "Output width = height of every map")->check(CLI::Range(8, adaptex::kMaxTextureSize));
  sub->add_option("--factor", a->factor, "Or: K times fewer texels than the base colour map (each side / sqrt(K))");
  sub->add_option("--candidate", a->candidate,
                  "Output this candidate (downsized, artist, repacked, budget, island_warp, warped) instead of the best");
  sub->add_option("--max-face-growth", a->max_face_growth,
                  "Largest share of faces the new layout may add (0.1 = 10 %; the shrink adds none)")
      ->check(cli::kFiniteNonNegative)
      ->capture_default_str();
  sub->add_flag("--no-refine", a->no_refine, "Keep the input's faces exactly (--max-face-growth 0)");
  sub->add_option("--name", a->name, "Base name of the output files (default: the mesh file's stem)");
  sub->callback([a, &ctx] { run_shrink(*a, ctx); });
}

}  // namespace adaptex::cli
