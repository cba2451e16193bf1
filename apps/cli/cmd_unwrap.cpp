// `adaptex unwrap`: cut every component to a disk (§3.2), parameterize it (Floater + Yoshizawa,
// §2.2/§3.3), pack the charts into [0,1]^2, and write the OBJ (+ report JSON, + layout PNG).
#include <chrono>
#include <iomanip>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "adaptex/adapt/report_json.h"
#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/timer.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/param/layout_image.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"
#include "cli_common.h"
#include "topology_report.h"

namespace adaptex::cli {

namespace {

struct UnwrapArgs {
  std::string input, output, report, layout;
  bool repair = false;
  int layout_size = 1024;
  int texture_size = UnwrapOptions{}.gutter_texture_size;
  int max_augmentations = UnwrapOptions{}.max_augmentations;
  double augment_time_budget = UnwrapOptions{}.augment_time_budget;
  int yoshizawa_iterations = UnwrapOptions{}.yoshizawa_max_iterations;
  bool mean_value = false;
  std::string charts = enum_name(UnwrapOptions{}.charts);
};

using Clock = std::chrono::steady_clock;

void run_unwrap(const UnwrapArgs& a, const Context& ctx) {
  const auto t_start = Clock::now();
  // Read.
  ReadOptions ro;
  ro.repair = a.repair;
  ReadReport rr;
  auto t0 = Clock::now();
  const TriMesh mesh = read_mesh(a.input, ro, &rr);
  const double time_read = seconds_since(t0);
  for (const std::string& w : rr.warnings) ctx.warn(w);
  ctx.info("unwrap: " + a.input + ": " + std::to_string(mesh.num_vertices()) + " vertices, " +
           std::to_string(mesh.num_faces()) + " faces");

  // Unwrap, with one progress line per phase (not per chart or per iteration).
  UnwrapOptions opt;
  opt.max_augmentations = a.max_augmentations;
  opt.augment_time_budget = a.augment_time_budget;
  opt.yoshizawa_max_iterations = a.yoshizawa_iterations;
  if (a.mean_value) opt.weights = EmbeddingWeights::MeanValue;
  opt.charts = parse_enum<ChartMode>(a.charts, "chart mode");
  opt.gutter_texture_size = a.texture_size;
  std::set<std::string, std::less<>> seen;
  opt.progress = [&](std::string_view phase, double) {
    if (seen.find(phase) == seen.end()) {
      seen.emplace(phase);
      std::ostringstream line;
      line << "unwrap: " << phase << " (" << std::fixed << std::setprecision(2) << seconds_since(t_start)
           << " s)";
      ctx.info(line.str());
    }
    return true;
  };
  const UnwrapResult res = unwrap(mesh, opt);
  const UnwrapReport& r = res.report;
  const StretchStats stats = measure_stretch(mesh, res.param);

  // Write every output through one AtomicOutput: all or nothing.
  t0 = Clock::now();
  AtomicOutput out;
  write_obj(out.add(a.output), mesh, &res.param);
  if (!a.layout.empty()) {
    LayoutImageOptions lo;
    lo.size = a.layout_size;
    write_png(out.add(a.layout), render_layout(res.param, face_l2_stretch(mesh, res.param), lo));
  }
  const double time_write = seconds_since(t0);
  if (!a.report.empty()) {
    // The unwrap's own report (report_json.h) with the file, the mesh and the layout's figures
    // placed among its keys, and the times of reading and writing around the unwrap's own.
    nlohmann::ordered_json j;
    j["input"] = a.input;
    j["format"] = rr.format;
    j["vertices"] = mesh.num_vertices();
    j["faces"] = mesh.num_faces();
    const nlohmann::ordered_json report = unwrap_report_json(r);
    for (const auto& [key, value] : report.items()) {
      if (key == "time") continue;
      j[key] = value;
      if (key == "boundary_loops") j["component_topology"] = component_topology_json(analyze_topology(mesh));
      if (key == "charts") j["wedges"] = res.param.num_wedges();
    }
    const nlohmann::ordered_json stretch = stretch_json(stats);
    for (const auto& [key, value] : stretch.items())
      if (key != "l2" && key != "linf") j[key] = value;  // the unwrap's final_l2 / final_linf stand for them
    j["repair"] = read_report_json(rr);
    nlohmann::ordered_json& time = j["time"];
    time["read"] = time_read;
    for (const auto& [key, value] : report["time"].items()) time[key == "total" ? "unwrap" : key] = value;
    time["write"] = time_write;
    time["total"] = seconds_since(t_start);
    write_text(out, a.report, j.dump(2) + "\n");
  }
  out.commit();
  std::ostringstream line;
  line << std::setprecision(4) << "unwrap: " << r.num_charts << " chart(s), genus " << r.genus
       << ", " << r.boundary_loops << " boundary loop(s), cut length " << r.cut_length
       << ", L2 stretch " << r.floater_l2 << " (Floater) -> " << r.final_l2 << ", L-inf "
       << r.final_linf << ", effective texel share " << std::setprecision(3)
       << r.effective_texel_share << ", " << seconds_since(t_start) << " s";
  ctx.info(line.str());
  if (r.gutter < r.requested_gutter) {
    // Thousands of charts (scans) do not fit with the full gutter: say what the paint will get.
    std::ostringstream w;
    w << std::setprecision(3) << "unwrap: the " << r.num_charts << " charts fit only with a gutter of "
      << r.gutter * a.texture_size << " texel(s) at " << a.texture_size << "x" << a.texture_size << " ("
      << r.requested_gutter * a.texture_size
      << " requested): paint may bleed between neighbouring charts in mipmaps; a larger --texture-size "
         "keeps a wider gutter";
    ctx.warn(w.str());
  }
}

}  // namespace

void add_unwrap_command(CLI::App& app, Context& ctx) {
  auto args = std::make_shared<UnwrapArgs>();
  auto* sub = app.add_subcommand(
      "unwrap",
      "Cut every component into a disk (thesis §3.2), parameterize it (Floater + Yoshizawa) and "
      "pack the charts into [0,1]^2; writes an OBJ with the input positions, vt and f v/vt");
  sub->add_option("input", args->input, "Input mesh (OBJ, OFF, PLY, STL, glTF/GLB)")->required();
  sub->add_option("-o,--output", args->output, "Output OBJ")->required();
  sub->add_option("--report", args->report,
                  "Write a JSON report (counts, genus, loops, cut length, stretch, times)");
  sub->add_option("--layout", args->layout, "Write a PNG of the UV layout coloured by L2 stretch");
  // The one texture-size cap of core/limits.h; out of range (or not a number) is bad input, exit 2.
  sub->add_option("--layout-size", args->layout_size,
                  "Side of the layout PNG in pixels, 16.." + std::to_string(kMaxTextureSize))
      ->check(CLI::Range(16, kMaxTextureSize))
      ->capture_default_str();
  sub->add_option("--texture-size", args->texture_size,
                  "Side of the texture the layout is for: the gutter between charts is " +
                      std::to_string(static_cast<int>(UnwrapOptions{}.gutter_texels)) +
                      " texels at this size, narrowed only where the charts do not fit otherwise")
      ->check(CLI::Range(64, kMaxTextureSize))
      ->capture_default_str();
  sub->add_flag("--repair", args->repair,
                "Split non-manifold vertices and drop duplicate faces instead of failing");
  sub->add_option("--max-augmentations", args->max_augmentations,
                  "Cut augmentations per chart (0 = off)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  sub->add_option("--augment-time-budget", args->augment_time_budget,
                  "Wall seconds from the start after which no new cut augmentation starts (a bound "
                  "for slow machines; the deterministic face budget decides below it)")
      ->check(cli::kFiniteNonNegative)
      ->capture_default_str();
  sub->add_option("--yoshizawa-iterations", args->yoshizawa_iterations,
                  "Yoshizawa stretch-minimization iterations (0 = Floater only)")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  sub->add_flag("--mean-value", args->mean_value,
                "Mean-value weights for the initial embedding instead of shape-preserving");
  sub->add_option("--charts", args->charts,
                  "single: one chart per connected component; auto: segment into several charts "
                  "only when one chart per component has an effective texel share (coverage / "
                  "L2^2) below 0.5 (docs/charts.md)")
      ->check(CLI::IsMember(enum_choices<ChartMode>()))
      ->capture_default_str();
  sub->callback([args, &ctx] { run_unwrap(*args, ctx); });
}

}  // namespace adaptex::cli
