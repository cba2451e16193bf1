#pragma once
/// \file method.h
/// The seam between the adaptation (adapt.h, session.h) and the methods that warp the square. A method
/// is a solver created once per session. Adding one: a class derived from AdaptMethod in its own
/// folder, and one line
///   register_adapt_method({"name", "one-line description", [] { return std::make_unique<M>(); }});
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adaptex/adapt/adapt.h"
#include "adaptex/paint/strokes.h"

namespace adaptex {

struct ErrorDensity;

/// Everything a method may read for one cycle.
struct WarpInput {
  const TriMesh& mesh;
  const Parameterization& param;  ///< Current layout (the warp maps its UV square).
  const ImageRGBA8& texture;      ///< Current texture, drawn with param.
  const TexelMap& map;            ///< Texel map of param at the texture's size.
  const StrokeFile* history;      ///< Exact stroke history, or nullptr (texture only).
  const AdaptOptions& options;
  /// A precomputed error model (a layered material's, error_density.h), used instead of the history's
  /// or the texture's by the methods that have one (density-flow); null: none.
  const ErrorDensity* model = nullptr;
};

/// What a method's model predicts before it computes a warp (the gate of each-stroke sessions).
struct GainModel {
  double least_error = 0;        ///< The model's error for the history at its best layout.
  double held_error = 0;         ///< The model's error for the history at the held layout (hold()).
  double signal_fraction = 0;    ///< As AdaptReport::signal_fraction.
  double predicted_gain_db = 0;  ///< As AdaptReport::predicted_gain_db.
};

/// A re-parameterization method: computes the warp of [0,1]² (a homeomorphism keeping the square).
class AdaptMethod {
 public:
  virtual ~AdaptMethod() = default;
  /// Sets result.warp, the maps it used and its report fields; not result.param.
  /// \throw InvalidInputError bad options \throw CancelledError the progress callback returned false
  virtual void compute(const WarpInput& input, AdaptResult& result) = 0;
  virtual bool wants_refinement() const { return false; }  ///< The warp varies faster than triangles.
  /// Every later cycle starts from \p layout of \p mesh (both outlive the method); caches may use them.
  virtual void fix_layout(const TriMesh& /*mesh*/, const Parameterization& /*layout*/, int /*texture_size*/,
                          const Vec3& /*background*/) {}
  virtual void update(const StrokeFile& /*history*/, const AdaptOptions& /*options*/) {}  ///< History grew.
  /// The model's prediction for \p input (after fix_layout()), or nothing without a model.
  virtual std::optional<GainModel> predict_gain(const WarpInput& /*input*/) { return std::nullopt; }
  virtual void hold(const AdaptResult* /*result*/) {}  ///< The held layout (null: fix_layout()'s).
};

/// A registered method.
struct AdaptMethodInfo {
  std::string name;         ///< Command-line name (`--adapt NAME`).
  std::string description;  ///< One line for help texts and the studio.
  std::function<std::unique_ptr<AdaptMethod>()> make;  ///< A new solver; null for `none`.
};

/// Registers a method. \throw InvalidInputError empty or taken name, or no factory
void register_adapt_method(AdaptMethodInfo info);
/// Every registered method, `none` first, then the built-in ones, then in registration order.
std::vector<const AdaptMethodInfo*> adapt_methods();
/// The registered method \p mode names, or nullptr.
const AdaptMethodInfo* find_adapt_method(AdaptMode mode);
/// A new solver of \p mode. \throw InvalidInputError `none` or an unknown name
std::unique_ptr<AdaptMethod> make_adapt_method(AdaptMode mode);

/// adapt_parameterization() with a session's solver \p method (of \p input.options.mode).
/// \throw as adapt_parameterization()
AdaptResult adapt_with(AdaptMethod& method, const WarpInput& input);

}  // namespace adaptex
