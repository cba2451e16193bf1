// Tests of io/mesh_io: every input format read back from small files written here, welding,
// exact positions, tristrips, COFF/CRLF, validation, repair, write_obj / read_textured_obj.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "adaptex/core/errors.h"
#include "adaptex/core/shapes.h"
#include "adaptex/core/topology.h"
#include "adaptex/io/mesh_io.h"
#include "io_test_files.h"
#include "test_support.h"

namespace adaptex {
namespace {

using test::TempDir;

/// Positions that need all 17 digits (not representable in float, not short decimals).
TriMesh irrational_sphere() {
  TriMesh m = shapes::sphere(12, 7, 1.0);
  for (auto& p : m.positions) p = p * (1.0 / 3.0) + Vec3(std::sqrt(2.0), -M_PI, 1e-7 / 7.0);
  return m;
}

/// Every interior edge is used once in each direction: orientation is consistent.
bool consistently_oriented(const TriMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const Face& f : m.faces)
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  for (const auto& [e, n] : directed)
    if (n != 1) return false;
  return true;
}

void expect_same_mesh(const TriMesh& a, const TriMesh& b, bool exact_positions) {
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_faces(), b.num_faces());
  for (int v = 0; v < a.num_vertices(); ++v) {
    if (exact_positions)
      ASSERT_EQ(a.positions[v], b.positions[v]) << "vertex " << v;
    else
      ASSERT_LT((a.positions[v] - b.positions[v]).norm(), 1e-6) << "vertex " << v;
  }
  EXPECT_EQ(a.faces, b.faces);
}

TEST(MeshIo, ObjRoundTripIsExact) {
  TempDir dir;
  const TriMesh m = irrational_sphere();
  write_obj(dir.path / "a.obj", m, nullptr);
  ReadReport r;
  const TriMesh back = read_mesh(dir.path / "a.obj", {}, &r);
  EXPECT_EQ(r.format, "obj");
  EXPECT_EQ(r.welded_vertices, 0);
  expect_same_mesh(m, back, true);
}

