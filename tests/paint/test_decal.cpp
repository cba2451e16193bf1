// Decal projection (docs/decals.md): the camera model and image orientation, the depth test against
// the mesh (hidden surfaces stay unpainted), back-facing and out-of-frustum points, opacity and
// alpha-weighted sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <vector>
#include <random>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/paint/decal.h"
#include "adaptex/paint/ray_scene.h"

using namespace adaptex;

namespace {

/// Appends \p b (translated by \p offset) to \p a.
TriMesh merge(TriMesh a, const TriMesh& b, const Vec3& offset) {
  const int base = a.num_vertices();
  for (const Vec3& p : b.positions) a.positions.push_back(p + offset);
  for (Face f : b.faces) a.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
  return a;
}

/// 4x4 image, each 2x2 quadrant one opaque colour: bottom-left red, bottom-right green,
/// top-left blue, top-right yellow (rows from v = 0 = bottom).
ImageRGBA8 quadrant_image() {
  ImageRGBA8 img(4, 4);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      std::array<std::uint8_t, 4> c;
      if (j < 2) c = i < 2 ? std::array<std::uint8_t, 4>{255, 0, 0, 255}
                           : std::array<std::uint8_t, 4>{0, 255, 0, 255};
      else c = i < 2 ? std::array<std::uint8_t, 4>{0, 0, 255, 255}
                     : std::array<std::uint8_t, 4>{255, 255, 0, 255};
      std::copy(c.begin(), c.end(), img.texel(i, j));
    }
  return img;
}

Stroke make_decal(const Vec3& eye, const Vec3& target, double fov, ImageRGBA8 image) {
  Stroke s;
  s.type = Stroke::Type::Decal;
  s.camera.eye = eye;
  s.camera.target = target;
  s.camera.up = Vec3(0, 1, 0);
  s.camera.fov_y_degrees = fov;
  s.camera.aspect = 1.0;
  s.opacity = 1.0;
  s.image = std::move(image);
  return s;
}

/// Face of \p mesh containing (x, y) on the plane z = \p z (the planes here are axis-aligned grids).
int face_at(const TriMesh& mesh, double x, double y, double z) {
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Vec3& a = mesh.positions[mesh.faces[f][0]];
    const Vec3& b = mesh.positions[mesh.faces[f][1]];
    const Vec3& c = mesh.positions[mesh.faces[f][2]];
    if (std::abs(a.z() - z) > 1e-9 || std::abs(b.z() - z) > 1e-9 || std::abs(c.z() - z) > 1e-9)
      continue;
    auto cross = [](const Vec3& p, const Vec3& q, double px, double py) {
      return (q.x() - p.x()) * (py - p.y()) - (q.y() - p.y()) * (px - p.x());
    };
    const double d0 = cross(a, b, x, y), d1 = cross(b, c, x, y), d2 = cross(c, a, x, y);
    if ((d0 >= 0 && d1 >= 0 && d2 >= 0) || (d0 <= 0 && d1 <= 0 && d2 <= 0)) return f;
  }
  return -1;
}

// Two parallel planes as one mesh: front [0,1]^2 at z = 0, back [-1,2]^2 at z = -1; the camera looks
// down -z from (0.5, 0.5, 3).
struct TwoPlanes : ::testing::Test {
  TriMesh mesh = merge(shapes::plane(8, 1.0), shapes::plane(12, 3.0), Vec3(-1, -1, -1));
  Stroke decal = make_decal(Vec3(0.5, 0.5, 3), Vec3(0.5, 0.5, 0), 60.0, quadrant_image());
};

}  // namespace

TEST_F(TwoPlanes, FrontPlaneGetsTheImageInTheRightOrientation) {
  DecalProjector proj(mesh);
  // The frustum exactly spans the front plane: fov = 2 atan(0.5 / 3), so (u, v) = (x, y).
  const Stroke fit = make_decal(Vec3(0.5, 0.5, 3), Vec3(0.5, 0.5, 0),
                                2.0 * std::atan(0.5 / 3.0) * 180.0 / M_PI, quadrant_image());
  // Camera frame: right = +x, up = +y; a point left/below the centre maps to the image's
  // bottom-left (red) quadrant, right/above to the top-right (yellow) one.
  struct Probe {
    double x, y;
    Eigen::Vector3d rgb;
  };
  const Probe probes[] = {{0.3, 0.3, {1, 0, 0}},
                          {0.7, 0.3, {0, 1, 0}},
                          {0.3, 0.7, {0, 0, 1}},
                          {0.7, 0.7, {1, 1, 0}}};
  for (const Probe& pr : probes) {
    const Vec3 p(pr.x, pr.y, 0);
    const int f = face_at(mesh, pr.x, pr.y, 0);
    ASSERT_GE(f, 0);
    const Eigen::Vector4d c = proj.evaluate(fit, p, f);
    EXPECT_NEAR(c.w(), 1.0, 1e-12) << pr.x << "," << pr.y;
    EXPECT_LT((c.head<3>() - pr.rgb).norm(), 1e-9) << pr.x << "," << pr.y << ": " << c.transpose();
  }
}

