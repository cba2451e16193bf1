// MikkTSpace wedge tangents (paint/tangent_frame.h): unit, orthogonal to the vertex normal, along
// ∂P/∂u, with the handedness that makes w · (n × t) point along ∂P/∂v (flipped on mirrored charts);
// the normal map derived from height decodes, in the frame a renderer interpolates from NORMAL and
// TANGENT, to the surface normal perturbed by the height's gradient; the .glb carries them.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>

#include "adaptex/core/shapes.h"
#include "adaptex/paint/export.h"
#include "adaptex/paint/material_paint.h"
#include "adaptex/paint/tangent_frame.h"
#include "adaptex/paint/texel_map.h"
#include "brush_test_util.h"

namespace adaptex {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The unit plane with uv = offset + A (x, y), A = [[0.5, 0.2], [-0.1, 0.4]] (sheared, det > 0).
Parameterization sheared_param(const TriMesh& mesh) {
  Parameterization p = test::planar_param(mesh);
  for (size_t w = 0; w < p.uv.size(); ++w) {
    const Vec3& x = mesh.positions[w];
    p.uv[w] = Vec2(0.2 + 0.5 * x.x() + 0.2 * x.y(), 0.3 - 0.1 * x.x() + 0.4 * x.y());
  }
  return p;
}

/// ∂P/∂u and ∂P/∂v of the sheared map: the columns of A⁻¹.
void sheared_gradients(Vec3& pu, Vec3& pv) {
  const double det = 0.5 * 0.4 - 0.2 * -0.1;
  pu = Vec3(0.4, 0.1, 0) / det;
  pv = Vec3(-0.2, 0.5, 0) / det;
}

TEST(TangentFrame, PlaneTangentsFollowTheUvDerivatives) {
  const TriMesh mesh = shapes::plane(6);
  const Parameterization param = sheared_param(mesh);
  const std::vector<Vec3> n = vertex_normals(mesh);
  const std::vector<Eigen::Vector4d> t = wedge_tangents(mesh, param, n);
  Vec3 pu, pv;
  sheared_gradients(pu, pv);
  ASSERT_EQ(t.size(), param.uv.size());
  for (size_t w = 0; w < t.size(); ++w) {
    const Vec3 tw = t[w].head<3>();
    EXPECT_NEAR(tw.norm(), 1.0, 1e-12);
    EXPECT_NEAR(tw.dot(n[w]), 0.0, 1e-12);
    EXPECT_LT((tw - pu.normalized()).norm(), 1e-12) << "wedge " << w;
    EXPECT_EQ(t[w].w(), 1.0);
    EXPECT_GT((t[w].w() * n[w].cross(tw)).dot(pv), 0.0);  // bitangent along +v
  }
}

TEST(TangentFrame, MirroredUvsFlipTheHandednessChartByChart) {
  // Left half (x < 0.5) keeps uv = xy; the right half is its own chart with u mirrored (u = 1 - x).
  const TriMesh mesh = shapes::plane(8);
  Parameterization param = test::planar_param(mesh);
  std::vector<int> mirrored_wedge(mesh.positions.size(), -1);
  std::vector<char> right(mesh.faces.size(), 0);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    Vec3 c = Vec3::Zero();
    for (int v : mesh.faces[f]) c += mesh.positions[v] / 3;
    if (c.x() < 0.5) continue;
    right[f] = 1;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.faces[f][k];
      if (mirrored_wedge[v] < 0) {
        mirrored_wedge[v] = static_cast<int>(param.uv.size());
        param.uv.push_back(Vec2(1 - mesh.positions[v].x(), mesh.positions[v].y()));
        param.wedge_vertex.push_back(v);
      }
      param.uv_faces[f][k] = mirrored_wedge[v];
    }
  }
  const std::vector<Vec3> n = vertex_normals(mesh);
  const std::vector<Eigen::Vector4d> t = wedge_tangents(mesh, param, n);
  int left_wedges = 0, right_wedges = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int w : param.uv_faces[f]) {
      const double expect_w = right[f] ? -1.0 : 1.0;
      const Vec3 expect_t = right[f] ? Vec3(-1, 0, 0) : Vec3(1, 0, 0);  // ∂P/∂u
      ASSERT_EQ(t[w].w(), expect_w) << "wedge " << w;
      ASSERT_LT((t[w].head<3>() - expect_t).norm(), 1e-12) << "wedge " << w;
      // Either way the bitangent w · (n × t) points along ∂P/∂v = +y.
      ASSERT_GT((t[w].w() * n[param.wedge_vertex[w]].cross(Vec3(t[w].head<3>()))).y(), 0.99);
      (right[f] ? right_wedges : left_wedges)++;
    }
  EXPECT_GT(left_wedges, 0);
  EXPECT_GT(right_wedges, 0);
}

