// Quality study of the signal-adaptive re-parameterization and acceptance tool of issue 12
// (docs/quality.md): for every mesh x stroke kind x texture size N, the PSNR (adaptex eval metric) of
// the fixed layout ("none", a Painter on unwrap()'s layout) at N, 2N and 4N, and of each requested
// adaptive mode at N (a PaintSession, end mode, replay). Each mode's *texel saving factor* is the
// texture area none needs to reach the mode's PSNR, interpolated linearly in log2 N
// (paint/texel_saving.h). One markdown row per case, printed as soon as the case is done, then a
// summary per stroke kind and mode. The channel cases (--kinds roughness-scratches,height-engravings,
// material) paint a version 2 file with every channel on the fixed layout and adapt_material() at N,
// judged by the weighted PSNR of every channel (paint/material_eval.h), with a per-channel table last.
//
//   adaptex_adapt_quality [--meshes a.obj,spot,...] [--kinds lines,dots,mixed,blobs,roughness-scratches,...] [--sizes 128,256,512]
//                         [--modes two-stage,single,...[:no-refine]] [--samples K] [--eval-seed E]
//                         [--count N] [--seed S]
//                         [--grid C,F] [--alpha A] [--beta B] [--schedule end|each-stroke]
//                         [--update replay|resample] [--no-safeguard] [--no-refine] [--verbose]
//                         [--charts single|auto] [--unwrap-gutter paint|fixed] [--probe-first-charts N] [--floor F] [--density-cells L]
//                         [--no-quarter-texel]
//                         [--refine-factor F] [--blur CELLS] [--max-density D]
//                         [--refine-levels L] [--refine-tol TEXELS] [--flow-cells C] [--flow-step CELLS] [--flow-tol CELLS] [--flow-interp CELLS]
//                         [--untangle-sor W] [--polish-sweeps N] [--polish-omega W] [--polish-floor K] [--polish-reach C] [--polish-shape MU] [--polish-cells M] [--polish-isotropy B] [--polish-charts | --no-polish-charts]
//                         [--no-damp-overlaps] [--snap-round R] [--polish-prepass N] [--polish-after N] [--polish-levels N]
//
// Mode names go to cli::make_session_options() (apps/cli/session_options.h, parse_adapt_mode), so every mode the library knows works.
// A mode written NAME:no-refine runs with mesh refinement off (see set_refine below); --no-refine
// turns it off for every mode. Meshes: paths, names of meshes built in code (bench/common/named_mesh.h:
// genus4, holes11, torus96x40, ...), or names/stems of ADAPTEX_SHARED_DIR/meshes (default: all of
// them), run in order of increasing face count.
// GCC 12 reports a false -Wrestrict inside std::string copies at -O3 (GCC bug 105329).
#pragma GCC diagnostic ignored "-Wrestrict"
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "adaptex/core/allocator.h"
#include "adaptex/adapt/session.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/generate.h"
#include "adaptex/adapt/material_adapt.h"
#include "adaptex/paint/material_eval.h"
#include "adaptex/paint/material_generate.h"
#include "adaptex/paint/texel_saving.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"
#include "../common/named_mesh.h"
#include "session_options.h"  // apps/cli: the option strings of adaptex paint

using namespace adaptex;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string x;
  while (std::getline(ss, x, ','))
    if (!x.empty()) out.push_back(x);
  return out;
}

/// One adaptive configuration compared against none: a mode name for parse_adapt_mode, refinement on/off.
struct ModeSpec {
  std::string label;  ///< Column title, e.g. "two-stage" or "density-flow:no-refine".
  std::string name;   ///< The --adapt mode string.
  bool refine = true;
};

