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

SafeRemapResult safe_remap_layout(const Parameterization& param, const Parameterization& full,
                                  const SafeRemapOptions& o_in) {
  if (full.uv.size() != param.uv.size() || full.uv_faces.size() != param.uv_faces.size())
    throw InvalidInputError("safe_remap_layout: the warped layout has " + std::to_string(full.uv.size()) +
                            " wedges and " + std::to_string(full.uv_faces.size()) + " faces, the input " +
                            std::to_string(param.uv.size()) + " and " + std::to_string(param.uv_faces.size()));
  if (!(o_in.untangle_over_relaxation > 0 && o_in.untangle_over_relaxation < 2))
    throw InvalidInputError("safe_remap_layout: untangle_over_relaxation must be in (0, 2)");
  SafeRemapOptions o = o_in;
  // One chart whose boundary lies on the square's sides: grid points on the sides only slide along
  // them (here: stay fixed), so the boundary maps injectively onto itself; with no flipped triangle
  // the map is then globally injective (a local homeomorphism of a disk that is injective on its
  // boundary) and the O(F log F) overlap test is unnecessary.
  if (o.check_overlaps && single_chart_on_square(param)) o.check_overlaps = false;
  // A flip-free candidate usually has its charts in disjoint boxes and simple boundaries: then it is
  // proven overlap-free in linear time (overlap_certificate.h) and the O(F log F) pair counts of the
  // input and the candidate are not needed (measured: most of the remap's time on atlas layouts).
  // The certificate and the input's boundary edges are built side by side (each is serial inside;
  // about 10 ms each on a 115k-face atlas).
  std::unique_ptr<OverlapCertificate> certificate;
  std::vector<BoundaryEdge> boundary;
  bool damp_crossings = false;
  tbb::parallel_invoke(
      [&] {
        if (o.check_overlaps) certificate = std::make_unique<OverlapCertificate>(param, o.min_area);
      },
      [&] {
        boundary = uv_boundary_edges(param);
        // Charts that run into each other are damped locally too (their crossing boundary edges'
        // faces), when the input itself has no crossing boundaries.
        damp_crossings = o.check_overlaps && faces_of_crossing_boundaries(param, boundary).empty();
      });
  long overlaps_before = -1;  // counted on first need
  auto new_overlaps = [&](const Parameterization& out) {
    if (certificate->certifies(out)) return 0L;
    if (overlaps_before < 0) overlaps_before = count_overlapping_triangles(param);
    return std::max(0L, count_overlapping_triangles(out) - overlaps_before);
  };
  const int F = static_cast<int>(param.uv_faces.size());
  SafeRemapResult res;
  std::vector<float> tw;
  // Candidate at global blend t: uv = old + t * tw_w * (warped - old). Faces that flip or degenerate
  // get their wedges' local factor tw halved, round after round (local damping: a few bad triangles
  // do not cost the whole warp); after max_local_rounds the global bisection on t takes over.
  // Wedge 1-rings (wedges sharing a UV face), for smoothing the displacement where faces fail.
  std::vector<int> ring_start(param.uv.size() + 1, 0), ring;
  for (const Face& f : param.uv_faces)
    for (int k = 0; k < 3; ++k) ring_start[f[k] + 1] += 2;
  for (size_t w = 0; w < param.uv.size(); ++w) ring_start[w + 1] += ring_start[w];
  ring.resize(ring_start.back());
  {
    std::vector<int> fill(ring_start.begin(), ring_start.end() - 1);
    for (const Face& f : param.uv_faces)
      for (int k = 0; k < 3; ++k) {
        ring[fill[f[k]]++] = f[(k + 1) % 3];
        ring[fill[f[k]]++] = f[(k + 2) % 3];
      }
  }
  std::vector<Vec2> disp, next;
  // Candidate at global blend t: uv = old + disp, disp = t · (warped − old) to start with. The wedges of
  // faces that flip, degenerate (or, multi-chart, whose boundary edges cross another chart's) get their
  // displacement replaced by half the mean displacement of their 1-ring, round after round: local
  // damping that also smooths, so the damped patch does not tear its border (plain halving left
  // steep displacement jumps at the patch border that flipped the next faces). After max_local_rounds
  // the global bisection on t takes over.
  // Per-chart blend factors (multi-chart layouts): a chart whose faces still fail after local damping
  // is damped as a whole, so one bad chart does not cost the others their warp.
  std::vector<int> wedge_chart(param.uv.size(), 0);
  for (int f = 0; f < F; ++f)
    for (int w : param.uv_faces[f]) wedge_chart[w] = param.face_chart.empty() ? 0 : param.face_chart[f];
  std::vector<double> chart_t(std::max(1, param.num_charts), 1.0);
  std::vector<int> still_bad;
  int rounds = o.max_local_rounds;
  // Wedges on a UV boundary (chart borders) are never moved by the untangling.
  std::vector<char> on_border(param.uv.size(), 0);
  for (const BoundaryEdge& e : boundary) on_border[e.a] = on_border[e.b] = 1;
  std::vector<char> mark(param.uv.size(), 0);
  // Wedge -> incident UV faces (CSR), for re-testing only the faces around moved wedges.
  std::vector<int> face_start(param.uv.size() + 1, 0), wedge_faces;
  for (const Face& f : param.uv_faces)
    for (int w : f) ++face_start[w + 1];
  for (size_t w = 0; w < param.uv.size(); ++w) face_start[w + 1] += face_start[w];
  wedge_faces.resize(face_start.back());
  {
    std::vector<int> fill(face_start.begin(), face_start.end() - 1);
    for (int f = 0; f < F; ++f)
      for (int w : param.uv_faces[f]) wedge_faces[fill[w]++] = f;
  }
  // The faces of the overlapping pairs of a candidate, with two rings of faces around them, to be
  // damped locally (SafeRemapOptions::damp_overlaps). Only when the input has no overlapping pair at
  // all (as for damp_crossings): a layout that overlaps itself already (stacked or mirrored UVs given
  // to `adaptex reparam`) keeps the global blend.
  int input_overlaps = -1;  // counted on first need: 0 or 1
  auto faces_of_overlaps = [&](const Parameterization& out) {
    if (input_overlaps < 0) input_overlaps = static_cast<int>(count_overlapping_triangles(param, 1));
    std::vector<int> faces;
    if (input_overlaps > 0) return faces;
    for (const std::array<int, 2>& pr : overlapping_triangle_pairs(out)) faces.push_back(pr[0]), faces.push_back(pr[1]);
    // The overlaps come from a displacement that varies too fast around a tiny face; damping only
    // the pair moved the overlap to the next faces, one ring per round (triceratops 12 charts, lines
    // 256²: 24 rounds were not enough).
    for (int ring_step = 0; ring_step < 2 && !faces.empty(); ++ring_step) {
      const size_t n = faces.size();
      for (size_t i = 0; i < n; ++i)
        for (int w : param.uv_faces[faces[i]])
          for (int q = face_start[w]; q < face_start[w + 1]; ++q) faces.push_back(wedge_faces[q]);
      std::sort(faces.begin(), faces.end());
      faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    }
    return faces;
  };
  auto fails = [&](const Parameterization& out, int f) {
    const double a0 = uv_signed_area(param, f);
    if (std::abs(a0) <= o.min_area) return false;
    return uv_signed_area(out, f) * (a0 > 0 ? 1.0 : -1.0) <= o.min_area;
  };
  // The flipped or degenerate faces of \p out (every use is order-free: the rounds below compute all
  // new positions before writing any). moved == nullptr: test every face. Else
  // \p bad holds the failing faces before the wedges in *moved were changed: only those faces and
  // the faces around the moved wedges are tested (no other face's corners moved).
  std::vector<int> to_test;
  std::vector<char> face_mark(F, 0);
  auto failing_faces = [&](const Parameterization& out, const std::vector<int>* moved, std::vector<int>& bad) {
    if (!moved) {
      bad.clear();
      for (int f = 0; f < F; ++f)
        if (fails(out, f)) bad.push_back(f);
      return;
    }
    to_test.clear();
    auto add_face = [&](int f) {
      if (!face_mark[f]) face_mark[f] = 1, to_test.push_back(f);
    };
    for (int f : bad) add_face(f);
    for (int w : *moved)
      for (int q = face_start[w]; q < face_start[w + 1]; ++q) add_face(wedge_faces[q]);
    bad.clear();
    for (int f : to_test) {
      face_mark[f] = 0;
      if (fails(out, f)) bad.push_back(f);
    }
  };
  // Untangling before damping: the interior wedges of flipped or degenerate faces (with
  // untangle_rings, their 1-rings too) move to the mean of their 1-ring's *warped* positions, round
  // after round (local Laplacian
  // smoothing in the new domain, as in Tutte's embedding). A few flips of a strong warp are usually
  // slivers that the warp turns over; smoothing them keeps the warp around them, where damping them
  // toward their old position tears their neighbours (measured: halving turned 152 flips into 396).
  const double omega = o.untangle_over_relaxation;
  auto untangle = [&](Parameterization& out, std::vector<Vec2>& d) {
    std::vector<int> bad_faces, ws;
    std::vector<Vec2> pos;
    std::vector<size_t> counts;  // failing faces after each round (for untangle_patience)
    const int cap = o.untangle_patience > 0 ? std::max(o.untangle_rounds, o.untangle_max_rounds) : o.untangle_rounds;
    for (int r = 0; r < cap; ++r) {
      // Only faces around the wedges moved last round can change state: test those (and the faces
      // that still failed), not all F faces, after the first round.
      if (r == 0) failing_faces(out, nullptr, bad_faces);
      else failing_faces(out, &ws, bad_faces);
      if (bad_faces.empty()) return;
      counts.push_back(bad_faces.size());
      // Past untangle_rounds: go on only while the count is below its value untangle_patience rounds ago.
      if (r >= o.untangle_rounds && (r < o.untangle_patience || !(counts[r] < counts[r - o.untangle_patience]))) return;
      ws.clear();
      for (int f : bad_faces)
        for (int w : param.uv_faces[f]) {
          if (!mark[w]) ws.push_back(w), mark[w] = 1;
          if (!o.untangle_rings) continue;
          for (int q = ring_start[w]; q < ring_start[w + 1]; ++q)
            if (!mark[ring[q]]) ws.push_back(ring[q]), mark[ring[q]] = 1;
        }
      if (o.untangle_in_place) {
        // Gauss–Seidel: each wedge reads its ring's positions as already updated this round.
        for (const int w : ws) {
          mark[w] = 0;
          const int deg = ring_start[w + 1] - ring_start[w];
          if (on_border[w] || deg == 0) continue;
          Vec2 sum = Vec2::Zero();
          for (int q = ring_start[w]; q < ring_start[w + 1]; ++q) sum += out.uv[ring[q]];
          if (omega == 1.0) out.uv[w] = sum / deg;
          else out.uv[w] += omega * (Vec2(sum / deg) - out.uv[w]);
          d[w] = out.uv[w] - param.uv[w];
        }
        continue;
      }
      pos.resize(ws.size());
      for (size_t i = 0; i < ws.size(); ++i) {
        const int w = ws[i];
        mark[w] = 0;
        Vec2 sum = Vec2::Zero();
        for (int q = ring_start[w]; q < ring_start[w + 1]; ++q) sum += out.uv[ring[q]];
        const int deg = ring_start[w + 1] - ring_start[w];
        pos[i] = (on_border[w] || deg == 0) ? out.uv[w] : Vec2(sum / deg);
      }
      for (size_t i = 0; i < ws.size(); ++i) {
        out.uv[ws[i]] = pos[i];
        d[ws[i]] = pos[i] - param.uv[ws[i]];
      }
    }
  };
  // The untangled full-warp candidate (t = 1, per-chart factors as they were), kept for the attempt
  // with extended local rounds, which starts from the same untangled state (untangle() depends only
  // on its input): on the face mask with dots at 256² one such untangling is 500 rounds.
  struct Untangled {
    std::vector<double> chart_t;
    std::vector<Vec2> uv, disp;
  };
  std::unique_ptr<Untangled> full_untangled;
  auto attempt = [&](double t, Parameterization& out) {
    ++res.checks;
    out = param;
    RemapCheck c;
    std::vector<int> bad, wedges;
    if (t == 1.0 && full_untangled && full_untangled->chart_t == chart_t) {
      out.uv = full_untangled->uv;
      disp = full_untangled->disp;
    } else {
      disp.resize(param.uv.size());
      tbb::parallel_for(size_t(0), out.uv.size(), [&](size_t w) {
        disp[w] = t * chart_t[std::min<size_t>(wedge_chart[w], chart_t.size() - 1)] * (full.uv[w] - param.uv[w]);
        out.uv[w] = param.uv[w] + disp[w];
      });
      untangle(out, disp);
      if (t == 1.0 && o.extended_local_rounds > o.max_local_rounds)  // its only reader
        full_untangled = std::make_unique<Untangled>(Untangled{chart_t, out.uv, disp});
    }
    std::vector<int> flipping;
    bool certified = false;  // the overlap certificate proved the current `out` (last round)
    for (int round = 0; round <= rounds; ++round) {
      if (round == 0) failing_faces(out, nullptr, flipping);
      else failing_faces(out, &wedges, flipping);
      bad = flipping;
      if (bad.empty() && damp_crossings) bad = faces_of_crossing_boundaries(out, boundary);
      // The final check below would prove this layout overlap-free again: remember the proof.
      certified = false;
      if (bad.empty() && o.check_overlaps && o.damp_overlaps) {
        certified = certificate->certifies(out);
        if (!certified) bad = faces_of_overlaps(out);
      }
      still_bad = bad;
      if (bad.empty() || round == rounds) break;
      wedges.clear();
      for (int f : bad)
        for (int w : param.uv_faces[f]) wedges.push_back(w);
      std::sort(wedges.begin(), wedges.end());
      wedges.erase(std::unique(wedges.begin(), wedges.end()), wedges.end());
      next.resize(wedges.size());
      for (size_t i = 0; i < wedges.size(); ++i) {
        const int w = wedges[i];
        if (o.smooth_local_damping) {
          Vec2 sum = disp[w];
          for (int q = ring_start[w]; q < ring_start[w + 1]; ++q) sum += disp[ring[q]];
          next[i] = 0.5 * sum / double(1 + ring_start[w + 1] - ring_start[w]);
        } else {
          // Halving forever cannot settle a face whose input area is barely above min_area (its
          // area moves by |edge|·|disp|, so 20 halvings left 1–4 such faces flipped on
          // triceratops' 12 charts): after snap_round rounds a failing face's wedges go back to
          // their input position, where the face has its input area.
          next[i] = o.snap_round >= 0 && round >= o.snap_round ? Vec2::Zero() : Vec2(0.5 * disp[w]);
        }
      }
      for (size_t i = 0; i < wedges.size(); ++i) {
        disp[wedges[i]] = next[i];
        out.uv[wedges[i]] = param.uv[wedges[i]] + next[i];
      }
    }
    tw.assign(param.uv.size(), 1.0f);
    for (size_t w = 0; w < param.uv.size(); ++w) {
      const double full_len = (full.uv[w] - param.uv[w]).norm();
      if (full_len > 0) tw[w] = static_cast<float>(std::min(1.0, disp[w].norm() / (t * full_len + 1e-300)));
    }
    const FlipCount fc = count_flips(param, out, o.min_area);
    c.flipped = fc.flipped;
    c.degenerate = fc.degenerate;
    if (o.check_overlaps && c.flipped == 0 && c.degenerate == 0) c.overlaps = certified ? 0 : new_overlaps(out);
    return c;
  };
  auto finish = [&](double t) {
    res.damping = t;
    res.locally_damped = 0;
    double sum = 0;
    for (float x : tw) {
      if (x < 1.0f) ++res.locally_damped;
      sum += x;
    }
    res.mean_damping = tw.empty() ? t : t * sum / tw.size();
  };
  Parameterization cand;
  RemapCheck c = attempt(1.0, cand);
  for (int k = 0; k < o.chart_halvings && !c.ok() && !still_bad.empty() && param.num_charts > 1; ++k) {
    std::vector<char> hit(chart_t.size(), 0);
    for (int f : still_bad) hit[std::min<size_t>(param.face_chart[f], chart_t.size() - 1)] = 1;
    for (size_t ch = 0; ch < chart_t.size(); ++ch)
      if (hit[ch]) chart_t[ch] *= 0.5;
    c = attempt(1.0, cand);
  }
  if (c.ok()) {
    res.param = std::move(cand);
    res.check = c;
    finish(1.0);
    return res;
  }
  double lo = 0.0, hi = 1.0;
  res.param = param;
  res.damping = 0.0;
  res.mean_damping = 0.0;
  std::vector<float> best_tw(param.uv.size(), 0.0f);
  for (int s = 0; s < o.bisection_steps; ++s) {
    const double mid = 0.5 * (lo + hi);
    c = attempt(mid, cand);
    if (c.ok()) {
      lo = mid;
      res.param = std::move(cand);
      best_tw = tw;
    } else {
      hi = mid;
    }
  }
  tw = best_tw;
  finish(lo);
  res.check = RemapCheck{};  // the returned layout is t = lo, checked ok (or the input itself)
  // The global blend damps every face; many more local rounds may keep more of the warp where the
  // failing faces are few and spread (measured: triceratops lines 256², 65 charts: mean kept 0.03
  // globally, 0.16 locally; spot: 0.46 globally, 0.20 locally). Keep whichever keeps more.
  if (o.extended_local_rounds > o.max_local_rounds) {
    const SafeRemapResult global = res;
    rounds = o.extended_local_rounds;
    c = attempt(1.0, cand);
    if (c.ok()) {
      res.param = std::move(cand);
      finish(1.0);
      if (res.mean_damping > global.mean_damping) {
        res.check = c;
        return res;
      }
    }
    const int checks = res.checks;
    res = global;
    res.checks = checks;
  }
  return res;
}

}  // namespace adaptex
