#pragma once
/// \file density_flow_method.h
/// `density-flow`, the default method: error-model density (error_density.h), flow map per chart
/// (density_flow.h, atlas_flow.h), polish (error_polish.h). docs/error_model.md.
#include <memory>
#include <optional>
#include <vector>

#include "adaptex/adapt/error_density.h"
#include "adaptex/adapt/method.h"

namespace adaptex {

/// The density-flow solver of a session: with a fixed layout it keeps the history's signal there
/// (ErrorDensityReference), so the model's cost does not grow with the history.
class DensityFlowMethod final : public AdaptMethod {
 public:
  DensityFlowMethod();
  ~DensityFlowMethod() override;
  void compute(const WarpInput& input, AdaptResult& result) override;
  bool wants_refinement() const override { return true; }
  void fix_layout(const TriMesh& mesh, const Parameterization& layout, int texture_size,
                  const Vec3& background) override;
  void update(const StrokeFile& history, const AdaptOptions& options) override;
  /// The error model on the fixed layout (nothing without one or without strokes).
  std::optional<GainModel> predict_gain(const WarpInput& input) override;
  void hold(const AdaptResult* result) override;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace adaptex