struct Args {
  std::vector<std::string> meshes, kinds{"lines", "dots", "mixed", "blobs"};
  std::vector<int> sizes{128, 256, 512};
  std::vector<ModeSpec> modes;
  long long samples = 400000;
  std::uint64_t eval_seed = 1;
  int count = -1;
  std::uint64_t seed = 1;
  std::vector<int> grid;
  double alpha = -1, beta = -1;
  std::string schedule = "end", update = "replay";
  bool safeguard = true, verbose = false;
  std::string charts = "auto";  ///< --charts single|auto: the initial layout (unwrap's ChartMode).
  /// --unwrap-gutter paint|fixed. paint (default since session 16): the layout of every texture size M
  /// (N, 2N and 4N for none, N for the modes) is unwrapped with its gutter in texels of M, as
  /// `adaptex paint --size M` does (unwrap_options_for_texture(M, padding)). fixed: one layout per
  /// mesh with UnwrapOptions' own gutter (8 texels of 1024², 1 texel at 128²), as the tables before
  /// session 16 were made.
  std::string unwrap_gutter = "paint";
  int probe_first_charts = -1;  ///< --probe-first-charts: UnwrapOptions::probe_first_charts (-1: the default).
  double floor = -1;            ///< --floor: ErrorDensityOptions::floor (-1: the default).
  int density_cells = -1;       ///< --density-cells: ErrorDensityOptions::cells (-1: the default).
  /// --no-quarter-texel: ErrorDensityOptions::quarter_texel_reference = false (the 2N reference raster at every N).
  bool no_quarter_texel = false;
  double refine_factor = -1;    ///< --refine-factor: AdaptOptions::refine_max_face_factor (-1: default).
  double blur = -1;             ///< --blur: ErrorDensityOptions::blur_cells (-1: the default).
  double max_density = -1;      ///< --max-density: ErrorDensityOptions::max_density (-1: the default).
  int refine_levels = -1;       ///< --refine-levels: AdaptOptions::refine_max_levels (-1: the default).
  double refine_tol = -1;       ///< --refine-tol: AdaptOptions::refine_tolerance_texels (-1: the default).
  int flow_cells = -1;          ///< --flow-cells: DensityFlowOptions::cells (-1: the default).
  double flow_step = -1;        ///< --flow-step: DensityFlowOptions::max_step_cells (-1: the default).
  double flow_tol = -1;         ///< --flow-tol: DensityFlowOptions::tolerance (-1: the default).
  double flow_interp = -1;      ///< --flow-interp: DensityFlowOptions::interpolation_tolerance (-1: the default).
  int polish_sweeps = -1;       ///< --polish-sweeps: ErrorPolishOptions::sweeps (-1: the default; 0: off).
  double polish_floor = -1;     ///< --polish-floor: ErrorPolishOptions::floor_weight (-1: the default).
  double polish_omega = -1;     ///< --polish-omega: ErrorPolishOptions::over_relaxation (-1: the default).
  /// --polish-charts / --no-polish-charts: ErrorPolishOptions::charts = true / false (-1: the default,
  /// true since session 14; --no-polish-charts gives session 13's multi-chart layouts).
  int polish_charts = -1;
  bool damp_overlaps = true;  ///< --no-damp-overlaps: SafeRemapOptions::damp_overlaps = false.
  int snap_round = -2;        ///< --snap-round R: SafeRemapOptions::snap_round (-2: the default).
  int polish_prepass = -1;    ///< --polish-prepass N: ErrorPolishOptions::prepass_sweeps (-1: the default).
  int polish_after = -1;      ///< --polish-after N: ErrorPolishOptions::sweeps_after_prepass (-1: the default).
  int polish_levels = -1;     ///< --polish-levels N: ErrorPolishOptions::prepass_levels (-1: the default).
  int polish_reach = -1;        ///< --polish-reach: ErrorPolishOptions::reach_cells (-1: the default).
  int polish_cells = -1;        ///< --polish-cells: ErrorPolishOptions::cells (-1: the default; 0: the warp's).
  double polish_isotropy = -1;  ///< --polish-isotropy: ErrorPolishOptions::isotropy (-1: the default).
  double polish_shape = -1;     ///< --polish-shape: ErrorPolishOptions::shape_weight (-1: the default).
  double untangle_sor = -1;     ///< --untangle-sor: SafeRemapOptions::untangle_over_relaxation (-1: the default).
};

/// Refinement on or off (AdaptOptions::refine).
void set_refine(PaintSessionOptions& o, bool refine) { o.adapt.refine.enabled = refine; }

