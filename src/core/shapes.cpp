#include "adaptex/core/shapes.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <unordered_map>

#include "adaptex/core/errors.h"

namespace adaptex::shapes {

namespace {

constexpr double kPi = 3.14159265358979323846;

double signed_volume(const TriMesh& m) {
  double vol = 0;
  for (const Face& t : m.faces)
    vol += m.positions[t[0]].dot(m.positions[t[1]].cross(m.positions[t[2]]));
  return vol / 6.0;
}

// Closed shapes: make the faces counter-clockwise seen from outside.
void orient_outward(TriMesh& m) {
  if (signed_volume(m) < 0)
    for (Face& t : m.faces) std::swap(t[1], t[2]);
}

// Grid surface P(i, j), i in [0, nu], j in [0, nv]; wrap_u / wrap_v identify the last row/column
// with the first. Quads are split along alternating diagonals.
TriMesh grid_surface(int nu, int nv, bool wrap_u, bool wrap_v,
                     const std::function<Vec3(double, double)>& P) {
  TriMesh m;
  const int cu = wrap_u ? nu : nu + 1, cv = wrap_v ? nv : nv + 1;
  for (int j = 0; j < cv; ++j)
    for (int i = 0; i < cu; ++i) m.positions.push_back(P(double(i) / nu, double(j) / nv));
  auto id = [&](int i, int j) { return (j % cv) * cu + (i % cu); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.faces.push_back({a, b, c});
        m.faces.push_back({a, c, d});
      } else {
        m.faces.push_back({a, b, d});
        m.faces.push_back({b, c, d});
      }
    }
  return m;
}

TriMesh merge(const TriMesh& a, const TriMesh& b) {
  TriMesh m = a;
  const int off = a.num_vertices();
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (Face t : b.faces) m.faces.push_back({t[0] + off, t[1] + off, t[2] + off});
  return m;
}

// Marching tetrahedra of f < 0 on a regular grid (Kuhn subdivision: 6 tetrahedra per cube,
// consistent across cubes, so the output is a closed manifold when no sample is exactly 0).
TriMesh marching_tetrahedra(const std::function<double(const Vec3&)>& f, const Vec3& lo,
                            const Vec3& hi, int res) {
  const Vec3 ext = hi - lo;
  const double h = ext.maxCoeff() / res;
  const int nx = int(std::ceil(ext.x() / h)) + 1, ny = int(std::ceil(ext.y() / h)) + 1,
            nz = int(std::ceil(ext.z() / h)) + 1;
  auto gid = [&](int i, int j, int k) { return (long(k) * (ny + 1) + j) * (nx + 1) + i; };
  auto gpos = [&](int i, int j, int k) { return Vec3(lo + h * Vec3(i, j, k)); };
  std::vector<double> val(size_t(nx + 1) * (ny + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        double v = f(gpos(i, j, k));
        if (v == 0.0) v = 1e-12;  // never exactly on the surface
        val[gid(i, j, k)] = v;
      }
  TriMesh m;
  std::map<std::pair<long, long>, int> edge_vertex;
  auto crossing = [&](long a, const Vec3& pa, long b, const Vec3& pb) {
    auto key = std::minmax(a, b);
    auto it = edge_vertex.find(key);
    if (it != edge_vertex.end()) return it->second;
    const double t = val[a] / (val[a] - val[b]);
    m.positions.push_back(pa + t * (pb - pa));
    const int id = m.num_vertices() - 1;
    edge_vertex.emplace(key, id);
    return id;
  };
  static const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                   {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  static const int tets[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                 {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& tet : tets) {
          long id[4];
          Vec3 p[4];
          for (int c = 0; c < 4; ++c) {
            const int* o = corner[tet[c]];
            id[c] = gid(i + o[0], j + o[1], k + o[2]);
            p[c] = gpos(i + o[0], j + o[1], k + o[2]);
          }
          std::vector<int> in, out;
          for (int c = 0; c < 4; ++c) (val[id[c]] < 0 ? in : out).push_back(c);
          if (in.empty() || out.empty()) continue;
          Vec3 dir = Vec3::Zero();  // from inside to outside
          for (int c : out) dir += p[c] / double(out.size());
          for (int c : in) dir -= p[c] / double(in.size());
          auto emit = [&](int a, int b, int c) {
            const Vec3 n = (m.positions[b] - m.positions[a]).cross(m.positions[c] - m.positions[a]);
            if (n.dot(dir) < 0) std::swap(b, c);
            m.faces.push_back({a, b, c});
          };
          auto X = [&](int a, int b) { return crossing(id[a], p[a], id[b], p[b]); };
          if (in.size() == 1 || out.size() == 1) {
            const int s = in.size() == 1 ? in[0] : out[0];
            const auto& o = in.size() == 1 ? out : in;
            emit(X(s, o[0]), X(s, o[1]), X(s, o[2]));
          } else {
            const int a = X(in[0], out[0]), b = X(in[0], out[1]), c = X(in[1], out[1]),
                      d = X(in[1], out[0]);
            emit(a, b, c);
            emit(a, c, d);
          }
        }
  return m;
}

}  // namespace

TriMesh plane(int n, double size) {
  return grid_surface(n, n, false, false,
                      [&](double u, double v) { return Vec3(u * size, v * size, 0.0); });
}

TriMesh sphere(int slices, int stacks, double r) {
  TriMesh m;
  m.positions.push_back(Vec3(0, 0, r));
  for (int j = 1; j < stacks; ++j) {
    const double th = kPi * j / stacks;
    for (int i = 0; i < slices; ++i) {
      const double ph = 2 * kPi * i / slices;
      m.positions.push_back(r * Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph),
                                     std::cos(th)));
    }
  }
  m.positions.push_back(Vec3(0, 0, -r));
  const int south = m.num_vertices() - 1;
  auto ring = [&](int j, int i) { return 1 + (j - 1) * slices + (i % slices); };
  for (int i = 0; i < slices; ++i) m.faces.push_back({0, ring(1, i), ring(1, i + 1)});
  for (int j = 1; j < stacks - 1; ++j)
    for (int i = 0; i < slices; ++i) {
      m.faces.push_back({ring(j, i), ring(j + 1, i), ring(j + 1, i + 1)});
      m.faces.push_back({ring(j, i), ring(j + 1, i + 1), ring(j, i + 1)});
    }
  for (int i = 0; i < slices; ++i) m.faces.push_back({south, ring(stacks - 1, i + 1), ring(stacks - 1, i)});
  orient_outward(m);
  return m;
}

TriMesh icosphere(int subdivisions, double r) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriMesh m;
  m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
             {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (Vec3& p : m.positions) p.normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.positions.push_back((m.positions[a] + m.positions[b]).normalized());
      return mid[key] = m.num_vertices() - 1;
    };
    std::vector<Face> faces;
    for (const Face& f : m.faces) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      faces.insert(faces.end(), {{f[0], a, c}, {f[1], b, a}, {f[2], c, b}, {a, b, c}});
    }
    m.faces = std::move(faces);
  }
  for (Vec3& p : m.positions) p *= r;
  orient_outward(m);
  return m;
}

