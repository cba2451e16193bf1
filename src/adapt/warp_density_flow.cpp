// `--adapt density-flow`: the texel density that minimizes the reconstruction error for the texel
// budget (error_density.h, from the exact stroke history when there is one), reached by the flow-based
// density-equalizing map (density_flow.h). docs/error_model.md explains the model and the choices.
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <vector>

#include "adaptex/adapt/error_polish.h"
#include "adaptex/adapt/warp_method.h"
#include "adaptex/core/timer.h"

namespace adaptex {

namespace {
class DensityFlowWarp final : public WarpMethod {
 public:
  bool wants_refinement() const override { return true; }

  void compute(const WarpInput& in, AdaptResult& res) const override {
    const AdaptOptions& o = in.options;
    AdaptReport& rep = res.report;
    auto t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "density", 0);
    const ErrorDensityOptions& eo = o.density;
    ErrorDensityReference* cache = in.density_reference;
    const bool cached = in.history && cache && cache->matches(in.mesh, in.param, in.texture.width, eo);
    ErrorDensity ed = in.density   ? *in.density
                      : cached     ? compute_error_density(in.mesh, in.param, in.texture, in.map, *in.history, *cache, eo)
                      : in.history ? compute_error_density(in.mesh, in.param, in.texture, in.map, *in.history, eo)
                                   : compute_error_density(in.mesh, in.param, in.texture, in.map, eo);
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
    const std::vector<UvRect> boxes = o.atlas_flow && in.param.num_charts > 1 ? chart_boxes(in.param) : std::vector<UvRect>{};
    const double gap = boxes.empty() ? 0.0 : smallest_box_gap(boxes);
    std::vector<ChartMove> moves;
    std::vector<GridWarp> lattices;
    FlowWarp flow;  // with o.flow.direct
    if (gap > 0) {
      // Charts in disjoint boxes: re-pack them by density, then one flow per chart rectangle, with
      // the layout's own gutter (atlas_flow.h).
      ChartRepackOptions ro;
      const int texels = std::max(in.texture.width, in.texture.height);
      ro.padding = std::min(std::max(gap, o.chart_gutter_texels / texels), 0.2);
      moves = o.chart_sizes_by_error_model ? allocate_charts_by_error(boxes, res.density, ed.error, ed.exponent, ro)
                                           : repack_charts_by_density(boxes, res.density, ro);
      lattices = chart_flow_warps(moves, res.density, o.flow, 8, &st);
      if (o.flow.direct) flow = chart_flows(moves, res.density, o.flow);
    } else {
      lattices = {density_equalizing_warp(res.density, o.flow, &st)};
      if (o.flow.direct) {
        flow.options = o.flow;
        flow.parts = {FlowWarp::Part{Vec2(0, 0), Vec2(1, 1), std::make_shared<const DensityFlow>(res.density)}};
      }
    }
    rep.flow_tangled_cells = st.tangled_cells;
    rep.flow_inverted_cells = st.inverted_cells;
    rep.flow_steps = st.total_steps;
    rep.flow_advected_points = st.advected_points;
    rep.time_flow = seconds_since(t0);
    if (o.flow.direct) {
      res.warp = std::make_shared<const FlowLayoutWarp>(std::move(flow), std::move(lattices), std::move(moves));
      return;
    }
    polish(o, ed, in.texture, in.warm_start, moves, lattices, res);
    res.warp = std::make_shared<const LatticeWarp>(std::move(lattices), std::move(moves));
  }

