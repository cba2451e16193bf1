// Re-parameterization by the optimized grid (thesis §3.7.2) with the no-flip / no-overlap guarantee.
#include "adaptex/adapt/remap.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "adaptex/adapt/overlap_certificate.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/stretch.h"

namespace adaptex {

Parameterization remap_parameterization(const Parameterization& param, const std::vector<const GridWarp*>& warps) {
  Parameterization out = param;
  const WarpChain chain(warps);
  tbb::parallel_for(size_t(0), out.uv.size(),
                    [&](size_t k) { out.uv[k] = chain.apply(param.uv[k]).cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1)); });
  return out;
}

namespace {
/// UV boundary edges (wedge pairs used by exactly one face), with their face.
struct BoundaryEdge {
  int a, b, face;
};
/// bucket_edges() of the layout's UV faces (over every wedge a face names).
EdgeBuckets uv_edge_buckets(const Parameterization& param) {
  int nw = static_cast<int>(param.uv.size());
  for (const Face& f : param.uv_faces)
    for (int w : f) nw = std::max(nw, w + 1);
  return bucket_edges(param.uv_faces, nw);
}

/// Calls fn(a, b, face) for every UV edge a < b used by exactly one UV face, in (a, b) order.
template <class Fn>
void for_boundary_edges(const Parameterization& param, Fn&& fn) {
  const EdgeBuckets eb = uv_edge_buckets(param);
  for (size_t a = 0; a + 1 < eb.start.size(); ++a) {
    const auto first = eb.records.begin() + eb.start[a], last = eb.records.begin() + eb.start[a + 1];
    for (auto i = first; i != last;) {
      auto j = i + 1;
      while (j != last && j->b == i->b) ++j;
      if (j - i == 1 && !fn(static_cast<int>(a), i->b, i->face)) return;
      i = j;
    }
  }
}

std::vector<BoundaryEdge> uv_boundary_edges(const Parameterization& param) {
  std::vector<BoundaryEdge> out;
  for_boundary_edges(param, [&out](int a, int b, int face) {
    out.push_back({a, b, face});
    return true;
  });
  return out;
}

/// Faces where charts of a multi-chart layout run into each other after a warp: boundary edges that
/// properly cross another boundary edge (sharing no wedge), and boundary wedges strictly inside a face
/// of another chart (with the faces containing them). Uniform grids over the boxes.
std::vector<int> faces_of_crossing_boundaries(const Parameterization& p, const std::vector<BoundaryEdge>& edges) {
  std::vector<int> out;
  if (edges.size() < 2) return out;
  const int n = std::clamp(static_cast<int>(std::sqrt(double(edges.size()))), 1, 1024);
  auto cell = [n](double x) { return std::clamp(static_cast<int>(x * n), 0, n - 1); };
  std::vector<std::vector<int>> grid(static_cast<size_t>(n) * n);
  for (size_t e = 0; e < edges.size(); ++e) {
    const Vec2 &a = p.uv[edges[e].a], &b = p.uv[edges[e].b];
    for (int y = cell(std::min(a.y(), b.y())); y <= cell(std::max(a.y(), b.y())); ++y)
      for (int x = cell(std::min(a.x(), b.x())); x <= cell(std::max(a.x(), b.x())); ++x)
        grid[static_cast<size_t>(y) * n + x].push_back(static_cast<int>(e));
  }
  auto orient = [](const Vec2& a, const Vec2& b, const Vec2& c) {
    const double d = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    return (d > 0) - (d < 0);
  };
  std::vector<char> hit(p.uv_faces.size(), 0);
  for (const auto& list : grid)
    for (size_t i = 0; i < list.size(); ++i)
      for (size_t j = i + 1; j < list.size(); ++j) {
        const BoundaryEdge &e = edges[list[i]], &g = edges[list[j]];
        if (e.a == g.a || e.a == g.b || e.b == g.a || e.b == g.b) continue;
        const Vec2 &a = p.uv[e.a], &b = p.uv[e.b], &c = p.uv[g.a], &d = p.uv[g.b];
        if (orient(a, b, c) * orient(a, b, d) < 0 && orient(c, d, a) * orient(c, d, b) < 0)
          hit[e.face] = hit[g.face] = 1;
      }
  // A chart may also have moved wholly inside another: boundary wedges strictly inside a face of
  // another chart.
  std::vector<std::vector<int>> faces_in(static_cast<size_t>(n) * n);
  for (size_t f = 0; f < p.uv_faces.size(); ++f) {
    const Vec2 &a = p.uv[p.uv_faces[f][0]], &b = p.uv[p.uv_faces[f][1]], &c = p.uv[p.uv_faces[f][2]];
    const Vec2 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
    for (int y = cell(lo.y()); y <= cell(hi.y()); ++y)
      for (int x = cell(lo.x()); x <= cell(hi.x()); ++x) faces_in[static_cast<size_t>(y) * n + x].push_back(static_cast<int>(f));
  }
  for (const BoundaryEdge& e : edges) {
    const Vec2& q = p.uv[e.a];
    const int chart = p.face_chart.empty() ? -1 : p.face_chart[e.face];
    for (int f : faces_in[static_cast<size_t>(cell(q.y())) * n + cell(q.x())]) {
      if (chart >= 0 && p.face_chart[f] == chart) continue;
      const Face& t = p.uv_faces[f];
      const int s0 = orient(p.uv[t[0]], p.uv[t[1]], q), s1 = orient(p.uv[t[1]], p.uv[t[2]], q),
                s2 = orient(p.uv[t[2]], p.uv[t[0]], q);
      if (s0 != 0 && s0 == s1 && s1 == s2) hit[e.face] = hit[f] = 1;
    }
  }
  for (size_t f = 0; f < hit.size(); ++f)
    if (hit[f]) out.push_back(static_cast<int>(f));
  return out;
}

struct FlipCount {
  int flipped = 0, degenerate = 0;
};
FlipCount count_flips(const Parameterization& before, const Parameterization& after, double min_area) {
  const int F = static_cast<int>(before.uv_faces.size());
  return tbb::parallel_reduce(
      tbb::blocked_range<int>(0, F, 4096), FlipCount{},
      [&](const tbb::blocked_range<int>& r, FlipCount c) {
        for (int f = r.begin(); f < r.end(); ++f) {
          const double a0 = uv_signed_area(before, f);
          if (std::abs(a0) <= min_area) continue;  // already degenerate in the input
          const double a1 = uv_signed_area(after, f) * (a0 > 0 ? 1.0 : -1.0);
          if (a1 <= 0) ++c.flipped;
          else if (a1 <= min_area) ++c.degenerate;
        }
        return c;
      },
      [](FlipCount a, const FlipCount& b) {
        a.flipped += b.flipped;
        a.degenerate += b.degenerate;
        return a;
      });
}
}  // namespace