TEST(MeshIo, ObjWriterStreamsTheSameTextAsOneSerialLoop) {
  // Over 2^19 faces: the writer formats 16 blocks of 2^15 lines at a time and writes each batch;
  // the file must equal the text of one plain loop (block and batch borders included).
  TempDir dir;
  const TriMesh m = shapes::plane(520, 1.37);  // 540,800 faces
  Parameterization p;
  for (const Vec3& x : m.positions) p.uv.push_back(Vec2(x.x() / 1.37, x.y() / 1.37));
  p.uv_faces = m.faces;
  ASSERT_GT(m.faces.size(), std::size_t{1} << 19);
  write_obj(dir.path / "big.obj", m, &p);
  const auto num = [](double x) {
    char buf[32];
    return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
  };
  std::string expect = "# written by adaptex: v = input positions (shortest round-trip digits), vt = UV layout, f v/vt\n";
  for (const Vec3& x : m.positions) expect += "v " + num(x.x()) + ' ' + num(x.y()) + ' ' + num(x.z()) + '\n';
  for (const Vec2& t : p.uv) expect += "vt " + num(t.x()) + ' ' + num(t.y()) + '\n';
  for (const Face& f : m.faces) {
    expect += 'f';
    for (int k = 0; k < 3; ++k) expect += ' ' + std::to_string(f[k] + 1) + '/' + std::to_string(f[k] + 1);
    expect += '\n';
  }
  std::ifstream in(dir.path / "big.obj", std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(text.size(), expect.size());
  EXPECT_TRUE(text == expect);
}

TEST(MeshIo, ObjShortDecimalsAreCorrectlyRounded) {
  // tinyobjloader alone gets these wrong by 1-2 ulp; the reader must match strtod exactly.
  TempDir dir;
  test::write_text(dir.path / "t.obj",
                   "v -0.354446 0.351858 0.219842\nv 0.348799 -0.334989 -0.0832331\nv 0.101779 0.233283 0.108189\n"
                   "f 1 2 3\n");
  const TriMesh m = read_mesh(dir.path / "t.obj");
  const double expect[9] = {-0.354446, 0.351858, 0.219842, 0.348799, -0.334989, -0.0832331,
                            0.101779,  0.233283, 0.108189};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(m.positions[i / 3][i % 3], expect[i]) << i;
}

TEST(MeshIo, ObjSeparateIndicesAndQuadsAndNegativeIndices) {
  TempDir dir;
  // A unit cube as quads with v/vt/vn corners and one face with relative (negative) indices.
  test::write_text(dir.path / "cube.obj",
                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
                   "f 1/1/1 4/4/1 3/3/1 2/2/1\nf 5/1/1 6/2/1 7/3/1 8/4/1\nf 1/1 2/2 6/3 5/4\n"
                   "f 2//1 3//1 7//1 6//1\nf 3 4 8 7\nf -4 -1 -5 -8\n");
  const TriMesh m = read_mesh(dir.path / "cube.obj");
  EXPECT_EQ(m.num_vertices(), 8);
  EXPECT_EQ(m.num_faces(), 12);
  const MeshTopology t = analyze_topology(m);
  EXPECT_TRUE(t.is_manifold());
  EXPECT_EQ(t.total_loops(), 0);
  EXPECT_TRUE(consistently_oriented(m));
  EXPECT_NEAR(signed_volume(m), 1.0, 1e-12);
}

TEST(MeshIo, ObjDuplicatedPositionsAreWelded) {
  TempDir dir;
  // Two triangles whose shared edge is written twice (as exporters do at UV seams).
  test::write_text(dir.path / "w.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 4 6 5\n");
  ReadReport r;
  const TriMesh m = read_mesh(dir.path / "w.obj", {}, &r);
  EXPECT_EQ(m.num_vertices(), 4);
  EXPECT_EQ(r.welded_vertices, 2);
  EXPECT_EQ(analyze_topology(m).num_edges, 5);
}

TEST(MeshIo, OffRoundTripIsExactAndCoffCrlf) {
  TempDir dir;
  const TriMesh m = irrational_sphere();
  test::write_off(dir.path / "a.off", m);
  test::write_off(dir.path / "c.off", m, /*coff=*/true, /*crlf=*/true);
  ReadReport r;
  expect_same_mesh(m, read_mesh(dir.path / "a.off", {}, &r), true);
  EXPECT_EQ(r.format, "off");
  expect_same_mesh(m, read_mesh(dir.path / "c.off"), true);
}

TEST(MeshIo, PlyAsciiKeepsTheDecimalText) {
  TempDir dir;
  const TriMesh m = irrational_sphere();
  // Declared float: the reader keeps the written decimal at double precision.
  test::write_ply_ascii(dir.path / "f.ply", m, "float");
  expect_same_mesh(m, read_mesh(dir.path / "f.ply"), true);
  test::write_ply_ascii(dir.path / "d.ply", m, "double");
  expect_same_mesh(m, read_mesh(dir.path / "d.ply"), true);
}

TEST(MeshIo, PlyBinaryFaces) {
  TempDir dir;
  const TriMesh m = irrational_sphere();
  test::write_ply_binary(dir.path / "b.ply", m);
  expect_same_mesh(m, read_mesh(dir.path / "b.ply"), true);
}

TEST(MeshIo, PlyTristripsUnstripWithConsistentWinding) {
  TempDir dir;
  // Grid of (n+1) x (n+1) vertices; one strip per row of quads, rows separated by -1.
  const int n = 5;
  TriMesh grid = shapes::plane(n);
  ASSERT_EQ(grid.num_vertices(), (n + 1) * (n + 1));
  // shapes::plane's vertex (i, j) position is (i, j)/n: find the index of each grid point.
  std::map<std::pair<long, long>, int> at;
  for (int v = 0; v < grid.num_vertices(); ++v)
    at[{std::lround(grid.positions[v].x() * n), std::lround(grid.positions[v].y() * n)}] = v;
  std::vector<int> strips;
  for (int j = 0; j < n; ++j) {
    if (j > 0) strips.push_back(-1);
    for (int i = 0; i <= n; ++i) {
      strips.push_back(at.at({i, j}));      // bottom row
      strips.push_back(at.at({i, j + 1}));  // top row
    }
  }
  // Strip triangle 0 is (b0, t0, b1): clockwise seen from +z, so every unstripped face points to -z.
  test::write_ply_binary(dir.path / "s.ply", grid, &strips);
  const TriMesh m = read_mesh(dir.path / "s.ply");
  EXPECT_EQ(m.num_faces(), 2 * n * n);
  EXPECT_EQ(m.num_vertices(), (n + 1) * (n + 1));
  EXPECT_TRUE(consistently_oriented(m));
  for (int f = 0; f < m.num_faces(); ++f) EXPECT_LT(face_normal(m, f).z(), -0.99) << "face " << f;
  EXPECT_EQ(analyze_topology(m).total_loops(), 1);
}

TEST(MeshIo, StlBinaryAndAsciiAreWelded) {
  TempDir dir;
  const TriMesh m = shapes::sphere(16, 9, 2.0);
  test::write_stl_binary(dir.path / "b.stl", m);
  test::write_stl_ascii(dir.path / "a.stl", m);
  for (const char* f : {"b.stl", "a.stl"}) {
    ReadReport r;
    const TriMesh back = read_mesh(dir.path / f, {}, &r);
    EXPECT_EQ(back.num_vertices(), m.num_vertices()) << f;
    EXPECT_EQ(back.num_faces(), m.num_faces()) << f;
    EXPECT_EQ(r.welded_vertices, 3 * m.num_faces() - m.num_vertices()) << f;
    const MeshTopology t = analyze_topology(back);
    EXPECT_TRUE(t.is_manifold()) << f;
    EXPECT_EQ(t.total_genus(), 0) << f;
    EXPECT_EQ(t.total_loops(), 0) << f;
    EXPECT_TRUE(consistently_oriented(back)) << f;
  }
  // ASCII STL keeps the written 17-digit decimals exactly.
  const TriMesh a = read_mesh(dir.path / "a.stl");
  std::set<std::array<double, 3>> original, read;
  for (const auto& p : m.positions) original.insert({p.x(), p.y(), p.z()});
  for (const auto& p : a.positions) read.insert({p.x(), p.y(), p.z()});
  EXPECT_EQ(original, read);
}

/// A glTF model with one triangle mesh (float positions, uint32 indices) under a node.
void write_gltf(const std::filesystem::path& p, const TriMesh& m, bool binary, bool translate) {
  tinygltf::Model model;
  tinygltf::Buffer buffer;
  auto append = [&](const void* data, size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    buffer.data.insert(buffer.data.end(), b, b + n);
  };
  std::vector<float> xyz;
  std::vector<double> lo(3, 1e300), hi(3, -1e300);
  for (const auto& v : m.positions)
    for (int k = 0; k < 3; ++k) {
      xyz.push_back(static_cast<float>(v[k]));
      lo[k] = std::min(lo[k], static_cast<double>(xyz.back()));
      hi[k] = std::max(hi[k], static_cast<double>(xyz.back()));
    }
  std::vector<std::uint32_t> idx;
  for (const auto& f : m.faces)
    for (int v : f) idx.push_back(static_cast<std::uint32_t>(v));
  append(xyz.data(), xyz.size() * 4);
  append(idx.data(), idx.size() * 4);
  model.buffers.push_back(buffer);
  tinygltf::BufferView pos_view, idx_view;
  pos_view.buffer = 0;
  pos_view.byteOffset = 0;
  pos_view.byteLength = xyz.size() * 4;
  pos_view.target = TINYGLTF_TARGET_ARRAY_BUFFER;
  idx_view.buffer = 0;
  idx_view.byteOffset = xyz.size() * 4;
  idx_view.byteLength = idx.size() * 4;
  idx_view.target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
  model.bufferViews = {pos_view, idx_view};
  tinygltf::Accessor pos, ind;
  pos.bufferView = 0;
  pos.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  pos.count = m.positions.size();
  pos.type = TINYGLTF_TYPE_VEC3;
  pos.minValues = lo;
  pos.maxValues = hi;
  ind.bufferView = 1;
  ind.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  ind.count = idx.size();
  ind.type = TINYGLTF_TYPE_SCALAR;
  model.accessors = {pos, ind};
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = 0;
  prim.indices = 1;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  if (translate) node.translation = {1.0, 2.0, 3.0};
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  model.asset.version = "2.0";
  tinygltf::TinyGLTF writer;
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&model, p.string(), true, true, true, binary));
}