TriMesh torus(int major_segments, int minor_segments, double R, double r) {
  TriMesh m = grid_surface(major_segments, minor_segments, true, true, [&](double u, double v) {
    const double a = 2 * kPi * u, b = 2 * kPi * v;
    return Vec3((R + r * std::cos(b)) * std::cos(a), (R + r * std::cos(b)) * std::sin(a),
                r * std::sin(b));
  });
  orient_outward(m);
  return m;
}

TriMesh double_torus(int resolution) {
  auto torus_sdf = [](const Vec3& p, double cx) {
    const Vec3 q = p - Vec3(cx, 0, 0);
    const double d = std::hypot(q.x(), q.y()) - 1.0;
    return std::hypot(d, q.z()) - 0.4;
  };
  auto f = [&](const Vec3& p) {
    const double a = torus_sdf(p, -1.05), b = torus_sdf(p, 1.05), k = 0.25;
    const double hh = std::clamp(0.5 + 0.5 * (b - a) / k, 0.0, 1.0);  // smooth union
    return b + (a - b) * hh - k * hh * (1 - hh);
  };
  TriMesh m = marching_tetrahedra(f, Vec3(-2.7, -1.7, -0.7), Vec3(2.7, 1.7, 0.7), resolution);
  orient_outward(m);
  return m;
}

