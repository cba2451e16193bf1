// `--adapt density-flow` (density_flow_method.h). docs/error_model.md explains the model and the
// choices.
#include "adaptex/adapt/density_flow_method.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

#include "adaptex/adapt/error_polish.h"
#include "adaptex/core/timer.h"

namespace adaptex {

namespace {
/// \p density (mean 1) of a warp applied with blend factor \p t: ρ^t, scaled to mean 1 again (the
/// warp's Jacobian determinant interpolated geometrically; t = 0: the unwarped layout, empty).
ImageF damped_density(const ImageF& density, double t) {
  if (t <= 0 || density.data.empty()) return ImageF{};
  if (t == 1.0) return density;
  ImageF d = density;
  double sum = 0;
  for (float& v : d.data) sum += (v = static_cast<float>(std::pow(v, t)));
  for (float& v : d.data) v = static_cast<float>(v * d.data.size() / sum);
  return d;
}
}  // namespace

struct DensityFlowMethod::State {
  void compute(const WarpInput& in, AdaptResult& res) {
    const AdaptOptions& o = in.options;
    AdaptReport& rep = res.report;
    auto t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "density", 0);
    ErrorDensity ed = error_model(in);
    rep.signal_fraction = ed.signal_fraction;
    rep.predicted_gain_db = ed.predicted_gain_db;
    // The error map, scaled to [0,1], is what the studio and the debug maps show as "importance".
    float top = 0;
    for (float v : ed.error.data) top = std::max(top, v);
    res.importance = ed.error;
    if (top > 0)
      for (float& v : res.importance.data) v /= top;
    res.density = std::move(ed.density);
    rep.time_density = seconds_since(t0);

