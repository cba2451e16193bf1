// Issue 8, "Topology that is right": boundary loops are traced fan by fan (a loop through a pinched
// vertex, inconsistent face winding), components are separated at pinched vertices, and every
// component satisfies euler == 2 - 2 genus - loops. split_pinched_vertices() keeps positions exactly;
// orient_faces() makes a mixed winding consistent and finds non-orientable pieces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "adaptex/core/orientation.h"
#include "adaptex/core/pinched.h"
#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"

using namespace adaptex;

namespace {

/// Every component: euler == 2 - 2 genus - loops, and the counts add up to the mesh's.
void expect_consistent(const TriMesh& mesh, const MeshTopology& t) {
  ASSERT_EQ(static_cast<int>(t.components.size()), t.num_components);
  int faces = 0, edges = 0, loops = 0;
  for (int c = 0; c < t.num_components; ++c) {
    const ComponentTopology& ct = t.components[c];
    EXPECT_EQ(ct.euler, ct.vertices - ct.edges + ct.faces) << "component " << c;
    EXPECT_EQ(ct.euler, 2 - 2 * ct.genus - static_cast<int>(ct.loops.size())) << "component " << c;
    EXPECT_EQ(t.component_genus[c], ct.genus);
    EXPECT_EQ(t.component_loops[c], static_cast<int>(ct.loops.size()));
    for (int l : ct.loops) EXPECT_EQ(t.loop_component[l], c);
    faces += ct.faces;
    edges += ct.edges;
    loops += static_cast<int>(ct.loops.size());
  }
  EXPECT_EQ(faces, mesh.num_faces());
  EXPECT_EQ(edges, t.num_edges);
  EXPECT_EQ(loops, t.total_loops());
  // Every loop is a closed cycle of distinct boundary edges, and all boundary edges are used once.
  const EdgeConnectivity ec = build_edges(mesh);
  std::map<std::pair<int, int>, int> boundary;
  for (int e = 0; e < ec.num_edges(); ++e)
    if (ec.is_boundary(e)) boundary[{ec.edges[e][0], ec.edges[e][1]}] = 0;
  for (const auto& loop : t.boundary_loops)
    for (size_t k = 0; k < loop.size(); ++k) {
      const auto key = std::minmax(loop[k], loop[(k + 1) % loop.size()]);
      auto it = boundary.find(key);
      ASSERT_NE(it, boundary.end()) << loop[k] << "-" << loop[(k + 1) % loop.size()] << " is not a boundary edge";
      EXPECT_EQ(++it->second, 1) << "boundary edge used twice";
    }
  for (const auto& [e, n] : boundary) EXPECT_EQ(n, 1) << e.first << "-" << e.second << " in no loop";
}

int count(const std::vector<int>& loop, int v) { return static_cast<int>(std::count(loop.begin(), loop.end(), v)); }

}  // namespace

TEST(TopologyPinched, AnnulusTouchingItselfIsOneLoopThroughTheVertexTwice) {
  for (int n : {3, 8}) {
    SCOPED_TRACE(n);
    const TriMesh m = shapes::pinched_annulus(n);
    const MeshTopology t = analyze_topology(m);
    ASSERT_EQ(t.nonmanifold_vertices.size(), 1u);
    EXPECT_TRUE(t.nonmanifold_edges.empty());
    const int v = t.nonmanifold_vertices[0];
    EXPECT_DOUBLE_EQ(m.positions[v].x(), (n - 1.0) / n);
    EXPECT_DOUBLE_EQ(m.positions[v].y(), (n - 1.0) / n);
    EXPECT_EQ(t.num_components, 1);
    ASSERT_EQ(t.total_loops(), 1);
    EXPECT_EQ(static_cast<int>(t.boundary_loops[0].size()), 8 * n - 8);
    EXPECT_EQ(count(t.boundary_loops[0], v), 2);
    EXPECT_EQ(t.components[0].genus, 0);
    EXPECT_EQ(t.components[0].euler, 1);  // counted with the pinched vertex split: a disk
    EXPECT_EQ(t.euler_characteristic, 0);  // counted on the input vertices
    expect_consistent(m, t);
  }
}

TEST(TopologyPinched, ClosedSurfaceWithPinchedHole) {
  struct Case {
    const char* name;
    TriMesh closed;
    int genus;
  };
  for (const Case& c : {Case{"sphere", shapes::icosphere(2), 0}, Case{"torus", shapes::torus(24, 12), 1},
                        Case{"double_torus", shapes::double_torus(32), 2}}) {
    SCOPED_TRACE(c.name);
    const TriMesh m = shapes::with_pinched_hole(c.closed);
    ASSERT_EQ(m.num_faces(), c.closed.num_faces() - 2);
    const MeshTopology t = analyze_topology(m);
    ASSERT_EQ(t.nonmanifold_vertices.size(), 1u);
    EXPECT_EQ(t.num_components, 1);
    EXPECT_EQ(t.total_genus(), c.genus);
    ASSERT_EQ(t.total_loops(), 1);
    EXPECT_EQ(t.boundary_loops[0].size(), 6u);
    EXPECT_EQ(count(t.boundary_loops[0], t.nonmanifold_vertices[0]), 2);
    // On the input vertices chi is one less than 2 - 2g - 1 (the pinched vertex counts once).
    EXPECT_EQ(t.euler_characteristic, 2 - 2 * c.genus - 1 - 1);
    expect_consistent(m, t);
  }
}