TEST(MeshIo, GltfAndGlb) {
  TempDir dir;
  const TriMesh m = shapes::torus(12, 8);
  write_gltf(dir.path / "t.gltf", m, false, false);
  write_gltf(dir.path / "t.glb", m, true, true);
  for (const char* f : {"t.gltf", "t.glb"}) {
    ReadReport r;
    const TriMesh back = read_mesh(dir.path / f, {}, &r);
    EXPECT_EQ(back.num_vertices(), m.num_vertices()) << f;
    EXPECT_EQ(back.num_faces(), m.num_faces()) << f;
    const MeshTopology t = analyze_topology(back);
    EXPECT_EQ(t.total_genus(), 1) << f;
    EXPECT_TRUE(t.is_manifold()) << f;
    const Vec3 shift = std::string(f) == "t.glb" ? Vec3(1, 2, 3) : Vec3(0, 0, 0);
    // Identity transform: the float32 values of the file, exactly.
    for (int v = 0; v < m.num_vertices() && shift.isZero(); ++v)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(back.positions[v][k], static_cast<double>(static_cast<float>(m.positions[v][k])));
    EXPECT_NEAR((bounding_box(back).min - bounding_box(m).min - shift).norm(), 0.0, 1e-6) << f;
  }
}

TEST(MeshIo, DegenerateAndUnreferencedAreDroppedWithWarnings) {
  TempDir dir;
  TriMesh m = shapes::icosphere(1);
  m.positions.push_back(Vec3(5, 5, 5));        // unreferenced
  m.positions.push_back(Vec3(6, 6, 6));        // only used by the degenerate face below
  m.faces.push_back({0, m.num_vertices() - 1, 0});  // repeated index: degenerate
  test::write_off(dir.path / "d.off", m);
  ReadReport r;
  const TriMesh back = read_mesh(dir.path / "d.off", {}, &r);
  EXPECT_EQ(back.num_faces(), 80);
  EXPECT_EQ(back.num_vertices(), 42);
  EXPECT_EQ(r.dropped_degenerate_faces, 1);
  EXPECT_EQ(r.dropped_unreferenced_vertices, 2);
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings[0].find("d.off"), std::string::npos);
  // Zero area with distinct indices (collinear).
  TriMesh c = shapes::icosphere(1);
  c.positions.insert(c.positions.end(), {Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)});  // collinear
  c.faces.push_back({c.num_vertices() - 3, c.num_vertices() - 2, c.num_vertices() - 1});
  ReadReport rc;
  const TriMesh vc = validate_mesh(c, "collinear", {}, &rc);
  EXPECT_EQ(rc.dropped_degenerate_faces, 1);
  EXPECT_EQ(vc.num_faces(), 80);
}