TEST_F(TwoPlanes, ProjectionMatchesTheDocumentedFormula) {
  DecalProjector proj(mesh);
  const DecalFrame fr = decal_frame(decal.camera);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.05, 0.95);
  for (int k = 0; k < 200; ++k) {
    const Vec3 p(U(rng), U(rng), 0);
    // Pinhole: depth 3, half-extent at depth 3 is 3 tan(30 deg); (u,v) = 0.5 (x/ext + 1).
    const double ext = 3.0 * std::tan(M_PI / 6.0);
    const double u = 0.5 * ((p.x() - 0.5) / ext + 1.0), v = 0.5 * ((p.y() - 0.5) / ext + 1.0);
    Vec2 uv;
    double depth;
    ASSERT_TRUE(fr.project(p, uv, depth));
    EXPECT_NEAR(depth, 3.0, 1e-12);
    EXPECT_NEAR(uv.x(), u, 1e-12);
    EXPECT_NEAR(uv.y(), v, 1e-12);
    const Eigen::Vector4d expect = sample_decal_image(decal.image, u, v);
    const Eigen::Vector4d got = proj.evaluate(decal, p, face_at(mesh, p.x(), p.y(), 0));
    EXPECT_LT((got - expect).norm(), 1e-9);
  }
}

TEST_F(TwoPlanes, HiddenBackPlaneStaysUnpaintedVisiblePartIsPainted) {
  DecalProjector proj(mesh);
  // Behind the front plane (the segment to the eye crosses z = 0 inside [0,1]^2): hidden.
  for (double x : {0.1, 0.4, 0.6, 0.9})
    for (double y : {0.1, 0.5, 0.9}) {
      const int f = face_at(mesh, x, y, -1);
      ASSERT_GE(f, 0);
      EXPECT_EQ(proj.evaluate(decal, Vec3(x, y, -1), f), Eigen::Vector4d::Zero()) << x << "," << y;
      EXPECT_FALSE(proj.visible(decal.camera.eye, Vec3(x, y, -1)));
    }
  // Outside the front plane's shadow but inside the frustum: painted.
  for (double x : {-0.8, 1.8})
    for (double y : {-0.5, 0.5, 1.5}) {
      const int f = face_at(mesh, x, y, -1);
      ASSERT_GE(f, 0);
      const Eigen::Vector4d c = proj.evaluate(decal, Vec3(x, y, -1), f);
      EXPECT_NEAR(c.w(), 1.0, 1e-12) << x << "," << y;
    }
  // Batch form agrees with the single-point form.
  std::vector<Vec3> pts;
  std::vector<int> faces;
  for (double x = -0.95; x < 2.0; x += 0.173)
    for (double y = -0.95; y < 2.0; y += 0.131) {
      pts.emplace_back(x, y, -1);
      faces.push_back(face_at(mesh, x, y, -1));
    }
  std::vector<Eigen::Vector4d> out(pts.size());
  proj.evaluate(decal, pts, faces, out);
  int painted = 0, hidden = 0;
  for (size_t k = 0; k < pts.size(); ++k) {
    EXPECT_EQ(out[k], proj.evaluate(decal, pts[k], faces[k]));
    (out[k].w() > 0 ? painted : hidden)++;
  }
  EXPECT_GT(painted, 0);
  EXPECT_GT(hidden, 0);
  // Texel form: a hand-made texel map holding the same points (every other texel outside).
  TexelMap map;
  map.width = static_cast<int>(pts.size());
  map.height = 2;
  map.face.assign(2 * pts.size(), -1);
  map.bary.assign(2 * pts.size(), Eigen::Vector2f::Zero());
  map.position.assign(2 * pts.size(), Vec3f::Zero());
  for (size_t k = 0; k < pts.size(); ++k) {
    map.face[2 * k] = faces[k];
    map.position[2 * k] = pts[k].cast<float>();
    map.inside.push_back(static_cast<int>(2 * k));
  }
  std::vector<Eigen::Vector4f> tex;
  proj.evaluate_texels(decal, map, tex);
  ASSERT_EQ(tex.size(), pts.size());
  for (size_t k = 0; k < pts.size(); ++k)
    EXPECT_LT((tex[k].cast<double>() - out[k]).norm(), 1e-6) << k;
}

