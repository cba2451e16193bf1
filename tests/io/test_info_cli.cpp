// `adaptex info` through the CLI: every kind of bad input exits 2 with one line on stderr that names
// the file and the problem; good input prints the report (text and JSON); --repair.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "adaptex/core/shapes.h"
#include "io_test_files.h"
#include "test_support.h"

namespace adaptex {
namespace {

using test::run_cli;
using test::TempDir;

/// Runs `info FILE`, expects exit 2 and a single stderr line containing the file name and \p what.
void expect_bad(const std::filesystem::path& file, const std::string& what, const std::string& extra = "") {
  const auto r = run_cli("info '" + file.string() + "'" + extra);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.find("adaptex: error: "), 0u) << r.err;
  EXPECT_NE(r.err.find(file.filename().string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << "expected '" << what << "' in: " << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line: " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(InfoCli, Help) {
  const auto r = run_cli("info --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--repair"), std::string::npos);
  EXPECT_NE(r.out.find("--json"), std::string::npos);
}

TEST(InfoCli, GoodMeshTextAndJson) {
  TempDir dir;
  test::write_off(dir.path / "torus.off", shapes::torus(16, 8));
  auto r = run_cli("info '" + (dir.path / "torus.off").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("vertices:    128"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("faces:       256"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("genus 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("manifold:    yes"), std::string::npos) << r.out;
  r = run_cli("info --json '" + (dir.path / "torus.off").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 128);
  EXPECT_EQ(j["faces"], 256);
  EXPECT_EQ(j["edges"], 384);
  EXPECT_EQ(j["components"], 1);
  EXPECT_EQ(j["genus"], 1);
  EXPECT_EQ(j["boundary_loops"], 0);
  EXPECT_EQ(j["manifold"], true);
  EXPECT_EQ(j["orientation"], "ccw (outward)");
  EXPECT_GT(j["surface_area"].get<double>(), 0.0);
  test::write_off(dir.path / "two.off", shapes::two_components());
  r = run_cli("info --json '" + (dir.path / "two.off").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["components"], 2);
}

TEST(InfoCli, Unreadable) {
  TempDir dir;
  expect_bad(dir.path / "missing.obj", "does not exist");
  std::filesystem::create_directories(dir.path / "folder.obj");
  expect_bad(dir.path / "folder.obj", "is a directory");
  test::write_text(dir.path / "empty.off", "");
  expect_bad(dir.path / "empty.off", "file is empty");
}

TEST(InfoCli, UnknownExtension) {
  TempDir dir;
  test::write_text(dir.path / "mesh.xyz", "1 2 3\n");
  expect_bad(dir.path / "mesh.xyz", "unknown mesh format '.xyz'");
}

TEST(InfoCli, Corrupt) {
  TempDir dir;
  test::write_text(dir.path / "bad.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty floot x\nend_header\n");
  expect_bad(dir.path / "bad.ply", "corrupt PLY header: line 4: unknown property type 'floot'");
  test::write_text(dir.path / "int.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty int x\nend_header\n1\n");
  expect_bad(dir.path / "int.ply", "PLY vertex element has no float or double property 'x'");
  test::write_text(dir.path / "bad2.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  expect_bad(dir.path / "bad2.ply", "corrupt PLY header: no 'end_header' line");
  test::write_text(dir.path / "bad.off", "HELLO\n3 1 0\n");
  expect_bad(dir.path / "bad.off", "not a valid OFF file");
  test::write_text(dir.path / "bad.stl", "solid x\n facet normal 0 0 0\n outer loop\n vertex 0 0 zero\n");
  expect_bad(dir.path / "bad.stl", "corrupt ASCII STL");
  test::write_text(dir.path / "bad.glb", "glTF this is not a binary gltf");
  expect_bad(dir.path / "bad.glb", "corrupt glTF");
  test::write_text(dir.path / "bad.obj", "v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n");
  expect_bad(dir.path / "bad.obj", "line 2: 'v' statement 2 has a non-numeric coordinate");
}

TEST(InfoCli, Truncated) {
  TempDir dir;
  const TriMesh m = shapes::icosphere(1);
  // Binary STL shorter than its triangle count says.
  test::write_stl_binary(dir.path / "t.stl", m);
  std::filesystem::resize_file(dir.path / "t.stl", 84 + 50 * 10 + 7);
  expect_bad(dir.path / "t.stl", "binary STL truncated: the header says 80 triangles");
  // Binary PLY cut in the face list.
  test::write_ply_binary(dir.path / "t.ply", m);
  std::filesystem::resize_file(dir.path / "t.ply", std::filesystem::file_size(dir.path / "t.ply") - 30);
  expect_bad(dir.path / "t.ply", "PLY truncated or corrupt: element 'face' item 77 of 80");
  // OFF with fewer vertex lines than the header says (the last face line goes missing).
  test::write_off(dir.path / "t.off", m);
  std::string text;
  {
    std::ifstream in(dir.path / "t.off");
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const auto header_end = text.find('\n', text.find('\n') + 1) + 1;
  const auto second_vertex = text.find('\n', header_end) + 1;
  test::write_text(dir.path / "t.off", text.substr(0, header_end) + text.substr(second_vertex));
  expect_bad(dir.path / "t.off", "face 79 is missing or unreadable: file truncated, or fewer vertex or face lines than the header says (the header says 42 vertices, 80 faces)");
}

TEST(InfoCli, NoFaces) {
  TempDir dir;
  test::write_text(dir.path / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expect_bad(dir.path / "points.obj", "no faces (3 vertices, 0 faces)");
  test::write_text(dir.path / "points.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  expect_bad(dir.path / "points.off", "no faces");
}

TEST(InfoCli, NonFinite) {
  TempDir dir;
  test::write_text(dir.path / "nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nv 1 1 1\nf 1 2 3\nf 1 2 4\n");
  expect_bad(dir.path / "nan.obj", "vertex 3 has a non-finite coordinate (0, nan, 0)");
  TriMesh m = shapes::icosphere(0);
  m.positions[5].x() = std::numeric_limits<double>::infinity();
  test::write_stl_binary(dir.path / "inf.stl", m);
  expect_bad(dir.path / "inf.stl", "has a non-finite coordinate (inf");
  test::write_ply_binary(dir.path / "inf.ply", m);
  expect_bad(dir.path / "inf.ply", "vertex 5 has a non-finite coordinate (inf");
}

TEST(InfoCli, IndexOutOfRange) {
  TempDir dir;
  test::write_text(dir.path / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 9\n");
  expect_bad(dir.path / "range.obj", "face 2 refers to vertex 9, out of range (the file has 3 vertices, numbered from 1)");
  test::write_text(dir.path / "range.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 7\n");
  expect_bad(dir.path / "range.off", "face 1 refers to a vertex index out of range (the file has 3 vertices");
  TriMesh m = shapes::icosphere(0);
  m.faces[4][2] = 12;
  test::write_ply_binary(dir.path / "range.ply", m);
  expect_bad(dir.path / "range.ply", "face 4 refers to vertex 12, out of range (the file has 12 vertices, numbered from 0)");
}

TEST(InfoCli, NonManifoldEdgeAndVertex) {
  TempDir dir;
  test::write_off(dir.path / "fan.off", shapes::nonmanifold_fan());
  expect_bad(dir.path / "fan.off", "1 non-manifold edge (first: vertices ");
  expect_bad(dir.path / "fan.off", "rerun with --repair");
  // A pinched vertex alone is not an error: it is split with a warning (InfoCli.PinchedVertices...).
  test::write_off(dir.path / "bowtie.off", shapes::bowtie_vertex());
  const auto r = run_cli("info --json '" + (dir.path / "bowtie.off").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("bowtie.off: split 1 pinched vertex"), std::string::npos) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["components"], 2);
}

TEST(InfoCli, PinchedVerticesSplitAndTopologyPerComponent) {
  TempDir dir;
  // A genus-2 surface whose hole touches itself, an annulus whose two boundaries touch, a torus.
  const TriMesh m = shapes::disjoint_union({shapes::with_pinched_hole(shapes::double_torus(24)),
                                            shapes::pinched_annulus(5), shapes::torus(12, 6)});
  test::write_off(dir.path / "p.off", m);
  auto r = run_cli("info --json '" + (dir.path / "p.off").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("p.off: split 2 pinched vertices"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["manifold"], true);
  EXPECT_EQ(j["split_pinched_vertices"], 2);
  EXPECT_EQ(j["components"], 3);
  EXPECT_EQ(j["genus"], 3);
  EXPECT_EQ(j["boundary_loops"], 2);
  EXPECT_EQ(j["component_genus"], nlohmann::json::array({2, 0, 1}));
  EXPECT_EQ(j["component_boundary_loops"], nlohmann::json::array({1, 1, 0}));
  const auto& comps = j["component_topology"];
  ASSERT_EQ(comps.size(), 3u);
  EXPECT_EQ(comps[0]["boundary_loop_lengths"], nlohmann::json::array({6}));
  EXPECT_EQ(comps[1]["boundary_loop_lengths"], nlohmann::json::array({32}));
  EXPECT_EQ(comps[2]["boundary_loop_lengths"], nlohmann::json::array());
  EXPECT_EQ(comps[2]["faces"], 144);
  int faces = 0;
  for (const auto& c : comps) {
    faces += c["faces"].get<int>();
    EXPECT_EQ(c["euler"].get<int>(), c["vertices"].get<int>() - c["edges"].get<int>() + c["faces"].get<int>());
    EXPECT_EQ(c["euler"].get<int>(), 2 - 2 * c["genus"].get<int>() - c["boundary_loops"].get<int>());
  }
  EXPECT_EQ(faces, m.num_faces());
  r = run_cli("info '" + (dir.path / "p.off").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  component 0: genus 2, 1 boundary loop (lengths: 6 edges), euler char. -3"),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  component 1: genus 0, 1 boundary loop (lengths: 32 edges), euler char. 1"),
            std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  component 2: genus 1, 0 boundary loops, euler char. 0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pinched:     2 vertices split"), std::string::npos) << r.out;
}

TEST(InfoCli, RepairMakesThemManifold) {
  TempDir dir;
  test::write_off(dir.path / "fan.off", shapes::nonmanifold_fan());
  test::write_off(dir.path / "bowtie.off", shapes::bowtie_vertex());
  for (const char* f : {"fan.off", "bowtie.off"}) {
    const auto r = run_cli("info --repair --json '" + (dir.path / f).string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["manifold"], true) << f;
    EXPECT_EQ(j["nonmanifold_edges"], 0) << f;
    EXPECT_EQ(j["nonmanifold_vertices"], 0) << f;
    // The fan's non-manifold edge is repaired; the bow-tie's pinched vertex is split anyway.
    EXPECT_GT(j["split_nonmanifold_vertices"].get<int>() + j["split_pinched_vertices"].get<int>(), 0) << f;
    EXPECT_TRUE(r.err.find("repair split") != std::string::npos || r.err.find("pinched") != std::string::npos)
        << r.err;
  }
}

TEST(InfoCli, DegenerateAndUnreferencedWarn) {
  TempDir dir;
  TriMesh m = shapes::icosphere(1);
  m.positions.push_back(Vec3(9, 9, 9));  // unreferenced
  m.positions.push_back(m.positions[0]);
  m.faces.push_back({0, 1, m.num_vertices() - 1});  // zero area (two corners at the same position)
  test::write_off(dir.path / "dirty.off", m);
  const auto r = run_cli("info --json '" + (dir.path / "dirty.off").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("dirty.off: dropped 1 degenerate (zero-area) face"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("dirty.off: dropped 2 unreferenced vertices"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["dropped_degenerate_faces"], 1);
  EXPECT_EQ(j["dropped_unreferenced_vertices"], 2);
  EXPECT_EQ(j["faces"], 80);
  EXPECT_EQ(j["vertices"], 42);
}

}  // namespace
}  // namespace adaptex
