// Issue 8: meshes with pinched vertices (several fans of faces at one vertex, e.g. a boundary that
// touches itself) unwrap through the library and the CLI: UVs in [0,1]^2, no flipped or overlapping
// triangles, every chart a disk, the genus and loops of every component in the report, and the
// exported positions bit-exact. Mixed face winding (the cause of "slice_along_cut: the sliced mesh is
// pinched at vertex ...") is made consistent; a non-orientable surface is a clear error.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"
#include "test_support.h"
#include "unwrap_checks.h"

namespace adaptex {
namespace {

using test::check_unwrap;
using test::run_cli;
using test::TempDir;

TEST(UnwrapPinched, LibrarySplitsPinchedVerticesAndLaysOutEveryComponent) {
  struct Case {
    const char* name;
    TriMesh mesh;
    int components, genus, loops;
  };
  const std::vector<Case> cases = {
      {"pinched_annulus", shapes::pinched_annulus(8), 1, 0, 1},
      {"double_torus_pinched_hole", shapes::with_pinched_hole(shapes::double_torus(24)), 1, 2, 1},
      {"genus3_pinched_hole", shapes::with_pinched_hole(shapes::genus_surface(3)), 1, 3, 1},
      {"bowtie", shapes::bowtie_vertex(), 2, 0, 0},
      {"mixed", shapes::disjoint_union({shapes::pinched_annulus(5), shapes::torus(16, 8),
                                        shapes::with_pinched_hole(shapes::icosphere(2))}),
       3, 1, 2},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const MeshTopology topo = analyze_topology(c.mesh);
    ASSERT_FALSE(topo.nonmanifold_vertices.empty());
    ASSERT_TRUE(topo.nonmanifold_edges.empty());
    UnwrapResult r;
    check_unwrap(c.name, c.mesh, {}, &r);  // [0,1]^2, no flips/overlaps, charts are disks
    EXPECT_EQ(r.report.num_components, c.components);
    EXPECT_EQ(r.report.genus, c.genus);
    EXPECT_EQ(r.report.boundary_loops, c.loops);
    EXPECT_GE(r.param.num_charts, c.components);
  }
}

TEST(UnwrapPinched, LibraryHandlesMixedWindingAndRejectsNonOrientable) {
  // The failure: a genus-3 surface with one hole that touches itself, some faces wound
  // against their neighbours ("slice_along_cut: the sliced mesh is pinched at vertex ...").
  const TriMesh ref = shapes::with_pinched_hole(shapes::genus_surface(3));
  TriMesh mixed = ref;
  std::vector<char> flipped(mixed.faces.size(), 0);
  for (size_t f = 0; f < mixed.faces.size(); f += 9) {
    std::swap(mixed.faces[f][1], mixed.faces[f][2]);
    flipped[f] = 1;
  }
  const UnwrapResult r = unwrap(mixed);
  EXPECT_EQ(r.report.genus, 3);
  EXPECT_EQ(r.report.boundary_loops, 1);
  // uv_faces follow the input corners: undo the flips on both and check the layout there.
  Parameterization p = r.param;
  for (size_t f = 0; f < p.uv_faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) ASSERT_EQ(p.wedge_vertex[p.uv_faces[f][k]], mixed.faces[f][k]);
    if (flipped[f]) std::swap(p.uv_faces[f][1], p.uv_faces[f][2]);
  }
  for (const Vec2& t : p.uv) ASSERT_TRUE(t.x() >= 0 && t.x() <= 1 && t.y() >= 0 && t.y() <= 1);
  const StretchStats s = measure_stretch(ref, p);
  EXPECT_EQ(s.flipped, 0);
  EXPECT_EQ(s.degenerate, 0);
  EXPECT_EQ(count_overlapping_triangles(p), 0);
  EXPECT_TRUE(std::isfinite(s.l2));
  // A Möbius band cannot be laid out: a clear error, not a failure deep in the cutting.
  TriMesh band;
  for (int i = 0; i < 16; ++i)
    for (double w : {-0.3, 0.3}) {
      const double t = 2 * 3.14159265358979 * i / 16, rr = 1 + w * std::cos(t / 2);
      band.positions.push_back(Vec3(rr * std::cos(t), rr * std::sin(t), w * std::sin(t / 2)));
    }
  for (int i = 0; i < 16; ++i) {
    const int a = 2 * i, b = 2 * i + 1, c = i == 15 ? 1 : 2 * i + 2, d = i == 15 ? 0 : 2 * i + 3;
    band.faces.push_back({a, c, d});
    band.faces.push_back({a, d, b});
  }
  try {
    unwrap(band);
    FAIL() << "no error for a Moebius band";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("not orientable"), std::string::npos) << e.what();
  }
}

/// The `v` lines of an OBJ, as text.
std::vector<std::string> obj_vertex_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("v ", 0) == 0) out.push_back(line);
  return out;
}

