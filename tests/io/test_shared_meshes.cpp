// Every mesh of ../shared/meshes reads with the counts of MANIFEST.md (V after dropping unreferenced
// vertices), and ascii positions are exactly the file's decimals (checked against strtod here).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "adaptex/core/topology.h"
#include "adaptex/io/mesh_io.h"
#include "test_support.h"

namespace adaptex {
namespace {

struct Expected {
  int v, f, genus, loops, unreferenced;
  int orientation;  // +1 ccw, -1 cw, 0 open
};

const std::map<std::string, Expected>& manifest() {
  static const std::map<std::string, Expected> m = {
      {"venus.off", {711, 1396, 0, 1, 0, 0}},        {"triceratops.off", {2832, 5660, 0, 0, 0, 1}},
      {"horse.ply", {48485, 96966, 0, 0, 0, -1}},    {"face.obj", {17157, 34144, 0, 1, 0, 0}},
      {"bunny.ply", {34834, 69451, 0, 5, 1113, 0}},  {"spot.obj", {2930, 5856, 0, 0, 0, 1}},
      {"armadillo.obj", {43243, 86482, 0, 0, 0, 1}}, {"camelhead.off", {11381, 22704, 0, 1, 0, 0}},
      {"fandisk.off", {6475, 12946, 0, 0, 0, 1}},    {"igea.ply", {134345, 268686, 0, 0, 0, 1}},
      {"kitten.obj", {9447, 18894, 1, 0, 0, 1}},     {"dino.off", {3916, 7828, 0, 0, 0, 1}},
  };
  return m;
}

bool skip_large() {
#if defined(__SANITIZE_ADDRESS__)
  return true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  return true;
#endif
#endif
  return false;
}

TEST(SharedMeshes, CountsMatchManifest) {
  ADAPTEX_REQUIRE_SHARED();
  const auto files = test::shared_meshes();
  ASSERT_EQ(files.size(), manifest().size());
  for (const auto& path : files) {
    const std::string name = path.filename().string();
    if (skip_large() && std::filesystem::file_size(path) > 2'000'000) continue;  // sanitizer build: too slow
    ASSERT_TRUE(manifest().count(name)) << name << " is not in the expected table";
    const Expected& e = manifest().at(name);
    ReadReport r;
    const TriMesh m = read_mesh(path, {}, &r);
    EXPECT_EQ(m.num_vertices(), e.v) << name;
    EXPECT_EQ(m.num_faces(), e.f) << name;
    EXPECT_EQ(r.dropped_unreferenced_vertices, e.unreferenced) << name;
    EXPECT_EQ(r.dropped_degenerate_faces, 0) << name;
    EXPECT_EQ(r.welded_vertices, 0) << name;
    const MeshTopology t = analyze_topology(m);
    EXPECT_TRUE(t.is_manifold()) << name;
    EXPECT_EQ(t.num_components, 1) << name;
    EXPECT_EQ(t.total_genus(), e.genus) << name;
    EXPECT_EQ(t.total_loops(), e.loops) << name;
    if (e.orientation != 0) {
      EXPECT_EQ(signed_volume(m) > 0 ? 1 : -1, e.orientation) << name;
    }
  }
}

/// The decimal numbers of the vertex lines of an ascii OFF / OBJ, converted with strtod.
std::vector<double> file_numbers(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<double> out;
  const bool obj = path.extension() == ".obj";
  int header_lines = 0, nv = -1;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    std::string first;
    if (!(ss >> first)) continue;
    if (obj) {
      if (first != "v") continue;
      for (int k = 0; k < 3; ++k) {
        std::string tok;
        ss >> tok;
        out.push_back(std::strtod(tok.c_str(), nullptr));
      }
    } else {
      if (++header_lines == 1) continue;  // OFF / COFF
      if (header_lines == 2) {
        nv = std::stoi(first);
        continue;
      }
      if (static_cast<int>(out.size()) == 3 * nv) break;
      out.push_back(std::strtod(first.c_str(), nullptr));
      for (int k = 0; k < 2; ++k) {
        std::string tok;
        ss >> tok;
        out.push_back(std::strtod(tok.c_str(), nullptr));
      }
    }
  }
  return out;
}

TEST(SharedMeshes, AsciiPositionsAreTheFilesDecimals) {
  ADAPTEX_REQUIRE_SHARED();
  for (const char* name : {"spot.obj", "kitten.obj", "venus.off", "camelhead.off", "dino.off"}) {
    const auto path = *test::shared_meshes_dir() / name;
    const TriMesh m = read_mesh(path);
    const auto expect = file_numbers(path);
    ASSERT_EQ(expect.size(), 3 * m.positions.size()) << name;
    for (size_t i = 0; i < expect.size(); ++i) ASSERT_EQ(m.positions[i / 3][i % 3], expect[i]) << name << " " << i;
  }
  // bunny.ply is ascii with float32 properties: the decimal text is kept, not its float rounding.
  const TriMesh bunny = read_mesh(*test::shared_meshes_dir() / "bunny.ply");
  EXPECT_EQ(bunny.positions[0], Vec3(-0.0378297, 0.12794, 0.00447467));
}

TEST(SharedMeshes, SpotTexturedObj) {
  ADAPTEX_REQUIRE_SHARED();
  const TexturedMesh t = read_textured_obj(*test::shared_meshes_dir() / "spot.obj");
  EXPECT_EQ(t.mesh.num_faces(), 5856);
  EXPECT_EQ(t.mesh.num_vertices(), 2930);
  EXPECT_EQ(t.param.num_wedges(), 3225);
  EXPECT_GE(t.param.num_charts, 1);
  for (int f = 0; f < t.mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(t.param.wedge_vertex[t.param.uv_faces[f][k]], t.mesh.faces[f][k]);
  for (const Vec2& uv : t.param.uv) EXPECT_TRUE(uv.allFinite());  // spot's atlas slightly exceeds [0,1]
}

}  // namespace
}  // namespace adaptex