TriMesh open_cylinder(int segments, int rings, double r, double h) {
  return grid_surface(segments, rings, true, false, [&](double u, double v) {
    const double a = 2 * kPi * u;
    return Vec3(r * std::cos(a), r * std::sin(a), h * v);
  });
}

TriMesh disk_with_holes(int holes, int resolution) {
  // A square grid with `holes` square holes (whole quads removed, separated by kept quads so that
  // no vertex is pinched), vertices then pushed onto a disk-like shape.
  const int n = std::max(resolution, 4 * holes + 4);
  TriMesh full = plane(n, 1.0);
  std::vector<char> removed(size_t(n) * n, 0);
  const int side = std::max(1, n / (2 * holes + 2));
  for (int h = 0; h < holes; ++h) {
    const int i0 = (2 * h + 1) * n / (2 * holes + 1) - side / 2;
    const int j0 = n / 2 - side / 2;
    for (int j = j0; j < j0 + side; ++j)
      for (int i = i0; i < i0 + side; ++i) removed[size_t(j) * n + i] = 1;
  }
  TriMesh m;
  m.positions = full.positions;
  for (int q = 0; q < n * n; ++q)
    if (!removed[q]) {
      m.faces.push_back(full.faces[2 * q]);
      m.faces.push_back(full.faces[2 * q + 1]);
    }
  // Drop unused vertices (hole interiors) and squash the square into a rounded disk.
  std::vector<int> remap(m.num_vertices(), -1);
  std::vector<Vec3> pos;
  for (Face& t : m.faces)
    for (int& v : t) {
      if (remap[v] < 0) {
        remap[v] = int(pos.size());
        const Vec3 p = m.positions[v] - Vec3(0.5, 0.5, 0);
        const double s = std::max(std::abs(p.x()), std::abs(p.y())), l = std::hypot(p.x(), p.y());
        const double k = l > 0 ? 0.5 * s / l + 0.5 : 1.0;  // halfway between square and disk
        pos.push_back(Vec3(p.x() * k, p.y() * k, 0.1 * std::sin(3 * p.x()) * std::cos(2 * p.y())));
      }
      v = remap[v];
    }
  m.positions = std::move(pos);
  return m;
}

TriMesh two_components() {
  TriMesh a = icosphere(2, 0.8);
  TriMesh b = torus(32, 12, 1.0, 0.3);
  for (Vec3& p : b.positions) p += Vec3(3, 0, 0);
  return merge(a, b);
}

TriMesh nonmanifold_fan() {
  TriMesh m;
  m.positions = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0.5}, {-1, 0.5, 0.5}, {0, -1, 0.5}};
  m.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  return m;
}

TriMesh bowtie_vertex() {
  TriMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 5, 4}, {0, 4, 6}, {0, 6, 5}, {4, 5, 6}};
  return m;
}

TriMesh trefoil_knot(int segments, int sides, double tube) {
  auto curve = [](double t) {
    return Vec3(std::sin(t) + 2 * std::sin(2 * t), std::cos(t) - 2 * std::cos(2 * t), -std::sin(3 * t));
  };
  TriMesh m = grid_surface(segments, sides, true, true, [&](double u, double v) {
    const double t = 2 * kPi * u, a = 2 * kPi * v;
    const Vec3 c = curve(t);
    const Vec3 T = (curve(t + 1e-4) - curve(t - 1e-4)).normalized();
    const Vec3 N = T.cross(Vec3::UnitZ()).normalized();
    const Vec3 B = T.cross(N);
    return Vec3(c + tube * 3.0 * (std::cos(a) * N + std::sin(a) * B) * 0.3);
  });
  orient_outward(m);
  return m;
}

