#pragma once
/// \file surface.h
/// What the studio paints on: the loaded Model (mesh, its initial layout, picking) and the current
/// Surface (the layout in use, the mesh it belongs to, its canvas), plus the results the background
/// jobs hand back (adaptation maps, fixed-vs-adaptive comparison).
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "adaptex/adapt/grid.h"
#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "backend.h"
#include "ray_caster.h"

namespace adaptex::studio {

/// A loaded mesh and its initial parameterization (the unwrap() result: the fixed baseline, and the
/// layout every re-parameterization starts from).
struct Model {
  std::string path;
  std::shared_ptr<const TriMesh> mesh;
  std::shared_ptr<const Parameterization> initial;
  int unwrap_size = 0, unwrap_padding = 0;  ///< Texture size and padding the initial layout is for.
  /// The artist's base-colour texture when *initial is the model's own UV atlas (the canvas starts
  /// from it); null when the model was unwrapped.
  std::shared_ptr<const ImageRGBA8> base;
  /// Which layout it is, for the status line: "artist's UV atlas", "fresh unwrap" (+ why).
  std::string layout;
  bool unwrap_asked = false;   ///< Opened with LoadRequest::unwrap (a project's "layout": "unwrap").
  double shared_fraction = 0;  ///< The atlas's texels shared by overlapping charts (0 when unwrapped).
  BoundingBox box;
  std::shared_ptr<const RayCaster> caster;  ///< Picking on *mesh.
};

/// The layout in use with its texture. mesh is the model's mesh, or its refinement after a
/// density-flow re-parameterization (same surface, more faces; caster then picks on it).
struct Surface {
  std::shared_ptr<const Model> model;
  std::shared_ptr<const TriMesh> mesh;
  std::shared_ptr<const RayCaster> caster;
  /// Shading normals of a refined mesh (backend.h SessionOutcome::normals); null: vertex_normals(*mesh).
  std::shared_ptr<const std::vector<Vec3>> normals;
  std::shared_ptr<const Parameterization> param;
  /// The texture under the strokes on *param: the artist's (model->base) on the atlas, the artist's
  /// fitted onto an adapted atlas; null: the paper colour.
  std::shared_ptr<const ImageRGBA8> base;
  /// A layered material's textures on *param (the canvas starts from their base colour); null: a
  /// single base-colour history painted on the canvas.
  std::shared_ptr<const MaterialTextures> material;
  std::uint64_t generation = 0;  ///< History generation (material: document generation) the canvas was built for.
  /// Material: the textures and layout are paint_material_history()'s for the generation (what
  /// `adaptex paint` writes), not an each-stroke session's.
  bool settled = false;
  size_t painted = 0;            ///< History strokes painted into the canvas.
  int size = 0;                  ///< Texture width = height.
  std::unique_ptr<Canvas> canvas;  ///< Declared last: destroyed before param / mesh.
};

/// Maps of the last adaptive re-parameterization (Inspect panel).
struct AdaptMaps {
  ImageF importance, stretch, ls2;  ///< Thesis methods (over the initial layout's domain).
  ImageF density;                   ///< density-flow: target texel density (mean 1).
  GridWarp coarse, fine;            ///< Optimized grids (empty when not used).
  bool accepted = true;             ///< false: the safeguard kept the initial layout.
  double damping = 1;
};

/// Fixed vs adaptive parameterization on the same strokes at the same texture size (Inspect panel).
struct Comparison {
  std::shared_ptr<const Parameterization> fixed_param, adaptive_param;
  ImageRGBA8 fixed_texture, adaptive_texture;
  double psnr_fixed = 0, psnr_adaptive = 0;  ///< dB against the exact stroke signal (adaptex eval).
  size_t strokes = 0;
};

/// A canvas rebuilt for one history generation (a background job's result).
struct RebuildResult {
  std::unique_ptr<Surface> surface;
  std::vector<std::pair<std::string, double>> phase_ms;
  std::shared_ptr<const AdaptMaps> maps;  ///< Set when the job re-parameterized.
  std::string note;  ///< What an adaptation of the artist's atlas did, for the status line (else empty).
};

/// The surface of a painting session's outcome on \p model (its mesh or a refinement; the model's own
/// initial layout when not re-parameterized), with its maps and phase times. The caller sets the
/// surface's generation, size and painted.
/// \p caster: picking on o.mesh if already built (else built here when o.mesh is a refinement).
/// The surface of a layered material's outcome \p o on \p model (generation and settled left to the
/// caller): the canvas starts from its base colour. \p caster: picking on o.mesh if already built.
RebuildResult surface_from_material(const std::shared_ptr<const Model>& model, MaterialOutcome o,
                                    const MaterialValue& background, int size, int padding,
                                    std::shared_ptr<const RayCaster> caster = nullptr);

RebuildResult surface_from_session(const std::shared_ptr<const Model>& model, SessionOutcome o,
                                   std::shared_ptr<const RayCaster> caster = nullptr);

}  // namespace adaptex::studio