RemapCheck check_remap(const Parameterization& before, const Parameterization& after, const SafeRemapOptions& o) {
  RemapCheck c;
  const FlipCount fc = count_flips(before, after, o.min_area);
  c.flipped = fc.flipped;
  c.degenerate = fc.degenerate;
  if (o.check_overlaps && c.flipped == 0 && c.degenerate == 0)
    c.overlaps = std::max(0L, count_overlapping_triangles(after) - count_overlapping_triangles(before));
  return c;
}

bool single_chart_on_square(const Parameterization& param) {
  if (param.num_charts != 1) return false;
  auto on_square = [&](int w) {
    const Vec2& p = param.uv[w];
    const double e = 1e-9;
    return p.x() <= e || p.x() >= 1 - e || p.y() <= e || p.y() >= 1 - e;
  };
  bool all = true;
  for_boundary_edges(param, [&](int a, int b, int) { return all = on_square(a) && on_square(b); });
  return all;
}

Parameterization blend_layouts(const Parameterization& from, const Parameterization& to, double t) {
  if (from.uv.size() != to.uv.size())
    throw InvalidInputError("blend_layouts: " + std::to_string(from.uv.size()) + " and " +
                            std::to_string(to.uv.size()) + " wedges");
  Parameterization out = from;
  for (size_t w = 0; w < out.uv.size(); ++w)
    out.uv[w] = ((1 - t) * from.uv[w] + t * to.uv[w]).cwiseMax(Vec2(0, 0)).cwiseMin(Vec2(1, 1));
  return out;
}

SafeRemapResult safe_remap(const Parameterization& param, const std::vector<const GridWarp*>& warps,
                           const SafeRemapOptions& options) {
  return safe_remap_layout(param, remap_parameterization(param, warps), options);
}