TEST_F(TwoPlanes, OutsideTheFrustumOrBehindTheEyeIsNotPainted) {
  // Narrow camera: 10 degrees sees only |x - 0.5| < 3 tan(5 deg) ~ 0.26 on the front plane.
  Stroke narrow = make_decal(Vec3(0.5, 0.5, 3), Vec3(0.5, 0.5, 0), 10.0, quadrant_image());
  DecalProjector proj(mesh);
  EXPECT_GT(proj.evaluate(narrow, Vec3(0.5, 0.5, 0), face_at(mesh, 0.5, 0.5, 0)).w(), 0.0);
  EXPECT_EQ(proj.evaluate(narrow, Vec3(0.9, 0.5, 0), face_at(mesh, 0.9, 0.5, 0)),
            Eigen::Vector4d::Zero());
  EXPECT_EQ(proj.evaluate(narrow, Vec3(0.5, 0.05, 0), face_at(mesh, 0.5, 0.05, 0)),
            Eigen::Vector4d::Zero());
  // Camera between the planes looking up +z: the back plane is behind the eye.
  Stroke up = make_decal(Vec3(0.5, 0.5, -0.5), Vec3(0.5, 0.5, 1), 120.0, quadrant_image());
  EXPECT_EQ(proj.evaluate(up, Vec3(0.5, 0.5, -1), face_at(mesh, 0.5, 0.5, -1)),
            Eigen::Vector4d::Zero());
  EXPECT_GT(proj.evaluate(up, Vec3(0.5, 0.5, 0), face_at(mesh, 0.5, 0.5, 0)).w(), 0.0);
}

TEST(Decal, BackFacingHalfOfAClosedMeshIsNotPaintedWhateverTheWinding) {
  TriMesh ccw = shapes::icosphere(4);
  TriMesh cw = ccw;
  for (Face& f : cw.faces) std::swap(f[1], f[2]);
  ImageRGBA8 white(2, 2, {255, 255, 255, 255});
  const Stroke decal = make_decal(Vec3(0, 0, 5), Vec3(0, 0, 0), 40.0, white);
  for (const TriMesh* m : {&ccw, &cw}) {
    DecalProjector proj(*m);
    int front_painted = 0, front = 0, back_painted = 0, back = 0;
    for (int f = 0; f < m->num_faces(); ++f) {
      const Vec3 c = point_on_face(*m, f, 1.0 / 3, 1.0 / 3);
      const bool painted = proj.evaluate(decal, c, f).w() > 0;
      if (c.z() > 0.4) {  // well inside the visible cap (its rim is at z = 0.2)
        ++front;
        front_painted += painted;
      } else if (c.z() < -0.05) {
        ++back;
        back_painted += painted;
      }
    }
    EXPECT_EQ(front_painted, front);
    EXPECT_EQ(back_painted, 0);
    EXPECT_GT(back, 100);
  }
}

