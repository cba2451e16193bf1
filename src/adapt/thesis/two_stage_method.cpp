// Thesis §3.8: the two-stage framework (`--adapt two-stage`). A coarse grid gathers points in
// low-signal regions; the fine grid, relaxed in the domain already warped by the coarse stage, spreads
// points around detail. new uv = fine(coarse(old uv)).
#include <algorithm>
#include <chrono>

#include "adaptex/core/timer.h"
#include "thesis_methods.h"

namespace adaptex {

namespace {
class TwoStageMethod final : public AdaptMethod {
 public:
  void compute(const WarpInput& in, AdaptResult& res) override {
    compute_thesis_weights(in, res);
    const AdaptOptions& o = in.options;
    AdaptReport& rep = res.report;
    const RelaxOptions ro = thesis_relax_options(in);
    auto t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "coarse", 0);
    GridWarp coarse = GridWarp::uniform(o.thesis.coarse_grid);
    rep.coarse_iterations = relax_grid(coarse, pool_for_grid(res.ls2, o.thesis.coarse_grid, o.thesis.pool), ro).iterations;
    rep.time_coarse = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "fine", 0);
    // The fine stage's weight field is the L_s² of the content now at each place (pulled back through
    // the coarse warp). It only refines locally (thesis Fig. 3.13): capped at fine_max_iterations.
    const ImageF pooled = pool_for_grid(res.ls2, o.thesis.fine_grid, o.thesis.pool);
    const ImageF field = pull_back_field(pooled, coarse, std::max(pooled.width, pooled.height));
    GridWarp fine = GridWarp::uniform(o.thesis.fine_grid);
    RelaxOptions fo = ro;
    fo.max_iterations = o.thesis.fine_max_iterations;
    rep.fine_iterations = relax_grid(fine, field, fo).iterations;
    rep.time_fine = seconds_since(t0);
    std::vector<GridWarp> lattices;
    lattices.push_back(std::move(coarse));
    lattices.push_back(std::move(fine));
    res.warp = std::make_shared<const LatticeWarp>(std::move(lattices));
  }
};
}  // namespace

std::unique_ptr<AdaptMethod> make_two_stage_method() { return std::make_unique<TwoStageMethod>(); }

}  // namespace adaptex
