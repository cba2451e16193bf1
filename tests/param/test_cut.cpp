// Topological tests of the §3.2 surgery (cut.h): every component of every shape becomes a disk.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/charts.h"
#include "adaptex/param/cut.h"

namespace adaptex {
namespace {

struct Named {
  std::string name;
  TriMesh mesh;
};

std::vector<Named> connected_shapes() {
  return {{"sphere", shapes::sphere(24, 12)},
          {"icosphere", shapes::icosphere(2)},
          {"torus", shapes::torus(32, 12)},
          {"double_torus", shapes::double_torus(32)},
          {"open_cylinder", shapes::open_cylinder(24, 8)},
          {"disk_with_holes", shapes::disk_with_holes(3, 24)},
          {"trefoil", shapes::trefoil_knot(120, 12)},
          {"plane", shapes::plane(8)}};
}

TEST(Cut, InitialCutSlicesEveryShapeIntoADisk) {
  for (const auto& [name, mesh] : connected_shapes()) {
    SCOPED_TRACE(name);
    const MeshTopology topo = analyze_topology(mesh);
    ASSERT_EQ(topo.num_components, 1);
    const EdgeConnectivity ec = build_edges(mesh);
    const EdgeGraph g = build_edge_graph(mesh, ec);
    const std::vector<char> cut = initial_cut(mesh, ec, g);
    for (int e = 0; e < ec.num_edges(); ++e)
      if (ec.is_boundary(e)) {
        EXPECT_EQ(cut[e], 0);
      }
    const SlicedDisk d = slice_along_cut(mesh, ec, cut);
    const MeshTopology dt = analyze_topology(d.disk);
    EXPECT_EQ(dt.num_components, 1);
    EXPECT_EQ(dt.total_genus(), 0);
    EXPECT_EQ(dt.total_loops(), 1);
    EXPECT_TRUE(dt.is_manifold());
    EXPECT_EQ(d.boundary_loop.size(), dt.boundary_loops.at(0).size());
    EXPECT_GE(d.boundary_loop.size(), 4u);
    ASSERT_EQ(d.disk.faces.size(), mesh.faces.size());
    for (int f = 0; f < mesh.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) EXPECT_EQ(d.wedge_vertex[d.disk.faces[f][k]], mesh.faces[f][k]);
    // A disk needs no cut; a closed genus-0 surface needs a single path.
    const double len = cut_length(g, cut);
    if (topo.total_loops() == 1 && topo.total_genus() == 0) {
      EXPECT_EQ(len, 0.0);
    } else {
      EXPECT_GT(len, 0.0);
    }
    // Augmentation: adding the shortest path from an interior vertex keeps a disk.
    std::vector<char> aug = cut;
    const std::vector<char> on = cut_vertices(mesh, ec, aug);
    int from = -1;
    for (int v = 0; v < mesh.num_vertices() && from < 0; ++v)
      if (!on[v]) from = v;
    if (from >= 0) {
      const std::vector<int> path = shortest_path_to_cut(g, on, from);
      EXPECT_FALSE(path.empty());
      for (int e : path) aug[e] = 1;
      const SlicedDisk d2 = slice_along_cut(mesh, ec, aug);
      const MeshTopology t2 = analyze_topology(d2.disk);
      EXPECT_EQ(t2.total_genus(), 0);
      EXPECT_EQ(t2.total_loops(), 1);
      EXPECT_EQ(t2.num_components, 1);
    }
  }
}

TEST(Cut, ADiskNeedsNoCut) {
  // unwrap() skips initial_cut() on a connected piece with Euler characteristic 1 (a disk: the
  // segmented charts mostly are): its face tree crosses every interior edge that separates the
  // disk, and pruning removes the rest. Disks of several kinds, including every chart of a
  // segmentation.
  std::vector<TriMesh> disks = {shapes::plane(8), shapes::sphere_with_holes(1, 3)};
  const TriMesh g3 = shapes::genus_surface(3);
  ChartSegmentOptions so;
  so.num_charts = 12;
  const std::vector<int> label = segment_charts(g3, so);
  const int k = *std::max_element(label.begin(), label.end()) + 1;
  int disk_charts = 0;
  for (ChartMesh& c : extract_charts(g3, label, k)) {
    const EdgeConnectivity ec = build_edges(c.mesh);
    if (c.mesh.num_vertices() - ec.num_edges() + c.mesh.num_faces() != 1) continue;
    disks.push_back(std::move(c.mesh));
    ++disk_charts;
  }
  EXPECT_GE(disk_charts, 2);  // 4 of the 12 (the others keep a handle or several loops)
  for (const TriMesh& d : disks) {
    const EdgeConnectivity ec = build_edges(d);
    ASSERT_EQ(d.num_vertices() - ec.num_edges() + d.num_faces(), 1);
    const std::vector<char> cut = initial_cut(d, ec, build_edge_graph(d, ec));
    EXPECT_EQ(std::count(cut.begin(), cut.end(), 1), 0);
  }
}

TEST(Cut, GenusLoopsAreShortOnTheTorus) {
  // The torus has R = 1, r = 0.35: its shortest non-contractible loops are the meridian (2π·0.35)
  // and the inner equator (2π·0.65). The cut is about one of each.
  const TriMesh mesh = shapes::torus(64, 24);
  const EdgeConnectivity ec = build_edges(mesh);
  const EdgeGraph g = build_edge_graph(mesh, ec);
  const double len = cut_length(g, initial_cut(mesh, ec, g));
  EXPECT_LT(len, 1.3 * 2 * 3.14159265 * (0.35 + 0.65));
}

TEST(Cut, ANonDiskCutIsRejected) {
  const TriMesh mesh = shapes::torus(16, 8);
  const EdgeConnectivity ec = build_edges(mesh);
  const std::vector<char> none(ec.num_edges(), 0);
  EXPECT_THROW(slice_along_cut(mesh, ec, none), TopologyError);
}

}  // namespace
}  // namespace adaptex
