// Linear-time no-overlap proof for flip-free remaps (overlap_certificate.h).
#include "adaptex/adapt/overlap_certificate.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "adaptex/core/errors.h"
#include "adaptex/core/predicates.h"
#include "adaptex/core/topology.h"

namespace adaptex {

namespace {
int orient(const Vec2& a, const Vec2& b, const Vec2& c) { return orient2d_filtered(a, b, c); }

/// True if the closed segments ab and cd (no shared endpoint) may intersect or touch.
bool segments_may_touch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  if (std::max(a.x(), b.x()) < std::min(c.x(), d.x()) || std::max(c.x(), d.x()) < std::min(a.x(), b.x()) ||
      std::max(a.y(), b.y()) < std::min(c.y(), d.y()) || std::max(c.y(), d.y()) < std::min(a.y(), b.y()))
    return false;
  return orient(a, b, c) * orient(a, b, d) <= 0 && orient(c, d, a) * orient(c, d, b) <= 0;
}

/// True if the segments s->p and s->q (sharing their start s) may overlap: collinear, same direction.
bool fold_back(const Vec2& s, const Vec2& p, const Vec2& q) {
  return orient(s, p, q) == 0 && (p - s).dot(q - s) > 0;
}
}  // namespace

OverlapCertificate::OverlapCertificate(const Parameterization& before, double min_area)
    : wedges_(before.uv.size()), faces_(before.uv_faces.size()) {
  for (const Face& t : before.uv_faces)
    for (int w : t)
      if (w < 0 || static_cast<size_t>(w) >= wedges_)
        throw InvalidInputError("overlap certificate: a face refers to wedge " + std::to_string(w) + " of " +
                                std::to_string(wedges_));
  // Pieces: the components of faces joined by shared wedges (a chart may have several).
  std::vector<int> parent(wedges_);
  for (size_t w = 0; w < wedges_; ++w) parent[w] = static_cast<int>(w);
  auto root = [&](int w) {
    while (parent[w] != w) w = parent[w] = parent[parent[w]];
    return w;
  };
  for (const Face& t : before.uv_faces) parent[root(t[1])] = root(t[0]), parent[root(t[2])] = root(t[0]);
  wedge_chart_.assign(wedges_, -1);
  std::vector<int> id(wedges_, -1);
  pieces_ = 0;
  for (const Face& t : before.uv_faces) {
    const int r = root(t[0]);
    if (id[r] < 0) id[r] = pieces_++;
  }
  for (size_t w = 0; w < wedges_; ++w)
    if (id[root(static_cast<int>(w))] >= 0) wedge_chart_[w] = id[root(static_cast<int>(w))];
  // Every face non-degenerate, one orientation per piece.
  std::vector<int> sign(pieces_, 0);
  for (size_t f = 0; f < faces_; ++f) {
    const double a = uv_signed_area(before, static_cast<int>(f));
    if (!(std::abs(a) > min_area)) return;
    const int s = a > 0 ? 1 : -1, c = wedge_chart_[before.uv_faces[f][0]];
    if (sign[c] != 0 && sign[c] != s) return;
    sign[c] = s;
  }
  // Edges by their wedges (bucket_edges()): an edge in one face is a boundary edge, in two faces it
  // must be ordered oppositely by them, in more the layout is not a surface.
  const EdgeBuckets eb = bucket_edges(before.uv_faces, static_cast<int>(wedges_));
  std::vector<int> boundary_degree(wedges_, 0);
  auto min_to_max = [&](const EdgeBuckets::Record& r) {
    const Face& t = before.uv_faces[static_cast<size_t>(r.face)];
    return t[r.corner] < t[(r.corner + 1) % 3];
  };
  for (size_t a = 0; a < wedges_; ++a) {
    const auto first = eb.records.begin() + eb.start[a], last = eb.records.begin() + eb.start[a + 1];
    for (auto i = first; i != last;) {
      auto j = i + 1;
      while (j != last && j->b == i->b) ++j;
      if (j - i > 2 || (j - i == 2 && min_to_max(*i) == min_to_max(*(i + 1)))) return;
      if (j - i == 1) {
        boundary_.push_back({static_cast<int>(a), i->b, wedge_chart_[a]});
        ++boundary_degree[a], ++boundary_degree[static_cast<size_t>(i->b)];
      }
      i = j;
    }
  }
  for (int d : boundary_degree)
    if (d != 0 && d != 2) return;  // a pinched wedge: its loops may nest without crossing
  applicable_ = true;
}