TEST(Decal, OpacityAndAlphaWeightedSampling) {
  TriMesh mesh = shapes::plane(2, 1.0);
  // Left column opaque red, right column fully transparent (with green colour bytes).
  ImageRGBA8 img(2, 1);
  const std::array<std::uint8_t, 4> red{255, 0, 0, 255}, clear_green{0, 255, 0, 0};
  std::copy(red.begin(), red.end(), img.texel(0, 0));
  std::copy(clear_green.begin(), clear_green.end(), img.texel(1, 0));
  // Halfway between the texel centres: alpha 0.5, and the colour stays pure red (no green fringe).
  const Eigen::Vector4d s = sample_decal_image(img, 0.5, 0.5);
  EXPECT_NEAR(s.w(), 0.5, 1e-12);
  EXPECT_LT((s.head<3>() - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
  // Clamp to edge: beyond the first texel centre the value is the edge texel.
  EXPECT_LT((sample_decal_image(img, 0.01, 0.5) - Eigen::Vector4d(1, 0, 0, 1)).norm(), 1e-12);
  EXPECT_EQ(sample_decal_image(img, 0.99, 0.5), Eigen::Vector4d::Zero());

  Stroke d = make_decal(Vec3(0.5, 0.5, 2), Vec3(0.5, 0.5, 0), 40.0, img);
  d.opacity = 0.25;
  DecalProjector proj(mesh);
  const Eigen::Vector4d c = proj.evaluate(d, Vec3(0.5, 0.5, 0), face_at(mesh, 0.5, 0.5, 0));
  EXPECT_NEAR(c.w(), 0.5 * 0.25, 1e-12);
  // A brush stroke is not a decal: zero.
  Stroke brush;
  EXPECT_EQ(proj.evaluate(brush, Vec3(0.5, 0.5, 0), 0), Eigen::Vector4d::Zero());
}

TEST(Decal, InvalidCamerasAreRejectedWithOneLine) {
  DecalCamera c;
  c.up = Vec3(0, 0, 1);  // parallel to the viewing direction (0,0,-1)
  EXPECT_THROW(decal_frame(c, "s.json: stroke 2"), InvalidInputError);
  try {
    decal_frame(c, "s.json: stroke 2");
  } catch (const InvalidInputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("stroke 2"), std::string::npos);
    EXPECT_NE(msg.find("up"), std::string::npos);
    EXPECT_EQ(msg.find('\n'), std::string::npos);
  }
  DecalCamera d;
  d.fov_y_degrees = 180;
  EXPECT_THROW(decal_frame(d), InvalidInputError);
  d.fov_y_degrees = 40;
  d.aspect = 0;
  EXPECT_THROW(decal_frame(d), InvalidInputError);
  d.aspect = 1;
  d.target = d.eye;
  EXPECT_THROW(decal_frame(d), InvalidInputError);
  d.target = Vec3(0, 0, std::nan(""));
  EXPECT_THROW(decal_frame(d), InvalidInputError);
}

TEST_F(TwoPlanes, RaySceneClosestHitOcclusionAndStreamAgree) {
  const RayScene scene(mesh, {}, "test");
  // Down -z through (0.31, 0.67): the front plane (z = 0) is hit first, at the face containing it.
  const RayScene::Ray down{Vec3(0.31, 0.67, 3), Vec3(0, 0, -1), 0.0f, std::numeric_limits<float>::infinity()};
  const std::optional<RayScene::Hit> hit = scene.intersect(down);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->face, face_at(mesh, 0.31, 0.67, 0.0));
  const Face& f = mesh.faces[hit->face];
  const Vec3 p = (1.0 - hit->u - hit->v) * mesh.positions[f[0]] + double(hit->u) * mesh.positions[f[1]] +
                 double(hit->v) * mesh.positions[f[2]];
  EXPECT_NEAR((p - Vec3(0.31, 0.67, 0)).norm(), 0.0, 1e-5);
  // Outside the front plane only the back plane is hit; beside both, nothing.
  const std::optional<RayScene::Hit> back =
      scene.intersect({Vec3(1.62, 1.31, 3), Vec3(0, 0, -1), 0.0f, std::numeric_limits<float>::infinity()});
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->face, face_at(mesh, 1.62, 1.31, -1.0));
  EXPECT_FALSE(scene.intersect({Vec3(5, 5, 3), Vec3(0, 0, -1), 0.0f, 10.0f}).has_value());
  // Segments: stopped above the front plane (free), through it (blocked), beside it to the back plane.
  const std::vector<RayScene::Ray> rays = {{Vec3(0.31, 0.67, 3), Vec3(0, 0, -1), 0.0f, 2.5f},
                                           {Vec3(0.31, 0.67, 3), Vec3(0, 0, -1), 0.0f, 3.5f},
                                           {Vec3(1.62, 1.31, 3), Vec3(0, 0, -1), 0.0f, 3.5f},
                                           {Vec3(1.62, 1.31, 3), Vec3(0, 0, -1), 0.0f, 4.5f}};
  std::vector<char> blocked(rays.size(), 7);
  scene.occluded(rays, blocked);
  EXPECT_EQ(blocked, (std::vector<char>{0, 1, 0, 1}));
  for (size_t k = 0; k < rays.size(); ++k) EXPECT_EQ(scene.occluded(rays[k]), blocked[k] != 0) << k;
  // A mesh without faces is an empty scene.
  const RayScene empty(TriMesh{}, {}, "test");
  EXPECT_FALSE(empty.intersect(down).has_value());
  EXPECT_FALSE(empty.occluded(rays[1]));
}
