/// \file signal.cpp
/// Exact ground-truth colour of a stroke file at surface points (see signal.h, strokes.md).
#include "adaptex/paint/signal.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "adaptex/core/errors.h"
#include "cell_hash.h"
#include "texel_grid.h"
#include "adaptex/paint/decal.h"

namespace adaptex {

namespace {

/// Dabs of the strokes whose radius is in one power-of-two class; cell size >= 2 * radius, so a
/// dab overlaps at most 2x2x2 cells and a point looks at exactly one cell.
struct Level {
  double cell = 1;
  Vec3 origin = Vec3::Zero();
  std::uint32_t max_coord = 0;
  struct Entry {
    Vec3 c;
    int stroke;
  };
  std::vector<Entry> entries;  // sorted by (cell key, stroke)
  detail::CellHash table;

  bool cell_of(const Vec3& p, std::uint64_t& key) const {
    std::uint32_t q[3];
    for (int a = 0; a < 3; ++a) {
      const double f = std::floor((p[a] - origin[a]) / cell);
      if (f < 0 || f > max_coord) return false;
      q[a] = static_cast<std::uint32_t>(f);
    }
    key = detail::morton3(q[0], q[1], q[2]);
    return true;
  }
};

}  // namespace

struct StrokeSignal::Impl {
  const TriMesh& mesh;
  const StrokeFile& file;
  std::vector<Level> levels;
  std::vector<double> r2, inv_r, hard, opac;
  std::vector<int> decals;  // stroke indices of decal strokes, ascending
  std::unique_ptr<DecalProjector> projector;

  Impl(const TriMesh& m, const StrokeFile& f) : mesh(m), file(f) {
    const int S = static_cast<int>(f.strokes.size());
    r2.assign(S, 0);
    inv_r.assign(S, 0);
    hard.assign(S, 0);
    opac.assign(S, 0);
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
    double rmax = 0;
    std::map<int, std::vector<int>> by_level;  // exponent -> strokes
    for (int s = 0; s < S; ++s) {
      const Stroke& st = f.strokes[s];
      validate_stroke(st, "stroke " + std::to_string(s));
      opac[s] = st.opacity;
      if (st.type == Stroke::Type::Decal) {
        decals.push_back(s);
        continue;
      }
      r2[s] = st.radius * st.radius;
      inv_r[s] = 1.0 / st.radius;
      hard[s] = st.hardness;
      rmax = std::max(rmax, st.radius);
      for (const Vec3& c : st.dabs) {
        lo = lo.cwiseMin(c);
        hi = hi.cwiseMax(c);
      }
      by_level[static_cast<int>(std::ceil(std::log2(2.0 * st.radius)))].push_back(s);
    }
    if (!decals.empty()) {
      projector = std::make_unique<DecalProjector>(m);
    }
    if (by_level.empty()) return;
    const Vec3 origin = lo - Vec3::Constant(rmax);
    const double extent = (hi - lo).maxCoeff() + 2 * rmax;
    // Merge classes so that no level needs more than 2^20 cells per axis.
    const int min_exp = static_cast<int>(std::ceil(std::log2(std::max(extent, 1e-300) / (1 << 20))));
    std::map<int, std::vector<int>> merged;
    for (auto& [e, strokes] : by_level) {
      auto& dst = merged[std::max(e, min_exp)];
      dst.insert(dst.end(), strokes.begin(), strokes.end());
    }
    for (auto& [e, strokes] : merged) {
      Level lv;
      lv.cell = std::ldexp(1.0, e);
      lv.origin = origin;
      lv.max_coord = static_cast<std::uint32_t>(std::min<double>((1 << 21) - 1, std::floor(extent / lv.cell) + 1));
      std::vector<std::pair<std::uint64_t, std::pair<int, int>>> keyed;  // key, (stroke, dab)
      for (int s : strokes) {
        const Stroke& st = f.strokes[s];
        for (int d = 0; d < static_cast<int>(st.dabs.size()); ++d) {
          const Vec3& c = st.dabs[d];
          std::uint32_t a[3], b[3];
          for (int k = 0; k < 3; ++k) {
            a[k] = static_cast<std::uint32_t>(std::floor((c[k] - st.radius - origin[k]) / lv.cell));
            b[k] = static_cast<std::uint32_t>(std::floor((c[k] + st.radius - origin[k]) / lv.cell));
          }
          for (std::uint32_t z = a[2]; z <= b[2]; ++z)
            for (std::uint32_t y = a[1]; y <= b[1]; ++y)
              for (std::uint32_t x = a[0]; x <= b[0]; ++x) keyed.push_back({detail::morton3(x, y, z), {s, d}});
        }
      }
      tbb::parallel_sort(keyed.begin(), keyed.end());
      std::vector<std::uint64_t> keys(keyed.size());
      lv.entries.resize(keyed.size());
      for (size_t k = 0; k < keyed.size(); ++k) {
        keys[k] = keyed[k].first;
        const auto [s, d] = keyed[k].second;
        lv.entries[k] = Level::Entry{f.strokes[s].dabs[d], s};
      }
      lv.table = detail::CellHash(keys);
      levels.push_back(std::move(lv));
    }
  }

