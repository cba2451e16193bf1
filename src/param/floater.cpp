/// \file floater.cpp
/// Floater shape-preserving / mean-value weights, square boundary, Tutte system solver (§2.2).
#include "adaptex/param/floater.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/predicates.h"
#include "amg.h"

#ifdef ADAPTEX_HAVE_UMFPACK
#include <Eigen/UmfPackSupport>
#endif
#ifdef ADAPTEX_HAVE_KLU
#include <klu.h>
#endif

namespace adaptex {

namespace {

using SpMat = Eigen::SparseMatrix<double>;
using RowMat = Eigen::SparseMatrix<double, Eigen::RowMajor>;
constexpr int kAutoDirectLimit = 20000;  // unknowns; see docs/parameterization.md

/// For every vertex, the pairs (b, c) of its incident faces (v, b, c) in face order, CSR.
struct CornerPairs {
  std::vector<int> offsets;
  std::vector<std::array<int, 2>> pairs;
};

CornerPairs corner_pairs(const TriMesh& m) {
  CornerPairs cp;
  const int nv = m.num_vertices();
  cp.offsets.assign(nv + 1, 0);
  for (const Face& f : m.faces)
    for (int k = 0; k < 3; ++k) ++cp.offsets[f[k] + 1];
  for (int v = 0; v < nv; ++v) cp.offsets[v + 1] += cp.offsets[v];
  cp.pairs.resize(cp.offsets.back());
  std::vector<int> fill(cp.offsets.begin(), cp.offsets.end() - 1);
  for (const Face& f : m.faces)
    for (int k = 0; k < 3; ++k) cp.pairs[fill[f[k]]++] = {f[(k + 1) % 3], f[(k + 2) % 3]};
  return cp;
}

/// The closed one-ring of interior vertex v in face order (w_{i+1} follows w_i around v).
/// Returns false if the fan is not a single closed cycle.
bool ordered_ring(const CornerPairs& cp, int v, std::vector<int>& ring) {
  const int b = cp.offsets[v], e = cp.offsets[v + 1];
  const int d = e - b;
  ring.clear();
  if (d < 3) return false;
  int cur = cp.pairs[b][0];
  for (int step = 0; step < d; ++step) {
    ring.push_back(cur);
    int nxt = -1;
    for (int k = b; k < e; ++k)
      if (cp.pairs[k][0] == cur) {
        if (nxt != -1) return false;
        nxt = cp.pairs[k][1];
      }
    if (nxt == -1) return false;
    cur = nxt;
  }
  return cur == ring.front();
}

/// Floater 2003 mean-value row. Each corner angle's tan(α/2) and each edge length is computed once.
/// Regularized for degenerate rings (zero-length edges of duplicate points, zero-area slivers): edge
/// lengths are floored at 1e-3 of the ring's mean, tan(α/2) capped at 1e6 (α within 1e-4° of π; a
/// cap of 1e3 already changed the weights of triceratops.off, which has near-flat corners), and
/// every weight floored at 1e-6 of the row's largest, so the row stays finite, strictly positive and
/// the system well conditioned enough for the iterative solver. Never active on ordinary meshes.
/// False only when no length is positive.
bool mean_value_row(const TriMesh& m, int v, const std::vector<int>& ring, double* out,
                    std::vector<double>& len, std::vector<double>& th) {
  const int d = static_cast<int>(ring.size());
  const Vec3& p = m.positions[v];
  len.resize(d);
  th.resize(d);
  double mean_len = 0;
  for (int i = 0; i < d; ++i) mean_len += len[i] = (m.positions[ring[i]] - p).norm();
  mean_len /= d;
  if (!(mean_len > 0) || !std::isfinite(mean_len)) return false;
  for (int i = 0; i < d; ++i) {  // th[i] = tan(α_i / 2), α_i the angle between e_i and e_{i+1}
    const int j = (i + 1) % d;
    const Vec3 a = m.positions[ring[i]] - p, b = m.positions[ring[j]] - p;
    const double den = len[i] * len[j] + a.dot(b);
    th[i] = den > 0 ? std::min(a.cross(b).norm() / den, 1e6) : 1e6;
    if (!std::isfinite(th[i])) th[i] = 1e6;
  }
  double sum = 0, mx = 0;
  for (int i = 0; i < d; ++i) {
    out[i] = (th[(i + d - 1) % d] + th[i]) / std::max(len[i], 1e-3 * mean_len);
    mx = std::max(mx, out[i]);
  }
  if (!(mx > 0) || !std::isfinite(mx)) return false;
  for (int i = 0; i < d; ++i) sum += out[i] = std::max(out[i], 1e-6 * mx);
  for (int i = 0; i < d; ++i) out[i] /= sum;
  return true;
}

/// Floater 1997 shape-preserving row. False when the polar map has an angle >= π or a coordinate
/// would not be strictly positive (the caller falls back to mean-value weights).
bool shape_preserving_row(const TriMesh& m, int v, const std::vector<int>& ring, double* out,
                          std::vector<Vec2>& polar, std::vector<double>& phi) {
  const int d = static_cast<int>(ring.size());
  const Vec3& p = m.positions[v];
  phi.assign(d + 1, 0.0);
  for (int i = 0; i < d; ++i) {
    const Vec3 a = m.positions[ring[i]] - p, b = m.positions[ring[(i + 1) % d]] - p;
    phi[i + 1] = phi[i] + std::atan2(a.cross(b).norm(), a.dot(b));
  }
  const double total = phi[d];
  if (!(total > 0)) return false;
  const double scale = 2 * std::numbers::pi / total;
  polar.resize(d);
  for (int i = 0; i < d; ++i) {
    const double ang = phi[i] * scale;
    if ((phi[i + 1] - phi[i]) * scale >= std::numbers::pi) return false;
    const double r = (m.positions[ring[i]] - p).norm();
    polar[i] = Vec2(r * std::cos(ang), r * std::sin(ang));
  }
  std::fill(out, out + d, 0.0);
  if (d == 3) {
    const double area = cross2d(polar[1] - polar[0], polar[2] - polar[0]);
    for (int i = 0; i < 3; ++i)
      out[i] = cross2d(polar[(i + 1) % 3], polar[(i + 2) % 3]) / area;  // area(O, p_{i+1}, p_{i+2})
  } else {
    for (int i = 0; i < d; ++i) {
      // Find r with the origin in triangle (p_i, p_r, p_{r+1}): the ray from p_i through O leaves the
      // polygon between p_r and p_{r+1}, i.e. cross(p_r, -p_i) >= 0 > cross(p_{r+1}, -p_i) ... scan.
      const Vec2 dir = -polar[i];
      int r = -1;
      for (int k = 1; k < d - 1; ++k) {
        const int a = (i + k) % d, b = (i + k + 1) % d;
        if (cross2d(polar[a], dir) >= 0 && cross2d(dir, polar[b]) > 0) {
          r = a;
          break;
        }
      }
      if (r < 0) return false;
      const int r1 = (r + 1) % d;
      const Vec2 &A = polar[i], &B = polar[r], &C = polar[r1];
      const double area = cross2d(B - A, C - A);
      if (!(area > 0)) return false;
      const double la = cross2d(B, C) / area;  // area(O,B,C)/area(A,B,C)
      const double lb = cross2d(C, A) / area;
      const double lc = cross2d(A, B) / area;
      if (la < 0 || lb < 0 || lc < 0) return false;
      out[i] += la;
      out[r] += lb;
      out[r1] += lc;
    }
    for (int i = 0; i < d; ++i) out[i] /= d;
  }
  double sum = 0;
  for (int i = 0; i < d; ++i) {
    if (!(out[i] > 0)) return false;
    sum += out[i];
  }
  for (int i = 0; i < d; ++i) out[i] /= sum;
  return true;
}

}  // namespace

namespace {

/// True when row \p p of \p pattern is the row of sub-disk vertex v with ring \p ring: the same
/// length and, at every position, the same vertex wherever the ring vertex is interior in the
/// sub-disk (at least one such position, which fixes the ring's rotation).
bool row_lines_up(const ConvexWeights& pattern, int p, const std::vector<int>& ring,
                  const std::vector<char>& is_boundary, const std::vector<int>& to_pattern) {
  if (p < 0 || p >= pattern.num_vertices()) return false;
  const int b = pattern.offsets[p];
  if (pattern.offsets[p + 1] - b != static_cast<int>(ring.size())) return false;
  bool any = false;
  for (size_t i = 0; i < ring.size(); ++i) {
    if (is_boundary[ring[i]]) continue;
    if (to_pattern[ring[i]] != pattern.neighbors[b + static_cast<int>(i)]) return false;
    any = true;
  }
  return any;
}

/// compute_embedding_weights(); with \p pattern, rows that line up with it are copied.
ConvexWeights embedding_weights(const TriMesh& disk, const std::vector<char>& is_boundary,
                                EmbeddingWeights weights, const ConvexWeights* pattern,
                                const std::vector<int>* to_pattern) {
  const int nv = disk.num_vertices();
  const CornerPairs cp = corner_pairs(disk);
  ConvexWeights w;
  w.offsets.assign(nv + 1, 0);
  for (int v = 0; v < nv; ++v)
    w.offsets[v + 1] = w.offsets[v] + (is_boundary[v] ? 0 : cp.offsets[v + 1] - cp.offsets[v]);
  w.neighbors.assign(w.offsets.back(), -1);
  w.values.assign(w.offsets.back(), 0.0);
  std::atomic<int> bad_vertex{-1};
  tbb::parallel_for(tbb::blocked_range<int>(0, nv, 2048), [&](const tbb::blocked_range<int>& r) {
    std::vector<int> ring;
    std::vector<Vec2> polar;
    std::vector<double> phi, len, th;
    for (int v = r.begin(); v != r.end(); ++v) {
      if (is_boundary[v]) continue;
      if (cp.offsets[v + 1] == cp.offsets[v]) continue;  // isolated vertex: empty row
      if (!ordered_ring(cp, v, ring)) {
        bad_vertex = v;
        continue;
      }
      double* out = w.values.data() + w.offsets[v];
      std::copy(ring.begin(), ring.end(), w.neighbors.begin() + w.offsets[v]);
      if (pattern && row_lines_up(*pattern, (*to_pattern)[v], ring, is_boundary, *to_pattern)) {
        const int b = pattern->offsets[(*to_pattern)[v]];
        std::copy(pattern->values.begin() + b, pattern->values.begin() + b + ring.size(), out);
        continue;
      }
      bool ok = weights == EmbeddingWeights::ShapePreserving &&
                shape_preserving_row(disk, v, ring, out, polar, phi);
      if (!ok) ok = mean_value_row(disk, v, ring, out, len, th);
      if (!ok) {  // only for degenerate geometry: uniform (Tutte) weights
        for (size_t i = 0; i < ring.size(); ++i) out[i] = 1.0 / static_cast<double>(ring.size());
      }
    }
  });
  if (bad_vertex >= 0)
    throw TopologyError("interior vertex " + std::to_string(bad_vertex.load()) +
                        " has an open or non-manifold one-ring; the mesh is not a disk");
  return w;
}

}  // namespace

ConvexWeights compute_embedding_weights(const TriMesh& disk, const std::vector<char>& is_boundary,
                                        EmbeddingWeights weights) {
  return embedding_weights(disk, is_boundary, weights, nullptr, nullptr);
}

ConvexWeights compute_subdisk_weights(const TriMesh& disk, const std::vector<char>& is_boundary,
                                      EmbeddingWeights weights, const ConvexWeights& pattern,
                                      const std::vector<int>& to_pattern) {
  if (to_pattern.size() != is_boundary.size() || static_cast<int>(to_pattern.size()) != disk.num_vertices())
    throw InvalidInputError("compute_subdisk_weights: to_pattern has " +
                            std::to_string(to_pattern.size()) + " entries for " +
                            std::to_string(disk.num_vertices()) + " vertices");
  return embedding_weights(disk, is_boundary, weights, &pattern, &to_pattern);
}

// ---------------------------------------------------------------------------------------------
// Boundary on the square.

DiskBoundary map_boundary_to_square(const TriMesh& disk, const std::vector<int>& loop_in) {
  const int n = static_cast<int>(loop_in.size());
  if (n < 3)
    throw TopologyError("disk boundary loop has " + std::to_string(n) + " vertices (need at least 3)");
  const int nv = disk.num_vertices();
  // Directed face edges a->b (CSR by a), to orient the loop and to find chords and ears.
  std::vector<int> out_off(nv + 1, 0), out_to(disk.faces.size() * 3);
  for (const Face& f : disk.faces)
    for (int k = 0; k < 3; ++k) ++out_off[f[k] + 1];
  for (int v = 0; v < nv; ++v) out_off[v + 1] += out_off[v];
  {
    std::vector<int> fill(out_off.begin(), out_off.end() - 1);
    for (const Face& f : disk.faces)
      for (int k = 0; k < 3; ++k) out_to[fill[f[k]]++] = f[(k + 1) % 3];
  }
  auto has_edge = [&](int a, int b) {
    for (int k = out_off[a]; k < out_off[a + 1]; ++k)
      if (out_to[k] == b) return true;
    return false;
  };
  DiskBoundary out;
  out.loop = loop_in;
  const bool fwd = has_edge(loop_in[0], loop_in[1]);
  const bool bwd = has_edge(loop_in[1], loop_in[0]);
  if (fwd == bwd)
    throw TopologyError("boundary loop edge (" + std::to_string(loop_in[0]) + "," +
                        std::to_string(loop_in[1]) + ") is not a boundary edge of the disk");
  if (!fwd) std::reverse(out.loop.begin(), out.loop.end());
  const auto& loop = out.loop;

  std::vector<int> pos(nv, -1);
  for (int i = 0; i < n; ++i) pos[loop[i]] = i;
  // Arc length, each edge floored at 1e-3 of the mean edge (duplicate points on the boundary would
  // otherwise share one UV position and collapse their triangles).
  std::vector<double> edge_len(n);
  double mean_edge = 0;
  for (int i = 0; i < n; ++i)
    mean_edge += edge_len[i] = (disk.positions[loop[(i + 1) % n]] - disk.positions[loop[i]]).norm();
  mean_edge = mean_edge > 0 && std::isfinite(mean_edge) ? mean_edge / n : 1.0;
  std::vector<double> arc(n + 1, 0.0);
  for (int i = 0; i < n; ++i) arc[i + 1] = arc[i] + std::max(edge_len[i], 1e-3 * mean_edge);
  const double total = arc[n];
  // Chords: edges between two boundary vertices that are not consecutive on the loop.
  std::vector<std::array<int, 2>> chords;
  std::vector<int> faces_at(n, 0);
  std::vector<double> angle_at(n, 0.0);
  for (const Face& f : disk.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = f[k], b = f[(k + 1) % 3];
      if (pos[a] >= 0) {
        ++faces_at[pos[a]];
        const Vec3 e1 = disk.positions[b] - disk.positions[a];
        const Vec3 e2 = disk.positions[f[(k + 2) % 3]] - disk.positions[a];
        angle_at[pos[a]] += std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      }
      if (pos[a] < 0 || pos[b] < 0 || a > b) continue;
      const int d = std::abs(pos[a] - pos[b]);
      if (d == 1 || d == n - 1) {
        // Consecutive on the loop: a chord only if the edge is interior (two faces).
        if (!(has_edge(a, b) && has_edge(b, a))) continue;
      }
      chords.push_back({pos[a], pos[b]});
    }
  std::vector<int> ears;
  for (int i = 0; i < n; ++i)
    if (faces_at[i] == 1) ears.push_back(i);

  // Validity of a corner set c0 < c1 < c2 < c3 (loop indices, sorted cyclically from c0).
  auto side_of = [&](const std::array<int, 4>& c, int i) {  // side index in [0,4) of a non-corner
    const int rel = (i - c[0] + n) % n;
    int s = 0;
    while (s < 3 && rel > (c[s + 1] - c[0] + n) % n) ++s;
    return s;
  };
  auto valid = [&](const std::array<int, 4>& c) {
    for (int k = 0; k < 4; ++k)
      if (c[k] == c[(k + 1) % 4]) return false;
    for (int e : ears)
      if (std::find(c.begin(), c.end(), e) == c.end()) return false;
    auto sides = [&](int i) {  // bitmask of the sides containing loop index i
      for (int k = 0; k < 4; ++k)
        if (c[k] == i) return (1 << k) | (1 << ((k + 3) % 4));
      return 1 << side_of(c, i);
    };
    for (const auto& ch : chords)
      if (sides(ch[0]) & sides(ch[1])) return false;
    return true;
  };
  auto nearest_vertex = [&](double s) {
    s = std::fmod(s, total);
    if (s < 0) s += total;
    const int i = static_cast<int>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin()) - 1;
    const int j = std::min(i, n - 1);
    return (s - arc[j] <= arc[j + 1] - s) ? j : (j + 1) % n;
  };
  std::array<int, 4> best{};
  double best_score = std::numeric_limits<double>::infinity();
  const int trials = std::min(n, 256);
  for (int t = 0; t < trials; ++t) {
    const double s0 = arc[static_cast<int>(static_cast<long long>(t) * n / trials)];
    std::array<int, 4> c;
    for (int k = 0; k < 4; ++k) c[k] = nearest_vertex(s0 + k * total / 4);
    // With at most 4 ears, snap each ear to the nearest quarter slot.
    if (!ears.empty() && ears.size() <= 4) {
      std::array<bool, 4> used{};
      for (int e : ears) {
        int bk = -1;
        double bd = 1e300;
        for (int k = 0; k < 4; ++k) {
          if (used[k]) continue;
          double dist = std::abs(arc[e] - arc[c[k]]);
          dist = std::min(dist, total - dist);
          if (dist < bd) bd = dist, bk = k;
        }
        used[bk] = true;
        c[bk] = e;
      }
    }
    // Sort cyclically starting at c[0].
    std::array<int, 4> sorted = c;
    std::sort(sorted.begin(), sorted.end(), [&](int a, int b) { return (a - c[0] + n) % n < (b - c[0] + n) % n; });
    if (!valid(sorted)) continue;
    double score = 0;  // smallest summed interior angle = most corner-like; plus arc-length balance
    for (int k = 0; k < 4; ++k) {
      const double len = std::fmod(arc[sorted[(k + 1) % 4]] - arc[sorted[k]] + total, total);
      score += angle_at[sorted[k]] + 2.0 * std::abs(len / total - 0.25);
    }
    if (score < best_score) best_score = score, best = sorted;
  }
  out.uv.resize(n);
  if (std::isfinite(best_score)) {
    // Rotate so that corner 0 of the square is at the start of the list.
    out.corners = best;
    static const Vec2 sq[5] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
    for (int k = 0; k < 4; ++k) {
      const int a = best[k], b = best[(k + 1) % 4];
      const double len = std::fmod(arc[b] - arc[a] + total, total);
      for (int i = a;; i = (i + 1) % n) {
        const double s = std::fmod(arc[i] - arc[a] + total, total);
        const double t = (i == a || len <= 0) ? 0.0 : std::min(1.0, s / len);
        out.uv[i] = (1 - t) * sq[k] + t * sq[k + 1];
        if ((i + 1) % n == b) break;
      }
    }
  } else {
    out.on_square = false;
    out.corners = {0, n / 4, n / 2, 3 * n / 4};
    for (int i = 0; i < n; ++i) {
      const double ang = 2 * std::numbers::pi * arc[i] / total;
      out.uv[i] = Vec2(0.5 + 0.5 * std::cos(ang), 0.5 + 0.5 * std::sin(ang));
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Solver.

#ifdef ADAPTEX_HAVE_KLU
namespace {

/// KLU factorization of Aᵀ (the row-major A's arrays read as compressed columns). Aᵀ is column
/// diagonally dominant (each row of A: diagonal 1, off-diagonal magnitudes summing to <= 1), so the
/// diagonal pivots of the first factorization stay good for any later weights: refactor() keeps the
/// pivot order and only redoes the numbers (klu_refactor). solve() uses klu_tsolve: A x = b.
class KluFactor {
 public:
  KluFactor() {
    klu_defaults(&common_);
    common_.btf = 0;    // the Tutte matrix of a disk is irreducible: a block triangular form has one block
    common_.scale = -1;  // diagonally dominant already: no row scaling (results are checked instead)
  }
  ~KluFactor() { clear(); }
  KluFactor(const KluFactor&) = delete;
  KluFactor& operator=(const KluFactor&) = delete;

  /// Factorizes \p a; reuses the symbolic analysis and, when \p refactor, the pivot order.
  bool factorize(RowMat& a, bool refactor) {
    int* ap = a.outerIndexPtr();
    int* ai = a.innerIndexPtr();
    double* ax = a.valuePtr();
    if (!symbolic_) symbolic_ = klu_analyze(static_cast<int>(a.rows()), ap, ai, &common_);
    if (!symbolic_) return false;
    if (numeric_ && refactor && klu_refactor(ap, ai, ax, symbolic_, numeric_, &common_)) return true;
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    numeric_ = klu_factor(ap, ai, ax, symbolic_, &common_);
    return numeric_ != nullptr;
  }
  /// Overwrites the column-major n×2 block \p b with A⁻¹ b.
  bool solve(Eigen::MatrixX2d& b) {
    return klu_tsolve(symbolic_, numeric_, static_cast<int>(b.rows()), 2, b.data(), &common_) != 0;
  }
  void clear() {
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    if (symbolic_) klu_free_symbolic(&symbolic_, &common_);
  }

 private:
  klu_common common_{};
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
};

}  // namespace
#endif

struct TutteSolver::Impl {
  RowMat A;                   ///< Master matrix (row-major), pattern fixed at construction.
  std::vector<int> entry_pos; ///< Weight entry -> position in A's values (-1: boundary neighbour).
  std::vector<int> diag_pos;  ///< Unknown -> position of its diagonal entry.
#ifdef ADAPTEX_HAVE_UMFPACK
  Eigen::UmfPackLU<SpMat> umf;
#endif
#ifdef ADAPTEX_HAVE_KLU
  KluFactor klu;
#endif
  Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>> lu;
  detail::AmgPreconditioner amg;
  // Whether each backend's symbolic analysis (AMG: hierarchy) of A's pattern exists.
  bool klu_analyzed = false, umf_analyzed = false, lu_analyzed = false, amg_analyzed = false;

  bool solve_direct(Backend b, const Eigen::MatrixX2d& rhs, Eigen::MatrixX2d& x);

  /// ||A x - b|| <= tol ||b|| for both columns, and x finite.
  bool residual_ok(const Eigen::MatrixX2d& b, const Eigen::MatrixX2d& x, double tol) const {
    if (!x.allFinite()) return false;
    const Eigen::MatrixX2d r = A * x - b;
    for (int c = 0; c < 2; ++c)
      if (!(r.col(c).norm() <= tol * std::max(b.col(c).norm(), 1e-300))) return false;
    return true;
  }
};

TutteSolver::TutteSolver(const ConvexWeights& pattern, const std::vector<char>& is_boundary,
                         Backend backend)
    : impl_(std::make_unique<Impl>()), backend_(backend) {
  const int nv = pattern.num_vertices();
  unknown_.assign(nv, -1);
  for (int v = 0; v < nv; ++v)
    if (!is_boundary[v] && pattern.offsets[v + 1] > pattern.offsets[v]) {
      unknown_[v] = static_cast<int>(interior_.size());
      interior_.push_back(v);
    }
  const int n = num_interior();
  if (backend_ == Backend::Auto) backend_ = n <= kAutoDirectLimit ? Backend::Klu : Backend::Multigrid;
#ifndef ADAPTEX_HAVE_KLU
  if (backend_ == Backend::Klu) backend_ = Backend::Umfpack;
#endif
#ifndef ADAPTEX_HAVE_UMFPACK
  if (backend_ == Backend::Umfpack) backend_ = Backend::SparseLU;
#endif
  // Build the pattern with each entry's id as its value, then read the ids back as positions.
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(pattern.values.size() + n);
  const double diag_tag = -1.0;
  for (int i = 0; i < n; ++i) {
    const int v = interior_[i];
    trip.emplace_back(i, i, diag_tag - i);
    for (int k = pattern.offsets[v]; k < pattern.offsets[v + 1]; ++k)
      if (unknown_[pattern.neighbors[k]] >= 0)
        trip.emplace_back(i, unknown_[pattern.neighbors[k]], static_cast<double>(k));
  }
  RowMat& A = impl_->A;
  A.resize(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  A.makeCompressed();
  impl_->entry_pos.assign(pattern.values.size(), -1);
  impl_->diag_pos.assign(n, -1);
  for (int p = 0; p < A.nonZeros(); ++p) {
    const double tag = A.valuePtr()[p];
    if (tag < 0) impl_->diag_pos[static_cast<int>(diag_tag - tag)] = p;
    else impl_->entry_pos[static_cast<size_t>(tag)] = p;
  }
}

TutteSolver::~TutteSolver() = default;

/// Direct solve of A x = rhs with the backend \p b (Klu, Umfpack or SparseLU), reusing its symbolic
/// analysis. Returns false on factorization failure or a non-finite / inaccurate result.
bool TutteSolver::Impl::solve_direct(Backend b, const Eigen::MatrixX2d& rhs, Eigen::MatrixX2d& x) {
  Impl& im = *this;
  constexpr double kDirectTolerance = 1e-8;
  switch (b) {
#ifdef ADAPTEX_HAVE_KLU
    case Backend::Klu: {
      const bool refactor = klu_analyzed;
      klu_analyzed = true;
      if (!im.klu.factorize(im.A, refactor)) return false;
      x = rhs;
      if (im.klu.solve(x) && im.residual_ok(rhs, x, kDirectTolerance)) return true;
      if (!refactor) return false;
      // The kept pivot order no longer suits the new values: factorize afresh (partial pivoting).
      if (!im.klu.factorize(im.A, false)) return false;
      x = rhs;
      return im.klu.solve(x) && im.residual_ok(rhs, x, kDirectTolerance);
    }
#endif
#ifdef ADAPTEX_HAVE_UMFPACK
    case Backend::Umfpack: {
      const SpMat Ac(im.A);
      if (!umf_analyzed) im.umf.analyzePattern(Ac), umf_analyzed = true;
      im.umf.factorize(Ac);
      if (im.umf.info() != Eigen::Success) return false;
      x = im.umf.solve(rhs);
      return im.residual_ok(rhs, x, kDirectTolerance);
    }
#endif
    default: {
      const SpMat Ac(im.A);
      if (!lu_analyzed) im.lu.analyzePattern(Ac), lu_analyzed = true;
      im.lu.factorize(Ac);
      if (im.lu.info() != Eigen::Success) return false;
      x = im.lu.solve(rhs);
      return im.residual_ok(rhs, x, kDirectTolerance);
    }
  }
}

void TutteSolver::solve(const ConvexWeights& w, std::vector<Vec2>& uv) {
  const int n = num_interior();
  if (n == 0) return;
  Impl& im = *impl_;
  RowMat& A = im.A;
  // A(i,i) = 1, A(i,j) = -λ_vw (w interior); rhs_i = Σ_{w boundary} λ_vw ψ(w).
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n, 2);
  double* val = A.valuePtr();
  auto assemble = [&](int i) {
    const int v = interior_[i];
    val[im.diag_pos[i]] = 1.0;
    for (int k = w.offsets[v]; k < w.offsets[v + 1]; ++k) {
      const int p = im.entry_pos[k];
      if (p >= 0) val[p] = -w.values[k];
      else rhs.row(i) += w.values[k] * uv[w.neighbors[k]].transpose();
    }
  };
  if (n < 8192) {
    for (int i = 0; i < n; ++i) assemble(i);
  } else {
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 4096), [&](const tbb::blocked_range<int>& r) {
      for (int i = r.begin(); i != r.end(); ++i) assemble(i);
    });
  }
  Eigen::MatrixX2d x(n, 2);
  for (int i = 0; i < n; ++i) x.row(i) = uv[interior_[i]].transpose();  // BiCGSTAB's initial guess
  solve_assembled(rhs, x);
  for (int i = 0; i < n; ++i) uv[interior_[i]] = x.row(i).transpose();
}

TutteSolver::SubdiskMap TutteSolver::map_subdisk(const ConvexWeights& w,
                                                 const std::vector<int>& to_pattern) const {
  const int nv = w.num_vertices();
  if (static_cast<int>(to_pattern.size()) != nv)
    throw InvalidInputError("TutteSolver::map_subdisk: to_pattern has " +
                            std::to_string(to_pattern.size()) + " entries for " +
                            std::to_string(nv) + " vertices");
  const RowMat& A = impl_->A;
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  SubdiskMap map;
  map.unknown.assign(nv, -1);
  for (int v = 0; v < nv; ++v) {
    if (w.offsets[v + 1] == w.offsets[v]) continue;  // boundary
    const int p = to_pattern[v];
    map.unknown[v] = p >= 0 && p < static_cast<int>(unknown_.size()) ? unknown_[p] : -1;
    if (map.unknown[v] < 0)
      throw InvalidInputError("TutteSolver::map_subdisk: interior vertex " + std::to_string(v) +
                              " is not an interior vertex of the pattern");
  }
  map.entry_pos.assign(w.neighbors.size(), -1);
  for (int v = 0; v < nv; ++v) {
    const int i = map.unknown[v];
    if (i < 0) continue;
    for (int k = w.offsets[v]; k < w.offsets[v + 1]; ++k) {
      const int j = map.unknown[w.neighbors[k]];
      if (j < 0) continue;  // boundary neighbour: right-hand side
      const int* pos = std::find(inner + outer[i], inner + outer[i + 1], j);
      if (pos == inner + outer[i + 1])
        throw InvalidInputError("TutteSolver::map_subdisk: edge " + std::to_string(v) + "-" +
                                std::to_string(w.neighbors[k]) + " is not in the pattern");
      map.entry_pos[k] = static_cast<int>(pos - inner);
    }
  }
  return map;
}

void TutteSolver::solve_subdisk(const ConvexWeights& w, const SubdiskMap& map,
                                std::vector<Vec2>& uv) {
  const int n = num_interior();
  const int nv = w.num_vertices();
  if (static_cast<int>(map.unknown.size()) != nv || static_cast<int>(uv.size()) != nv ||
      map.entry_pos.size() != w.neighbors.size())
    throw InvalidInputError("TutteSolver::solve_subdisk: map / uv sizes differ from the weights'");
  Impl& im = *impl_;
  double* val = im.A.valuePtr();
  std::fill(val, val + im.A.nonZeros(), 0.0);
  // Rows of the pattern's unknowns that are not interior here stay identity rows (x = 0).
  for (int i = 0; i < n; ++i) val[im.diag_pos[i]] = 1.0;
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n, 2), x = Eigen::MatrixX2d::Zero(n, 2);
  for (int v = 0; v < nv; ++v) {
    const int i = map.unknown[v];
    if (i < 0) continue;
    x.row(i) = uv[v].transpose();
    for (int k = w.offsets[v]; k < w.offsets[v + 1]; ++k) {
      const int p = map.entry_pos[k];
      if (p >= 0) val[p] = -w.values[k];
      else rhs.row(i) += w.values[k] * uv[w.neighbors[k]].transpose();
    }
  }
  solve_assembled(rhs, x);
  for (int v = 0; v < nv; ++v)
    if (map.unknown[v] >= 0) uv[v] = x.row(map.unknown[v]).transpose();
}

