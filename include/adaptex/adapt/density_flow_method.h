#pragma once
/// \file density_flow_method.h
/// `density-flow`, the default method: the texel density that minimizes the reconstruction error for
/// the texel budget (error_density.h, from the exact stroke history when there is one), reached by
/// the flow-based density-equalizing map (density_flow.h; one flow per re-packed chart on atlases,
/// atlas_flow.h) and polished by the anisotropic error model (error_polish.h). docs/error_model.md.
#include <memory>
#include <optional>
#include <vector>

#include "adaptex/adapt/error_density.h"
#include "adaptex/adapt/method.h"

namespace adaptex {

/// The density-flow solver of a session. With a fixed layout (fix_layout()) it keeps the history's
/// signal on that layout (ErrorDensityReference), updated stroke by stroke, so the model's cost does
/// not grow with the history; predict_gain()'s model is reused by the compute() that follows; and
/// with WarpInput::warm the polish starts from the previous compute()'s.
class DensityFlowMethod final : public AdaptMethod {
 public:
  DensityFlowMethod();
  ~DensityFlowMethod() override;
  void compute(const WarpInput& input, AdaptResult& result) override;
  bool wants_refinement() const override { return true; }
  void fix_layout(const TriMesh& mesh, const Parameterization& layout, int texture_size,
                  const Vec3& background) override;
  void update(const StrokeFile& history, const AdaptOptions& options) override;
  /// The error model for the history on the fixed layout, its least error and the held layout's
  /// (predicted_error()); nothing without a fixed layout or strokes.
  std::optional<GainModel> predict_gain(const WarpInput& input) override;
  void hold(const AdaptResult* result) override;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace adaptex
