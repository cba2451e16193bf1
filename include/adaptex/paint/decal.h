#pragma once
/// \file decal.h
/// Decal strokes (thesis Figs. 4.6, 4.7: "an image is texture mapped to simulate painting strokes"):
/// an RGBA image projected from a pinhole camera onto the part of the surface the camera sees.
/// The exact definition (camera model, projection, sampling, visibility rule) is docs/decals.md.
///
/// Visibility is winding-independent (meshes may be wound clockwise): a surface point p is seen iff
/// nothing lies on the segment eye -> p before p (an Embree occlusion ray that stops a relative
/// epsilon short of p). On a closed mesh this also removes every back-facing point, because the
/// front surface is always in front of it.
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/strokes.h"
#include "adaptex/paint/texel_map.h"

namespace adaptex {

/// Relative epsilon of the decal visibility ray: occluders closer than (1 - kDecalRayEpsilon) * |p - eye|
/// hide p; anything nearer to p than that (p's own face, its neighbours at a shared edge) does not.
inline constexpr double kDecalRayEpsilon = 1e-4;

/// The orthonormal frame and projection of a DecalCamera (see docs/decals.md).
struct DecalFrame {
  Vec3 eye;           ///< Camera centre.
  Vec3 forward;       ///< Unit viewing direction, normalize(target - eye).
  Vec3 right;         ///< Unit, normalize(forward x up): image u grows along it.
  Vec3 up;            ///< Unit, right x forward: image v grows along it.
  double tan_half_y;  ///< tan(fov_y / 2).
  double tan_half_x;  ///< aspect * tan(fov_y / 2).

  /// Image coordinates (u, v) of p, each in [0,1] inside the frustum (v = 0 is the image's bottom
  /// row), and the depth along forward. \return false if p is not strictly in front of the eye.
  bool project(const Vec3& p, Vec2& uv, double& depth) const;
};

/// Builds the frame of \p camera.
/// \throw InvalidInputError non-finite values, eye == target, up parallel to the viewing direction,
///        fov_y outside (0, 180) degrees or aspect <= 0. \p where prefixes the message (e.g.
///        "strokes.json: stroke 3").
DecalFrame decal_frame(const DecalCamera& camera, const std::string& where = "decal");

/// Samples a decal image at (u, v) in [0,1]^2 (v = 0 bottom row): bilinear with clamp-to-edge,
/// texel centres at ((i+0.5)/W, (j+0.5)/H), on alpha-weighted colour (so fully transparent texels
/// add no colour). \return (r, g, b, a) in [0,1]; rgb is the straight (un-premultiplied) colour.
/// \pre !image.empty()
Eigen::Vector4d sample_decal_image(const ImageRGBA8& image, double u, double v);

/// Projects decal strokes onto one mesh. Holds an Embree 3 BVH of the mesh (built once in the
/// constructor, O(F log F)); queries are thread-safe and may run in parallel.
class DecalProjector {
 public:
  /// \pre mesh has valid indices. The mesh is copied into the BVH: it need not outlive the projector.
  /// \throw InvalidInputError mesh without faces; Error if Embree fails
  explicit DecalProjector(const TriMesh& mesh);
  ~DecalProjector();
  DecalProjector(DecalProjector&&) noexcept;
  DecalProjector& operator=(DecalProjector&&) noexcept;

  /// Decal colour and coverage at surface point p on face \p face: (r, g, b, alpha) with rgb the
  /// straight image colour in [0,1] and alpha = image alpha * opacity, when p is inside the camera
  /// frustum and visible from the eye (see the file comment); else (0, 0, 0, 0).
  /// Composite as C <- C (1 - alpha) + rgb alpha.
  /// \pre decal.type == Stroke::Type::Decal (a brush stroke returns zero)
  /// \throw InvalidInputError invalid camera (see decal_frame) or empty image
  Eigen::Vector4d evaluate(const Stroke& decal, const Vec3& p, int face) const;

  /// Batch form of evaluate() (parallel): out[k] = evaluate(decal, points[k], faces[k]).
  /// \pre points.size() == faces.size() == out.size()
  void evaluate(const Stroke& decal, std::span<const Vec3> points, std::span<const int> faces,
                std::span<Eigen::Vector4d> out) const;

  /// Evaluates the decal at every chart texel of \p map (parallel): out[k] belongs to texel
  /// map.inside[k]; out is resized to map.inside.size().
  void evaluate_texels(const Stroke& decal, const TexelMap& map,
                       std::vector<Eigen::Vector4f>& out) const;

  /// True iff nothing hides surface point p from \p eye (the visibility rule above).
  bool visible(const Vec3& eye, const Vec3& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace adaptex
