/// \file generate.cpp
/// Seeded test stroke sets: surface walks (tangent step + closest-point projection); dots sprinkled
/// in a Euclidean ball around a random surface point.
#include "adaptex/paint/generate.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "adaptex/core/errors.h"
#include "adaptex/core/topology.h"
#include "splitmix.h"

namespace adaptex {

namespace {

using detail::Rng;

/// Closest point to p on triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double den = 1.0 / (va + vb + vc);
  return a + ab * (vb * den) + ac * (vc * den);
}

class Walker {
 public:
  explicit Walker(const TriMesh& m) : mesh_(m), vf_(build_vertex_faces(m)) {
    cdf_.resize(m.faces.size());
    double total = 0;
    for (int f = 0; f < m.num_faces(); ++f) cdf_[f] = total += face_area(m, f);
    total_ = total;
    if (!(total > 0)) throw InvalidInputError("strokes generate: the mesh has no face of positive area");
  }

  /// Area-uniform random point among \p faces (all faces if empty).
  std::pair<Vec3, int> random_point(Rng& rng, const std::vector<int>& faces = {}) const {
    int f;
    if (faces.empty()) {
      f = static_cast<int>(std::upper_bound(cdf_.begin(), cdf_.end(), rng.uniform() * total_) - cdf_.begin());
      f = std::min(f, mesh_.num_faces() - 1);
    } else {
      double sum = 0;
      for (int g : faces) sum += face_area(mesh_, g);
      double x = rng.uniform() * sum;
      f = faces.back();
      for (int g : faces)
        if ((x -= face_area(mesh_, g)) <= 0) {
          f = g;
          break;
        }
    }
    const double s = std::sqrt(rng.uniform()), t = rng.uniform();
    return {point_on_face(mesh_, f, 1 - s, s * (1 - t)), f};
  }

  /// Closest surface point to p, by descent over vertex-adjacent faces starting at face f.
  std::pair<Vec3, int> project(const Vec3& p, int f) const {
    Vec3 best = closest(p, f);
    double bd = (best - p).squaredNorm();
    for (int it = 0; it < 64; ++it) {
      int next = -1;
      for (int k = 0; k < 3; ++k) {
        const int v = mesh_.faces[f][k];
        for (int o = vf_.offsets[v]; o < vf_.offsets[v + 1]; ++o) {
          const int g = vf_.faces[o];
          if (g == f) continue;
          const Vec3 q = closest(p, g);
          const double d = (q - p).squaredNorm();
          if (d < bd * (1 - 1e-12) - 1e-300) {
            bd = d;
            best = q;
            next = g;
          }
        }
      }
      if (next < 0) break;
      f = next;
    }
    return {best, f};
  }

  /// Dabs of a walk of about \p length from (p, f), spaced \p step, curving randomly.
  std::vector<Vec3> walk(Rng& rng, Vec3 p, int f, double length, double step) const {
    std::vector<Vec3> dabs{p};
    Vec3 n = face_normal(mesh_, f);
    Vec3 dir = random_tangent(rng, n);
    const double curvature = rng.uniform(-1.5, 1.5) / std::max(length, 1e-300);  // radians per unit length
    const int steps = std::max(1, static_cast<int>(std::ceil(length / step)));
    int stalled = 0;
    for (int k = 0; k < steps && stalled < 3; ++k) {
      n = face_normal(mesh_, f);
      dir -= dir.dot(n) * n;
      if (dir.norm() < 1e-12) dir = random_tangent(rng, n);
      dir.normalize();
      const double turn = curvature * step + rng.uniform(-0.15, 0.15);
      dir = Eigen::AngleAxisd(turn, n) * dir;
      auto [q, g] = project(p + step * dir, f);
      const Vec3 moved = q - p;
      if (moved.norm() < 0.1 * step) {
        ++stalled;
        dir = random_tangent(rng, n);
        continue;
      }
      stalled = 0;
      dir = moved.normalized();
      p = q;
      f = g;
      dabs.push_back(p);
    }
    return dabs;
  }

  /// Radius of the Euclidean ball around \p c whose faces (by centroid distance) hold \p fraction of
  /// the total surface area.
  double ball_radius_for_area(const Vec3& c, double fraction) const {
    std::vector<std::pair<double, int>> by_distance(mesh_.faces.size());
    for (int f = 0; f < mesh_.num_faces(); ++f) {
      by_distance[f] = {(centroid(f) - c).norm(), f};
    }
    std::sort(by_distance.begin(), by_distance.end());
    double area = 0;
    for (const auto& [d, f] : by_distance)
      if ((area += face_area(mesh_, f)) >= fraction * total_) return d;
    return by_distance.back().first;
  }