    t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "flow", 0);
    DensityFlowStats st;
    const std::vector<UvRect> boxes = in.param.num_charts > 1 ? chart_boxes(in.param) : std::vector<UvRect>{};
    const double gap = boxes.empty() ? 0.0 : smallest_box_gap(boxes);
    std::vector<ChartMove> moves;
    std::vector<GridWarp> lattices;
    if (gap > 0) {
      // Charts in disjoint boxes: re-pack them by density, then one flow per chart rectangle, with
      // the layout's own gutter (atlas_flow.h).
      ChartRepackOptions ro;
      const int texels = std::max(in.texture.width, in.texture.height);
      ro.padding = std::min(std::max(gap, o.density_flow.chart_gutter_texels / texels), 0.2);
      moves = allocate_charts_by_error(boxes, res.density, ed.error, ed.exponent, ro);
      lattices = chart_flow_warps(moves, res.density, o.density_flow.flow, 8, &st);
    } else {
      lattices = {density_equalizing_warp(res.density, o.density_flow.flow, &st)};
    }
    rep.flow_tangled_cells = st.tangled_cells;
    rep.flow_inverted_cells = st.inverted_cells;
    rep.flow_steps = st.total_steps;
    rep.flow_advected_points = st.advected_points;
    rep.time_flow = seconds_since(t0);
    polish(o, ed, in.texture, moves, lattices, res, edges);
    res.warp = std::make_shared<const LatticeWarp>(std::move(lattices), std::move(moves));
  }

  /// The error model of \p in: predict_gain()'s when it was computed for this input, else through
  /// the reference when it applies, else from the history or the texture alone.
  ErrorDensity error_model(const WarpInput& in) {
    if (in.model) return *in.model;
    const ErrorDensityOptions& eo = in.options.density_flow.density;
    ErrorDensityReference* cache = in.history ? reference_now(*in.history, in.options) : nullptr;
    if (model && in.history && model_strokes == in.history->strokes.size() && fixed && &in.param == fixed->layout) {
      ErrorDensity ed = std::move(*model);
      model.reset();
      return ed;
    }
    model.reset();
    const bool cached = cache && cache->matches(in.mesh, in.param, in.texture.width, eo);
    return cached       ? compute_error_density(in.mesh, in.param, in.texture, in.map, *in.history, *cache, eo)
           : in.history ? compute_error_density(in.mesh, in.param, in.texture, in.map, *in.history, eo)
                        : compute_error_density(in.mesh, in.param, in.texture, in.map, eo);
  }

  /// The history's signal on the fixed layout, built on first use and brought up to date; null
  /// without a fixed layout.
  ErrorDensityReference* reference_now(const StrokeFile& history, const AdaptOptions& o) {
    if (!fixed) return nullptr;
    if (!reference)
      reference = std::make_unique<ErrorDensityReference>(*fixed->mesh, *fixed->layout, fixed->texture_size,
                                                          fixed->background, o.density_flow.density);
    reference->update(history);
    return reference.get();
  }

  struct Fixed {
    const TriMesh* mesh;
    const Parameterization* layout;
    int texture_size;
    Vec3 background;
  };
  std::optional<Fixed> fixed;                       // fix_layout()
  std::unique_ptr<ErrorDensityReference> reference;  // the history's signal on fixed->layout
  std::optional<ErrorDensity> model;                 // predict_gain()'s, for the next compute()
  size_t model_strokes = 0;                          // the history's length it saw
  ImageF held_density;                               // hold(): the held layout's density, empty: fixed
  EdgeTensor edges;  // the polish's, its storage kept between cycles (no fresh pages: docs/benchmarks.md)

  /// Polishes lattice \p c of \p lattices (coarse to fine, ErrorPolishOptions::prepass_sweeps) with
  /// \p progress; \p cell gets the area of one of its cells in cells of the density raster.
  static ErrorPolishStats polish_lattice(const AdaptOptions& o, const ErrorDensity& ed, const EdgeTensor& edges,
                                         const std::vector<ChartMove>& moves, std::vector<GridWarp>& lattices,
                                         AdaptResult& res, size_t c, const ProgressCallback& progress,
                                         double& cell) {
    GridWarp& g = lattices[c];
    UvRect src{Vec2(0, 0), Vec2(1, 1)};
    double scale = 1, extent = 1;
    if (!moves.empty()) {
      src = moves[c].src, scale = moves[c].scale;
      extent = std::clamp(moves[c].dst().size().maxCoeff(), 1e-9, 1.0);
    }
    if (src.size().minCoeff() <= 0 || g.n < 2) return {};
    ErrorPolishOptions po = o.density_flow.polish;
    po.progress = progress;
    const int m = polish_cells(g.n, po, extent);
    auto fields = [&](int cells) {
      PolishFields f = polish_fields(ed.error, ed.exponent, res.density, src.lo, src.hi, cells, scale);
      if (o.density_flow.polish.isotropy < 1) add_edge_directions(f, edges, src.lo, src.hi, o.density_flow.polish.isotropy);
      return f;
    };
    const PolishFields f = fields(m);
    // The report's figures are the model's on the warp's own lattice: a coarser lattice sampled
    // from a strongly compressed flow starts from far worse cells than the flow's own (genus0
    // `mixed` 128²: 12.4 dB "gained" on the coarse lattice). The gain is reported against the flow's
    // lattice. Measured on a copy, beside the polish: a lattice's coarsest levels are too small to
    // keep two cores busy.
    const bool own_lattice = m != g.n;
    const GridWarp flow = own_lattice ? g : GridWarp{};
    const ErrorPolishOptions measure_options = po;  // the polish below changes po's sweeps
    PolishFields own;
    double before = -1;
    ErrorPolishStats st;
    tbb::parallel_invoke(
        [&] {
          if (own_lattice) own = fields(g.n);
          if (own_lattice) before = polish_model_error(flow, own, measure_options);
        },
        [&] {
          if (po.prepass_sweeps > 0 && m >= 32) {
            // Coarse to fine (ErrorPolishOptions::prepass_sweeps, prepass_levels): the coarsest
            // lattice of at least 16 cells first, then each finer one.
            int levels = 1;
            while (levels < po.prepass_levels && (m >> (levels + 1)) >= 16) ++levels;
            for (int level = levels; level >= 1; --level) {
              ErrorPolishOptions pre = po;
              pre.sweeps = level == levels ? po.prepass_sweeps : po.sweeps_after_prepass;
              polish_warp(g, fields(m >> level), pre);
            }
            po.sweeps = po.sweeps_after_prepass;
          }
          st = polish_warp(g, f, po);
        });
    if (before >= 0) st.error_before = before;
    if (own_lattice) st.error_after = polish_model_error(g, own, po);
    // In cells of the density raster: a lattice cell covers area(src) / n² of the square.
    cell = src.area() / (double(g.n) * g.n) * ed.error.width * ed.error.width;
    return st;
  }

  /// Every flow lattice polished by the anisotropic error model (error_polish.h). The charts' lattices
  /// are polished in parallel (each polish is also parallel inside): an atlas has many small lattices
  /// whose own sweeps cannot keep two cores busy (armadillo, 1024²: 15 charts of 16–55 polish cells).
  /// Each lattice's result does not depend on the others or on the threads. \p edges: storage for the
  /// texture's edge tensor.
  static void polish(const AdaptOptions& o, const ErrorDensity& ed, const ImageRGBA8& texture,
                     const std::vector<ChartMove>& moves, std::vector<GridWarp>& lattices, AdaptResult& res,
                     EdgeTensor& edges) {
    if (o.density_flow.polish.sweeps <= 0 || (!moves.empty() && !o.density_flow.polish.charts)) return;
    const auto t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "polish", 0);
    if (o.density_flow.polish.isotropy < 1) edge_tensor(texture, edges);  // else not read
    // The caller's callback is called by one thread at a time: with one lattice, with its sweeps'
    // fraction; with several, with the fraction of lattices done.
    const ProgressCallback& user = o.density_flow.polish.progress ? o.density_flow.polish.progress : o.progress;
    std::mutex progress_mutex;
    std::atomic<size_t> done{0};
    const size_t count = lattices.size();
    ProgressCallback shared;
    if (user && count == 1)
      shared = user;
    else if (user)
      shared = [&](std::string_view phase, double) {
        const std::lock_guard<std::mutex> lock(progress_mutex);
        return user(phase, double(done.load()) / double(count));
      };
    std::vector<ErrorPolishStats> stats(count);
    std::vector<double> cells(count, 0.0);
    auto one = [&](size_t c) {
      stats[c] = polish_lattice(o, ed, edges, moves, lattices, res, c, shared, cells[c]);
      ++done;
    };
    if (o.density_flow.polish.parallel)
      tbb::parallel_for(size_t(0), count, one);
    else
      for (size_t c = 0; c < count; ++c) one(c);
    for (size_t c = 0; c < count; ++c) {  // in chart order: the sums do not depend on the threads
      res.report.polish_sweeps = std::max(res.report.polish_sweeps, stats[c].sweeps);
      res.report.polish_error_before += cells[c] * stats[c].error_before;
      res.report.polish_error_after += cells[c] * stats[c].error_after;
    }
    report_progress(user, "polish", 1);
    res.report.time_polish = seconds_since(t0);
  }
};

