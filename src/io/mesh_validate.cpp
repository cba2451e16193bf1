/// \file mesh_validate.cpp
/// Validation and repair of triangle meshes: non-finite coordinates, indices
/// out of range, degenerate faces and unreferenced vertices (dropped with a warning), pinched vertices
/// (split with a warning), duplicate faces and non-manifold edges (rejected, or repaired with
/// ReadOptions::repair), mixed face winding (made consistent with a warning), and the common
/// polygon-soup -> TriMesh step of every reader (fan triangulation, welding by identical position).
#include <algorithm>
#include <charconv>
#include <cstring>
#include <limits>
#include <cmath>
#include <numeric>
#include <sstream>
#include <unordered_map>

#include "adaptex/core/errors.h"
#include "adaptex/core/orientation.h"
#include "adaptex/core/pinched.h"
#include "adaptex/core/topology.h"
#include "adaptex/core/union_find.h"
#include "mesh_soup.h"

namespace adaptex {
namespace io_detail {

std::string format_point(const Vec3& p) {
  std::string out = "(";
  for (int k = 0; k < 3; ++k) {
    char buf[32];
    auto res = std::to_chars(buf, buf + sizeof buf, p[k]);
    out.append(buf, res.ptr);
    out += k < 2 ? ", " : ")";
  }
  return out;
}

namespace {

/// Key of a position for welding: -0.0 and 0.0 are the same position.
struct PositionKey {
  double x, y, z;
  bool operator==(const PositionKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PositionHash {
  size_t operator()(const PositionKey& k) const {
    auto bits = [](double d) {
      std::uint64_t u;
      d = d == 0.0 ? 0.0 : d;
      std::memcpy(&u, &d, sizeof u);
      return u;
    };
    std::uint64_t h = bits(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= bits(k.y) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
    h ^= bits(k.z) + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
    return static_cast<size_t>(h ^ (h >> 31));
  }
};

void warn(ReadReport& report, const std::string& line) { report.warnings.push_back(line); }

std::string plural(long n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

/// Keeps the faces with keep[f] set, in order, updating face_source.
void filter_faces(TriMesh& mesh, const std::vector<char>& keep, std::vector<int>& face_source) {
  size_t out = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!keep[f]) continue;
    mesh.faces[out] = mesh.faces[f];
    if (!face_source.empty()) face_source[out] = face_source[f];
    ++out;
  }
  mesh.faces.resize(out);
  if (!face_source.empty()) face_source.resize(out);
}

/// Splits vertices so that every vertex has one fan and every edge at most two faces.
/// Corners of a vertex are grouped through the edges they share with a neighbouring face; at an edge
/// with more than two faces only one pair (opposite orientation preferred) stays connected, the other
/// faces are detached there. Every group after the first becomes a new vertex (same position).
/// \p ec: build_edges(mesh) of the mesh before the split. Returns the number of vertices added.
int split_nonmanifold(TriMesh& mesh, const EdgeConnectivity& ec, std::vector<int>& vertex_source) {
  const int nf = mesh.num_faces();
  UnionFind corners(3 * nf);
  auto corner_of = [&](int f, int v) {
    const Face& t = mesh.faces[f];
    return 3 * f + (t[0] == v ? 0 : t[1] == v ? 1 : 2);
  };
  auto directed = [&](int f, int a, int b) {  // does face f contain the directed edge a -> b?
    const Face& t = mesh.faces[f];
    for (int k = 0; k < 3; ++k)
      if (t[k] == a && t[(k + 1) % 3] == b) return true;
    return false;
  };
  for (int e = 0; e < ec.num_edges(); ++e) {
    const auto& fs = ec.edge_faces[e];
    if (fs.size() < 2) continue;
    const int a = ec.edges[e][0], b = ec.edges[e][1];
    int f0 = fs[0], f1 = fs[1];
    if (fs.size() > 2) {
      const bool f0_ab = directed(f0, a, b);
      for (size_t k = 1; k < fs.size(); ++k)
        if (directed(fs[k], a, b) != f0_ab) {
          f1 = fs[k];
          break;
        }
    }
    corners.unite(corner_of(f0, a), corner_of(f1, a));
    corners.unite(corner_of(f0, b), corner_of(f1, b));
  }
  // First group of each vertex keeps its id; further groups get new vertices.
  std::vector<int> group_vertex(3 * nf, -1);
  std::vector<char> vertex_taken(mesh.positions.size(), 0);
  int added = 0;
  for (int f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int root = corners.find(3 * f + k);
      int& gv = group_vertex[root];
      if (gv < 0) {
        const int v = mesh.faces[f][k];
        if (!vertex_taken[v]) {
          vertex_taken[v] = 1;
          gv = v;
        } else {
          gv = mesh.num_vertices();
          mesh.positions.push_back(mesh.positions[v]);
          if (!vertex_source.empty()) vertex_source.push_back(vertex_source[v]);
          ++added;
        }
      }
      mesh.faces[f][k] = gv;
    }
  return added;
}

/// Last resort of the repair: faces beyond the second at a non-manifold edge get their own copies of
/// all three vertices. Returns the number of vertices added.
int detach_excess_faces(TriMesh& mesh, std::vector<int>& vertex_source) {
  const EdgeConnectivity ec = build_edges(mesh);
  std::vector<char> detach(mesh.faces.size(), 0);
  for (int e = 0; e < ec.num_edges(); ++e)
    for (size_t k = 2; k < ec.edge_faces[e].size(); ++k) detach[ec.edge_faces[e][k]] = 1;
  int added = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (!detach[f]) continue;
    for (int& v : mesh.faces[f]) {
      mesh.positions.push_back(mesh.positions[v]);
      if (!vertex_source.empty()) vertex_source.push_back(vertex_source[v]);
      v = mesh.num_vertices() - 1;
      ++added;
    }
  }
  return added;
}

/// Whether every edge of \p mesh has at most two faces and every vertex one fan: the same test as
/// analyze_topology(mesh).is_manifold() without the components, loops and orientation.
bool is_manifold(const TriMesh& mesh, const EdgeConnectivity& ec) {
  for (const auto& fs : ec.edge_faces)
    if (fs.size() > 2) return false;
  const VertexFans fans = build_vertex_fans(mesh, ec);
  std::vector<char> has_fan(mesh.positions.size(), 0);
  for (int v : fans.fan_vertex) {
    if (has_fan[v]) return false;
    has_fan[v] = 1;
  }
  return true;
}

/// Whether the faces of the manifold \p mesh agree in winding with their neighbours: the two faces
/// of every edge run it in opposite directions (what analyze_topology() reports as every component
/// consistently_oriented: orient_faces() then flips no face).
bool consistently_wound(const TriMesh& mesh, const EdgeConnectivity& ec) {
  std::vector<signed char> forward(ec.edges.size(), 0);  // faces running the edge from a to b (a < b)
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k)
      forward[ec.face_edges[f][k]] += mesh.faces[f][k] < mesh.faces[f][(k + 1) % 3];
  for (size_t e = 0; e < forward.size(); ++e)
    if (ec.edge_faces[e].size() == 2 && forward[e] != 1) return false;
  return true;
}

/// What repair_nonmanifold() did and found.
struct NonmanifoldRepair {
  int added = 0;            ///< Vertices added.
  bool manifold = false;    ///< Manifold after the repair.
  bool consistent = false;  ///< If manifold: consistently_wound().
};

/// The non-manifold repair of validate_tracked(): rounds of split_nonmanifold(), then
/// detach_excess_faces() if still needed. Manifoldness and winding are checked on the last edges
/// built, so the caller needs no analyze_topology() of a mesh the repair made manifold.
NonmanifoldRepair repair_nonmanifold(TriMesh& mesh, std::vector<int>& vertex_source) {
  NonmanifoldRepair r;
  EdgeConnectivity ec = build_edges(mesh);
  for (int round = 0; round < 4 && !r.manifold; ++round) {  // the caller found it non-manifold
    r.added += split_nonmanifold(mesh, ec, vertex_source);
    ec = EdgeConnectivity();  // free the old edges before building the new ones (peak memory)
    ec = build_edges(mesh);
    r.manifold = is_manifold(mesh, ec);
  }
  if (!r.manifold) {
    ec = EdgeConnectivity();
    r.added += detach_excess_faces(mesh, vertex_source);
    r.added += split_nonmanifold(mesh, build_edges(mesh), vertex_source);
    ec = build_edges(mesh);
    r.manifold = is_manifold(mesh, ec);
  }
  if (r.manifold) r.consistent = consistently_wound(mesh, ec);
  return r;
}

std::string describe_nonmanifold(const TriMesh& mesh, const MeshTopology& topo) {
  std::ostringstream os;
  os << "mesh is not manifold: " << plural(static_cast<long>(topo.nonmanifold_edges.size()),
                                           "non-manifold edge", "non-manifold edges");
  if (!topo.nonmanifold_edges.empty()) {
    os << " (first:";
    const EdgeConnectivity ec = build_edges(mesh);
    std::unordered_map<std::int64_t, int> count;
    for (int e = 0; e < ec.num_edges(); ++e)
      count[static_cast<std::int64_t>(ec.edges[e][0]) * (1LL << 32) + ec.edges[e][1]] =
          static_cast<int>(ec.edge_faces[e].size());
    for (size_t k = 0; k < std::min<size_t>(3, topo.nonmanifold_edges.size()); ++k) {
      const auto& e = topo.nonmanifold_edges[k];
      os << (k ? "; " : " ") << "vertices " << e[0] << "-" << e[1] << " at "
         << format_point(mesh.positions[e[0]]) << "-" << format_point(mesh.positions[e[1]]) << " shared by "
         << count[static_cast<std::int64_t>(e[0]) * (1LL << 32) + e[1]] << " faces";
    }
    os << ")";
  }
  os << ", " << plural(static_cast<long>(topo.nonmanifold_vertices.size()), "non-manifold vertex",
                       "non-manifold vertices");
  if (!topo.nonmanifold_vertices.empty()) {
    os << " (first:";
    for (size_t k = 0; k < std::min<size_t>(3, topo.nonmanifold_vertices.size()); ++k) {
      const int v = topo.nonmanifold_vertices[k];
      os << (k ? "; " : " ") << "vertex " << v << " at " << format_point(mesh.positions[v]);
    }
    os << ")";
  }
  os << "; rerun with --repair to split them";
  return os.str();
}

/// Step 1 of validate_tracked(): every coordinate finite, every index in range, at least one face.
/// \throw InvalidInputError naming the first offending vertex or face.
void check_finite_indices(const TriMesh& mesh, const std::string& name) {
  const int nv = mesh.num_vertices();
  for (int v = 0; v < nv; ++v)
    if (!mesh.positions[v].allFinite())
      throw InvalidInputError(name + ": vertex " + std::to_string(v) + " has a non-finite coordinate " +
                              format_point(mesh.positions[v]));
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int v : mesh.faces[f])
      if (v < 0 || v >= nv)
        throw InvalidInputError(name + ": face " + std::to_string(f) + " refers to vertex " +
                                std::to_string(v) + ", out of range (the mesh has " +
                                plural(nv, "vertex", "vertices") + ")");
  if (mesh.faces.empty())
    throw InvalidInputError(name + ": no faces (" + plural(nv, "vertex", "vertices") + ", 0 faces)");
}

/// Step 2: drops degenerate faces (a repeated vertex or exactly zero area), with a warning.
/// \throw InvalidInputError if no face is left.
void drop_degenerate_faces(TriMesh& mesh, const std::string& name, ReadReport& report,
                           std::vector<int>& face_source) {
  std::vector<char> keep(mesh.faces.size(), 1);
  int dropped = 0, first = -1;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Face& t = mesh.faces[f];
    const bool degenerate = t[0] == t[1] || t[1] == t[2] || t[0] == t[2] ||
                            (mesh.positions[t[1]] - mesh.positions[t[0]])
                                    .cross(mesh.positions[t[2]] - mesh.positions[t[0]])
                                    .squaredNorm() == 0.0;
    if (degenerate) {
      keep[f] = 0;
      if (first < 0) first = face_source.empty() ? f : face_source[f];
      ++dropped;
    }
  }
  if (dropped == 0) return;
  const int total = mesh.num_faces();
  filter_faces(mesh, keep, face_source);
  report.dropped_degenerate_faces += dropped;
  warn(report, name + ": dropped " + plural(dropped, "degenerate (zero-area) face", "degenerate (zero-area) faces") +
                   " of " + std::to_string(total) + " (first: face " + std::to_string(first) + ")");
  if (mesh.faces.empty())
    throw InvalidInputError(name + ": no faces left: all " + std::to_string(total) +
                            " faces are degenerate (zero area)");
}

/// Step 3: duplicate faces (same vertex set), found by sorting the faces by their sorted corners;
/// dropped with a warning under \p options.repair.
/// \throw TopologyError naming the first duplicate when not repairing.
void drop_duplicate_faces(TriMesh& mesh, const std::string& name, const ReadOptions& options, ReadReport& report,
                          std::vector<int>& face_source) {
  std::vector<std::pair<Face, int>> keys(mesh.faces.size());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    Face t = mesh.faces[f];
    std::sort(t.begin(), t.end());
    keys[f] = {t, f};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<char> keep(mesh.faces.size(), 1);
  int dropped = 0, first = -1, first_of = -1;
  for (size_t k = 1; k < keys.size(); ++k) {
    if (keys[k].first != keys[k - 1].first) continue;
    // keys[k] repeats an earlier face of the same run; within a run faces are sorted by index.
    const int f = keys[k].second;
    keep[f] = 0;
    ++dropped;
    if (first < 0 || f < first) {
      size_t r = k;
      while (r > 0 && keys[r - 1].first == keys[k].first) --r;
      first = f;
      first_of = keys[r].second;
    }
  }
  if (dropped == 0) return;
  if (!options.repair)
    throw TopologyError(name + ": " + plural(dropped, "duplicate face", "duplicate faces") + " (first: face " +
                        std::to_string(first) + " repeats face " + std::to_string(first_of) + ", vertices " +
                        std::to_string(mesh.faces[first][0]) + " " + std::to_string(mesh.faces[first][1]) + " " +
                        std::to_string(mesh.faces[first][2]) + "); rerun with --repair to drop them");
  filter_faces(mesh, keep, face_source);
  report.dropped_duplicate_faces += dropped;
  warn(report, name + ": repair dropped " + plural(dropped, "duplicate face", "duplicate faces"));
}

/// Step 4: removes the vertices no face uses (file order kept); with \p count, counted and warned.
void drop_unreferenced_vertices(TriMesh& mesh, const std::string& name, ReadReport& report,
                                std::vector<int>& vertex_source, bool count) {
  std::vector<int> remap(mesh.positions.size(), -1);
  for (const Face& t : mesh.faces)
    for (int v : t) remap[v] = 0;
  int next = 0, dropped = 0, first = -1;
  for (size_t v = 0; v < remap.size(); ++v) {
    if (remap[v] < 0) {
      if (first < 0) first = static_cast<int>(v);
      ++dropped;
      continue;
    }
    remap[v] = next;
    mesh.positions[next] = mesh.positions[v];
    if (!vertex_source.empty()) vertex_source[next] = vertex_source[v];
    ++next;
  }
  if (dropped == 0) return;
  mesh.positions.resize(next);
  if (!vertex_source.empty()) vertex_source.resize(next);
  for (Face& t : mesh.faces)
    for (int& v : t) v = remap[v];
  if (count) {
    report.dropped_unreferenced_vertices += dropped;
    warn(report, name + ": dropped " + plural(dropped, "unreferenced vertex", "unreferenced vertices") +
                     " (used by no face; first: vertex " + std::to_string(first) + ")");
  }
}

/// Step 5a: pinched vertices (several fans of faces at one vertex) split into one vertex per fan, when
/// the edges are manifold. Returns the topology of the mesh after it.
MeshTopology split_pinched_step(TriMesh& mesh, const std::string& name, ReadReport& report,
                                std::vector<int>& vertex_source) {
  MeshTopology topo = analyze_topology(mesh);
  if (!topo.nonmanifold_edges.empty() || topo.nonmanifold_vertices.empty()) return topo;
  const int first = topo.nonmanifold_vertices.front();
  const std::string where = format_point(mesh.positions[first]);
  PinchedSplit split = split_pinched_vertices(mesh);
  if (!vertex_source.empty()) {  // tracked: compose with the file's vertex numbers
    for (int& v : split.vertex_source) v = vertex_source[v];
    vertex_source = std::move(split.vertex_source);
  }
  mesh = std::move(split.mesh);
  report.split_pinched_vertices += split.pinched_vertices;
  warn(report, name + ": split " + plural(split.pinched_vertices, "pinched vertex", "pinched vertices") +
                   " (separate fans of faces touching at one point; first: vertex " + std::to_string(first) +
                   " at " + where + ") into one vertex per fan: " +
                   plural(split.added_vertices, "copy", "copies") + " added at the same position");
  return analyze_topology(mesh);
}

/// Step 6: the faces whose winding disagrees with the majority of their surface are flipped
/// (\p face_flipped marks them), with a warning.
void fix_winding(TriMesh& mesh, const std::string& name, ReadReport& report, const std::vector<int>& face_source,
                 std::vector<char>& face_flipped) {
  const FaceOrientation orientation = orient_faces(mesh);
  if (orientation.num_flipped > 0) {
    int first = 0;
    while (!orientation.flip[first]) ++first;
    apply_orientation(mesh, orientation);
    face_flipped = orientation.flip;
    report.flipped_faces += orientation.num_flipped;
    warn(report, name + ": flipped " + plural(orientation.num_flipped, "face", "faces") + " of " +
                     std::to_string(mesh.num_faces()) +
                     " whose winding disagreed with their neighbours (first: face " +
                     std::to_string(face_source.empty() ? first : face_source[first]) + ")");
  }
  if (orientation.num_non_orientable_faces > 0)
    warn(report, name + ": " + plural(orientation.num_non_orientable_faces, "face lies", "faces lie") +
                     " on a non-orientable surface (a Moebius band or similar): no consistent winding");
}

}  // namespace

