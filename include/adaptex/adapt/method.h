#pragma once
/// \file method.h
/// The seam between the adaptation (adapt.h, session.h) and the methods that compute a warp of the
/// square. A method is a solver created once per session: it may keep what it derives from a fixed
/// layout and the stroke history between cycles (caches, the previous cycle's result). Refinement,
/// the remap, the safeguards, the texture update, the CLI, Python and the studio are the same for
/// every method. Built-in methods: `single` and `two-stage` (thesis §3.7 / §3.8, src/adapt/thesis/)
/// and `density-flow` (the default, src/adapt/density_flow/).
///
/// Adding a method: a class derived from AdaptMethod in its own folder, and one line
///   register_adapt_method({"name", "one-line description", [] { return std::make_unique<M>(); }});
/// (in builtin_methods() for a library method; anywhere before use for an application's or a test's).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adaptex/adapt/adapt.h"
#include "adaptex/paint/strokes.h"

namespace adaptex {

/// Everything a method may read for one cycle.
struct WarpInput {
  const TriMesh& mesh;
  const Parameterization& param;  ///< Current layout (the warp maps its UV square).
  const ImageRGBA8& texture;      ///< Current texture, drawn with param.
  const TexelMap& map;            ///< Texel map of param at the texture's size.
  const StrokeFile* history;      ///< Exact stroke history, or nullptr (texture only).
  const AdaptOptions& options;
  /// The cycle may start from the method's previous result (a painting session's cycle after a
  /// stroke, PaintSessionOptions::warm_start); the result then depends on that cycle too.
  bool warm = false;
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
  /// Sets result.warp (uv_warp.h), the maps the method used (result.importance, stretch, ls2,
  /// density: whichever apply) and its report fields (times, iterations, signal_fraction). Must not
  /// touch result.param. \throw InvalidInputError bad options \throw CancelledError progress
  /// callback returned false
  virtual void compute(const WarpInput& input, AdaptResult& result) = 0;
  /// True if the warp varies faster than a typical mesh's triangles (the remap should refine).
  virtual bool wants_refinement() const { return false; }
  /// Every later cycle starts from \p layout of \p mesh at \p texture_size texels (each-stroke
  /// sessions); both outlive the method. It may cache what it derives from them and the history.
  virtual void fix_layout(const TriMesh& /*mesh*/, const Parameterization& /*layout*/, int /*texture_size*/,
                          const Vec3& /*background*/) {}
  /// The history grew (after fix_layout()): bring caches up to date now, O(new strokes).
  virtual void update(const StrokeFile& /*history*/, const AdaptOptions& /*options*/) {}
  /// The model's prediction for \p input (after fix_layout(); its layout), or nothing when the
  /// method has no model for it. A compute() of the same input may reuse what this computed.
  virtual std::optional<GainModel> predict_gain(const WarpInput& /*input*/) { return std::nullopt; }
  /// The layout now held is \p result's warp damped to result.report.damping (null: the layout of
  /// fix_layout() itself); GainModel::held_error refers to it.
  virtual void hold(const AdaptResult* /*result*/) {}
};

/// A registered method.
struct AdaptMethodInfo {
  std::string name;         ///< Command-line name (`--adapt NAME`).
  std::string description;  ///< One line for help texts and the studio.
  /// A new solver; null for `none`.
  std::function<std::unique_ptr<AdaptMethod>()> make;
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