PaintSessionOptions session_options(const Args& a, const ModeSpec& m, int size) {
  PaintSessionOptions o = cli::make_session_options(size, 4, m.name, a.grid, a.alpha, a.beta, a.schedule, a.update);
  o.safeguard = a.safeguard;
  set_refine(o, m.refine);
  if (a.no_quarter_texel) o.adapt.density_flow.density.quarter_texel_reference = false;
  if (a.floor >= 0) o.adapt.density_flow.density.floor = a.floor;
  if (a.density_cells > 0) o.adapt.density_flow.density.cells = a.density_cells;
  if (a.refine_factor > 0) o.adapt.refine.max_face_factor = a.refine_factor;
  if (a.blur >= 0) o.adapt.density_flow.density.blur_cells = a.blur;
  if (a.max_density > 0) o.adapt.density_flow.density.max_density = a.max_density;
  if (a.refine_levels >= 0) o.adapt.refine.max_levels = a.refine_levels;
  if (a.refine_tol > 0) o.adapt.refine.tolerance_texels = a.refine_tol;
  if (a.flow_cells > 0) o.adapt.density_flow.flow.cells = a.flow_cells;
  if (a.flow_step > 0) o.adapt.density_flow.flow.max_step_cells = a.flow_step;
  if (a.flow_tol > 0) o.adapt.density_flow.flow.tolerance = a.flow_tol;
  if (a.flow_interp >= 0) o.adapt.density_flow.flow.interpolation_tolerance = a.flow_interp;
  if (a.polish_sweeps >= 0) o.adapt.density_flow.polish.sweeps = a.polish_sweeps;
  if (a.polish_omega > 0) o.adapt.density_flow.polish.over_relaxation = a.polish_omega;
  if (a.polish_charts >= 0) o.adapt.density_flow.polish.charts = a.polish_charts == 1;
  o.adapt.remap.damp_overlaps = a.damp_overlaps;
  if (a.snap_round != -2) o.adapt.remap.snap_round = a.snap_round;
  if (a.polish_prepass >= 0) o.adapt.density_flow.polish.prepass_sweeps = a.polish_prepass;
  if (a.polish_after >= 0) o.adapt.density_flow.polish.sweeps_after_prepass = a.polish_after;
  if (a.polish_levels >= 0) o.adapt.density_flow.polish.prepass_levels = a.polish_levels;
  if (a.polish_reach >= 0) o.adapt.density_flow.polish.reach_cells = a.polish_reach;
  if (a.polish_cells >= 0) o.adapt.density_flow.polish.cells = a.polish_cells;
  if (a.polish_isotropy > 0) o.adapt.density_flow.polish.isotropy = a.polish_isotropy;
  if (a.polish_shape >= 0) o.adapt.density_flow.polish.shape_weight = a.polish_shape;
  if (a.polish_floor >= 0) o.adapt.density_flow.polish.floor_weight = a.polish_floor;
  if (a.untangle_sor > 0) o.adapt.remap.untangle_over_relaxation = a.untangle_sor;
  return o;
}

/// Mesh arguments -> files: an existing path, else a name of a mesh built in code (named_mesh.h, kept
/// as it is), else a file name or stem in the shared meshes directory.
std::vector<std::string> resolve_meshes(const std::vector<std::string>& given) {
  const fs::path shared = fs::path(ADAPTEX_SHARED_DIR) / "meshes";
  std::vector<std::string> all;
  if (fs::is_directory(shared))
    for (const auto& e : fs::directory_iterator(shared))
      if (e.path().extension() != ".md") all.push_back(e.path().string());
  std::sort(all.begin(), all.end());
  if (given.empty()) return all;
  std::vector<std::string> out;
  for (const auto& g : given) {
    if (fs::exists(g) || bench::parse_code_built_name(g)) {
      out.push_back(g);
      continue;
    }
    std::string hit;
    for (const auto& p : all)
      if (fs::path(p).filename() == g || fs::path(p).stem() == g) hit = p;
    if (hit.empty()) throw std::invalid_argument(g + ": no such mesh file (nor in " + shared.string() + ")");
    out.push_back(hit);
  }
  return out;
}

/// The mesh of a resolved argument: the file, or the mesh built in code of that name.
TriMesh load_mesh(const std::string& path) {
  if (!fs::exists(path))
    if (std::optional<TriMesh> m = bench::code_built_mesh(path)) return std::move(*m);
  return read_mesh(path);
}

/// \p v as a number > 0 (>= 0 when \p zero_ok). \throw std::invalid_argument naming the flag otherwise
double positive(const std::string& flag, const std::string& v, bool zero_ok = false) {
  const double x = std::stod(v);
  if (!(zero_ok ? x >= 0 : x > 0) || !std::isfinite(x))
    throw std::invalid_argument(flag + ": expected a number " + (zero_ok ? ">= 0" : "> 0") + ", got " + v);
  return x;
}