TEST(TopologyPinched, SurfacesTouchingAtOneVertexAreSeparateComponents) {
  const MeshTopology bow = analyze_topology(shapes::bowtie_vertex());
  EXPECT_EQ(bow.num_components, 2);
  for (const ComponentTopology& c : bow.components) {
    EXPECT_EQ(c.euler, 2);
    EXPECT_EQ(c.genus, 0);
    EXPECT_TRUE(c.loops.empty());
  }
  expect_consistent(shapes::bowtie_vertex(), bow);
  // Two squares touching at a corner: two disks.
  TriMesh squares = shapes::plane(3);
  TriMesh other = shapes::plane(3);
  for (Vec3& p : other.positions) p += Vec3(1, 1, 0);
  squares = shapes::disjoint_union({squares, other});
  // Weld the corner (1, 1) of the first with the corner (1, 1) of the second.
  const int a = 15, b = 16;  // vertex (3, 3) of the first grid, vertex (0, 0) of the second
  ASSERT_EQ(squares.positions[a], squares.positions[b]);
  for (Face& f : squares.faces)
    for (int& v : f) v = v == b ? a : v > b ? v - 1 : v;
  squares.positions.erase(squares.positions.begin() + b);
  const MeshTopology t = analyze_topology(squares);
  ASSERT_EQ(t.nonmanifold_vertices, std::vector<int>{a});
  EXPECT_EQ(t.num_components, 2);
  EXPECT_EQ(t.total_loops(), 2);
  for (const ComponentTopology& c : t.components) {
    EXPECT_EQ(c.euler, 1);
    EXPECT_EQ(c.loops.size(), 1u);
  }
  expect_consistent(squares, t);
}

TEST(TopologyPinched, LoopsDoNotDependOnFaceWinding) {
  // Flipping faces (inconsistent winding, as in some scans) must not break the loops into chains.
  for (const auto& [name, mesh, loops] : std::vector<std::tuple<std::string, TriMesh, int>>{
           {"plane", shapes::plane(6), 1},
           {"disk_with_holes", shapes::disk_with_holes(3, 24), 4},
           {"pinched_annulus", shapes::pinched_annulus(6), 1}}) {
    SCOPED_TRACE(name);
    const MeshTopology ref = analyze_topology(mesh);
    TriMesh flipped = mesh;
    for (size_t f = 0; f < flipped.faces.size(); f += 3) std::swap(flipped.faces[f][1], flipped.faces[f][2]);
    const MeshTopology t = analyze_topology(flipped);
    ASSERT_EQ(t.total_loops(), loops);
    std::multiset<size_t> a, b;
    for (const auto& l : ref.boundary_loops) a.insert(l.size());
    for (const auto& l : t.boundary_loops) b.insert(l.size());
    EXPECT_EQ(a, b);
    EXPECT_EQ(t.total_genus(), 0);
    expect_consistent(flipped, t);
  }
}

TEST(TopologyPinched, ComponentsWithDifferentGenus) {
  const std::vector<TriMesh> parts = {shapes::icosphere(1),        shapes::torus(16, 8),
                                      shapes::double_torus(24),    shapes::pinched_annulus(5),
                                      shapes::open_cylinder(12, 3), shapes::with_pinched_hole(shapes::torus(16, 8))};
  const int genus[] = {0, 1, 2, 0, 0, 1};
  const int loops[] = {0, 0, 0, 1, 2, 1};
  const TriMesh m = shapes::disjoint_union(parts);
  const MeshTopology t = analyze_topology(m);
  ASSERT_EQ(t.num_components, 6);
  EXPECT_EQ(t.nonmanifold_vertices.size(), 2u);
  int first_face = 0;
  for (int c = 0; c < 6; ++c) {
    SCOPED_TRACE(c);
    // Components are numbered by their lowest vertex: the order of the parts.
    EXPECT_EQ(t.face_component[first_face], c);
    EXPECT_EQ(t.components[c].faces, parts[c].num_faces());
    EXPECT_EQ(t.components[c].genus, genus[c]);
    EXPECT_EQ(static_cast<int>(t.components[c].loops.size()), loops[c]);
    first_face += parts[c].num_faces();
  }
  EXPECT_EQ(t.total_genus(), 4);
  EXPECT_EQ(t.total_loops(), 4);
  expect_consistent(m, t);
}