  Vec3 eval(const Vec3& p, int face) const {
    // (stroke, alpha) of the brush strokes reaching p; strokes are unique per level.
    thread_local std::vector<std::pair<int, double>> hits;
    hits.clear();
    int levels_hit = 0;
    for (const Level& lv : levels) {
      std::uint64_t key;
      if (!lv.cell_of(p, key)) continue;
      std::uint32_t b, e;
      lv.table.find(key, b, e);
      if (b == e) continue;
      const size_t before = hits.size();
      int cur = -1;
      double best = 0;
      for (std::uint32_t k = b; k < e; ++k) {
        const Level::Entry& en = lv.entries[k];
        if (en.stroke != cur) {
          if (cur >= 0 && best > 0) hits.push_back({cur, best});
          cur = en.stroke;
          best = 0;
        }
        const double d2 = (p - en.c).squaredNorm();
        if (d2 >= r2[cur]) continue;
        const double w = opac[cur] * brush_falloff(std::sqrt(d2) * inv_r[cur], hard[cur]);
        best = std::max(best, w);
      }
      if (cur >= 0 && best > 0) hits.push_back({cur, best});
      if (hits.size() > before) ++levels_hit;
    }
    if (levels_hit > 1) std::sort(hits.begin(), hits.end());
    Vec3 C = file.background;
    size_t h = 0, d = 0;
    while (h < hits.size() || d < decals.size()) {
      if (d < decals.size() && (h == hits.size() || decals[d] < hits[h].first)) {
        if (face < 0) throw InvalidInputError("stroke signal: decal strokes need the face of every point");
        const Eigen::Vector4d v = projector->evaluate(file.strokes[decals[d]], p, face);
        C = C * (1 - v[3]) + v.head<3>() * v[3];
        ++d;
      } else {
        const double a = hits[h].second;
        C = C * (1 - a) + file.strokes[hits[h].first].color * a;
        ++h;
      }
    }
    return C;
  }
};

StrokeSignal::StrokeSignal(const TriMesh& mesh, const StrokeFile& strokes)
    : impl_(std::make_unique<Impl>(mesh, strokes)) {}
StrokeSignal::~StrokeSignal() = default;
StrokeSignal::StrokeSignal(StrokeSignal&&) noexcept = default;
StrokeSignal& StrokeSignal::operator=(StrokeSignal&&) noexcept = default;

Vec3 StrokeSignal::evaluate(const Vec3& p, int face) const { return impl_->eval(p, face); }

Vec3 StrokeSignal::evaluate(const SurfacePoint& sp) const {
  return impl_->eval(point_on_face(impl_->mesh, sp.face, sp.b0, sp.b1), sp.face);
}

std::vector<Vec3> StrokeSignal::evaluate(const std::vector<SurfacePoint>& points) const {
  std::vector<Vec3> out(points.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k < r.end(); ++k) out[k] = evaluate(points[k]);
  });
  return out;
}

bool StrokeSignal::has_decals() const { return !impl_->decals.empty(); }

struct PointSignalCache::Impl {
  const TriMesh& mesh;
  std::vector<SurfacePoint> points;
  std::vector<Vec3> position, value;
  Vec3 background;
  int count = 0;
  bool decal = false;
  std::unique_ptr<DecalProjector> projector;  // built at the first decal stroke
  std::vector<int> face;                      // points[k].face, for the projector's batch form

  std::unique_ptr<detail::TexelGrid> grid;  // the points' spatial index, built at the first brush stroke
  std::vector<double> cover;                 // per point: the stroke's coverage (0 between strokes)
  std::vector<int> touched;                  // the points a stroke's dabs reached
  double max_abs = 0;                        // largest |coordinate| of the points (float rounding bound)