TEST(UnwrapPinched, CliWarnsSplitsAndReportsTopologyPerComponent) {
  TempDir dir;
  // A genus-2 surface whose only hole touches itself, next to an annulus pinched into a disk, in odd
  // units so that any rounding of the positions would show.
  TriMesh mesh = shapes::disjoint_union(
      {shapes::with_pinched_hole(shapes::double_torus(24)), shapes::pinched_annulus(6)});
  for (Vec3& p : mesh.positions) p = p * 123.456789 + Vec3(1e3 / 3, -7.25, 0.1);
  const auto in = dir.path / "pinched.obj", out = dir.path / "out.obj", rep = dir.path / "r.json";
  write_obj(in, mesh, nullptr);
  const auto r = run_cli("unwrap '" + in.string() + "' -o '" + out.string() + "' --report '" + rep.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("pinched.obj: split 2 pinched vertices"), std::string::npos) << r.err;

  std::ifstream rf(rep);
  const auto j = nlohmann::json::parse(rf);
  EXPECT_EQ(j["components"], 2);
  EXPECT_EQ(j["genus"], 2);
  EXPECT_EQ(j["boundary_loops"], 2);
  EXPECT_EQ(j["flipped"], 0);
  EXPECT_EQ(j["repair"]["split_pinched_vertices"], 2);
  const auto& comps = j["component_topology"];
  ASSERT_EQ(comps.size(), 2u);
  EXPECT_EQ(comps[0]["genus"], 2);
  EXPECT_EQ(comps[0]["boundary_loops"], 1);
  EXPECT_EQ(comps[0]["boundary_loop_lengths"], nlohmann::json::array({6}));
  EXPECT_EQ(comps[1]["genus"], 0);
  EXPECT_EQ(comps[1]["boundary_loop_lengths"], nlohmann::json::array({40}));
  for (const auto& c : comps)
    EXPECT_EQ(c["euler"].get<int>(), 2 - 2 * c["genus"].get<int>() - c["boundary_loops"].get<int>());

  // Exported positions: the input's `v` lines, plus one bit-identical copy per split vertex.
  const std::vector<std::string> vin = obj_vertex_lines(in), vout = obj_vertex_lines(out);
  ASSERT_EQ(vout.size(), vin.size() + 2);
  EXPECT_TRUE(std::equal(vin.begin(), vin.end(), vout.begin()));
  const std::set<std::string> known(vin.begin(), vin.end());
  for (size_t k = vin.size(); k < vout.size(); ++k) EXPECT_TRUE(known.count(vout[k])) << vout[k];
  // The layout: every vt in [0,1]^2, and the mesh read back has a UV layout for every face.
  const TexturedMesh back = read_textured_obj(out);
  EXPECT_EQ(back.mesh.num_faces(), mesh.num_faces());
  for (const Vec2& t : back.param.uv) EXPECT_TRUE(t.x() >= 0 && t.x() <= 1 && t.y() >= 0 && t.y() <= 1);
}

TEST(UnwrapPinched, CliUnwrapsGenus3WithPinchedHoleAndMixedWinding) {
  TempDir dir;
  TriMesh mesh = shapes::with_pinched_hole(shapes::genus_surface(3));
  for (size_t f = 0; f < mesh.faces.size(); f += 11) std::swap(mesh.faces[f][1], mesh.faces[f][2]);
  const auto in = dir.path / "sculpture.off", out = dir.path / "out.obj", rep = dir.path / "r.json";
  {
    std::ofstream f(in);
    f << "OFF\n" << mesh.num_vertices() << " " << mesh.num_faces() << " 0\n";
    f.precision(17);
    for (const Vec3& p : mesh.positions) f << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const Face& t : mesh.faces) f << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  }
  auto r = run_cli("info --json '" + in.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out);
  EXPECT_EQ(info["genus"], 3);
  EXPECT_EQ(info["boundary_loops"], 1);
  EXPECT_EQ(info["boundary_loop_lengths"], nlohmann::json::array({6}));
  EXPECT_EQ(info["flipped_faces"], static_cast<int>((mesh.faces.size() + 10) / 11));
  r = run_cli("unwrap '" + in.string() + "' -o '" + out.string() + "' --report '" + rep.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("split 1 pinched vertex"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("whose winding disagreed with their neighbours"), std::string::npos) << r.err;
  std::ifstream rf(rep);
  const auto j = nlohmann::json::parse(rf);
  EXPECT_EQ(j["genus"], 3);
  EXPECT_EQ(j["boundary_loops"], 1);
  EXPECT_EQ(j["flipped"], 0);
  EXPECT_EQ(j["degenerate"], 0);
  EXPECT_EQ(j["component_topology"][0]["euler"], -5);
  const TexturedMesh back = read_textured_obj(out);
  for (int f = 0; f < back.mesh.num_faces(); ++f) EXPECT_GT(uv_signed_area(back.param, f), 0.0) << "face " << f;
  EXPECT_EQ(count_overlapping_triangles(back.param), 0);
}

}  // namespace
}  // namespace adaptex