namespace {

/// Wedge 1-rings: for every corner of a wedge, the face's two other corners, face by face (a
/// neighbour across an interior edge appears twice). CSR with twice the offsets of VertexFaces.
struct WedgeRings {
  std::vector<int> start, ring;
  int degree(int w) const { return start[w + 1] - start[w]; }
};
WedgeRings wedge_rings(const std::vector<Face>& faces, const VertexFaces& vf) {
  WedgeRings r;
  r.start.resize(vf.offsets.size());
  for (size_t w = 0; w < vf.offsets.size(); ++w) r.start[w] = 2 * vf.offsets[w];
  r.ring.resize(r.start.back());
  std::vector<int> fill(r.start.begin(), r.start.end() - 1);
  for (const Face& f : faces)
    for (int k = 0; k < 3; ++k) {
      r.ring[fill[f[k]]++] = f[(k + 1) % 3];
      r.ring[fill[f[k]]++] = f[(k + 2) % 3];
    }
  return r;
}

/// safe_remap_layout() in named steps. A candidate at global blend t starts as uv = old + disp,
/// disp = t · chart_t · (warped − old); it is untangled, then damped locally round by round; a
/// chart that still fails may be halved as a whole; last, the global blend t is bisected.
class SafeRemapper {
 public:
  SafeRemapper(const Parameterization& param, const Parameterization& full, const SafeRemapOptions& o);
  SafeRemapResult run();

 private:
  bool fails(const Parameterization& out, int f) const;
  void failing_faces(const Parameterization& out, const std::vector<int>* moved, std::vector<int>& bad);
  long new_overlaps(const Parameterization& out);
  std::vector<int> faces_of_overlaps(const Parameterization& out);
  void untangle(Parameterization& out);
  void smooth_wedges(Parameterization& out, const std::vector<int>& ws);
  void start_candidate(double t, Parameterization& out);
  std::vector<int> damp_locally(Parameterization& out, bool& certified);
  void damp_wedges(int round);
  RemapCheck attempt(double t, Parameterization& out);
  void finish(double t);
  bool halve_failing_charts(RemapCheck& c, Parameterization& cand);
  void bisect_global_blend();
  void try_extended_rounds();

