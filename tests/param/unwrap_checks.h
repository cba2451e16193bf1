#pragma once
/// \file unwrap_checks.h
/// The properties every unwrap() result must have, checked independently of how it was made
/// (shared by the generated-mesh and the shared-mesh tests).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"

namespace adaptex::test {

/// Five tori of different sizes side by side (five components, about 1.3k faces in all).
inline TriMesh five_tori() {
  TriMesh m;
  for (int i = 0; i < 5; ++i) {
    TriMesh t = shapes::torus(16 + 4 * i, 8, 1.0 + i, 0.3 + 0.1 * i);
    const int off = m.num_vertices();
    for (const Vec3& p : t.positions) m.positions.push_back(p + Vec3(10.0 * i, 0, 0));
    for (Face f : t.faces) m.faces.push_back({f[0] + off, f[1] + off, f[2] + off});
  }
  return m;
}

/// Every property unwrap() promises, checked independently of how it was made.
/// Unwraps \p mesh and checks the result; the result is stored in \p out if given.
inline void check_unwrap(const std::string& name, const TriMesh& mesh, const UnwrapOptions& opt = {},
                         UnwrapResult* out = nullptr) {
  SCOPED_TRACE(name);
  const MeshTopology topo = analyze_topology(mesh);
  UnwrapResult tmp;
  UnwrapResult& r = out ? *out : tmp;
  r = unwrap(mesh, opt);
  const Parameterization& p = r.param;
  ASSERT_EQ(p.uv_faces.size(), mesh.faces.size());
  ASSERT_EQ(p.face_chart.size(), mesh.faces.size());
  ASSERT_EQ(p.wedge_vertex.size(), p.uv.size());
  // One chart per component, more only when ChartMode::Auto segments them.
  EXPECT_EQ(r.report.num_charts, p.num_charts);
  if (opt.charts == ChartMode::Single) {
    EXPECT_EQ(p.num_charts, topo.num_components);
  } else {
    EXPECT_GE(p.num_charts, topo.num_components);
  }
  EXPECT_EQ(r.report.num_components, topo.num_components);
  EXPECT_EQ(r.report.genus, topo.total_genus());
  EXPECT_EQ(r.report.boundary_loops, topo.total_loops());
  // wedge_vertex is consistent with the mesh faces; UVs are in [0,1]^2.
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(p.uv_faces[f][k], 0);
      ASSERT_LT(p.uv_faces[f][k], p.num_wedges());
      ASSERT_EQ(p.wedge_vertex[p.uv_faces[f][k]], mesh.faces[f][k]);
    }
  for (const Vec2& t : p.uv) {
    ASSERT_TRUE(t.x() >= 0 && t.x() <= 1 && t.y() >= 0 && t.y() <= 1) << t.transpose();
  }
  // Every chart is a topological disk: the mesh of wedges, chart by chart.
  for (int c = 0; c < p.num_charts; ++c) {
    TriMesh chart;
    chart.positions.resize(p.num_wedges(), Vec3::Zero());
    for (int f = 0; f < mesh.num_faces(); ++f)
      if (p.face_chart[f] == c) chart.faces.push_back(p.uv_faces[f]);
    const MeshTopology ct = analyze_topology(chart);
    EXPECT_EQ(ct.num_components, 1) << "chart " << c;
    EXPECT_EQ(ct.total_genus(), 0) << "chart " << c;
    EXPECT_EQ(ct.total_loops(), 1) << "chart " << c;
    EXPECT_TRUE(ct.is_manifold()) << "chart " << c;
  }
  // No flipped, degenerate or overlapping UV triangles.
  const StretchStats s = measure_stretch(mesh, p);
  EXPECT_EQ(s.flipped, 0);
  EXPECT_EQ(s.degenerate, 0);
  for (int f = 0; f < mesh.num_faces(); ++f) ASSERT_GT(uv_signed_area(p, f), 0.0) << "face " << f;
  EXPECT_EQ(count_overlapping_triangles(p), 0);
  // Stretch figures: finite, Yoshizawa (and augmentation) never make it worse than Floater.
  EXPECT_TRUE(std::isfinite(r.report.final_l2));
  EXPECT_GE(r.report.final_l2, 1.0 - 1e-9);
  EXPECT_LE(r.report.final_l2, r.report.floater_l2 * (1 + 1e-9));
  EXPECT_NEAR(r.report.final_l2, s.l2, 1e-9 * s.l2);
  EXPECT_GE(r.report.final_linf, r.report.final_l2 * (1 - 1e-9));
  // Cut length: zero only for a single disk.
  if (topo.num_components == 1 && topo.total_genus() == 0 && topo.total_loops() == 1 &&
      r.report.augmentations == 0 && p.num_charts == 1) {
    EXPECT_EQ(r.report.cut_length, 0.0);
  } else if (topo.total_loops() == 0 || topo.total_genus() > 0) {
    EXPECT_GT(r.report.cut_length, 0.0);
  }
  EXPECT_GE(r.report.time_total, 0.0);
}

}  // namespace adaptex::test