TriMesh genus_surface(int genus, int cells_per_unit) {
  if (genus < 0 || genus > 64)
    throw InvalidInputError("genus_surface: genus " + std::to_string(genus) + " is outside [0, 64]");
  if (cells_per_unit < 2 || cells_per_unit > 200)
    throw InvalidInputError("genus_surface: cells_per_unit " + std::to_string(cells_per_unit) +
                            " is outside [2, 200]");
  if (genus == 0) {
    // An icosphere with about as many faces per unit area as one torus of the row.
    int s = 0;
    while (s < 7 && 20.0 * std::pow(4.0, s + 1) <= 110.0 * cells_per_unit * cells_per_unit) ++s;
    return icosphere(s);
  }
  const double spacing = 2.1, R = 1.0, r = 0.4, k = 0.25;
  auto f = [&](const Vec3& p) {
    double d = 0;
    for (int i = 0; i < genus; ++i) {
      const Vec3 q = p - Vec3(spacing * (i - 0.5 * (genus - 1)), 0, 0);
      const double t = std::hypot(std::hypot(q.x(), q.y()) - R, q.z()) - r;
      if (i == 0) {
        d = t;
      } else {  // smooth union (polynomial smooth minimum)
        const double hh = std::clamp(0.5 + 0.5 * (t - d) / k, 0.0, 1.0);
        d = t + (d - t) * hh - k * hh * (1 - hh);
      }
    }
    return d;
  };
  const double half = 0.5 * spacing * (genus - 1) + R + r + 0.3;
  const Vec3 lo(-half, -(R + r + 0.3), -(r + 0.3)), hi(half, R + r + 0.3, r + 0.3);
  const int res = std::max(4, static_cast<int>(std::ceil(2 * half * cells_per_unit)));
  TriMesh m = marching_tetrahedra(f, lo, hi, res);
  orient_outward(m);
  return m;
}

TriMesh sphere_with_holes(int holes, int subdivisions) {
  if (subdivisions < 0 || subdivisions > 7)
    throw InvalidInputError("sphere_with_holes: subdivisions " + std::to_string(subdivisions) +
                            " is outside [0, 7]");
  if (holes < 1 || holes > (1 << (2 * subdivisions)))
    throw InvalidInputError("sphere_with_holes: " + std::to_string(holes) +
                            " holes do not fit on an icosphere with " +
                            std::to_string(subdivisions) + " subdivisions");
  const TriMesh ico = icosphere(subdivisions);
  const double radius = std::min(0.6, 0.3 * std::sqrt(4 * kPi / holes));
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  std::vector<Vec3> centres;
  for (int i = 0; i < holes; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / holes, rho = std::sqrt(1.0 - z * z);
    centres.push_back(Vec3(rho * std::cos(golden * i), rho * std::sin(golden * i), z));
  }
  const int nv = ico.num_vertices();
  std::vector<char> keep(nv, 1);
  for (int v = 0; v < nv; ++v)
    for (const Vec3& c : centres)
      if (std::acos(std::clamp(ico.positions[v].dot(c), -1.0, 1.0)) < radius) keep[v] = 0;
  // Remove pinched vertices: the kept faces around a kept vertex must form one fan. In the closed
  // star of v, the number of fans of kept faces is (kept faces) - (edges at v shared by two kept
  // faces), unless every face is kept.
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<int> kept_faces(nv, 0), star_faces(nv, 0);
    std::map<std::pair<int, int>, int> kept_edge_faces;
    for (const Face& t : ico.faces) {
      const bool kf = keep[t[0]] && keep[t[1]] && keep[t[2]];
      for (int j = 0; j < 3; ++j) {
        ++star_faces[t[j]];
        if (!kf) continue;
        ++kept_faces[t[j]];
        ++kept_edge_faces[std::minmax(t[j], t[(j + 1) % 3])];
      }
    }
    std::vector<int> shared(nv, 0);
    for (const auto& [e, n] : kept_edge_faces)
      if (n == 2) ++shared[e.first], ++shared[e.second];
    for (int v = 0; v < nv; ++v)
      if (keep[v] && kept_faces[v] < star_faces[v] && kept_faces[v] - shared[v] != 1) {
        keep[v] = 0;
        changed = true;
      }
  }
  TriMesh m;
  std::vector<int> remap(nv, -1);
  for (const Face& t : ico.faces) {
    if (!(keep[t[0]] && keep[t[1]] && keep[t[2]])) continue;
    Face nt;
    for (int j = 0; j < 3; ++j) {
      if (remap[t[j]] < 0) {
        remap[t[j]] = m.num_vertices();
        m.positions.push_back(ico.positions[t[j]]);
      }
      nt[j] = remap[t[j]];
    }
    m.faces.push_back(nt);
  }
  return m;
}