bool OverlapCertificate::certifies(const Parameterization& after) const {
  if (after.uv.size() != wedges_ || after.uv_faces.size() != faces_)
    throw InvalidInputError("overlap certificate: the layout has other wedges or faces than the one it was built for");
  if (!applicable_) return false;
  // 1. Charts in pairwise disjoint boxes cannot overlap each other.
  std::vector<Vec2> lo(pieces_, Vec2::Constant(1e300)), hi(pieces_, Vec2::Constant(-1e300));
  for (size_t w = 0; w < wedges_; ++w) {
    const int c = wedge_chart_[w];
    if (c < 0) continue;  // a wedge of no face
    lo[c] = lo[c].cwiseMin(after.uv[w]);
    hi[c] = hi[c].cwiseMax(after.uv[w]);
  }
  std::vector<int> order;
  for (int c = 0; c < pieces_; ++c)
    if (lo[c].x() <= hi[c].x()) order.push_back(c);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lo[a].x() < lo[b].x(); });
  for (size_t i = 0; i < order.size(); ++i)
    for (size_t j = i + 1; j < order.size() && !(lo[order[j]].x() > hi[order[i]].x()); ++j) {
      const int a = order[i], b = order[j];
      if (!(lo[a].y() > hi[b].y() || lo[b].y() > hi[a].y())) return false;  // boxes touch or overlap
    }
  // 2. Within a chart: no two boundary edges touch (except consecutive ones at their shared wedge,
  // which must not fold back onto each other). Uniform grid of buckets over the square.
  const int B = static_cast<int>(boundary_.size());
  if (B < 2) return true;
  const int n = std::clamp(static_cast<int>(std::sqrt(double(B))), 1, 2048);
  Vec2 glo = Vec2::Constant(1e300), ghi = Vec2::Constant(-1e300);
  for (int c = 0; c < pieces_; ++c)
    if (lo[c].x() <= hi[c].x()) glo = glo.cwiseMin(lo[c]), ghi = ghi.cwiseMax(hi[c]);
  const Vec2 ext = (ghi - glo).cwiseMax(Vec2::Constant(1e-300));
  auto cell = [&](double x, int axis) { return std::clamp(static_cast<int>((x - glo[axis]) / ext[axis] * n), 0, n - 1); };
  std::vector<int> start(static_cast<size_t>(n) * n + 1, 0), items;
  auto for_cells = [&](const Edge& e, auto&& fn) {
    const Vec2 &p = after.uv[e.a], &q = after.uv[e.b];
    for (int y = cell(std::min(p.y(), q.y()), 1); y <= cell(std::max(p.y(), q.y()), 1); ++y)
      for (int x = cell(std::min(p.x(), q.x()), 0); x <= cell(std::max(p.x(), q.x()), 0); ++x) fn(static_cast<size_t>(y) * n + x);
  };
  for (const Edge& e : boundary_) for_cells(e, [&](size_t c) { ++start[c + 1]; });
  for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  items.resize(start.back());
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int e = 0; e < B; ++e) for_cells(boundary_[e], [&](size_t c) { items[fill[c]++] = e; });
  }
  for (size_t c = 0; c + 1 < start.size(); ++c)
    for (int i = start[c]; i < start[c + 1]; ++i)
      for (int j = i + 1; j < start[c + 1]; ++j) {
        const Edge &e = boundary_[items[i]], &g = boundary_[items[j]];
        if (e.chart != g.chart) continue;  // separated by their boxes
        const Vec2 &a = after.uv[e.a], &b = after.uv[e.b], &p = after.uv[g.a], &q = after.uv[g.b];
        if (e.a == g.a ? fold_back(a, b, q)
            : e.a == g.b ? fold_back(a, b, p)
            : e.b == g.a ? fold_back(b, a, q)
            : e.b == g.b ? fold_back(b, a, p)
                         : segments_may_touch(a, b, p, q))
          return false;
      }
  return true;
}

}  // namespace adaptex