TEST(MeshIo, ValidateRejectsBadInMemoryMeshes) {
  TriMesh m = shapes::icosphere(0);
  TriMesh nan = m;
  nan.positions[3].y() = std::nan("");
  try {
    validate_mesh(nan, "mem");
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 3"), std::string::npos) << e.what();
  }
  TriMesh range = m;
  range.faces[5][1] = 99;
  try {
    validate_mesh(range, "mem");
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 5"), std::string::npos) << e.what();
  }
  EXPECT_THROW(validate_mesh(TriMesh{m.positions, {}}, "mem"), InvalidInputError);
  TriMesh dup = m;
  dup.faces.push_back(dup.faces[2]);
  EXPECT_THROW(validate_mesh(dup, "mem"), TopologyError);
  ReadOptions repair;
  repair.repair = true;
  ReadReport r;
  const TriMesh fixed = validate_mesh(dup, "mem", repair, &r);
  EXPECT_EQ(r.dropped_duplicate_faces, 1);
  EXPECT_EQ(fixed.num_faces(), m.num_faces());
}

TEST(MeshIo, RepairMakesNonManifoldMeshesManifold) {
  ReadOptions repair;
  repair.repair = true;
  for (const auto& [name, mesh] : std::vector<std::pair<std::string, TriMesh>>{
           {"fan", shapes::nonmanifold_fan()}, {"bowtie", shapes::bowtie_vertex()}}) {
    EXPECT_FALSE(analyze_topology(mesh).is_manifold()) << name;
    ReadReport r;
    const TriMesh fixed = validate_mesh(mesh, name, repair, &r);
    const MeshTopology t = analyze_topology(fixed);
    EXPECT_TRUE(t.is_manifold()) << name;
    // The fan's non-manifold edge needs the repair; the bow-tie's pinched vertex is always split.
    EXPECT_GT(r.split_nonmanifold_vertices + r.split_pinched_vertices, 0) << name;
    EXPECT_EQ(fixed.num_faces(), mesh.num_faces()) << name;
    // Split copies keep the position of their original.
    std::set<std::array<double, 3>> before, after;
    for (const auto& p : mesh.positions) before.insert({p.x(), p.y(), p.z()});
    for (const auto& p : fixed.positions) after.insert({p.x(), p.y(), p.z()});
    EXPECT_EQ(before, after) << name;
  }
  // Harder: four "pages" around one edge plus two tetrahedra sharing an edge.
  TriMesh book;
  book.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  book.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {1, 0, 5}};
  TriMesh tets;
  tets.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  tets.faces = {{0, 2, 1}, {0, 3, 2}, {0, 1, 3}, {1, 2, 3}, {0, 1, 4}, {0, 4, 5}, {0, 5, 1}, {1, 5, 4}};
  for (const TriMesh& m : {book, tets}) {
    EXPECT_FALSE(analyze_topology(m).is_manifold());
    const TriMesh fixed = validate_mesh(m, "m", repair);
    EXPECT_TRUE(analyze_topology(fixed).is_manifold());
    EXPECT_EQ(fixed.num_faces(), m.num_faces());
  }
}