  /// A brush stroke: max coverage over its dabs (as StrokeSignal::Impl::eval), composited over C.
  /// Each dab visits only the points in its ball (TexelGrid), so a stroke costs its dabs times the
  /// points each one reaches, not every point in the stroke's box times every dab. The index compares
  /// in float: it is queried wider than the radius by the float rounding of the coordinates (relative
  /// to their magnitude, which far from the origin dwarfs a small brush) and of r², and the test
  /// itself is the double one, so no point inside the radius is missed.
  void add_brush(const Stroke& s) {
    if (s.dabs.empty()) return;
    if (!grid) {
      std::vector<Vec3f> pf(position.size());
      for (size_t k = 0; k < position.size(); ++k) {
        pf[k] = position[k].cast<float>();
        max_abs = std::max(max_abs, position[k].cwiseAbs().maxCoeff());
      }
      const double spacing = std::sqrt(surface_area(mesh) / std::max<size_t>(position.size(), 1));
      grid = std::make_unique<detail::TexelGrid>(pf, spacing);
      cover.assign(position.size(), 0.0);
    }
    const double r2 = s.radius * s.radius, inv_r = 1.0 / s.radius;
    const std::vector<int>& order = grid->order();
    touched.clear();
    for (const Vec3& c : s.dabs) {
      // Each coordinate of p − c in float is off by at most 2^-23 (|p| + |c|) (two roundings to float
      // and one subtraction), the distance by √3 times that: 8 · FLT_EPSILON is a safe margin.
      const double slack = 8 * std::numeric_limits<float>::epsilon() * (max_abs + c.cwiseAbs().maxCoeff());
      grid->for_each_in_ball(c, s.radius * (1 + 1e-5) + slack + 1e-30, [&](int slot, float) {
        const int k = order[static_cast<size_t>(slot)];
        const double d2 = (position[k] - c).squaredNorm();
        if (d2 >= r2) return;
        const double a = s.opacity * brush_falloff(std::sqrt(d2) * inv_r, s.hardness);
        if (cover[k] == 0 && a > 0) touched.push_back(k);
        cover[k] = std::max(cover[k], a);
      });
    }
    for (int k : touched) {
      value[k] = value[k] * (1 - cover[k]) + s.color * cover[k];
      cover[k] = 0;
    }
  }

  /// A decal: (colour, a) at every point from one projector (its BVH built at the first decal and
  /// kept), composited as StrokeSignal does: C <- C (1 - a) + colour a.
  void add_decal(const Stroke& s) {
    if (!projector) {
      projector = std::make_unique<DecalProjector>(mesh);
      face.resize(points.size());
      for (size_t k = 0; k < points.size(); ++k) face[k] = points[k].face;
    }
    std::vector<Eigen::Vector4d> v(points.size());
    projector->evaluate(s, position, face, v);
    for (size_t k = 0; k < points.size(); ++k) value[k] = value[k] * (1 - v[k][3]) + v[k].head<3>() * v[k][3];
    decal = true;
  }
};

PointSignalCache::PointSignalCache(const TriMesh& mesh, std::vector<SurfacePoint> points, const Vec3& background)
    : impl_(std::make_unique<Impl>(Impl{mesh, std::move(points), {}, {}, background})) {
  Impl& m = *impl_;
  m.position.resize(m.points.size());
  for (size_t k = 0; k < m.points.size(); ++k) {
    const SurfacePoint& sp = m.points[k];
    if (sp.face < 0 || sp.face >= mesh.num_faces())
      throw InvalidInputError("point signal cache: point " + std::to_string(k) + " has face " +
                              std::to_string(sp.face) + ", the mesh has " + std::to_string(mesh.num_faces()));
    m.position[k] = point_on_face(mesh, sp.face, sp.b0, sp.b1);
  }
  m.value.assign(m.points.size(), background);
}
PointSignalCache::~PointSignalCache() = default;
PointSignalCache::PointSignalCache(PointSignalCache&&) noexcept = default;
PointSignalCache& PointSignalCache::operator=(PointSignalCache&&) noexcept = default;

void PointSignalCache::add_stroke(const Stroke& stroke) {
  validate_stroke(stroke, "point signal cache");
  if (stroke.type == Stroke::Type::Decal)
    impl_->add_decal(stroke);
  else
    impl_->add_brush(stroke);
  ++impl_->count;
}

void PointSignalCache::update(const StrokeFile& history) {
  for (size_t k = static_cast<size_t>(impl_->count); k < history.strokes.size(); ++k) add_stroke(history.strokes[k]);
}

const std::vector<SurfacePoint>& PointSignalCache::points() const { return impl_->points; }
const std::vector<Vec3>& PointSignalCache::values() const { return impl_->value; }
int PointSignalCache::strokes() const { return impl_->count; }
bool PointSignalCache::has_decals() const { return impl_->decal; }

Vec3 evaluate_strokes_reference(const StrokeFile& file, const Vec3& p) {
  Vec3 C = file.background;
  for (const Stroke& s : file.strokes) {
    if (s.type == Stroke::Type::Decal)
      throw InvalidInputError("evaluate_strokes_reference: decal strokes are not supported");
    double a = 0;
    for (const Vec3& c : s.dabs) a = std::max(a, s.opacity * brush_falloff((p - c).norm() / s.radius, s.hardness));
    C = C * (1 - a) + s.color * a;
  }
  return C;
}

}  // namespace adaptex