DensityFlowMethod::DensityFlowMethod() : s_(std::make_unique<State>()) {}
DensityFlowMethod::~DensityFlowMethod() = default;

void DensityFlowMethod::compute(const WarpInput& input, AdaptResult& result) { s_->compute(input, result); }

void DensityFlowMethod::fix_layout(const TriMesh& mesh, const Parameterization& layout, int texture_size,
                                   const Vec3& background) {
  s_->fixed = State::Fixed{&mesh, &layout, texture_size, background};
  s_->reference.reset();
}

void DensityFlowMethod::update(const StrokeFile& history, const AdaptOptions& options) {
  s_->reference_now(history, options);
}

std::optional<GainModel> DensityFlowMethod::predict_gain(const WarpInput& in) {
  if (!in.history || in.history->strokes.empty()) return std::nullopt;
  ErrorDensityReference* ref = s_->reference_now(*in.history, in.options);
  if (!ref) return std::nullopt;
  s_->model = compute_error_density(in.mesh, in.param, in.texture, in.map, *in.history, *ref, in.options.density_flow.density);
  s_->model_strokes = in.history->strokes.size();
  const ErrorDensity& m = *s_->model;
  GainModel g;
  g.least_error = predicted_error(m, m.density);
  g.held_error = predicted_error(m, s_->held_density);
  g.signal_fraction = m.signal_fraction;
  g.predicted_gain_db = m.predicted_gain_db;
  return g;
}

void DensityFlowMethod::hold(const AdaptResult* result) {
  s_->held_density = result ? damped_density(result->density, result->report.damping) : ImageF{};
}

}  // namespace adaptex