/// A whole number in [lo, hi] (a double that is not a whole number or out of range is an error, not a
/// silent truncation or an out-of-range cast).
int whole(const std::string& flag, const std::string& v, int lo, int hi) {
  const double x = std::stod(v);
  if (!(x >= lo && x <= hi) || x != std::floor(x))
    throw std::invalid_argument(flag + ": expected a whole number in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "], got " + v);
  return static_cast<int>(x);
}

/// The channel cases (docs/quality.md, "Channel cases"): stroke files of version 2.
bool is_material_kind(const std::string& kind) {
  return kind == "roughness-scratches" || kind == "height-engravings" || kind == "material";
}

/// The generated version 2 file of a channel case \p kind.
MaterialStrokeFile material_case(const std::string& kind, const TriMesh& mesh, std::uint64_t seed) {
  if (kind == "roughness-scratches") return generate_material_detail(mesh, MaterialDetail::RoughnessScratches, seed);
  if (kind == "height-engravings") return generate_material_detail(mesh, MaterialDetail::HeightEngravings, seed);
  return generate_material_strokes(mesh, seed);
}

Args parse_args(int argc, char** argv) {
  Args a;
  bool no_refine = false;
  std::vector<std::string> modes{"two-stage"};
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    if (k == "--no-safeguard") { a.safeguard = false; continue; }
    if (k == "--no-refine") { no_refine = true; continue; }
    if (k == "--verbose") { a.verbose = true; continue; }
    if (k == "--no-quarter-texel") { a.no_quarter_texel = true; continue; }
    if (k == "--no-damp-overlaps") {
      a.damp_overlaps = false;
      continue;
    }
    if (k == "--polish-charts" || k == "--no-polish-charts") {
      a.polish_charts = k == "--polish-charts";
      continue;
    }
    if (i + 1 >= argc) throw std::invalid_argument(k + ": unknown option or missing value");
    const std::string v = argv[++i];
    if (k == "--meshes") a.meshes = split(v);
    else if (k == "--kinds") a.kinds = split(v);
    else if (k == "--sizes") {
      a.sizes.clear();
      for (const auto& s : split(v)) a.sizes.push_back(std::stoi(s));
    } else if (k == "--modes" || k == "--mode") modes = split(v);
    else if (k == "--samples") a.samples = std::stoll(v);
    else if (k == "--eval-seed") a.eval_seed = std::stoull(v);
    else if (k == "--count") a.count = std::stoi(v);
    else if (k == "--seed") a.seed = std::stoull(v);
    else if (k == "--grid") {
      for (const auto& s : split(v)) a.grid.push_back(std::stoi(s));
    } else if (k == "--alpha") a.alpha = std::stod(v);
    else if (k == "--beta") a.beta = std::stod(v);
    else if (k == "--schedule") a.schedule = v;
    else if (k == "--update") a.update = v;
    else if (k == "--charts") a.charts = v;
    else if (k == "--unwrap-gutter") {
      if (v != "paint" && v != "fixed") throw std::invalid_argument("--unwrap-gutter: expected paint or fixed, got " + v);
      a.unwrap_gutter = v;
    }
    else if (k == "--probe-first-charts") a.probe_first_charts = whole(k, v, 0, 1000);
    else if (k == "--snap-round") a.snap_round = whole(k, v, -1, 1000);
    else if (k == "--polish-prepass") a.polish_prepass = whole(k, v, 0, 100000);
    else if (k == "--polish-after") a.polish_after = whole(k, v, 0, 100000);
    else if (k == "--polish-levels") a.polish_levels = whole(k, v, 1, 4);
    else if (k == "--floor") a.floor = std::stod(v);
    else if (k == "--density-cells") a.density_cells = std::stoi(v);
    else if (k == "--refine-factor") a.refine_factor = positive(k, v);
    else if (k == "--blur") a.blur = std::stod(v);
    else if (k == "--max-density") a.max_density = std::stod(v);
    else if (k == "--refine-levels") a.refine_levels = std::stoi(v);
    else if (k == "--refine-tol") a.refine_tol = positive(k, v);
    else if (k == "--flow-cells") a.flow_cells = whole(k, v, 1, kMaxGridCells);
    else if (k == "--flow-step") a.flow_step = positive(k, v);
    else if (k == "--flow-tol") a.flow_tol = positive(k, v);
    else if (k == "--flow-interp") a.flow_interp = positive(k, v, true);
    else if (k == "--polish-sweeps") a.polish_sweeps = whole(k, v, 0, 100000);
    else if (k == "--polish-floor") a.polish_floor = positive(k, v, true);
    else if (k == "--polish-reach") a.polish_reach = whole(k, v, 0, kMaxGridCells);
    else if (k == "--polish-cells") a.polish_cells = whole(k, v, 0, kMaxGridCells);
    else if (k == "--polish-isotropy") {
      a.polish_isotropy = positive(k, v);
      if (!(a.polish_isotropy <= 1)) throw std::invalid_argument("--polish-isotropy must be in (0, 1], got " + v);
    }
    else if (k == "--polish-shape") a.polish_shape = positive(k, v, true);
    else if (k == "--polish-omega") {
      a.polish_omega = positive(k, v);
      if (!(a.polish_omega < 2)) throw std::invalid_argument("--polish-omega must be in (0, 2), got " + v);
    }
    else if (k == "--untangle-sor") {
      a.untangle_sor = positive(k, v);
      if (!(a.untangle_sor < 2)) throw std::invalid_argument("--untangle-sor must be in (0, 2), got " + v);
    }
    else throw std::invalid_argument(k + ": unknown option");
  }
  for (const auto& m : modes) {
    const auto colon = m.find(':');
    ModeSpec s{m, m.substr(0, colon), !no_refine};
    if (colon != std::string::npos) {
      if (m.substr(colon + 1) != "no-refine") throw std::invalid_argument(m + ": the only mode suffix is :no-refine");
      s.refine = false;
    }
    if (no_refine && colon == std::string::npos) s.label += ":no-refine";
    a.modes.push_back(s);
  }
  if (a.charts != "single" && a.charts != "auto") throw std::invalid_argument("--charts: single or auto");
  for (int n : a.sizes)
    if (n < 8 || n > 4096) throw std::invalid_argument("--sizes: each N must be in [8, 4096] (4N is painted too)");
  for (const auto& k : a.kinds) {
    if (is_material_kind(k)) continue;
    try {
      (void)parse_stroke_kind(k);
    } catch (const std::exception&) {
      throw std::invalid_argument("--kinds: unknown kind \"" + k + "\" (expected lines, blobs, mixed, dots, "
                                  "roughness-scratches, height-engravings or material)");
    }
  }
  for (const auto& m : a.modes) (void)session_options(a, m, a.sizes.front());  // fail early on bad names
  a.meshes = resolve_meshes(a.meshes);
  return a;
}