 private:
  /// Polishes lattice \p c of \p lattices (coarse to fine, ErrorPolishOptions::prepass_sweeps) with
  /// \p progress; \p cell gets the area of one of its cells in cells of the density raster. With
  /// \p warm (an earlier cycle's result) the polish starts from that cycle's correction
  /// (add_polish_correction()) and runs warm_sweeps; \p warmed says whether it did.
  static ErrorPolishStats polish_lattice(const AdaptOptions& o, const ErrorDensity& ed, const EdgeTensor& edges,
                                         const AdaptResult* warm, const std::vector<ChartMove>& moves,
                                         std::vector<GridWarp>& lattices, AdaptResult& res, size_t c,
                                         const ProgressCallback& progress, double& cell, bool& warmed) {
    GridWarp& g = lattices[c];
    UvRect src{Vec2(0, 0), Vec2(1, 1)};
    double scale = 1, extent = 1;
    if (!moves.empty()) {
      src = moves[c].src, scale = moves[c].scale;
      extent = std::clamp(moves[c].dst().size().maxCoeff(), 1e-9, 1.0);
    }
    if (src.size().minCoeff() <= 0 || g.n < 2) return {};
    ErrorPolishOptions po = o.polish;
    po.progress = progress;
    const int m = polish_cells(g.n, po, extent);
    auto fields = [&](int cells) {
      PolishFields f = polish_fields(ed.error, ed.exponent, res.density, src.lo, src.hi, cells, scale);
      if (o.polish.isotropy < 1) add_edge_directions(f, edges, src.lo, src.hi, o.polish.isotropy);
      return f;
    };
    const PolishFields f = fields(m);
    // The report's figures are the model's on the warp's own lattice: a coarser lattice sampled
    // from a strongly compressed flow starts from far worse cells than the flow's own (genus0
    // `mixed` 128²: 12.4 dB "gained" on the coarse lattice). The gain is reported against the flow's
    // lattice, also when the polish starts from a warm start. Measured on a copy, beside the polish:
    // a lattice's coarsest levels are too small to keep two cores busy.
    const bool own_lattice = m != g.n, measure = own_lattice || warm;
    const GridWarp flow = measure ? g : GridWarp{};
    const ErrorPolishOptions measure_options = po;  // the polish below changes po's sweeps
    PolishFields own;
    double before = -1;
    ErrorPolishStats st;
    tbb::parallel_invoke(
        [&] {
          if (own_lattice) own = fields(g.n);
          if (measure) before = polish_model_error(flow, own_lattice ? own : f, measure_options);
        },
        [&] {
          warmed = warm && add_polish_correction(g, warm->flow_grids[c], warm->warp->lattices()[c]) > 0;
          if (warmed) {
            po.sweeps = po.warm_sweeps;
          } else if (po.prepass_sweeps > 0 && m >= 32) {
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
  /// Each lattice's result does not depend on the others or on the threads.
  /// \p warm: an earlier cycle's result (WarpInput::warm_start) or null; used when it has as many
  /// lattices.
  static void polish(const AdaptOptions& o, const ErrorDensity& ed, const ImageRGBA8& texture, const AdaptResult* warm,
                     const std::vector<ChartMove>& moves, std::vector<GridWarp>& lattices, AdaptResult& res) {
    if (o.polish.sweeps <= 0 || (!moves.empty() && !o.polish.charts)) return;
    res.flow_grids = lattices;
    if (warm && (!warm->warp || warm->warp->lattices().size() != lattices.size() ||
                 warm->flow_grids.size() != lattices.size()))
      warm = nullptr;
    const auto t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "polish", 0);
    const EdgeTensor edges = o.polish.isotropy < 1 ? edge_tensor(texture) : EdgeTensor{};
    // The caller's callback is called by one thread at a time: with one lattice, with its sweeps'
    // fraction; with several, with the fraction of lattices done.
    const ProgressCallback& user = o.polish.progress ? o.polish.progress : o.progress;
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
    std::vector<char> warmed(count, 0);
    auto one = [&](size_t c) {
      bool w = false;
      stats[c] = polish_lattice(o, ed, edges, warm, moves, lattices, res, c, shared, cells[c], w);
      warmed[c] = w;
      ++done;
    };
    if (o.polish.parallel)
      tbb::parallel_for(size_t(0), count, one);
    else
      for (size_t c = 0; c < count; ++c) one(c);
    for (size_t c = 0; c < count; ++c) {  // in chart order: the sums do not depend on the threads
      res.report.polish_sweeps = std::max(res.report.polish_sweeps, stats[c].sweeps);
      res.report.polish_error_before += cells[c] * stats[c].error_before;
      res.report.polish_error_after += cells[c] * stats[c].error_after;
      res.report.polish_warm_lattices += warmed[c];
    }
    report_progress(user, "polish", 1);
    res.report.time_polish = seconds_since(t0);
  }
};
}  // namespace

std::unique_ptr<WarpMethod> make_density_flow_warp() { return std::make_unique<DensityFlowWarp>(); }

}  // namespace adaptex