TEST(PinchedSplit, OneVertexPerFanSamePositionSameTopology) {
  const TriMesh in = shapes::disjoint_union({shapes::pinched_annulus(6), shapes::bowtie_vertex(),
                                             shapes::with_pinched_hole(shapes::double_torus(24))});
  const MeshTopology before = analyze_topology(in);
  const PinchedSplit s = split_pinched_vertices(in);
  EXPECT_EQ(s.pinched_vertices, 3);
  EXPECT_EQ(s.added_vertices, 3);
  ASSERT_EQ(s.mesh.num_vertices(), in.num_vertices() + 3);
  ASSERT_EQ(s.vertex_source.size(), s.mesh.positions.size());
  ASSERT_EQ(s.mesh.num_faces(), in.num_faces());
  for (int v = 0; v < s.mesh.num_vertices(); ++v) {
    const Vec3& p = s.mesh.positions[v];
    const Vec3& q = in.positions[s.vertex_source[v]];
    EXPECT_TRUE(p.x() == q.x() && p.y() == q.y() && p.z() == q.z()) << "vertex " << v;  // bit-exact
  }
  for (int v = 0; v < in.num_vertices(); ++v) EXPECT_EQ(s.vertex_source[v], v);
  for (int f = 0; f < in.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(s.vertex_source[s.mesh.faces[f][k]], in.faces[f][k]);
  const MeshTopology after = analyze_topology(s.mesh);
  EXPECT_TRUE(after.is_manifold());
  ASSERT_EQ(after.num_components, before.num_components);
  for (int c = 0; c < after.num_components; ++c) {
    EXPECT_EQ(after.components[c].euler, before.components[c].euler);
    EXPECT_EQ(after.components[c].genus, before.components[c].genus);
    EXPECT_EQ(after.components[c].loops.size(), before.components[c].loops.size());
  }
  // A manifold mesh is returned unchanged.
  const PinchedSplit none = split_pinched_vertices(shapes::torus(12, 6));
  EXPECT_EQ(none.pinched_vertices, 0);
  EXPECT_EQ(none.mesh.faces, shapes::torus(12, 6).faces);
}

namespace {

/// A Möbius band: a strip of n quads whose ends are glued with a half twist.
TriMesh moebius(int n) {
  TriMesh m;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * 3.14159265358979 * i / n;
    for (double s : {-0.3, 0.3}) {
      const double r = 1 + s * std::cos(t / 2);
      m.positions.push_back(Vec3(r * std::cos(t), r * std::sin(t), s * std::sin(t / 2)));
    }
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1;
    const bool last = i + 1 == n;
    const int c = last ? 1 : 2 * i + 2, d = last ? 0 : 2 * i + 3;  // the twist swaps the sides
    m.faces.push_back({a, c, d});
    m.faces.push_back({a, d, b});
  }
  return m;
}

}  // namespace

TEST(Orientation, MixedWindingIsMadeConsistentKeepingTheMajority) {
  const TriMesh ref = shapes::with_pinched_hole(shapes::genus_surface(3));
  TriMesh mixed = ref;
  int changed = 0;
  for (size_t f = 0; f < mixed.faces.size(); f += 7, ++changed) std::swap(mixed.faces[f][1], mixed.faces[f][2]);
  const MeshTopology before = analyze_topology(mixed);
  ASSERT_EQ(before.num_components, 1);
  EXPECT_TRUE(before.components[0].orientable);
  EXPECT_FALSE(before.components[0].consistently_oriented);
  // The loops and genus are right even before the winding is fixed (the genus-3 mesh).
  EXPECT_EQ(before.total_genus(), 3);
  EXPECT_EQ(before.total_loops(), 1);
  const FaceOrientation o = orient_faces(mixed);
  EXPECT_EQ(o.num_flipped, changed);
  EXPECT_EQ(o.num_non_orientable_faces, 0);
  apply_orientation(mixed, o);
  EXPECT_EQ(mixed.faces, ref.faces);
  EXPECT_TRUE(analyze_topology(mixed).components[0].consistently_oriented);
  // Already consistent: nothing to flip; the minority is what gets flipped.
  EXPECT_EQ(orient_faces(ref).num_flipped, 0);
  TriMesh most = ref;
  for (size_t f = 0; f < most.faces.size(); ++f)
    if (f % 4 != 0) std::swap(most.faces[f][1], most.faces[f][2]);
  const FaceOrientation om = orient_faces(most);
  EXPECT_EQ(om.num_flipped, static_cast<int>((ref.faces.size() + 3) / 4));
}

TEST(Orientation, MoebiusBandIsNotOrientable) {
  const TriMesh m = moebius(24);
  const MeshTopology t = analyze_topology(m);
  ASSERT_EQ(t.num_components, 1);
  EXPECT_TRUE(t.is_manifold());
  EXPECT_FALSE(t.components[0].orientable);
  EXPECT_EQ(t.total_loops(), 1);  // the band's single boundary loop, traced regardless of winding
  EXPECT_EQ(t.boundary_loops[0].size(), 48u);
  const FaceOrientation o = orient_faces(m);
  EXPECT_EQ(o.num_flipped, 0);
  EXPECT_EQ(o.num_non_orientable_faces, m.num_faces());
}