/// An open cylinder of radius 1 around z with uv = (angle / 2π, z) and a seam at angle 0 (wedges
/// doubled there); faces wound outwards.
struct Cylinder {
  TriMesh mesh;
  Parameterization param;
};

Cylinder cylinder(int segments, int rings) {
  Cylinder c;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i <= segments; ++i) {
      const double a = 2 * kPi * i / segments, z = double(j) / rings;
      if (i < segments) c.mesh.positions.push_back(Vec3(std::cos(a), std::sin(a), z));
      c.param.uv.push_back(Vec2(double(i) / segments, z));
      c.param.wedge_vertex.push_back(j * segments + i % segments);
    }
  auto v = [&](int i, int j) { return j * segments + i % segments; };
  auto w = [&](int i, int j) { return j * (segments + 1) + i; };
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      c.mesh.faces.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      c.param.uv_faces.push_back({w(i, j), w(i + 1, j), w(i + 1, j + 1)});
      c.mesh.faces.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
      c.param.uv_faces.push_back({w(i, j), w(i + 1, j + 1), w(i, j + 1)});
    }
  c.param.face_chart.assign(c.mesh.faces.size(), 0);
  c.param.num_charts = 1;
  return c;
}

TEST(TangentFrame, CylinderTangentsRunAroundTheAxis) {
  const Cylinder c = cylinder(12, 3);
  const std::vector<Vec3> n = vertex_normals(c.mesh);
  const std::vector<Eigen::Vector4d> t = wedge_tangents(c.mesh, c.param, n);
  for (int w = 0; w < c.param.num_wedges(); ++w) {
    const int v = c.param.wedge_vertex[w];
    const Vec3 p = c.mesh.positions[v], tw = t[w].head<3>();
    const Vec3 around = Vec3(-p.y(), p.x(), 0).normalized();  // ∂P/∂u of the smooth cylinder
    EXPECT_NEAR(tw.dot(n[v]), 0.0, 1e-12);
    EXPECT_GT(tw.dot(around), std::cos(0.1)) << "wedge " << w;
    EXPECT_EQ(t[w].w(), 1.0);
  }
  // The two wedges of a seam vertex (u = 0 and u = 1) agree: both see the same surface direction.
  EXPECT_LT((t[0].head<3>() - t[12].head<3>()).norm(), 1e-9);
}

