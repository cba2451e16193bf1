// Tests of the plain-OBJ reader (io/read_obj_plain.cpp): on OBJ text built here it must give the
// mesh and report that tinyobjloader's path gives. That path is forced by one statement the plain
// reader does not take and tinyobjloader ignores (`cstype`), appended (line numbers unchanged).
#include <gtest/gtest.h>

#include <charconv>
#include <cstring>
#include <random>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/io/mesh_io.h"

namespace adaptex {
namespace {

/// The OBJ text with a statement only tinyobjloader reads (it ignores `cstype`).
std::string tinyobj_only(const std::string& obj) { return obj + "cstype bmatrix\n"; }

/// Both paths on \p obj: same positions (bit for bit), faces and report.
void expect_both_paths_agree(const std::string& obj, bool repair = false) {
  ReadOptions o;
  o.repair = repair;
  ReadReport ra, rb;
  const TriMesh a = read_mesh_from_memory(obj, "obj", "m.obj", o, &ra);
  const TriMesh b = read_mesh_from_memory(tinyobj_only(obj), "obj", "m.obj", o, &rb);
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_faces(), b.num_faces());
  for (int v = 0; v < a.num_vertices(); ++v)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(std::memcmp(&a.positions[v][k], &b.positions[v][k], sizeof(double)), 0) << v;
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(ra.warnings, rb.warnings);
  EXPECT_EQ(ra.welded_vertices, rb.welded_vertices);
  EXPECT_EQ(ra.dropped_degenerate_faces, rb.dropped_degenerate_faces);
  EXPECT_EQ(ra.split_nonmanifold_vertices, rb.split_nonmanifold_vertices);
}

/// A number written in one of several forms (shortest digits, 17 digits, exponent, '+').
std::string number(double x, int form) {
  char buf[64];
  std::to_chars_result r{};
  if (form == 0) r = std::to_chars(buf, buf + sizeof buf, x);
  if (form == 1) r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::fixed, 17);
  if (form == 2) r = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::scientific, 12);
  if (form == 3) r = std::to_chars(buf + 1, buf + sizeof buf, std::abs(x));
  if (form == 3) buf[0] = '+';
  return std::string(buf, r.ptr);
}

/// A grid of quads over a bumpy height field, written with every corner form (`v`, `v/vt`,
/// `v//vn`, `v/vt/vn`, negative indices), quads and triangles, comments, groups, smoothing and
/// material lines, blank lines and (\p crlf) CRLF line ends; each vertex written twice (welded).
std::string grid_obj(int n, unsigned seed, bool crlf) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::string nl = crlf ? "\r\n" : "\n";
  std::string s = "# grid" + nl + "mtllib none.mtl" + nl + "o grid" + nl;
  std::vector<std::string> v;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = i / 3.0 + 1e-3 * u(rng), y = j * 0.7, z = std::sin(i * 1.3) * std::cos(j) / 7;
      const int form = (i * 7 + j) % 4;
      v.push_back("v " + number(x, form) + " \t" + number(y, (form + 1) % 4) + " " + number(z, form) + nl);
    }
  for (const std::string& line : v) s += line;
  for (const std::string& line : v) s += line;  // duplicates, welded by the soup step
  s += "vt 0 0" + nl + "vt 1 0" + nl + "vn 0 0 1" + nl + nl + "g half" + nl + "s 1" + nl +
       "usemtl a" + nl;
  const int nv = (n + 1) * (n + 1);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      // The second copy of each vertex for odd cells, by a negative index for every third cell.
      const int off = (i + j) % 2 ? nv : 0;
      auto idx = [&](int a, int b) {
        const int k = off + a * (n + 1) + b + 1;
        return (i * n + j) % 3 == 0 ? std::to_string(k - 2 * nv - 1) : std::to_string(k);
      };
      const std::string c[4] = {idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)};
      const int form = (i + 2 * j) % 4;
      auto corner = [&](const std::string& x) {
        return form == 0 ? x : form == 1 ? x + "/1" : form == 2 ? x + "//1" : x + "/2/1";
      };
      if ((i + j) % 5 == 0) {
        s += "f " + corner(c[0]) + " " + corner(c[1]) + " " + corner(c[2]) + nl;
        s += "f " + corner(c[0]) + " " + corner(c[2]) + " " + corner(c[3]) + "  " + nl;
      } else {
        s += "  f " + corner(c[0]) + " " + corner(c[1]) + " " + corner(c[2]) + " " + corner(c[3]) + nl;
      }
    }
  return s;
}

TEST(ObjPlain, GridsReadAsTinyobjloaderReadsThem) {
  for (unsigned seed = 1; seed <= 3; ++seed) {
    SCOPED_TRACE(seed);
    expect_both_paths_agree(grid_obj(9 + static_cast<int>(seed), seed, seed == 2));
  }
}

TEST(ObjPlain, RepairReadsAsTinyobjloaderReadsIt) {
  // A duplicate face, a zero-area face and an unreferenced vertex, with --repair.
  expect_both_paths_agree(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 2 2 0\nv 5 5 5\n"
      "f 1 2 3\nf 2 4 3\nf 3 2 4\nf 1 2 5\nf 1 4 5\n",
      true);
}

TEST(ObjPlain, TheSameErrorsAsTinyobjloaderPath) {
  // Out of range and non-finite: reported by the shared soup step, the same message either way.
  const std::string cases[] = {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
                               "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"};
  for (const std::string& obj : cases) {
    SCOPED_TRACE(obj);
    std::string plain, tiny;
    try {
      read_mesh_from_memory(obj, "obj", "m.obj");
    } catch (const InvalidInputError& e) {
      plain = e.what();
    }
    try {
      read_mesh_from_memory(tinyobj_only(obj), "obj", "m.obj");
    } catch (const InvalidInputError& e) {
      tiny = e.what();
    }
    EXPECT_FALSE(plain.empty());
    EXPECT_EQ(plain, tiny);
  }
}

TEST(ObjPlain, StatementsItDoesNotTakeGoToTinyobjloader) {
  // A zero index, a vertex with a w, a line continuation, a trailing comment and a non-numeric
  // coordinate: tinyobjloader's path decides (error or not) exactly as before this reader.
  const std::string cases[] = {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
                               "v 0 0 0 1\nv 1 0 0 1\nv 0 1 0 1\nf 1 2 3\n",
                               "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n3\n",
                               "v 0 0 0 # origin\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                               "v 0 0 0\nv 1 0 x\nv 0 1 0\nf 1 2 3\n"};
  for (const std::string& obj : cases) {
    SCOPED_TRACE(obj);
    std::string direct, forced;
    TriMesh a, b;
    try {
      a = read_mesh_from_memory(obj, "obj", "m.obj");
    } catch (const std::exception& e) {
      direct = e.what();
    }
    try {
      b = read_mesh_from_memory(tinyobj_only(obj), "obj", "m.obj");
    } catch (const std::exception& e) {
      forced = e.what();
    }
    EXPECT_EQ(direct, forced);
    EXPECT_EQ(a.faces, b.faces);
    EXPECT_EQ(a.positions.size(), b.positions.size());
  }
}

}  // namespace
}  // namespace adaptex