TriMesh disjoint_union(const std::vector<TriMesh>& meshes) {
  TriMesh m;
  for (const TriMesh& part : meshes) m = merge(m, part);
  return m;
}

TriMesh pinched_annulus(int n) {
  if (n < 3) throw InvalidInputError("pinched_annulus: n " + std::to_string(n) + " is below 3");
  const TriMesh grid = plane(n);
  TriMesh m;
  std::vector<int> remap(grid.positions.size(), -1);
  // plane() emits two faces per cell, cell (i, j) at 2 (j n + i).
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool ring = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      if (!ring || (i == n - 1 && j == n - 1)) continue;
      for (int h = 0; h < 2; ++h) {
        Face t = grid.faces[2 * (j * n + i) + h];
        for (int& v : t) {
          if (remap[v] < 0) {
            remap[v] = m.num_vertices();
            m.positions.push_back(grid.positions[v]);
          }
          v = remap[v];
        }
        m.faces.push_back(t);
      }
    }
  return m;
}

TriMesh with_pinched_hole(const TriMesh& closed) {
  std::vector<std::vector<int>> vertex_faces(closed.positions.size());
  for (int f = 0; f < closed.num_faces(); ++f)
    for (int v : closed.faces[f]) vertex_faces[v].push_back(f);
  auto corner = [&](int f, int v) {
    const Face& t = closed.faces[f];
    return t[0] == v ? 0 : t[1] == v ? 1 : 2;
  };
  for (int v = 0; v < closed.num_vertices(); ++v) {
    const auto& around = vertex_faces[v];
    if (around.size() < 4) continue;
    // Order the one-ring: the face after (v, a, b) contains the edge v -> b.
    std::vector<int> ring{around[0]};
    while (ring.size() <= around.size()) {
      const int b = closed.faces[ring.back()][(corner(ring.back(), v) + 2) % 3];
      int next = -1;
      for (int f : around)
        if (closed.faces[f][(corner(f, v) + 1) % 3] == b) next = f;
      if (next < 0 || next == ring[0]) break;
      ring.push_back(next);
    }
    if (ring.size() != around.size()) continue;
    TriMesh m = closed;
    const int drop0 = ring[0], drop1 = ring[ring.size() / 2];
    m.faces.erase(m.faces.begin() + std::max(drop0, drop1));
    m.faces.erase(m.faces.begin() + std::min(drop0, drop1));
    return m;
  }
  throw InvalidInputError("with_pinched_hole: no vertex of valence >= 4 with a closed one-ring");
}

namespace {

/// Deterministic uniform numbers in [0, 1) (64-bit LCG, same sequence on every platform).
struct Lcg {
  unsigned long long s;
  double next() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(s >> 11) * (1.0 / 9007199254740992.0);
  }
};

/// Closed fan of \p nf faces around vertex 0 (rim on the unit circle, centre raised by 0.3).
TriMesh tiny_fan(int nf, int variant) {
  TriMesh m;
  m.positions.push_back(Vec3(0, 0, 0.3));
  for (int j = 0; j < nf; ++j) {
    const double a = 2 * 3.14159265358979323846 * j / nf;
    m.positions.push_back(Vec3(std::cos(a), std::sin(a), 0));
  }
  if (nf == 4 && variant == 0) {  // exact rim (1,0),(0,1),(-1,0),(0,-1); centre on the first rim edge
    m.positions = {Vec3(0.5, 0.5, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0, 0), Vec3(0, -1, 0)};
  }
  if (nf == 5 && variant == 0) m.positions[2] = m.positions[1];  // duplicate points
  for (int j = 0; j < nf; ++j) m.faces.push_back({0, 1 + j, 1 + (j + 1) % nf});
  return m;
}

/// Triangle strip of \p nf faces; the last triangle is a sliver when \p sliver.
TriMesh tiny_strip(int nf, bool sliver) {
  TriMesh m;
  for (int j = 0; j < nf + 2; ++j)
    m.positions.push_back(Vec3(0.5 * j, (j % 2) ? 1.0 : 0.0, 0.1 * std::sin(0.7 * j)));
  for (int j = 0; j < nf; ++j)
    m.faces.push_back(j % 2 ? Face{j, j + 1, j + 2} : Face{j, j + 2, j + 1});
  if (sliver) {
    const Vec3 a = m.positions[nf - 1], b = m.positions[nf];
    Vec3& c = m.positions[nf + 1];
    const Vec3 mid = 0.5 * (a + b), dir = (c - mid).normalized();
    c = mid + 1e-6 * (b - a).norm() * dir;
  }
  return m;
}