/// One adaptive run at N.
struct ModeResult {
  double psnr = 0, seconds = 0;
  TexelSaving saving;
  int flipped = 0, degenerate = 0, faces = 0, accepted = 0, reparams = 0;
  long overlaps = 0;
};

ModeResult run_mode(const Args& a, const ModeSpec& m, const TriMesh& mesh, const Parameterization& param,
                    const StrokeFile& strokes, int n, const std::array<double, 3>& none, const EvalOptions& eo) {
  ModeResult r;
  const auto t0 = std::chrono::steady_clock::now();
  PaintSession s(mesh, param, session_options(a, m, n), strokes.background);
  for (const auto& st : strokes.strokes) s.add_stroke(st);
  s.finish();
  const ImageRGBA8& texture = s.texture();
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.psnr = evaluate_texture(s.mesh(), s.param(), texture, strokes, eo).psnr;
  r.saving = texel_saving_factor(r.psnr, none);
  const StretchStats st = measure_stretch(s.mesh(), s.param());
  r.flipped = st.flipped;
  r.degenerate = st.degenerate;
  r.overlaps = count_overlapping_triangles(s.param());
  r.faces = s.mesh().num_faces();
  for (const auto& rep : s.reports()) r.accepted += rep.accepted;
  r.reparams = static_cast<int>(s.reports().size());
  if (a.verbose) std::fprintf(stderr, "%s\n", adapt_reports_json(s.reports()).dump().c_str());
  return r;
}

std::string factor_cell(const TexelSaving& s) {
  char buf[32];
  if (s.lossless) return "=1";
  std::snprintf(buf, sizeof buf, "%s%.2f", s.above_range ? ">" : (s.clamped ? "≤" : ""), s.factor);
  return buf;
}

