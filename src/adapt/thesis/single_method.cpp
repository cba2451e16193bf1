// Thesis §3.7: one relaxed grid on the L_s² of §3.5–§3.6 (`--adapt single`).
#include <chrono>

#include "adaptex/core/timer.h"
#include "thesis_methods.h"

namespace adaptex {

namespace {
class SingleMethod final : public AdaptMethod {
 public:
  void compute(const WarpInput& in, AdaptResult& res) override {
    compute_thesis_weights(in, res);
    const AdaptOptions& o = in.options;
    const auto t0 = std::chrono::steady_clock::now();
    report_progress(o.progress, "fine", 0);
    GridWarp fine = GridWarp::uniform(o.thesis.fine_grid);
    res.report.fine_iterations =
        relax_grid(fine, pool_for_grid(res.ls2, o.thesis.fine_grid, o.thesis.pool), thesis_relax_options(in)).iterations;
    std::vector<GridWarp> lattices;
    lattices.push_back(std::move(fine));
    res.warp = std::make_shared<const LatticeWarp>(std::move(lattices));
    res.report.time_fine = seconds_since(t0);
  }
};
}  // namespace

std::unique_ptr<AdaptMethod> make_single_method() { return std::make_unique<SingleMethod>(); }

}  // namespace adaptex