void TutteSolver::solve_assembled(const Eigen::MatrixX2d& rhs, Eigen::MatrixX2d& x) {
  const int n = num_interior();
  Impl& im = *impl_;
  RowMat& A = im.A;
  bool ok = false;
  if (backend_ == Backend::Multigrid) {
    try {
      if (!im.amg_analyzed) im.amg.setup(A), im.amg_analyzed = true;
      else im.amg.update(A);
      detail::AmgPreconditioner::Block xb = x, bb = rhs;
      if (!xb.allFinite()) xb.setConstant(0.5);
      const int its = detail::bicgstab(A, im.amg, bb, xb, tolerance_, max_iterations_);
      last_iterations_ += its >= 0 ? its : max_iterations_;
      x = xb;
      ok = its >= 0 && x.allFinite();
    } catch (const SolverError&) {  // the AMG hierarchy could not be built (singular coarse level)
      im.amg_analyzed = false;
      ok = false;
    }
  } else {
    ok = im.solve_direct(backend_, rhs, x);
  }
  if (!ok) {
    // Fallback: the iterative solver did not converge or the direct one failed. A direct
    // LU with partial pivoting (UMFPACK, else SparseLU) from scratch; the Tutte matrix of strictly
    // positive convex weights is a non-singular M-matrix, so this only fails on non-finite weights.
    ++fallbacks_;
#ifdef ADAPTEX_HAVE_UMFPACK
    const Backend fb = backend_ == Backend::Umfpack ? Backend::SparseLU : Backend::Umfpack;
#else
    const Backend fb = Backend::SparseLU;
#endif
    ok = im.solve_direct(fb, rhs, x);
  }
  if (!ok)
    throw SolverError("Tutte system (" + std::to_string(n) +
                      " unknowns): no backend produced a finite solution (non-finite weights?)");
}

template <>
std::span<const EnumName<EmbeddingWeights>> enum_names<EmbeddingWeights>() {
  static constexpr EnumName<EmbeddingWeights> names[] = {{EmbeddingWeights::MeanValue, "mean-value"},
                                                         {EmbeddingWeights::ShapePreserving, "shape-preserving"}};
  return names;
}

}  // namespace adaptex