/// PSNR of none (a Painter on the fixed layout) at \p size, cached per size.
double psnr_none(std::map<int, double>& cache, int size, const TriMesh& mesh, const Parameterization& param,
                 const StrokeFile& strokes, const EvalOptions& eo) {
  if (auto it = cache.find(size); it != cache.end()) return it->second;
  PainterOptions po;
  po.width = po.height = size;
  po.padding = PaintSessionOptions{}.padding;
  Painter p(mesh, param, po, strokes.background);
  p.paint_all(strokes);
  return cache[size] = evaluate_texture(mesh, param, p.texture(), strokes, eo).psnr;
}

/// One line of the per-channel table of the channel cases; with \p none (the fixed layout at N, 2N,
/// 4N) each channel's PSNR is followed by its own texel saving factor.
std::string channel_row(const std::string& head, const std::string& layout, const MaterialError& e,
                        const std::vector<MaterialError>& none = {}) {
  using Field = double MaterialError::*;
  std::string row = "| " + head + " | " + layout + " |";
  for (Field f : {&MaterialError::base_color, &MaterialError::roughness, &MaterialError::metallic, &MaterialError::alpha,
                  &MaterialError::normal, &MaterialError::weighted}) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " %.2f", psnr_from_mse(e.*f));
    row += buf;
    if (none.size() == 3) {
      const std::array<double, 3> curve{psnr_from_mse(none[0].*f), psnr_from_mse(none[1].*f), psnr_from_mse(none[2].*f)};
      const double target = psnr_from_mse(e.*f);
      if (std::isfinite(target) && std::isfinite(curve[0]) && std::isfinite(curve[1]) && std::isfinite(curve[2]))
        row += " (" + factor_cell(texel_saving_factor(target, curve)) + ")";
    }
    row += " |";
  }
  return row;
}

/// Every channel of a material painted on the fixed layout at \p size, judged, cached per size.
const MaterialError& material_none(std::map<int, MaterialError>& cache, int size, const TriMesh& mesh,
                                   const Parameterization& param, const MaterialStrokeFile& file,
                                   const MaterialEvalOptions& eo) {
  if (auto it = cache.find(size); it != cache.end()) return it->second;
  MaterialPaintOptions po;
  po.size = size;
  po.padding = PaintSessionOptions{}.padding;
  return cache[size] = evaluate_material_textures(mesh, param, paint_material(mesh, param, file, po), file, eo);
}

/// adapt_material() at N with mode \p m's adaptation settings, every channel judged.
ModeResult run_material_mode(const Args& a, const ModeSpec& m, const TriMesh& mesh, const Parameterization& param,
                             const MaterialStrokeFile& file, int n, const std::array<double, 3>& none,
                             const MaterialEvalOptions& eo, MaterialError& error) {
  ModeResult r;
  const auto t0 = std::chrono::steady_clock::now();
  MaterialAdaptOptions mo;
  mo.paint.size = n;
  mo.paint.padding = PaintSessionOptions{}.padding;
  mo.adapt = session_options(a, m, n).adapt;
  const MaterialAdaptResult run = adapt_material(mesh, param, file, mo);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  error = evaluate_material_textures(run.mesh, run.param, run.textures, file, eo);
  r.psnr = psnr_from_mse(error.weighted);
  r.saving = texel_saving_factor(r.psnr, none);
  const StretchStats st = measure_stretch(run.mesh, run.param);
  r.flipped = st.flipped;
  r.degenerate = st.degenerate;
  r.overlaps = count_overlapping_triangles(run.param);
  r.faces = run.mesh.num_faces();
  r.accepted = run.adapted;
  r.reparams = 1;
  return r;
}