  /// Faces with a vertex or the centroid within \p radius of \p c, plus \p c's own face \p cf.
  std::vector<int> faces_in_ball(const Vec3& c, double radius, int cf) const {
    std::vector<int> out;
    for (int f = 0; f < mesh_.num_faces(); ++f) {
      const Face& t = mesh_.faces[f];
      bool in = f == cf || (centroid(f) - c).norm() <= radius;
      for (int k = 0; k < 3 && !in; ++k) in = (mesh_.positions[t[k]] - c).norm() <= radius;
      if (in && face_area(mesh_, f) > 0) out.push_back(f);
    }
    return out;
  }

  /// Area-uniform random point of \p faces (cumulative areas \p cdf) inside the ball (c, radius),
  /// by rejection; \p fallback (a point of the ball on the surface) if 64 tries miss.
  std::pair<Vec3, int> random_point_in_ball(Rng& rng, const std::vector<int>& faces, const std::vector<double>& cdf,
                                            const Vec3& c, double radius, std::pair<Vec3, int> fallback) const {
    for (int attempt = 0; attempt < 64; ++attempt) {
      const size_t k = std::min(faces.size() - 1, static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(),
                                                                                       rng.uniform() * cdf.back()) -
                                                                      cdf.begin()));
      const double s = std::sqrt(rng.uniform()), t = rng.uniform();
      const Vec3 p = point_on_face(mesh_, faces[k], 1 - s, s * (1 - t));
      if ((p - c).norm() <= radius) return {p, faces[k]};
    }
    return fallback;
  }

  /// Faces with a vertex within \p radius of \p c.
  std::vector<int> faces_near(const Vec3& c, double radius) const {
    std::vector<int> out;
    for (int f = 0; f < mesh_.num_faces(); ++f)
      for (int k = 0; k < 3; ++k)
        if ((mesh_.positions[mesh_.faces[f][k]] - c).norm() <= radius && face_area(mesh_, f) > 0) {
          out.push_back(f);
          break;
        }
    return out;
  }

 const TriMesh& mesh() const { return mesh_; }

 private:
  Vec3 centroid(int f) const {
    const Face& t = mesh_.faces[f];
    return (mesh_.positions[t[0]] + mesh_.positions[t[1]] + mesh_.positions[t[2]]) / 3.0;
  }
  Vec3 closest(const Vec3& p, int f) const {
    const Face& t = mesh_.faces[f];
    return closest_on_triangle(p, mesh_.positions[t[0]], mesh_.positions[t[1]], mesh_.positions[t[2]]);
  }
  static Vec3 random_tangent(Rng& rng, const Vec3& n) {
    Vec3 a = std::abs(n.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    if (n.norm() < 1e-12) a = Vec3(1, 0, 0);
    const Vec3 t1 = (a - a.dot(n) * n).normalized(), t2 = n.cross(t1);
    const double phi = rng.uniform(0, 2 * std::numbers::pi);
    Vec3 d = std::cos(phi) * t1 + std::sin(phi) * t2;
    return d.norm() > 0 ? d : Vec3(1, 0, 0);
  }
  const TriMesh& mesh_;
  VertexFaces vf_;
  std::vector<double> cdf_;
  double total_ = 0;
};

/// Random HSV colour with saturation in [s_min, 1] and value in [v_min, 1].
Vec3 random_colour(Rng& rng, double s_min = 0.6, double v_min = 0.45) {
  const double h = rng.uniform(0, 6), s = rng.uniform(s_min, 1.0), v = rng.uniform(v_min, 1.0);
  const double c = v * s, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = v - c;
  Vec3 rgb;
  switch (static_cast<int>(h) % 6) {
    case 0: rgb = Vec3(c, x, 0); break;
    case 1: rgb = Vec3(x, c, 0); break;
    case 2: rgb = Vec3(0, c, x); break;
    case 3: rgb = Vec3(0, x, c); break;
    case 4: rgb = Vec3(x, 0, c); break;
    default: rgb = Vec3(c, 0, x); break;
  }
  return (rgb + Vec3::Constant(m)).cwiseMax(0.0).cwiseMin(1.0);
}

