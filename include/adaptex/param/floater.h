#pragma once
/// \file floater.h
/// Tutte-type barycentric embedding of a disk onto a convex domain (thesis §2.2): Floater 1997
/// shape-preserving weights ("Parametrization and smooth approximation of surface triangulations",
/// CAGD 14), Floater 2003 mean-value weights ("Mean value coordinates", CAGD 20), the boundary
/// mapped to the unit square by arc length, and a reusable sparse solver for the linear system
///   ψ(v) - Σ_{w∈N_v∩V_I} λ_vw ψ(w) = Σ_{w∈N_v∩V_B} λ_vw ψ(w),   v ∈ V_I.
#include <array>
#include <memory>
#include <vector>

#include "adaptex/core/enum_names.h"
#include "adaptex/core/mesh.h"

namespace adaptex {

/// Barycentric weights of the initial (Tutte-type) embedding.
enum class EmbeddingWeights {
  ShapePreserving,  ///< Floater 1997 shape-preserving weights (the thesis' choice).
  MeanValue,        ///< Floater 2003 mean-value coordinates.
};
/// "mean-value", "shape-preserving".
template <>
std::span<const EnumName<EmbeddingWeights>> enum_names<EmbeddingWeights>();

/// Strictly positive convex weights λ_vw (each interior row sums to 1), in CSR form by vertex.
/// Boundary vertices have empty rows.
struct ConvexWeights {
  std::vector<int> offsets;     ///< V+1 row offsets into neighbors / values.
  std::vector<int> neighbors;   ///< Neighbour vertex w of each entry (one-ring order, CCW by face order).
  std::vector<double> values;   ///< λ_vw of each entry, > 0.
  int num_vertices() const { return static_cast<int>(offsets.size()) - 1; }
};

/// The disk boundary placed on a convex domain.
struct DiskBoundary {
  std::vector<int> loop;        ///< Boundary vertex cycle, ordered like the face winding (disk on the left).
  std::vector<Vec2> uv;         ///< Position of loop[i] (same size as loop).
  std::array<int, 4> corners{}; ///< Indices into loop of the square's corners (0,0),(1,0),(1,1),(0,1).
  bool on_square = true;        ///< False: no valid corner choice exists (more than 4 "ear" triangles
                                ///< or chords); the boundary was put on the circle inscribed in [0,1]².
};

/// Orients \p loop like the faces of \p disk (so that a counter-clockwise image of the loop gives
/// positively oriented UV triangles) and maps it to the boundary of [0,1]² by arc length.
/// Corner choice: for many start positions s along the loop, the four corners are the boundary
/// vertices nearest to arc length s, s+L/4, s+L/2, s+3L/4; a choice is valid when no edge that is not a
/// boundary edge joins two vertices of the same side (such a "chord" would collapse the triangles
/// between them: Floater 2003 one-to-one condition for weakly convex boundaries) and every "ear"
/// (boundary vertex with a single face) is a corner. Among valid choices the one whose corners have the
/// smallest summed 3-D boundary angle (the most corner-like vertices) wins. If none is valid the loop is
/// mapped to the inscribed circle (strictly convex: always valid).
/// \pre \p loop is the only boundary cycle of \p disk (either direction), disk is a manifold disk.
/// \throw TopologyError the loop is shorter than 3 vertices or is not a boundary cycle of \p disk
DiskBoundary map_boundary_to_square(const TriMesh& disk, const std::vector<int>& loop);

/// Embedding weights for every vertex not flagged in \p is_boundary (size V).
/// ShapePreserving: Floater's local geodesic polar map of the one-ring (angles scaled to sum 2π,
/// lengths kept), then for each neighbour w_i the barycentric coordinates of v in the triangle
/// (p_i, p_r, p_{r+1}) containing v, averaged over the d neighbours (thesis §2.2). Where the polar map
/// has an angle ≥ π (coordinates would not be positive) the vertex falls back to mean-value weights.
/// MeanValue: λ_i ∝ (tan(α_{i-1}/2) + tan(α_i/2)) / |w_i - v| with the 3-D angles α.
/// \pre disk is manifold; every non-boundary vertex has a closed one-ring.
/// \throw TopologyError an interior vertex has an open or non-manifold one-ring
ConvexWeights compute_embedding_weights(const TriMesh& disk, const std::vector<char>& is_boundary,
                                        EmbeddingWeights weights);

/// compute_embedding_weights() of a disk cut from the same surface as \p pattern's disk along a
/// larger cut (TutteSolver::map_subdisk's situation). A row depends only on its vertex's closed
/// one-ring, which every interior vertex of the sub-disk keeps with the same faces in the same order,
/// so its row is copied from \p pattern when the rows line up (same length, same interior
/// neighbours at the same positions); otherwise it is computed. Same result as
/// compute_embedding_weights(disk, is_boundary, weights) when \p pattern was computed by it with
/// the same \p weights.
/// \param pattern the weights of the other disk (before any Yoshizawa re-weighting).
/// \param to_pattern V: the vertex of the other disk of each interior vertex (others ignored).
/// \pre as compute_embedding_weights()
/// \throw InvalidInputError to_pattern has the wrong size
/// \throw TopologyError as compute_embedding_weights()
ConvexWeights compute_subdisk_weights(const TriMesh& disk, const std::vector<char>& is_boundary,
                                      EmbeddingWeights weights, const ConvexWeights& pattern,
                                      const std::vector<int>& to_pattern);

/// Sparse solver of the Tutte system for a fixed sparsity pattern. The symbolic analysis (fill-reducing
/// ordering) is done once; solve() refactorizes numerically for new weights with the same pattern, so
/// the Yoshizawa iterations only pay the numeric factorization (after geometry-central's
/// PositiveDefiniteSolver / SquareSolver).
class TutteSolver {
 public:
  /// Linear-algebra backend.
  enum class Backend {
    Auto,       ///< Klu up to 20k unknowns, Multigrid above (see docs/parameterization.md).
    Umfpack,    ///< SuiteSparse UMFPACK LU, symbolic analysis reused (SparseLU if not built with it).
    SparseLU,   ///< Eigen::SparseLU (supernodal LU, no extra library), symbolic analysis reused.
    Multigrid,  ///< BiCGSTAB preconditioned by smoothed-aggregation AMG (aggregates reused),
                ///< warm-started from the current uv. Scales linearly; for 100k+ faces.
    Klu,        ///< SuiteSparse KLU (Davis & Palamadai Natarajan 2010, "Algorithm 907: KLU"), symbolic
                ///< analysis and pivot order reused (klu_refactor): the fastest on small systems
                ///< (Umfpack if not built with it).
  };
  // Every backend checks its result (finite, relative residual <= 1e-8 for the direct ones, the
  // tolerance for Multigrid). On failure solve() falls back to a fresh direct LU with partial
  // pivoting (UMFPACK, or SparseLU when the failing backend is UMFPACK) and counts it in fallbacks().
  /// \param pattern weights whose sparsity pattern every later solve() uses.
  /// \param is_boundary V flags; boundary vertices are fixed.
  TutteSolver(const ConvexWeights& pattern, const std::vector<char>& is_boundary,
              Backend backend = Backend::Auto);
  ~TutteSolver();
  TutteSolver(const TutteSolver&) = delete;
  TutteSolver& operator=(const TutteSolver&) = delete;