/// Noisy height field over an nx x ny grid (cell size h) with isolated one-face holes.
TriMesh scan_patch(int nx, int ny, double h, Lcg& rng, const Vec3& origin) {
  TriMesh m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = i * h, y = j * h;
      const double z = 0.15 * std::sin(3 * x + origin.x()) * std::cos(2 * y) + 1e-3 * h * rng.next();
      m.positions.push_back(origin + Vec3(x, y, z));
    }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      // One-face holes on a sparse lattice of cells (never two in neighbouring cells).
      const bool hole = i < nx - 2 && j < ny - 2 && i % 29 == 8 && j % 31 == 11;
      m.faces.push_back({a, b, d});
      if (!hole) m.faces.push_back({a, d, c});
    }
  return m;
}

}  // namespace

TriMesh tiny_components(int count) {
  if (count < 1) throw InvalidInputError("tiny_components: count must be >= 1");
  std::vector<TriMesh> parts;
  Vec3 prev_first = Vec3::Zero();
  for (int i = 0; i < count; ++i) {
    const int nf = 1 + i % 10;
    TriMesh m = (nf >= 3 && i % 2 == 0) ? tiny_fan(nf, i % 4) : tiny_strip(nf, i % 3 == 2);
    const Vec3 offset = (i % 5 == 4) ? Vec3(prev_first - m.positions[0])
                                     : Vec3(6.0 * (i % 20), 3.0 * (i / 20), 0.0);
    for (Vec3& p : m.positions) p += offset;
    prev_first = m.positions[0];
    parts.push_back(std::move(m));
  }
  return disjoint_union(parts);
}

TriMesh synthetic_scan(int target_faces, int components, int zero_area_faces, unsigned seed) {
  if (components < 1 || target_faces < 100 * components || zero_area_faces < 0)
    throw InvalidInputError("synthetic_scan: need components >= 1, target_faces >= 100 components, "
                            "zero_area_faces >= 0");
  Lcg rng{seed * 2654435761ULL + 1};
  std::vector<TriMesh> parts;
  const int big = components > 1 ? target_faces / 2 : target_faces;
  const int regular = std::max(1, components - 1 - (components - 1) / 10);
  for (int c = 0; c < components; ++c) {
    const Vec3 origin(2.5 * (c % 16), 2.5 * (c / 16), 0.0);
    if (c > 0 && c % 10 == 0) {  // tiny component
      TriMesh m = tiny_strip(1 + c % 10, false);
      for (Vec3& p : m.positions) p = origin + 0.1 * p;
      parts.push_back(std::move(m));
      continue;
    }
    const int faces = c == 0 ? big : (target_faces - big) / regular;
    const int nx = std::max(2, static_cast<int>(std::sqrt(faces / 2.0 * (1.0 + 0.5 * (c % 3)))));
    const int ny = std::max(2, faces / (2 * nx));
    parts.push_back(scan_patch(nx, ny, 2.0 / std::max(nx, ny), rng, origin));
  }
  // Zero-area faces: collapse interior grid edges (a, a+1) of the big patch onto a.
  TriMesh& p0 = parts[0];
  const int nx0 = static_cast<int>(std::round(
      (p0.positions.back().x() - p0.positions.front().x()) / (p0.positions[1].x() - p0.positions[0].x())));
  const int rows = static_cast<int>(p0.positions.size()) / (nx0 + 1);
  for (int k = 0; k < zero_area_faces / 2; ++k) {
    const int j = 2 + static_cast<int>(rng.next() * (rows - 4));
    const int i = 2 + 4 * static_cast<int>(rng.next() * ((nx0 - 4) / 4));
    const int a = j * (nx0 + 1) + i;
    p0.positions[a + 1] = p0.positions[a];
  }
  return disjoint_union(parts);
}

}  // namespace adaptex::shapes