/// The Dots kind (generate.h): \p count dots (-1: 150-400) in a ball holding 10-20 % of the area.
void generate_dots(const Walker& walker, Rng& rng, double diag, int count, StrokeFile& file,
                   GeneratedRegion& region) {
  const auto centre = walker.random_point(rng);
  region.centre = centre.first;
  region.area_fraction = rng.uniform(0.10, 0.20);
  region.radius = walker.ball_radius_for_area(region.centre, region.area_fraction);
  const std::vector<int> faces = walker.faces_in_ball(region.centre, region.radius, centre.second);
  std::vector<double> cdf(faces.size());
  double total = 0;
  for (size_t k = 0; k < faces.size(); ++k) cdf[k] = total += face_area(walker.mesh(), faces[k]);
  if (count < 0) count = 150 + std::min(250, static_cast<int>(rng.uniform() * 251));
  for (int k = 0; k < count; ++k) {
    Stroke s;
    s.color = random_colour(rng, 0.8, 0.6);
    s.radius = rng.uniform(0.001, 0.002) * diag;
    s.hardness = rng.uniform(0.8, 1.0);
    s.opacity = 1.0;
    const int extra = std::min(2, static_cast<int>(rng.uniform() * 3));  // 1-3 dabs
    const double step = rng.uniform(0.5, 1.0) * s.radius;
    auto [p, f] = walker.random_point_in_ball(rng, faces, cdf, region.centre, region.radius, centre);
    if (extra == 0) {
      s.dabs = {p};
    } else {
      for (const Vec3& q : walker.walk(rng, p, f, extra * step, step))
        if ((q - region.centre).norm() <= region.radius) s.dabs.push_back(q);
    }
    file.strokes.push_back(std::move(s));
  }
}

}  // namespace

StrokeKind parse_stroke_kind(const std::string& name) {
  if (name == "lines") return StrokeKind::Lines;
  if (name == "blobs") return StrokeKind::Blobs;
  if (name == "mixed") return StrokeKind::Mixed;
  if (name == "dots") return StrokeKind::Dots;
  throw InvalidInputError("unknown stroke kind \"" + name + "\" (expected lines, blobs, mixed or dots)");
}

std::string to_string(StrokeKind kind) {
  switch (kind) {
    case StrokeKind::Lines: return "lines";
    case StrokeKind::Blobs: return "blobs";
    case StrokeKind::Dots: return "dots";
    default: return "mixed";
  }
}

StrokeFile generate_strokes(const TriMesh& mesh, const GenerateOptions& options, GeneratedRegion* region_out) {
  if (options.count < 1 && options.count != -1)
    throw InvalidInputError("strokes generate: --count must be >= 1 (got " + std::to_string(options.count) + ")");
  const Walker walker(mesh);
  const double diag = bounding_box(mesh).diagonal();
  Rng rng{options.seed * 0xA24BAED4963EE407ULL + 0x1234567ULL};
  StrokeFile file;
  file.background = options.background;
  GeneratedRegion ball;
  if (options.kind == StrokeKind::Dots) {
    generate_dots(walker, rng, diag, options.count, file, ball);
    if (region_out) *region_out = ball;
    return file;
  }
  if (region_out) *region_out = ball;
  int lines = 0, blobs = 0;
  switch (options.kind) {
    case StrokeKind::Lines: lines = options.count > 0 ? options.count : 60; break;
    case StrokeKind::Blobs: blobs = options.count > 0 ? options.count : 6; break;
    case StrokeKind::Mixed: {
      const int n = options.count > 0 ? options.count : 48;
      blobs = std::max(1, n / 8);
      lines = n - blobs;
      break;
    }
    case StrokeKind::Dots: break;
  }
  for (int k = 0; k < blobs; ++k) {
    Stroke s;
    s.color = random_colour(rng);
    s.radius = rng.uniform(0.04, 0.10) * diag;
    s.hardness = rng.uniform(0.0, 0.3);
    s.opacity = rng.uniform(0.4, 0.8);
    auto [p, f] = walker.random_point(rng);
    s.dabs = walker.walk(rng, p, f, rng.uniform(0.1, 0.3) * diag, 0.4 * s.radius);
    file.strokes.push_back(std::move(s));
  }
  if (lines > 0) {
    const auto [centre, cf] = walker.random_point(rng);
    (void)cf;
    std::vector<int> region = walker.faces_near(centre, 0.12 * diag);
    for (int k = 0; k < lines; ++k) {
      Stroke s;
      s.color = random_colour(rng);
      s.radius = rng.uniform(0.002, 0.005) * diag;
      s.hardness = rng.uniform(0.8, 1.0);
      s.opacity = rng.uniform(0.85, 1.0);
      auto [p, f] = walker.random_point(rng, region);
      s.dabs = walker.walk(rng, p, f, rng.uniform(0.05, 0.15) * diag, 0.4 * s.radius);
      file.strokes.push_back(std::move(s));
    }
  }
  return file;
}

}  // namespace adaptex