TriMesh validate_tracked(TriMesh mesh, const std::string& name, const ReadOptions& options,
                         ReadReport& report, std::vector<int>& face_source,
                         std::vector<int>& vertex_source, std::vector<char>& face_flipped) {
  check_finite_indices(mesh, name);
  drop_degenerate_faces(mesh, name, report, face_source);
  drop_duplicate_faces(mesh, name, options, report, face_source);
  drop_unreferenced_vertices(mesh, name, report, vertex_source, true);
  // 5. Pinched vertices, then manifoldness (repaired if asked).
  MeshTopology topo = split_pinched_step(mesh, name, report, vertex_source);
  bool repaired = false;  // made manifold by the repair: topo is stale, the winding known
  bool consistent = true;
  if (!topo.is_manifold() && options.repair) {
    const NonmanifoldRepair r = repair_nonmanifold(mesh, vertex_source);
    repaired = r.manifold;
    consistent = r.consistent;
    if (!repaired) topo = analyze_topology(mesh);
    report.split_nonmanifold_vertices += r.added;
    warn(report, name + ": repair split " + plural(r.added, "vertex", "vertices") +
                     " to make the mesh manifold (non-manifold edges and vertices)");
    drop_unreferenced_vertices(mesh, name, report, vertex_source, false);
  }
  if (!repaired && !topo.is_manifold())
    throw TopologyError(name + ": " + describe_nonmanifold(mesh, topo));
  // 6. Mixed winding.
  face_flipped.clear();
  if (!repaired)
    for (const ComponentTopology& c : topo.components) consistent = consistent && c.consistently_oriented;
  if (!consistent) fix_winding(mesh, name, report, face_source, face_flipped);
  return mesh;
}

