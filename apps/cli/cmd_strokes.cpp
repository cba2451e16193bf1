// `adaptex strokes generate MESH --kind lines|blobs|mixed|dots|material [--seed S] [--count N] -o S.json`:
// seeded, reproducible test stroke sets (paint/generate.h; material: a version 2 file,
// paint/material_generate.h).
// `adaptex strokes check S.json [-o OUT.json]`: strict validation of a stroke file (one line naming
// the stroke index and field on error, exit 2); with -o writes it back normalized (defaults filled).
// Both commands take version 1 and version 2 files (docs/strokes.md).
#include <nlohmann/json.hpp>

#include <iostream>

#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/material_generate.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/strokes.h"
#include "cli_common.h"

namespace adaptex::cli {

namespace {

struct GenerateArgs {
  std::string mesh, kind = "mixed", output;
  std::uint64_t seed = 1;
  int count = -1;
  bool repair = false;
};

/// The mesh of \p a, read as `paint --repair` reads it when --repair is given (scans).
TriMesh read_generate_mesh(const GenerateArgs& a, const Context& ctx) {
  ReadOptions ro;
  ro.repair = a.repair;
  ReadReport report;
  TriMesh mesh = read_mesh(a.mesh, ro, &report);
  for (const auto& w : report.warnings) ctx.warn(w);
  return mesh;
}

struct CheckArgs {
  std::string input, output;
};

void print_summary(const std::string& file, const StrokeFile& s, const GeneratedRegion& region = {}) {
  int decals = 0;
  for (const Stroke& st : s.strokes) decals += st.type == Stroke::Type::Decal;
  nlohmann::json j;
  j["file"] = file;
  j["strokes"] = s.strokes.size();
  j["decals"] = decals;
  j["dabs"] = s.num_dabs();
  j["background"] = {s.background[0], s.background[1], s.background[2]};
  if (region.radius > 0)
    j["region"] = {{"centre", {region.centre[0], region.centre[1], region.centre[2]}},
                   {"radius", region.radius},
                   {"area_fraction", region.area_fraction}};
  std::cout << j.dump() << "\n";
}

/// Summary line of a version 2 file: layers, strokes and dabs.
void print_summary(const std::string& file, const MaterialStrokeFile& s) {
  size_t strokes = 0, decals = 0;
  nlohmann::json layers = nlohmann::json::array();
  for (const MaterialLayer& l : s.layers) {
    strokes += l.strokes.size();
    for (const MaterialStroke& st : l.strokes) decals += st.type == MaterialStroke::Type::Decal;
    layers.push_back({{"name", l.name}, {"strokes", l.strokes.size()}, {"blend", blend_mode_name(l.blend)},
                      {"mask", l.mask.has_value()}, {"visible", l.visible}});
  }
  nlohmann::json j;
  j["file"] = file;
  j["version"] = 2;
  j["layers"] = layers;
  j["strokes"] = strokes;
  j["decals"] = decals;
  j["dabs"] = s.num_dabs();
  std::cout << j.dump() << "\n";
}

void run_generate_material(const GenerateArgs& a, const Context& ctx) {
  if (a.count != -1) throw InvalidInputError("strokes generate: --count has no meaning with --kind material");
  const TriMesh mesh = read_generate_mesh(a, ctx);
  const MaterialStrokeFile s = generate_material_strokes(mesh, a.seed);
  AtomicOutput out;
  write_material_strokes(out.add(a.output), s);
  out.commit();
  print_summary(a.output, s);
}

void run_generate(const GenerateArgs& a, const Context& ctx) {
  if (a.kind == "material") return run_generate_material(a, ctx);
  GenerateOptions opt;
  try {
    opt.kind = parse_stroke_kind(a.kind);
  } catch (const InvalidInputError&) {
    throw InvalidInputError("unknown stroke kind \"" + a.kind + "\" (expected lines, blobs, mixed, dots or material)");
  }
  opt.seed = a.seed;
  opt.count = a.count;
  if (opt.count < 1 && opt.count != -1)
    throw InvalidInputError("strokes generate: --count must be >= 1 (got " + std::to_string(a.count) + ")");
  const TriMesh mesh = read_generate_mesh(a, ctx);
  GeneratedRegion region;
  const StrokeFile s = generate_strokes(mesh, opt, &region);
  AtomicOutput out;
  write_strokes(out.add(a.output), s);
  out.commit();
  print_summary(a.output, s, region);
}

void run_check(const CheckArgs& a, const Context& ctx) {
  AnyStrokeFile any = read_any_strokes(a.input);
  if (const MaterialStrokeFile* m = std::get_if<MaterialStrokeFile>(&any)) {
    for (const auto& w : m->warnings) ctx.warn(w);
    if (!a.output.empty()) {
      AtomicOutput out;
      write_material_strokes(out.add(a.output), *m);
      out.commit();
    }
    return print_summary(a.input, *m);
  }
  const StrokeFile& s = std::get<StrokeFile>(any);
  for (const auto& w : s.warnings) ctx.warn(w);
  if (!a.output.empty()) {
    AtomicOutput out;
    write_strokes(out.add(a.output), s);
    out.commit();
  }
  print_summary(a.input, s);
}

}  // namespace

void add_strokes_command(CLI::App& app, Context& ctx) {
  auto* sub = app.add_subcommand("strokes", "Stroke files: generate test cases, check a file");
  sub->require_subcommand(1);

  auto g = std::make_shared<GenerateArgs>();
  auto* gen = sub->add_subcommand(
      "generate",
      "Generate a seeded, reproducible stroke set on a mesh: lines (many thin hard strokes in one "
      "region), blobs (a few broad soft strokes), mixed (both), dots (150-400 tiny hard dots "
      "sprinkled in a ball holding 10-20% of the surface: speckle, text-like), material (a version 2 "
      "file: three layers, one masked, painting base colour, roughness, metallic and height with pen "
      "pressure). Sizes are fractions of the bounding-box diagonal; dabs lie on the surface.");
  gen->add_option("mesh", g->mesh, "Input mesh (any format read_mesh reads)")->required();
  gen->add_option("--kind", g->kind, "lines | blobs | mixed | dots | material (default mixed)");
  gen->add_option("--seed", g->seed, "Random seed (default 1)");
  gen->add_option("--count", g->count,
                  "Number of strokes (default: 60 lines, 6 blobs, 48 mixed, 150-400 dots drawn from the seed)");
  gen->add_option("-o,--output", g->output, "Output stroke file (.json)")->required();
  gen->add_flag("--repair", g->repair,
                "Split non-manifold vertices / drop duplicate faces on reading (as paint --repair)");
  gen->callback([g, &ctx] { run_generate(*g, ctx); });

  auto c = std::make_shared<CheckArgs>();
  auto* chk = sub->add_subcommand(
      "check", "Validate a stroke file strictly and print a JSON summary; -o writes it normalized");
  chk->add_option("file", c->input, "Stroke file (adaptex.strokes, version 1 or 2)")->required();
  chk->add_option("-o,--output", c->output, "Write the normalized file here (defaults filled in)");
  chk->callback([c, &ctx] { run_check(*c, ctx); });
}

}  // namespace adaptex::cli