TEST(MeshIo, PinchedVerticesAreSplitWithoutRepair) {
  // A non-manifold edge stays an error without --repair.
  EXPECT_THROW(validate_mesh(shapes::nonmanifold_fan(), "fan"), TopologyError);
  // Pinched vertices (a boundary touching itself, two closed surfaces touching) are split, with a
  // warning that counts them; each fan gets its own vertex at the bit-identical position.
  const TriMesh in = shapes::disjoint_union({shapes::pinched_annulus(6), shapes::bowtie_vertex(),
                                             shapes::with_pinched_hole(shapes::torus(16, 8))});
  ASSERT_EQ(analyze_topology(in).nonmanifold_vertices.size(), 3u);
  ReadReport r;
  const TriMesh out = validate_mesh(in, "pinched", {}, &r);
  EXPECT_EQ(r.split_pinched_vertices, 3);
  EXPECT_EQ(r.split_nonmanifold_vertices, 0);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_EQ(r.warnings[0].find("pinched: split 3 pinched vertices"), 0u) << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("3 copies added at the same position"), std::string::npos) << r.warnings[0];
  ASSERT_EQ(out.num_vertices(), in.num_vertices() + 3);
  ASSERT_EQ(out.num_faces(), in.num_faces());
  for (int v = 0; v < in.num_vertices(); ++v) EXPECT_EQ(out.positions[v], in.positions[v]);
  for (int f = 0; f < in.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = out.positions[out.faces[f][k]];
      const Vec3& q = in.positions[in.faces[f][k]];
      EXPECT_TRUE(p.x() == q.x() && p.y() == q.y() && p.z() == q.z()) << "face " << f;
    }
  const MeshTopology t = analyze_topology(out);
  EXPECT_TRUE(t.is_manifold());
  EXPECT_EQ(t.num_components, 4);  // the bow-tie is two tetrahedra
  EXPECT_EQ(t.component_genus, (std::vector<int>{0, 0, 0, 1}));
  EXPECT_EQ(t.component_loops, (std::vector<int>{1, 0, 0, 1}));
  // Through a file, the reader tracks the file's vertex numbers.
  TempDir dir;
  test::write_off(dir.path / "p.off", shapes::pinched_annulus(4));
  ReadReport rf;
  const TriMesh m = read_mesh(dir.path / "p.off", {}, &rf);
  EXPECT_EQ(rf.split_pinched_vertices, 1);
  EXPECT_TRUE(analyze_topology(m).is_manifold());
}