TEST(TangentFrame, NormalMapDecodesToThePerturbedNormalInTheRendererFrame) {
  // A coarse cylinder (face and vertex normals up to 15° apart), height H = 0.8 x. A renderer builds
  // n = normalize(x T + y B + z N) from the interpolated NORMAL and TANGENT, B = w N × T; that must be
  // the shading normal tilted by the height's surface gradient, normalize(N − ∇H + (∇H·N) N).
  const Cylinder c = cylinder(12, 2);
  const int S = 256;
  const TexelMap map = build_texel_map(c.mesh, c.param, S, S);
  std::vector<double> h(static_cast<size_t>(S) * S, 0.0);
  for (int t : map.inside) h[t] = 0.8 * map.position[t].x();
  const std::vector<Vec3f> baked = height_normals(c.mesh, c.param, map, h);
  const std::vector<Vec3> n = vertex_normals(c.mesh);
  const std::vector<Eigen::Vector4d> tan = wedge_tangents(c.mesh, c.param, n);
  std::vector<double> err;
  for (int t : map.inside) {
    const int f = map.face[t];
    const double bc[3] = {map.bary[t].x(), map.bary[t].y(), 1.0 - map.bary[t].x() - map.bary[t].y()};
    Vec3 N = Vec3::Zero(), T = Vec3::Zero();
    double w = 0;
    for (int k = 0; k < 3; ++k) {
      N += bc[k] * n[c.mesh.faces[f][k]];
      T += bc[k] * tan[c.param.uv_faces[f][k]].head<3>();
      w += bc[k] * tan[c.param.uv_faces[f][k]].w();
    }
    N.normalize();
    T = (T - N * N.dot(T)).normalized();
    const Vec3 B = (w < 0 ? -1.0 : 1.0) * N.cross(T);
    const Vec3 ts = baked[t].cast<double>();
    const Vec3 decoded = (ts.x() * T + ts.y() * B + ts.z() * N).normalized();
    const Vec3 fn = face_normal(c.mesh, f);
    const Vec3 g = 0.8 * (Vec3::UnitX() - fn * fn.x());  // ∇H in the face's plane
    const Vec3 expect = (N - (g - N * N.dot(g))).normalized();
    err.push_back((decoded - expect).norm());
  }
  std::sort(err.begin(), err.end());
  // Texels whose central differences straddle a face edge differ; the bulk is exact (1e-7 here; the
  // face's own frame, used before, is off by 3e-3 at the median and 9e-3 at the 80th percentile).
  EXPECT_LT(err[err.size() / 2], 1e-5);
  EXPECT_LT(err[err.size() * 8 / 10], 1e-5);
}

TEST(TangentFrame, GlbCarriesUnitTangentsWithHandednessOnlyWithANormalMap) {
  const Cylinder c = cylinder(12, 2);
  const ImageRGBA8 tex(8, 8, {200, 100, 50, 255});
  ExportOptions o;
  o.maps = {{"normal", ImageRGBA8(8, 8, {128, 128, 255, 255})}};
  for (bool with_normal_map : {true, false}) {
    if (!with_normal_map) o.maps.clear();
    const std::vector<unsigned char> glb = encode_glb(c.mesh, c.param, tex, o);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), static_cast<unsigned>(glb.size())))
        << err;
    const auto& attr = model.meshes.at(0).primitives.at(0).attributes;
    ASSERT_EQ(attr.count("TANGENT"), with_normal_map ? 1u : 0u);
    if (!with_normal_map) continue;
    const tinygltf::Accessor& acc = model.accessors[attr.at("TANGENT")];
    ASSERT_EQ(acc.type, TINYGLTF_TYPE_VEC4);
    ASSERT_EQ(acc.count, static_cast<size_t>(c.param.num_wedges()));
    const tinygltf::BufferView& view = model.bufferViews[acc.bufferView];
    const float* data =
        reinterpret_cast<const float*>(model.buffers[view.buffer].data.data() + view.byteOffset + acc.byteOffset);
    const std::vector<Eigen::Vector4d> expect = wedge_tangents(c.mesh, c.param, vertex_normals(c.mesh));
    for (size_t w = 0; w < acc.count; ++w) {
      const Eigen::Vector3f t(data[4 * w], data[4 * w + 1], data[4 * w + 2]);
      EXPECT_NEAR(t.norm(), 1.0f, 1e-6f);
      EXPECT_LT((t.cast<double>() - expect[w].head<3>()).norm(), 1e-6);
      EXPECT_EQ(data[4 * w + 3], static_cast<float>(expect[w].w()));
    }
  }
}

}  // namespace
}  // namespace adaptex
