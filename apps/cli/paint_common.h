#pragma once
/// \file paint_common.h
/// Shared by `adaptex paint` and `adaptex demo`: unwrap with progress lines, paint the strokes, and
/// the report.json they write. Header-only (inline) so the CLI target needs no new source file.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "adaptex/adapt/report_json.h"
#include "adaptex/adapt/session.h"
#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/export.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/param/unwrap.h"
#include "cli_common.h"
#include "session_options.h"

namespace adaptex::cli {

/// Wall-clock stopwatch: lap() returns the seconds since the previous lap (or construction).
class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

/// A progress callback that prints one line per phase ("unwrap: cut") on stderr unless quiet.
inline ProgressCallback phase_printer(const Context& ctx, const std::string& prefix) {
  auto last = std::make_shared<std::string>();
  return [&ctx, prefix, last](std::string_view phase, double) {
    if (phase != *last) {
      *last = std::string(phase);
      ctx.info(prefix + ": " + *last);
    }
    return true;
  };
}

/// Settings of the adaptive re-parameterization (`--adapt` and friends), parsed and
/// validated by `adaptex paint` and turned into PaintSessionOptions by make_session_options().
struct AdaptSettings {
  std::string mode = to_string(AdaptOptions{}.mode);  ///< none | single | two-stage | density-flow
  bool refine = AdaptOptions{}.refine.enabled;  ///< false: --no-refine (keep the input's vertices)
  std::vector<int> grid;             ///< --grid: 1 (single) or 2 (coarse, fine) grid sizes; empty = default
  std::optional<double> alpha, beta; ///< --alpha / --beta L_s^2 weights; unset = the adaptive defaults
  std::string reparam = enum_name(PaintSessionOptions{}.schedule);  ///< each-stroke | end
  std::string update = enum_name(PaintSessionOptions{}.update);      ///< replay | resample
  /// --min-gain DB: each-stroke mode re-parameterizes only for at least this predicted gain
  /// (PaintSessionOptions::min_gain_db); unset = the library's default.
  std::optional<double> min_gain;
  std::filesystem::path debug_maps;  ///< --debug-maps DIR (empty = none)
};

using adaptex::kMaxTextureSize;  // core/limits.h: the one texture-size cap

/// Adds the `--size N` option (texture width = height, 1..kMaxTextureSize) to \p sub.
inline CLI::Option* add_size_option(CLI::App* sub, int& size) {
  return sub->add_option("--size", size, "Texture width = height in texels")
      ->check(CLI::Range(1, kMaxTextureSize))
      ->capture_default_str();
}

/// Settings of one unwrap + paint run.
struct PaintRunOptions {
  int size = 1024;     ///< Texture width = height.
  int padding = 4;     ///< Seam padding in texels.
  AdaptSettings adapt; ///< Adaptive re-parameterization (mode "none": plain painting).
};

/// What one unwrap + paint run produced.
struct PaintRun {
  TriMesh mesh;  ///< The painted mesh: the input, or its refinement (same surface) after density-flow.
  Parameterization param;
  UnwrapReport unwrap;
  ImageRGBA8 texture;
  long long texel_updates = 0;
  long long chart_texels = 0;  ///< Texels inside a chart at the final parameterization.
  double time_unwrap = 0, time_paint = 0;  ///< Seconds (paint includes re-parameterization).
  nlohmann::json adapt_reports = nlohmann::json::object();  ///< Per re-parameterization (adapt modes).
  /// Samples of the session's surface signal cache (PaintSession::surface_cache_samples(); 0: none).
  long long surface_cache_samples = 0;
  double initial_l2 = 0, final_l2 = 0;  ///< L2 stretch of the unwrap and of the final layout.
};

/// The unwrap options of a paint run: the gutter for the texture it paints (unwrap_options_for_texture,
/// param/unwrap.h: the seam padding in texels of options.size).
inline UnwrapOptions paint_unwrap_options(const PaintRunOptions& options, ProgressCallback progress) {
  UnwrapOptions uo;
  uo.progress = std::move(progress);
  return unwrap_options_for_texture(options.size, options.padding, std::move(uo));
}

/// Unwraps \p mesh (progress lines on stderr) and paints every stroke of \p strokes.
/// The adaptive step plugs in here, in the "paint" phase (see the comment there).
inline PaintRun unwrap_and_paint(const TriMesh& mesh, const StrokeFile& strokes,
                                 const PaintRunOptions& options, const Context& ctx) {
  PaintRun run;
  Stopwatch sw;
  UnwrapResult ur = unwrap(mesh, paint_unwrap_options(options, phase_printer(ctx, "unwrap")));
  run.param = std::move(ur.param);
  run.unwrap = ur.report;
  run.time_unwrap = sw.lap();

  ctx.info("paint: " + std::to_string(strokes.strokes.size()) + " strokes at " +
           std::to_string(options.size) + "x" + std::to_string(options.size) +
           (options.adapt.mode == "none" ? std::string()
                                         : ", adapt " + options.adapt.mode + " (" + options.adapt.reparam + ")"));
  if (options.adapt.mode == "none") {
    PainterOptions po;
    po.width = po.height = options.size;
    po.padding = options.padding;
    run.mesh = mesh;
    Painter painter(mesh, run.param, po, strokes.background);
    painter.paint_all(strokes);
    run.texture = painter.texture();
    run.texel_updates = painter.texel_updates();
    run.chart_texels = static_cast<long long>(painter.texel_map().inside.size());
  } else {
    // Signal-adaptive re-parameterization: a PaintSession paints every stroke and
    // re-parameterizes after each stroke or once at the end, replaying or resampling the texture.
    const AdaptSettings& a = options.adapt;
    const PaintSessionOptions so = make_session_options(
        options.size, options.padding, a.mode, a.grid, a.alpha.value_or(-1.0), a.beta.value_or(-1.0),
        a.reparam, a.update, a.debug_maps);
    PaintSessionOptions sor = so;
    sor.adapt.refine.enabled = a.refine;
    if (a.min_gain) sor.min_gain_db = *a.min_gain;
    PaintSession session(mesh, run.param, sor, strokes.background);
    const size_t n = strokes.strokes.size();
    for (size_t k = 0; k < n; ++k) {
      session.add_stroke(strokes.strokes[k]);
      if (so.schedule == ReparamSchedule::EachStroke && (k + 1) % 10 == 0) {
        long skipped = 0;
        for (const AdaptReport& r : session.reports()) skipped += r.skipped;
        ctx.info("adapt: " + std::to_string(k + 1) + "/" + std::to_string(n) + " strokes, " +
                 std::to_string(static_cast<long>(session.reports().size()) - skipped) + " re-parameterizations, " +
                 std::to_string(skipped) + " skipped (gain below " + std::to_string(sor.min_gain_db).substr(0, 4) +
                 " dB)");
      }
    }
    session.finish();
    run.mesh = session.mesh();
    run.param = session.param();
    run.texture = session.texture();
    run.texel_updates = session.painter().texel_updates();
    run.chart_texels = static_cast<long long>(session.texel_map().inside.size());
    run.adapt_reports = adapt_reports_json(session.reports());
    run.surface_cache_samples = session.surface_cache_samples();
  }
  run.time_paint = sw.lap();
  return run;
}

/// The JSON object of report.json shared by paint and demo (the caller adds command-specific keys).
inline nlohmann::json paint_report(const TriMesh& mesh, const StrokeFile& strokes, const PaintRun& run,
                                   const PaintRunOptions& options, const ExportedFiles& files) {
  using nlohmann::json;
  long long decals = 0;
  for (const Stroke& s : strokes.strokes) decals += s.type == Stroke::Type::Decal;
  const double n = static_cast<double>(run.texture.width) * run.texture.height;
  json files_json = json::object();
  auto put = [&](const char* key, const std::filesystem::path& p) {
    if (!p.empty()) files_json[key] = p.filename().string();
  };
  put("obj", files.obj);
  put("mtl", files.mtl);
  put("png", files.png);
  put("glb", files.glb);
  const UnwrapReport& u = run.unwrap;
  // The unwrap's figures, a part of its report (report_json.h) under the same names.
  const nlohmann::ordered_json unwrap = unwrap_report_json(u);
  json unwrap_json = json::object();
  for (const char* key : {"floater_l2", "final_l2", "final_linf", "cut_length", "augmentations", "yoshizawa_iterations"})
    unwrap_json[key] = json(unwrap.at(key));
  for (const char* key : {"cut", "floater", "yoshizawa", "augment", "pack"})
    unwrap_json["times_s"][key] = json(unwrap.at("time").at(key));
  return json{
      {"mesh", {{"vertices", mesh.num_vertices()},
                {"faces", mesh.num_faces()},
                {"wedges", run.param.num_wedges()},
                {"charts", run.param.num_charts},
                {"components", u.num_components},
                {"genus", u.genus},
                {"boundary_loops", u.boundary_loops}}},
      {"texture", {{"width", run.texture.width},
                   {"height", run.texture.height},
                   {"padding", options.padding},
                   {"chart_texels", run.chart_texels},
                   {"utilization", n > 0 ? run.chart_texels / n : 0.0}}},
      {"strokes", {{"count", strokes.strokes.size()},
                   {"brush", static_cast<long long>(strokes.strokes.size()) - decals},
                   {"decals", decals},
                   {"dabs", strokes.num_dabs()}}},
      {"paint", {{"texel_updates", run.texel_updates},
                 {"texel_updates_per_s", run.time_paint > 0 ? run.texel_updates / run.time_paint : 0.0}}},
      {"adapt", {{"mode", options.adapt.mode},
                 {"reparam", options.adapt.reparam},
                 {"update", options.adapt.update},
                 {"min_gain_db", options.adapt.min_gain.value_or(PaintSessionOptions{}.min_gain_db)},
                 {"surface_cache_samples", run.surface_cache_samples},
                 {"reparameterizations", run.adapt_reports}}},
      {"unwrap", unwrap_json},
      {"files", files_json}};
}

}  // namespace adaptex::cli