struct CaseRecord {
  std::string kind;
  double none_n = 0;
  std::vector<ModeResult> modes;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

void print_header(const Args& a) {
  std::printf("| mesh | faces | kind | N | none N | none 2N | none 4N |");
  for (const auto& m : a.modes) std::printf(" %s N | ×area | F/D/O | acc | faces after | t s |", m.label.c_str());
  std::printf("\n|---|---:|---|---:|---:|---:|---:|");
  for (size_t k = 0; k < a.modes.size(); ++k) std::printf("---:|---:|---:|---:|---:|---:|");
  std::printf("\n");
  std::fflush(stdout);
}

void print_summary(const Args& a, const std::vector<CaseRecord>& cases) {
  std::printf("\nSummary (×area: texel saving factor; below 1 = worse than none at N by > 0.1 dB, "
              "both >= 50 dB count as equal):\n\n");
  std::printf("| kind | mode | cases | median ×area | min ×area | max ×area | cases >= 4 | below 1 | "
              "median gain dB | F/D/O total |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& kind : a.kinds)
    for (size_t m = 0; m < a.modes.size(); ++m) {
      std::vector<double> f, gain;
      int below = 0, four = 0;
      long bad = 0;
      for (const auto& c : cases) {
        if (c.kind != kind) continue;
        const ModeResult& r = c.modes[m];
        f.push_back(r.saving.factor);
        gain.push_back(r.psnr - c.none_n);
        below += worse_than_none(r.psnr, c.none_n);
        four += r.saving.factor >= 4;
        bad += r.flipped + r.degenerate + r.overlaps;
      }
      if (f.empty()) continue;
      std::printf("| %s | %s | %zu | %.2f | %.2f | %.2f | %d | %d | %+.2f | %ld |\n", kind.c_str(),
                  a.modes[m].label.c_str(), f.size(), median(f), *std::min_element(f.begin(), f.end()),
                  *std::max_element(f.begin(), f.end()), four, below, median(gain), bad);
    }
  std::fflush(stdout);
}

/// One markdown row of a case: none at N, 2N, 4N, then each mode.
void print_case_row(const std::string& name, int faces, const std::string& kind, int n, const std::array<double, 3>& none,
                    const CaseRecord& c) {
  std::printf("| %s | %d | %s | %d | %.2f | %.2f | %.2f |", name.c_str(), faces, kind.c_str(), n, none[0], none[1],
              none[2]);
  for (const ModeResult& r : c.modes)
    std::printf(" %.2f | %s | %d/%d/%ld | %d/%d | %d | %.1f |", r.psnr, factor_cell(r.saving).c_str(), r.flipped,
                r.degenerate, r.overlaps, r.accepted, r.reparams, r.faces, r.seconds);
  std::printf("\n");
  std::fflush(stdout);
}

using LayoutOf = std::function<const Parameterization&(int)>;
using FailureReport = std::function<void(const std::string&, const std::exception&)>;

/// A channel case on one mesh at every size: the weighted PSNR of every channel (MaterialError)
/// of the fixed layout at N, 2N, 4N and of adapt_material() at N; per-channel rows to \p channel_rows.
void run_material_kind(const Args& a, const std::string& kind, const std::string& name, int faces, const TriMesh& mesh,
                       const std::vector<int>& sizes, const LayoutOf& layout, std::vector<CaseRecord>& cases,
                       std::vector<std::string>& channel_rows, const FailureReport& report_failure) {
  const MaterialStrokeFile file = material_case(kind, mesh, a.seed);
  MaterialEvalOptions eo;
  eo.samples = a.samples;
  eo.seed = a.eval_seed;
  std::map<int, MaterialError> none_cache;
  for (int n : sizes) {
    CaseRecord c{kind, 0, {}};
    std::array<double, 3> none{};
    std::vector<std::string> rows;
    try {
      for (int j = 0; j < 3; ++j) {
        const MaterialError& e = material_none(none_cache, n << j, mesh, layout(n << j), file, eo);
        none[j] = psnr_from_mse(e.weighted);
        rows.push_back(channel_row(name + " | " + kind + " | " + std::to_string(n), "none " + std::to_string(1 << j) + "N", e));
      }
      c.none_n = none[0];
      for (const auto& m : a.modes) {
        MaterialError e;
        c.modes.push_back(run_material_mode(a, m, mesh, layout(n), file, n, none, eo, e));
        rows.push_back(channel_row(name + " | " + kind + " | " + std::to_string(n), m.label + " N", e,
                                   {none_cache.at(n), none_cache.at(2 * n), none_cache.at(4 * n)}));
      }
    } catch (const std::exception& e) {
      report_failure(name + " " + kind + " " + std::to_string(n), e);
      continue;
    }
    print_case_row(name, faces, kind, n, none, c);
    channel_rows.insert(channel_rows.end(), rows.begin(), rows.end());
    cases.push_back(std::move(c));
  }
}

}  // namespace

int main(int argc, char** argv) {
  // As the adaptex programs run (core/allocator.h); ADAPTEX_DEFAULT_MALLOC=1 measures glibc's defaults.
  keep_freed_memory_in_process_unless_disabled();
  Args a;
  try {
    a = parse_args(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adaptex_adapt_quality: error: %s\n", e.what());
    return 2;
  }
  EvalOptions eo;
  eo.samples = a.samples;
  eo.seed = a.eval_seed;
  // Smallest meshes first: early rows come quickly. Each mesh is read (or built) once.
  struct Loaded {
    int faces;
    std::string path;
    TriMesh mesh;
  };
  std::vector<Loaded> order;
  for (const auto& path : a.meshes) {
    try {
      TriMesh m = load_mesh(path);
      order.push_back({m.num_faces(), path, std::move(m)});
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
    }
  }
  std::stable_sort(order.begin(), order.end(), [](const Loaded& x, const Loaded& y) {
    return x.faces != y.faces ? x.faces < y.faces : x.path < y.path;
  });
  std::vector<int> sizes = a.sizes;
  std::sort(sizes.begin(), sizes.end());
  print_header(a);
  std::vector<CaseRecord> cases;
  std::vector<std::string> channel_rows;
  int failed = 0;
  // A case (or a mesh's unwrap) that throws is reported on stderr and skipped; the others still run.
  auto report_failure = [&failed](const std::string& what, const std::exception& e) {
    std::fprintf(stderr, "adaptex_adapt_quality: %s: %s\n", what.c_str(), e.what());
    ++failed;
  };
  for (const Loaded& loaded : order) {
    const int faces = loaded.faces;
    const std::string& path = loaded.path;
    const TriMesh& mesh = loaded.mesh;
    const std::string name = fs::path(path).stem().string();
    UnwrapOptions uo;
    uo.charts = a.charts == "single" ? ChartMode::Single : ChartMode::Auto;
    if (a.probe_first_charts >= 0) uo.probe_first_charts = a.probe_first_charts;
    // The initial layout of each texture size (Args::unwrap_gutter), unwrapped once per size.
    std::map<int, Parameterization> layouts;
    auto layout = [&](int size) -> const Parameterization& {
      const int key = a.unwrap_gutter == "paint" ? size : 0;
      auto it = layouts.find(key);
      if (it == layouts.end())
        it = layouts.emplace(key, unwrap(mesh, key > 0 ? unwrap_options_for_texture(key, PaintSessionOptions{}.padding, uo)
                                                       : uo).param).first;
      return it->second;
    };
    try {
      layout(sizes.front());
    } catch (const std::exception& e) {
      report_failure(name + " (unwrap)", e);
      continue;
    }
    for (const auto& kind : a.kinds) {
      if (is_material_kind(kind)) {
        run_material_kind(a, kind, name, faces, mesh, sizes, layout, cases, channel_rows, report_failure);
        continue;
      }
      GenerateOptions go;
      go.kind = parse_stroke_kind(kind);
      go.count = a.count;
      go.seed = a.seed;
      const StrokeFile strokes = generate_strokes(mesh, go);
      std::map<int, double> none_cache;
      for (int n : sizes) {
        CaseRecord c{kind, 0, {}};
        std::array<double, 3> none{};
        try {
          none = {psnr_none(none_cache, n, mesh, layout(n), strokes, eo),
                  psnr_none(none_cache, 2 * n, mesh, layout(2 * n), strokes, eo),
                  psnr_none(none_cache, 4 * n, mesh, layout(4 * n), strokes, eo)};
          c.none_n = none[0];
          for (const auto& m : a.modes) c.modes.push_back(run_mode(a, m, mesh, layout(n), strokes, n, none, eo));
        } catch (const std::exception& e) {
          report_failure(name + " " + kind + " " + std::to_string(n), e);
          continue;
        }
        print_case_row(name, faces, kind, n, none, c);
        cases.push_back(std::move(c));
      }
    }
  }
  print_summary(a, cases);
  if (!channel_rows.empty()) {
    std::printf("\nChannel cases, PSNR dB per channel (normal: the shading normal from the height; weighted: the "
                "error model's sum, the one ×area uses; (×f): that channel's own texel saving):\n\n| mesh | kind | N | layout | base colour | roughness | "
                "metallic | alpha | normal | weighted |\n|---|---|---:|---|---:|---:|---:|---:|---:|---:|\n");
    for (const auto& row : channel_rows) std::printf("%s\n", row.c_str());
  }
  if (failed > 0) std::fprintf(stderr, "adaptex_adapt_quality: %d case(s) failed (above)\n", failed);
  return failed > 0 ? 1 : 0;
}
