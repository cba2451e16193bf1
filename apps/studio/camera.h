#pragma once
/// \file camera.h
/// Orbit camera of adaptex-studio: a target point, a distance and two angles. Pure math (no GL), so
/// picking, framing and the decal camera are unit-testable.
#include <Eigen/Core>

#include "adaptex/core/types.h"
#include "adaptex/paint/strokes.h"

namespace adaptex::studio {

/// A ray in world space (unit direction).
struct Ray {
  Vec3 origin = Vec3::Zero();
  Vec3 dir = Vec3(0, 0, -1);
};

/// Orbit camera: eye = target + distance * (cos p sin y, sin p, cos p cos y), world up = +Y.
struct Camera {
  Vec3 target = Vec3::Zero();
  double distance = 3.0;
  double yaw = 0.0;    ///< Radians, rotation about +Y (0 = looking down -Z).
  double pitch = 0.0;  ///< Radians, clamped to (-pi/2, pi/2).
  double fov_y_degrees = 40.0;
  int width = 1280, height = 800;  ///< Viewport in pixels.
  double scene_radius = 1.0;       ///< Radius of the framed model (sets the clip planes).

  Vec3 eye() const;
  Vec3 forward() const;  ///< Unit view direction.
  Vec3 right() const;    ///< Unit screen-right direction.
  Vec3 up() const;       ///< Unit screen-up direction.
  double aspect() const { return height > 0 ? double(width) / height : 1.0; }
  double near_plane() const;
  double far_plane() const;

  /// Column-major 4x4 matrices (OpenGL conventions).
  Eigen::Matrix4f view_matrix() const;
  Eigen::Matrix4f projection_matrix() const;
  Eigen::Matrix4d view_matrix_d() const;
  Eigen::Matrix4d projection_matrix_d() const;

  /// Ray through window pixel (x, y), origin at the top-left corner of the window, y down.
  Ray pixel_ray(double x, double y) const;
  /// Window coordinates (x right, y down) of a world point; z = NDC depth. Behind the eye: z > 1.
  Vec3 project(const Vec3& p) const;

  /// Rotates by pixel deltas (0.01 rad per pixel).
  void orbit(double dx_pixels, double dy_pixels);
  /// Moves the target so the model follows the cursor by (dx, dy) pixels at the target's depth.
  void pan(double dx_pixels, double dy_pixels);
  /// Wheel zoom: distance *= 0.85^steps (steps > 0 zooms in).
  void zoom(double steps);
  /// Wheel zoom towards \p p: the view scales about \p p, which stays at the same pixel.
  void zoom_towards(double steps, const Vec3& p);
  /// The point under window pixel (x, y) at the depth of the target.
  Vec3 point_at_target_depth(double x, double y) const;
  /// Frames a bounding box: target at its centre, the whole box visible.
  void frame(const BoundingBox& box);

  /// World length of one window pixel at the depth of \p p (along the view direction).
  double pixel_size_at(const Vec3& p) const;

  /// The decal camera equal to this view (eye, target, up, fov, aspect).
  DecalCamera decal_camera() const;
};

}  // namespace adaptex::studio