  /// Solves for the interior positions. \p uv (size V): boundary entries are read (the fixed boundary),
  /// interior entries are overwritten (and used as the initial guess by BiCgStab).
  /// \pre weights has the pattern given at construction.
  /// \throw SolverError neither the backend nor the direct fallback produced an accurate finite
  ///   solution (only with non-finite weights)
  void solve(const ConvexWeights& weights, std::vector<Vec2>& uv);

  /// Where the weight entries of another disk go in this solver's system (solve_subdisk()).
  struct SubdiskMap {
    std::vector<int> unknown;    ///< V': unknown of each interior vertex, -1 on the boundary.
    std::vector<int> entry_pos;  ///< Per weight entry: position in the matrix; -1 for a boundary
                                 ///< neighbour (right-hand side).
  };
  /// The SubdiskMap of another disk whose interior vertices are interior vertices of the pattern's
  /// disk, joined by the same edges: a disk cut from the same surface along a larger cut (unwrap's
  /// cut augmentation).
  /// \param weights V' rows of the other disk (empty rows on its boundary); only the pattern is read.
  /// \param to_pattern V': the vertex of the pattern's disk of each interior vertex (others ignored).
  /// \throw InvalidInputError wrong size; an interior vertex or an edge between interior vertices
  ///   that the pattern does not have
  SubdiskMap map_subdisk(const ConvexWeights& weights, const std::vector<int>& to_pattern) const;

  /// Solves the Tutte system of the other disk of \p map. Its matrix is the pattern's with the rows
  /// of the pattern's unknowns that are not interior there replaced by identity rows and their
  /// columns zeroed, so the symbolic analysis (and the Klu pivot order) of the pattern is reused
  /// instead of ordering and factorizing a new pattern; the solution is that of a TutteSolver built
  /// for the other disk (up to rounding). Interleaves freely with solve().
  /// \param weights weights with the pattern \p map was made for.
  /// \param uv V' positions: boundary entries are read, interior entries overwritten.
  /// \throw InvalidInputError sizes differ from map's
  /// \throw SolverError as solve()
  void solve_subdisk(const ConvexWeights& weights, const SubdiskMap& map, std::vector<Vec2>& uv);

  /// The backend in use (Auto resolved).
  Backend backend() const { return backend_; }
  /// Relative residual tolerance of the iterative backend (default 1e-10).
  void set_tolerance(double tol) { tolerance_ = tol; }
  /// Cap on BiCGSTAB iterations per solve (Multigrid backend, default 500); on reaching it solve()
  /// falls back to a direct factorization.
  void set_max_iterations(int its) { max_iterations_ = its; }
  /// BiCGSTAB iterations summed over all solves so far (iterative backend only).
  int iterations() const { return last_iterations_; }
  /// Solves so far that needed the direct fallback (the backend failed or did not converge).
  int fallbacks() const { return fallbacks_; }
  int num_interior() const { return static_cast<int>(interior_.size()); }

 private:
  /// Solves the assembled system A x = rhs (x: the initial guess on input) with the backend and
  /// the direct fallback. \throw SolverError as solve()
  void solve_assembled(const Eigen::MatrixX2d& rhs, Eigen::MatrixX2d& x);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  Backend backend_;
  double tolerance_ = 1e-10;
  int max_iterations_ = 500;
  int last_iterations_ = 0;
  int fallbacks_ = 0;
  std::vector<int> interior_;   ///< Interior vertex of each unknown.
  std::vector<int> unknown_;    ///< V: unknown index of each vertex (-1 on the boundary).
};

}  // namespace adaptex