  const Parameterization& param_;
  const Parameterization& full_;
  SafeRemapOptions o_;
  const int F_;
  // Built once: the overlap proof, the input's UV boundary, adjacency of wedges and faces.
  std::unique_ptr<OverlapCertificate> certificate_;
  std::vector<BoundaryEdge> boundary_;
  bool damp_crossings_ = false;  ///< Damp faces whose chart boundaries cross (the input has none).
  VertexFaces wedge_faces_;      ///< Wedge -> incident UV faces.
  WedgeRings rings_;
  std::vector<char> on_border_;  ///< Wedges on a UV boundary: never moved by the untangling.
  std::vector<int> wedge_chart_;
  long overlaps_before_ = -1;    ///< Counted on first need.
  int input_overlaps_ = -1;      ///< Counted on first need: 0 or 1.
  // The candidate being built and its scratch.
  std::vector<double> chart_t_;  ///< Per-chart blend factors.
  std::vector<Vec2> disp_, next_;
  std::vector<int> wedges_, still_bad_, to_test_;
  std::vector<char> mark_, face_mark_;
  std::vector<float> tw_;        ///< Per-wedge local factor of the last candidate.
  int rounds_;                   ///< Local damping rounds of the next attempt.
  /// The untangled full-warp candidate (t = 1, per-chart factors as they were), kept for the attempt
  /// with extended local rounds, which starts from the same untangled state (untangle() depends only
  /// on its input): on the face mask with dots at 256² one such untangling is 500 rounds.
  struct Untangled {
    std::vector<double> chart_t;
    std::vector<Vec2> uv, disp;
  };
  std::unique_ptr<Untangled> full_untangled_;
  SafeRemapResult res_;
};

SafeRemapper::SafeRemapper(const Parameterization& param, const Parameterization& full, const SafeRemapOptions& o)
    : param_(param), full_(full), o_(o), F_(static_cast<int>(param.uv_faces.size())), rounds_(o.max_local_rounds) {
  // One chart whose boundary lies on the square's sides: grid points on the sides only slide along
  // them (here: stay fixed), so the boundary maps injectively onto itself; with no flipped triangle
  // the map is then globally injective (a local homeomorphism of a disk that is injective on its
  // boundary) and the O(F log F) overlap test is unnecessary.
  if (o_.check_overlaps && single_chart_on_square(param)) o_.check_overlaps = false;
  // A flip-free candidate usually has its charts in disjoint boxes and simple boundaries: then it is
  // proven overlap-free in linear time (overlap_certificate.h) and the O(F log F) pair counts of the
  // input and the candidate are not needed (measured: most of the remap's time on atlas layouts).
  // The certificate and the input's boundary edges are built side by side (each is serial inside;
  // about 10 ms each on a 115k-face atlas).
  tbb::parallel_invoke(
      [&] {
        if (o_.check_overlaps) certificate_ = std::make_unique<OverlapCertificate>(param, o_.min_area);
      },
      [&] {
        boundary_ = uv_boundary_edges(param);
        // Charts that run into each other are damped locally too (their crossing boundary edges'
        // faces), when the input itself has no crossing boundaries.
        damp_crossings_ = o_.check_overlaps && faces_of_crossing_boundaries(param, boundary_).empty();
      });
  const int W = static_cast<int>(param.uv.size());
  wedge_faces_ = build_vertex_faces(param.uv_faces, W);
  rings_ = wedge_rings(param.uv_faces, wedge_faces_);
  on_border_.assign(W, 0);
  for (const BoundaryEdge& e : boundary_) on_border_[e.a] = on_border_[e.b] = 1;
  // Per-chart blend factors (multi-chart layouts): a chart whose faces still fail after local damping
  // is damped as a whole, so one bad chart does not cost the others their warp.
  wedge_chart_.assign(W, 0);
  for (int f = 0; f < F_; ++f)
    for (int w : param.uv_faces[f]) wedge_chart_[w] = param.face_chart.empty() ? 0 : param.face_chart[f];
  chart_t_.assign(std::max(1, param.num_charts), 1.0);
  mark_.assign(W, 0);
  face_mark_.assign(F_, 0);
}

bool SafeRemapper::fails(const Parameterization& out, int f) const {
  const double a0 = uv_signed_area(param_, f);
  if (std::abs(a0) <= o_.min_area) return false;
  return uv_signed_area(out, f) * (a0 > 0 ? 1.0 : -1.0) <= o_.min_area;
}

/// The flipped or degenerate faces of \p out (every use is order-free: the rounds compute all new
/// positions before writing any). moved == nullptr: test every face. Else \p bad holds the failing
/// faces before the wedges in *moved were changed: only those faces and the faces around the moved
/// wedges are tested (no other face's corners moved).
void SafeRemapper::failing_faces(const Parameterization& out, const std::vector<int>* moved, std::vector<int>& bad) {
  if (!moved) {
    bad.clear();
    for (int f = 0; f < F_; ++f)
      if (fails(out, f)) bad.push_back(f);
    return;
  }
  to_test_.clear();
  auto add_face = [&](int f) {
    if (!face_mark_[f]) face_mark_[f] = 1, to_test_.push_back(f);
  };
  for (int f : bad) add_face(f);
  for (int w : *moved)
    for (int q = wedge_faces_.offsets[w]; q < wedge_faces_.offsets[w + 1]; ++q) add_face(wedge_faces_.faces[q]);
  bad.clear();
  for (int f : to_test_) {
    face_mark_[f] = 0;
    if (fails(out, f)) bad.push_back(f);
  }
}

long SafeRemapper::new_overlaps(const Parameterization& out) {
  if (certificate_->certifies(out)) return 0L;
  if (overlaps_before_ < 0) overlaps_before_ = count_overlapping_triangles(param_);
  return std::max(0L, count_overlapping_triangles(out) - overlaps_before_);
}

/// The faces of the overlapping pairs of \p out, with two rings of faces around them, to be damped
/// locally (SafeRemapOptions::damp_overlaps). Only when the input has no overlapping pair at all (as
/// for damp_crossings): a layout that overlaps itself already (stacked or mirrored UVs given to
/// `adaptex reparam`) keeps the global blend.
std::vector<int> SafeRemapper::faces_of_overlaps(const Parameterization& out) {
  if (input_overlaps_ < 0) input_overlaps_ = static_cast<int>(count_overlapping_triangles(param_, 1));
  std::vector<int> faces;
  if (input_overlaps_ > 0) return faces;
  for (const std::array<int, 2>& pr : overlapping_triangle_pairs(out)) faces.push_back(pr[0]), faces.push_back(pr[1]);
  // The overlaps come from a displacement that varies too fast around a tiny face; damping only
  // the pair moved the overlap to the next faces, one ring per round (triceratops 12 charts, lines
  // 256²: 24 rounds were not enough).
  for (int ring_step = 0; ring_step < 2 && !faces.empty(); ++ring_step) {
    const size_t n = faces.size();
    for (size_t i = 0; i < n; ++i)
      for (int w : param_.uv_faces[faces[i]])
        for (int q = wedge_faces_.offsets[w]; q < wedge_faces_.offsets[w + 1]; ++q) faces.push_back(wedge_faces_.faces[q]);
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  }
  return faces;
}

/// Untangling before damping: the interior wedges of flipped or degenerate faces (with
/// untangle_rings, their 1-rings too) move to the mean of their 1-ring's *warped* positions, round
/// after round (local Laplacian smoothing in the new domain, as in Tutte's embedding). A few flips of
/// a strong warp are usually slivers that the warp turns over; smoothing them keeps the warp around
/// them, where damping them toward their old position tears their neighbours (measured: halving
/// turned 152 flips into 396).
void SafeRemapper::untangle(Parameterization& out) {
  std::vector<int> bad_faces, ws;
  std::vector<size_t> counts;  // failing faces after each round (for untangle_patience)
  const int cap = o_.untangle_patience > 0 ? std::max(o_.untangle_rounds, o_.untangle_max_rounds) : o_.untangle_rounds;
  for (int r = 0; r < cap; ++r) {
    // Only faces around the wedges moved last round can change state: test those (and the faces
    // that still failed), not all F faces, after the first round.
    if (r == 0) failing_faces(out, nullptr, bad_faces);
    else failing_faces(out, &ws, bad_faces);
    if (bad_faces.empty()) return;
    counts.push_back(bad_faces.size());
    // Past untangle_rounds: go on only while the count is below its value untangle_patience rounds ago.
    if (r >= o_.untangle_rounds && (r < o_.untangle_patience || !(counts[r] < counts[r - o_.untangle_patience]))) return;
    ws.clear();
    for (int f : bad_faces)
      for (int w : param_.uv_faces[f]) {
        if (!mark_[w]) ws.push_back(w), mark_[w] = 1;
        if (!o_.untangle_rings) continue;
        for (int q = rings_.start[w]; q < rings_.start[w + 1]; ++q)
          if (!mark_[rings_.ring[q]]) ws.push_back(rings_.ring[q]), mark_[rings_.ring[q]] = 1;
      }
    smooth_wedges(out, ws);
  }
}

/// One untangling round: the wedges \p ws (not on a border) move to the mean of their 1-ring.
void SafeRemapper::smooth_wedges(Parameterization& out, const std::vector<int>& ws) {
  const double omega = o_.untangle_over_relaxation;
  if (o_.untangle_in_place) {
    // Gauss–Seidel: each wedge reads its ring's positions as already updated this round.
    for (const int w : ws) {
      mark_[w] = 0;
      const int deg = rings_.degree(w);
      if (on_border_[w] || deg == 0) continue;
      Vec2 sum = Vec2::Zero();
      for (int q = rings_.start[w]; q < rings_.start[w + 1]; ++q) sum += out.uv[rings_.ring[q]];
      if (omega == 1.0) out.uv[w] = sum / deg;
      else out.uv[w] += omega * (Vec2(sum / deg) - out.uv[w]);
      disp_[w] = out.uv[w] - param_.uv[w];
    }
    return;
  }
  next_.resize(ws.size());  // Jacobi: every wedge reads the previous round's positions
  for (size_t i = 0; i < ws.size(); ++i) {
    const int w = ws[i];
    mark_[w] = 0;
    Vec2 sum = Vec2::Zero();
    for (int q = rings_.start[w]; q < rings_.start[w + 1]; ++q) sum += out.uv[rings_.ring[q]];
    const int deg = rings_.degree(w);
    next_[i] = (on_border_[w] || deg == 0) ? out.uv[w] : Vec2(sum / deg);
  }
  for (size_t i = 0; i < ws.size(); ++i) {
    out.uv[ws[i]] = next_[i];
    disp_[ws[i]] = next_[i] - param_.uv[ws[i]];
  }
}

/// The untangled candidate at global blend \p t (from the cache for the full warp).
void SafeRemapper::start_candidate(double t, Parameterization& out) {
  out = param_;
  if (t == 1.0 && full_untangled_ && full_untangled_->chart_t == chart_t_) {
    out.uv = full_untangled_->uv;
    disp_ = full_untangled_->disp;
    return;
  }
  disp_.resize(param_.uv.size());
  tbb::parallel_for(size_t(0), out.uv.size(), [&](size_t w) {
    disp_[w] = t * chart_t_[std::min<size_t>(wedge_chart_[w], chart_t_.size() - 1)] * (full_.uv[w] - param_.uv[w]);
    out.uv[w] = param_.uv[w] + disp_[w];
  });
  untangle(out);
  if (t == 1.0 && o_.extended_local_rounds > o_.max_local_rounds)  // its only reader
    full_untangled_ = std::make_unique<Untangled>(Untangled{chart_t_, out.uv, disp_});
}

/// Local damping of \p out: the wedges of faces that flip, degenerate (or, multi-chart, whose boundary
/// edges cross another chart's, or that overlap) are damped (damp_wedges()), round after round, up to
/// rounds_. Returns the faces that still fail; \p certified: the overlap certificate proved \p out.
std::vector<int> SafeRemapper::damp_locally(Parameterization& out, bool& certified) {
  std::vector<int> flipping, bad;
  certified = false;
  for (int round = 0; round <= rounds_; ++round) {
    if (round == 0) failing_faces(out, nullptr, flipping);
    else failing_faces(out, &wedges_, flipping);
    bad = flipping;
    if (bad.empty() && damp_crossings_) bad = faces_of_crossing_boundaries(out, boundary_);
    // The final check would prove this layout overlap-free again: remember the proof.
    certified = false;
    if (bad.empty() && o_.check_overlaps && o_.damp_overlaps) {
      certified = certificate_->certifies(out);
      if (!certified) bad = faces_of_overlaps(out);
    }
    if (bad.empty() || round == rounds_) break;
    wedges_.clear();
    for (int f : bad)
      for (int w : param_.uv_faces[f]) wedges_.push_back(w);
    std::sort(wedges_.begin(), wedges_.end());
    wedges_.erase(std::unique(wedges_.begin(), wedges_.end()), wedges_.end());
    damp_wedges(round);
    for (const int w : wedges_) out.uv[w] = param_.uv[w] + disp_[w];
  }
  return bad;
}

/// The displacement of every wedge in wedges_ is replaced by half the mean displacement of its
/// 1-ring (smooth_local_damping: the damped patch does not tear its border) or halved.
void SafeRemapper::damp_wedges(int round) {
  next_.resize(wedges_.size());
  for (size_t i = 0; i < wedges_.size(); ++i) {
    const int w = wedges_[i];
    if (o_.smooth_local_damping) {
      Vec2 sum = disp_[w];
      for (int q = rings_.start[w]; q < rings_.start[w + 1]; ++q) sum += disp_[rings_.ring[q]];
      next_[i] = 0.5 * sum / double(1 + rings_.degree(w));
    } else {
      // Halving forever cannot settle a face whose input area is barely above min_area (its area
      // moves by |edge|·|disp|, so 20 halvings left 1–4 such faces flipped on triceratops' 12
      // charts): after snap_round rounds a failing face's wedges go back to their input position,
      // where the face has its input area.
      next_[i] = o_.snap_round >= 0 && round >= o_.snap_round ? Vec2::Zero() : Vec2(0.5 * disp_[w]);
    }
  }
  for (size_t i = 0; i < wedges_.size(); ++i) disp_[wedges_[i]] = next_[i];
}

/// Builds the candidate at global blend \p t into \p out, damps it locally and checks it.
RemapCheck SafeRemapper::attempt(double t, Parameterization& out) {
  ++res_.checks;
  start_candidate(t, out);
  bool certified = false;
  still_bad_ = damp_locally(out, certified);
  tw_.assign(param_.uv.size(), 1.0f);
  for (size_t w = 0; w < param_.uv.size(); ++w) {
    const double full_len = (full_.uv[w] - param_.uv[w]).norm();
    if (full_len > 0) tw_[w] = static_cast<float>(std::min(1.0, disp_[w].norm() / (t * full_len + 1e-300)));
  }
  RemapCheck c;
  const FlipCount fc = count_flips(param_, out, o_.min_area);
  c.flipped = fc.flipped;
  c.degenerate = fc.degenerate;
  if (o_.check_overlaps && c.flipped == 0 && c.degenerate == 0) c.overlaps = certified ? 0 : new_overlaps(out);
  return c;
}

/// Fills the result's damping figures for global blend \p t and the last local factors.
void SafeRemapper::finish(double t) {
  res_.damping = t;
  res_.locally_damped = 0;
  double sum = 0;
  for (float x : tw_) {
    if (x < 1.0f) ++res_.locally_damped;
    sum += x;
  }
  res_.mean_damping = tw_.empty() ? t : t * sum / tw_.size();
}

/// Multi-chart layouts: halves the blend of every chart with a face that still fails, up to
/// chart_halvings times, while the full-warp candidate \p cand fails.
bool SafeRemapper::halve_failing_charts(RemapCheck& c, Parameterization& cand) {
  for (int k = 0; k < o_.chart_halvings && !c.ok() && !still_bad_.empty() && param_.num_charts > 1; ++k) {
    std::vector<char> hit(chart_t_.size(), 0);
    for (int f : still_bad_) hit[std::min<size_t>(param_.face_chart[f], chart_t_.size() - 1)] = 1;
    for (size_t ch = 0; ch < chart_t_.size(); ++ch)
      if (hit[ch]) chart_t_[ch] *= 0.5;
    c = attempt(1.0, cand);
  }
  return c.ok();
}

/// Bisection of the global blend t: the largest t (of bisection_steps halvings) whose candidate is
/// ok; t = 0 (the input) if none is.
void SafeRemapper::bisect_global_blend() {
  double lo = 0.0, hi = 1.0;
  res_.param = param_;
  res_.damping = 0.0;
  res_.mean_damping = 0.0;
  std::vector<float> best_tw(param_.uv.size(), 0.0f);
  Parameterization cand;
  for (int s = 0; s < o_.bisection_steps; ++s) {
    const double mid = 0.5 * (lo + hi);
    if (attempt(mid, cand).ok()) {
      lo = mid;
      res_.param = std::move(cand);
      best_tw = tw_;
    } else {
      hi = mid;
    }
  }
  tw_ = best_tw;
  finish(lo);
  res_.check = RemapCheck{};  // the returned layout is t = lo, checked ok (or the input itself)
}

/// The global blend damps every face; many more local rounds may keep more of the warp where the
/// failing faces are few and spread (measured: triceratops lines 256², 65 charts: mean kept 0.03
/// globally, 0.16 locally; spot: 0.46 globally, 0.20 locally). Keeps whichever keeps more.
void SafeRemapper::try_extended_rounds() {
  if (o_.extended_local_rounds <= o_.max_local_rounds) return;
  const SafeRemapResult global = res_;
  rounds_ = o_.extended_local_rounds;
  Parameterization cand;
  const RemapCheck c = attempt(1.0, cand);
  if (c.ok()) {
    res_.param = std::move(cand);
    finish(1.0);
    if (res_.mean_damping > global.mean_damping) {
      res_.check = c;
      return;
    }
  }
  const int checks = res_.checks;
  res_ = global;
  res_.checks = checks;
}

SafeRemapResult SafeRemapper::run() {
  Parameterization cand;
  RemapCheck c = attempt(1.0, cand);
  if (halve_failing_charts(c, cand)) {
    res_.param = std::move(cand);
    res_.check = c;
    finish(1.0);
    return std::move(res_);
  }
  bisect_global_blend();
  try_extended_rounds();
  return std::move(res_);
}

}  // namespace

SafeRemapResult safe_remap_layout(const Parameterization& param, const Parameterization& full,
                                  const SafeRemapOptions& o) {
  if (full.uv.size() != param.uv.size() || full.uv_faces.size() != param.uv_faces.size())
    throw InvalidInputError("safe_remap_layout: the warped layout has " + std::to_string(full.uv.size()) +
                            " wedges and " + std::to_string(full.uv_faces.size()) + " faces, the input " +
                            std::to_string(param.uv.size()) + " and " + std::to_string(param.uv_faces.size()));
  if (!(o.untangle_over_relaxation > 0 && o.untangle_over_relaxation < 2))
    throw InvalidInputError("safe_remap_layout: untangle_over_relaxation must be in (0, 2)");
  return SafeRemapper(param, full, o).run();
}

}  // namespace adaptex
