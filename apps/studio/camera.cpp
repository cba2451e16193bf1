/// \file camera.cpp
/// Orbit camera math (see camera.h).
#include "camera.h"

#include <algorithm>
#include <cmath>

namespace adaptex::studio {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

Vec3 Camera::eye() const {
  return target + distance * Vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                   std::cos(pitch) * std::cos(yaw));
}
Vec3 Camera::forward() const { return (target - eye()).normalized(); }
Vec3 Camera::right() const { return Vec3(std::cos(yaw), 0.0, -std::sin(yaw)); }
Vec3 Camera::up() const { return right().cross(forward()).normalized(); }
double Camera::near_plane() const { return std::max(1e-6, std::max(distance - 2.0 * scene_radius, distance * 0.01)); }
double Camera::far_plane() const { return distance + 4.0 * scene_radius; }

Eigen::Matrix4d Camera::view_matrix_d() const {
  const Vec3 f = forward(), r = right(), u = up(), e = eye();
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = r.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -r.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m;
}
Eigen::Matrix4f Camera::view_matrix() const { return view_matrix_d().cast<float>(); }

Eigen::Matrix4d Camera::projection_matrix_d() const {
  const double n = near_plane(), fa = far_plane();
  const double t = 1.0 / std::tan(fov_y_degrees * kPi / 360.0);
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  p(0, 0) = t / aspect();
  p(1, 1) = t;
  p(2, 2) = -(fa + n) / (fa - n);
  p(2, 3) = -2.0 * fa * n / (fa - n);
  p(3, 2) = -1.0;
  return p;
}
Eigen::Matrix4f Camera::projection_matrix() const { return projection_matrix_d().cast<float>(); }

Ray Camera::pixel_ray(double x, double y) const {
  const double th = std::tan(fov_y_degrees * kPi / 360.0);
  const double nx = (2.0 * x / std::max(1, width) - 1.0) * th * aspect();
  const double ny = (1.0 - 2.0 * y / std::max(1, height)) * th;
  Ray r;
  r.origin = eye();
  r.dir = (forward() + nx * right() + ny * up()).normalized();
  return r;
}

Vec3 Camera::project(const Vec3& p) const {
  const Eigen::Vector4d c = (projection_matrix_d() * view_matrix_d()) *
                            Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
  if (c.w() <= 0) return Vec3(0, 0, 2);
  const Vec3 ndc = c.head<3>() / c.w();
  return Vec3((ndc.x() + 1.0) * 0.5 * width, (1.0 - ndc.y()) * 0.5 * height, ndc.z());
}

void Camera::orbit(double dx, double dy) {
  yaw -= dx * 0.01;
  pitch = std::clamp(pitch + dy * 0.01, -kPi / 2 + 0.01, kPi / 2 - 0.01);
}

void Camera::pan(double dx, double dy) {
  const double units_per_pixel = 2.0 * distance * std::tan(fov_y_degrees * kPi / 360.0) / std::max(1, height);
  target += (-dx * right() + dy * up()) * units_per_pixel;
}

void Camera::zoom(double steps) {
  distance = std::clamp(distance * std::pow(0.85, steps), scene_radius * 0.02, scene_radius * 100.0);
}

void Camera::zoom_towards(double steps, const Vec3& p) {
  const double before = distance;
  zoom(steps);
  target = p + (target - p) * (distance / before);  // eye - p scales by the same factor
}

Vec3 Camera::point_at_target_depth(double x, double y) const {
  const Ray r = pixel_ray(x, y);
  return r.origin + r.dir * (distance / std::max(1e-12, r.dir.dot(forward())));
}

void Camera::frame(const BoundingBox& box) {
  target = 0.5 * (box.min + box.max);
  scene_radius = std::max(1e-9, 0.5 * box.diagonal());
  const double half = std::min(fov_y_degrees, fov_y_degrees * aspect()) * kPi / 360.0;
  distance = scene_radius / std::sin(half) * 1.05;
}

double Camera::pixel_size_at(const Vec3& p) const {
  const double depth = std::max((p - eye()).dot(forward()), near_plane());
  return 2.0 * depth * std::tan(fov_y_degrees * 3.14159265358979 / 360.0) / std::max(1, height);
}

DecalCamera Camera::decal_camera() const {
  DecalCamera d;
  d.eye = eye();
  d.target = target;
  d.up = up();
  d.fov_y_degrees = fov_y_degrees;
  d.aspect = aspect();
  return d;
}

}  // namespace adaptex::studio