TEST(MeshIo, RepairedMeshesGetTheirWindingMadeConsistent) {
  // The repair checks the winding on its own edges (no second topology pass): a mesh it makes
  // manifold is flipped exactly where its faces disagree, and left alone where none do.
  ReadOptions repair;
  repair.repair = true;
  const TriMesh torus = shapes::torus(16, 8);
  const TriMesh clean = shapes::disjoint_union({shapes::nonmanifold_fan(), torus});
  TriMesh mixed = clean;
  const int fan_faces = shapes::nonmanifold_fan().num_faces();
  for (int f = fan_faces; f < mixed.num_faces(); f += 5) std::swap(mixed.faces[f][1], mixed.faces[f][2]);
  ReadReport rc, rm;
  const TriMesh kept = validate_mesh(clean, "clean", repair, &rc);
  const TriMesh out = validate_mesh(mixed, "mixed", repair, &rm);
  EXPECT_GT(rm.split_nonmanifold_vertices, 0);
  EXPECT_EQ(rc.flipped_faces, 0);
  EXPECT_EQ(rm.flipped_faces, (torus.num_faces() + 4) / 5);
  EXPECT_EQ(out.faces, kept.faces);
  for (const ComponentTopology& c : analyze_topology(out).components) EXPECT_TRUE(c.consistently_oriented);
}