SoupMesh soup_to_mesh(PolygonSoup soup, const std::string& name, const ReadOptions& options,
                      ReadReport* report_out) {
  ReadReport local;
  ReadReport& report = report_out ? *report_out : local;
  report.format = soup.format;
  for (auto& w : soup.warnings) warn(report, w);
  const auto nv = static_cast<std::int64_t>(soup.positions.size());
  const int base = soup.index_base;
  for (std::int64_t v = 0; v < nv; ++v)
    if (!soup.positions[v].allFinite())
      throw InvalidInputError(name + ": vertex " + std::to_string(v + base) + " has a non-finite coordinate " +
                              format_point(soup.positions[v]));
  const std::int64_t np = soup.num_polygons();
  if (np == 0)
    throw InvalidInputError(name + ": no faces (" + plural(static_cast<long>(nv), "vertex", "vertices") +
                            ", 0 faces)");
  if (nv > std::numeric_limits<int>::max() / 2 || 3 * np > std::numeric_limits<int>::max() / 2)
    throw InvalidInputError(name + ": mesh too large (" + std::to_string(nv) + " vertices, " +
                            std::to_string(np) + " polygons)");
  for (std::int64_t p = 0; p < np; ++p)
    for (std::int64_t c = soup.offsets[p]; c < soup.offsets[p + 1]; ++c)
      if (soup.indices[c] < 0 || soup.indices[c] >= nv)
        throw InvalidInputError(name + ": " + soup.element + " " + std::to_string(p + base) + " refers to vertex " +
                                std::to_string(soup.indices[c] + base) + ", out of range (the file has " +
                                plural(static_cast<long>(nv), "vertex", "vertices") +
                                (base ? ", numbered from 1)" : ", numbered from 0)"));

  // Welding by identical position (formats that split vertices).
  std::vector<int> weld_map(nv);
  std::iota(weld_map.begin(), weld_map.end(), 0);
  std::vector<int> vertex_source(nv);
  std::iota(vertex_source.begin(), vertex_source.end(), 0);
  TriMesh mesh;
  if (soup.weld) {
    std::unordered_map<PositionKey, int, PositionHash> first;
    first.reserve(static_cast<size_t>(nv));
    vertex_source.clear();
    for (std::int64_t v = 0; v < nv; ++v) {
      const Vec3& p = soup.positions[v];
      auto [it, inserted] = first.emplace(PositionKey{p.x(), p.y(), p.z()}, mesh.num_vertices());
      if (inserted) {
        mesh.positions.push_back(p);
        vertex_source.push_back(static_cast<int>(v));
      }
      weld_map[v] = it->second;
    }
    // Only vertices that faces use count as welded (unused duplicates are "unreferenced").
    std::vector<char> used(nv, 0);
    for (auto i : soup.indices) used[i] = 1;
    std::vector<char> target_used(mesh.positions.size(), 0);
    int welded = 0;
    for (std::int64_t v = 0; v < nv; ++v) {
      if (!used[v]) continue;
      if (target_used[weld_map[v]]) ++welded;
      target_used[weld_map[v]] = 1;
    }
    report.welded_vertices += welded;
  } else {
    mesh.positions = std::move(soup.positions);
  }
  report.welded_vertices += soup.welded_by_reader;
  if (report.welded_vertices > 0)
    warn(report, name + ": welded " + plural(report.welded_vertices, "vertex", "vertices") +
                     " with identical positions (split by the " + soup.format + " format)");

  // Fan triangulation; polygons with fewer than 3 corners count as degenerate faces.
  SoupMesh out;
  std::vector<int> face_source;
  int short_polygons = 0;
  for (std::int64_t p = 0; p < np; ++p) {
    const std::int64_t b = soup.offsets[p], e = soup.offsets[p + 1];
    if (e - b < 3) {
      ++short_polygons;
      continue;
    }
    for (std::int64_t c = b + 1; c + 1 < e; ++c) {
      mesh.faces.push_back({weld_map[soup.indices[b]], weld_map[soup.indices[c]], weld_map[soup.indices[c + 1]]});
      out.face_corners.push_back({b, c, c + 1});
      face_source.push_back(static_cast<int>(out.face_corners.size()) - 1);
    }
  }
  if (short_polygons > 0) {
    report.dropped_degenerate_faces += short_polygons;
    warn(report, name + ": dropped " +
                     plural(short_polygons, "face with fewer than 3 vertices", "faces with fewer than 3 vertices"));
  }
  if (mesh.faces.empty())
    throw InvalidInputError(name + ": no faces: all " + std::to_string(np) + " faces have fewer than 3 vertices");
  std::vector<char> flipped;
  out.mesh = validate_tracked(std::move(mesh), name, options, report, face_source, vertex_source, flipped);
  std::vector<std::array<std::int64_t, 3>> corners(face_source.size());
  for (size_t f = 0; f < face_source.size(); ++f) {
    corners[f] = out.face_corners[face_source[f]];
    if (!flipped.empty() && flipped[f]) std::swap(corners[f][1], corners[f][2]);
  }
  out.face_corners = std::move(corners);
  out.vertex_source = std::move(vertex_source);
  return out;
}

}  // namespace io_detail

double signed_volume(const TriMesh& mesh) {
  double six_v = 0.0;
  for (const Face& t : mesh.faces)
    six_v += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]]));
  return six_v / 6.0;
}

TriMesh validate_mesh(TriMesh mesh, const std::string& name, const ReadOptions& options, ReadReport* report) {
  ReadReport local;
  std::vector<int> none_f, none_v;
  std::vector<char> flipped;
  return io_detail::validate_tracked(std::move(mesh), name, options, report ? *report : local, none_f, none_v,
                                     flipped);
}

}  // namespace adaptex