TEST(MeshIo, MixedWindingIsMadeConsistent) {
  // Some faces wound against their neighbours (as in some scans): flipped back, with a warning.
  const TriMesh ref = shapes::with_pinched_hole(shapes::torus(16, 8));
  TriMesh mixed = ref;
  for (size_t f = 0; f < mixed.faces.size(); f += 5) std::swap(mixed.faces[f][1], mixed.faces[f][2]);
  ReadReport r;
  const TriMesh out = validate_mesh(mixed, "mixed", {}, &r);
  EXPECT_EQ(r.flipped_faces, static_cast<int>((ref.faces.size() + 4) / 5));
  EXPECT_EQ(r.split_pinched_vertices, 1);
  ASSERT_EQ(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings[1].find("mixed: flipped " + std::to_string(r.flipped_faces) + " faces"), std::string::npos)
      << r.warnings[1];
  ASSERT_EQ(out.num_faces(), ref.num_faces());
  for (int f = 0; f < ref.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(out.positions[out.faces[f][k]], ref.positions[ref.faces[f][k]]);
  EXPECT_TRUE(analyze_topology(out).components[0].consistently_oriented);
  // A textured OBJ with mixed winding: the UV corners follow their vertices when a face is flipped.
  TempDir dir;
  const TriMesh plane = shapes::plane(4);
  TriMesh wound = plane;
  Parameterization p;
  for (const Vec3& x : plane.positions) {
    p.uv.push_back(Vec2(x.x(), x.y()));
    p.wedge_vertex.push_back(static_cast<int>(p.wedge_vertex.size()));
  }
  for (size_t f = 0; f < wound.faces.size(); f += 3) std::swap(wound.faces[f][1], wound.faces[f][2]);
  p.uv_faces = wound.faces;
  p.face_chart.assign(wound.faces.size(), 0);
  p.num_charts = 1;
  write_obj(dir.path / "wound.obj", wound, &p);
  ReadReport rt;
  const TexturedMesh back = read_textured_obj(dir.path / "wound.obj", {}, &rt);
  EXPECT_EQ(rt.flipped_faces, static_cast<int>((plane.faces.size() + 2) / 3));
  ASSERT_EQ(back.mesh.faces, plane.faces);
  for (int f = 0; f < back.mesh.num_faces(); ++f) {
    EXPECT_GT(uv_signed_area(back.param, f), 0.0) << "face " << f;
    for (int k = 0; k < 3; ++k) {
      const Vec2& t = back.param.uv[back.param.uv_faces[f][k]];
      const Vec3& x = back.mesh.positions[back.mesh.faces[f][k]];
      EXPECT_EQ(t, Vec2(x.x(), x.y())) << "face " << f << " corner " << k;
    }
  }
}

TEST(MeshIo, ErrorsNameTheFile) {
  TempDir dir;
  EXPECT_THROW(read_mesh(dir.path / "missing.obj"), IoError);
  test::write_text(dir.path / "x.xyz", "hello");
  EXPECT_THROW(read_mesh(dir.path / "x.xyz"), IoError);
  test::write_text(dir.path / "e.ply", "");
  try {
    read_mesh(dir.path / "e.ply");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("e.ply"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos);
  }
}

TEST(MeshIo, WriteObjAndReadTexturedObj) {
  TempDir dir;
  // Two charts: the plane's faces split into left and right halves with separate wedges.
  const TriMesh m = shapes::plane(4);
  Parameterization p;
  std::map<std::pair<int, int>, int> wedge;
  p.uv_faces.resize(m.num_faces());
  p.face_chart.resize(m.num_faces());
  for (int f = 0; f < m.num_faces(); ++f) {
    const int chart = point_on_face(m, f, 1.0 / 3, 1.0 / 3).x() < 0.5 ? 0 : 1;
    p.face_chart[f] = chart;
    for (int k = 0; k < 3; ++k) {
      const int v = m.faces[f][k];
      auto [it, inserted] = wedge.emplace(std::make_pair(v, chart), p.num_wedges());
      if (inserted) {
        const Vec3& x = m.positions[v];
        p.uv.emplace_back(0.5 * x.x() + 0.5 * chart + 1.0 / 3.0 * 1e-3, x.y() / 3.0);
        p.wedge_vertex.push_back(v);
      }
      p.uv_faces[f][k] = it->second;
    }
  }
  p.num_charts = 2;
  test::write_text(dir.path / "m.mtl", "newmtl adaptex_paint\nmap_Kd tex/paint.png\n");
  write_obj(dir.path / "m.obj", m, &p, std::string("m.mtl"));
  const TexturedMesh t = read_textured_obj(dir.path / "m.obj");
  expect_same_mesh(m, t.mesh, true);
  EXPECT_EQ(t.param.num_wedges(), p.num_wedges());
  EXPECT_EQ(t.param.num_charts, 2);
  ASSERT_EQ(t.param.uv_faces.size(), m.faces.size());
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(t.param.wedge_vertex[t.param.uv_faces[f][k]], t.mesh.faces[f][k]);
      EXPECT_EQ(t.param.uv[t.param.uv_faces[f][k]], p.uv[p.uv_faces[f][k]]);  // exact round trip
    }
  for (int f = 1; f < m.num_faces(); ++f)
    EXPECT_EQ(t.param.face_chart[f] == t.param.face_chart[0], p.face_chart[f] == p.face_chart[0]);

  // Faces without vt and non-finite vt are rejected, naming the file and the face / vt.
  test::write_text(dir.path / "novt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                          "f 1/1 2/2 3/3\nf 2 4 3\n");
  try {
    read_textured_obj(dir.path / "novt.obj");
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("novt.obj: face 2 has no texture coordinates"), std::string::npos)
        << e.what();
  }
  test::write_text(dir.path / "nanvt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt nan 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  try {
    read_textured_obj(dir.path / "nanvt.obj");
    FAIL();
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("nanvt.obj: vt 2 is not finite"), std::string::npos) << e.what();
  }
}

TEST(MeshIo, SignedVolumeSign) {
  TriMesh s = shapes::sphere(16, 8);
  EXPECT_NEAR(signed_volume(s), 4.0 / 3.0 * M_PI, 0.3);
  for (auto& f : s.faces) std::swap(f[0], f[1]);
  EXPECT_LT(signed_volume(s), 0.0);
}

}  // namespace
}  // namespace adaptex
