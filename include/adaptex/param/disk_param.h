#pragma once
/// \file disk_param.h
/// Initial parameterization of one disk (thesis §2.2 and §3.3): Floater embedding onto the unit
/// square, then Yoshizawa–Belyaev–Seidel 2004 stretch minimization ("A fast and simple
/// stretch-minimizing mesh parameterization", SMI 2004). See docs/parameterization.md.
#include <memory>
#include <vector>

#include "adaptex/core/mesh.h"
#include "adaptex/core/progress.h"
#include "adaptex/param/floater.h"

namespace adaptex {

/// Settings of parameterize_disk().
struct DiskParamOptions {
  /// Weights of the initial Tutte-type embedding.
  EmbeddingWeights weights = EmbeddingWeights::ShapePreserving;
  /// Run Yoshizawa stretch minimization after the Floater embedding.
  bool yoshizawa = true;
  /// Exponent η on the vertex stretch σ: λ_vw ← λ_vw / σ_w^η. The paper uses 1.0; 0.5 reaches a
  /// lower L2 on every mesh measured (docs/parameterization.md) at about the same time.
  double eta = 0.5;
  /// Cap on the Yoshizawa re-weighting iterations (the loop stops earlier when L2 stops improving).
  int max_iterations = 30;
  /// An iterate must lower the mesh L2 stretch by at least this relative amount, otherwise η is halved
  /// (restarting from the best weights so far).
  double min_improvement = 1e-3;
  /// Stop after this many halvings of η (0: stop at the first iterate that does not improve enough).
  /// 1 (2 before): the iterations after a second halving changed the final L2 of the
  /// shared meshes by < 0.2 % (docs/bench_unwrap.md, "One halving of η") and cost one or two solves
  /// (venus' unwrap 6.1 -> 5.9 ms), so they are skipped.
  int max_halvings = 1;
  /// Sparse solver backend.
  TutteSolver::Backend backend = TutteSolver::Backend::Auto;
  /// Cap on the BiCGSTAB iterations of one solve (Multigrid backend); a solve that reaches it is
  /// redone by the direct fallback (counted in DiskParamResult::solver_fallbacks).
  int max_solver_iterations = 500;
  /// Progress / cancel callback (phases "floater", "yoshizawa").
  ProgressCallback progress;
};

/// Result of parameterize_disk().
struct DiskParamResult {
  /// V_disk coordinates (indexed like disk.positions); the boundary lies on the unit square [0,1]²
  /// (on the inscribed circle when boundary.on_square is false), interior strictly inside.
  std::vector<Vec2> uv;
  double floater_l2 = 0, floater_linf = 0;  ///< Mesh stretch of the Floater embedding (1 = ideal).
  double final_l2 = 0, final_linf = 0;      ///< Mesh stretch of the returned uv.
  int iterations = 0;                       ///< Yoshizawa re-weighting iterations performed.
  int flipped = 0;     ///< UV triangles of the returned uv with negative area (measure_stretch()).
  int degenerate = 0;  ///< UV triangles of the returned uv with (numerically) zero area.
  double time_floater = 0, time_yoshizawa = 0;  ///< Seconds.
  bool on_square = true;                    ///< See DiskBoundary::on_square.
  /// Sparse solves whose backend failed (no convergence, failed factorization, inaccurate result)
  /// and were redone by the direct fallback (TutteSolver::fallbacks()).
  int solver_fallbacks = 0;
};

/// Parameterizes a disk onto the unit square without flipped triangles.
/// \param disk a TriMesh homeomorphic to a disk (exactly one boundary loop), manifold, no degenerate
///   faces, faces oriented consistently (CCW or CW globally). Every UV triangle of the result has the
///   same orientation as its face's vertex order (uv signed area > 0), whatever the 3-D winding.
/// \param boundary_loop the boundary vertex cycle (either direction, as analyze_topology() gives it);
///   empty to compute it.
/// \throw TopologyError not a disk (no boundary, several loops, several components, non-manifold)
/// \throw SolverError sparse solve failure of the backend and of its direct fallback
/// \throw CancelledError the progress callback returned false
DiskParamResult parameterize_disk(const TriMesh& disk, const std::vector<int>& boundary_loop,
                                  const DiskParamOptions& options = {});

/// Where a parameterize_disk() run stopped: the current weights and their factorized Tutte
/// system, η and its halvings, the best iterate. Lets a cheap run (few Yoshizawa iterations, as the
/// cut augmentation uses to compare cuts) be continued instead of redone from the Floater solve.
struct DiskParamState;

/// Deletes a DiskParamState (the type is opaque).
struct DiskParamStateDeleter {
  void operator()(DiskParamState* s) const;
};
/// Owner of a DiskParamState.
using DiskParamStatePtr = std::unique_ptr<DiskParamState, DiskParamStateDeleter>;

/// parameterize_disk() that also returns its state in \p state, for continue_disk_param().
/// Same result as parameterize_disk(disk, boundary_loop, options).
/// \pre as parameterize_disk(); state != nullptr
/// \throw as parameterize_disk()
DiskParamResult parameterize_disk(const TriMesh& disk, const std::vector<int>& boundary_loop,
                                  const DiskParamOptions& options, DiskParamStatePtr* state);

/// parameterize_disk() of a disk cut from the same surface as the disk of \p parent's solver, along a
/// larger cut (unwrap's cut augmentation): its interior vertices are interior vertices of that disk,
/// joined by the same edges. The Tutte systems are solved by \p parent's solver
/// (TutteSolver::solve_subdisk: no new ordering or pivoting, only numeric refactorizations), which
/// the returned \p state shares. The result equals parameterize_disk(disk, boundary_loop, options)
/// up to rounding. With the Multigrid backend a solver of its own is built instead.
/// \param to_pattern per vertex of \p disk: the vertex of the solver's disk for interior vertices
///   (ignored on the boundary). The solver's disk is that of the parameterize_disk() run that
///   started the chain of parameterize_subdisk() runs.
/// \param parent the state of that run or of any run sharing its solver; it must not be used
///   concurrently with the returned state.
/// \pre as parameterize_disk(); state may be nullptr
/// \throw InvalidInputError to_pattern has the wrong size or maps an interior vertex or edge outside
///   the solver's interior
/// \throw as parameterize_disk()
DiskParamResult parameterize_subdisk(const TriMesh& disk, const std::vector<int>& boundary_loop,
                                     const std::vector<int>& to_pattern, const DiskParamState& parent,
                                     const DiskParamOptions& options, DiskParamStatePtr* state);

/// vertex_stretch(disk, result.uv) (yoshizawa.h: per-vertex σ) from what the run measured already
/// (the Yoshizawa loop keeps σ of its best iterate); measured afresh when no Yoshizawa iteration ran.
/// \pre \p result is the latest result of the run of \p state, on \p disk
std::vector<double> result_vertex_stretch(const TriMesh& disk, DiskParamState& state,
                                          const DiskParamResult& result);

/// Continues a run of parameterize_disk() with \p options.max_iterations Yoshizawa iterations in
/// total (those already done included). The result equals that of one parameterize_disk() call
/// with \p options (up to the progress reports and the timings), because the Yoshizawa loop only
/// depends on the iteration count through its cap. \p state is updated (it can be continued again).
/// \param disk the same disk as in the run that made \p state (it may have been moved meanwhile).
/// \param previous the result of that run (or of the previous continuation).
/// \pre options equal those of that run except max_iterations (>= the previous one), yoshizawa and
///   progress; a run with yoshizawa == false can be continued with yoshizawa == true.
/// \throw SolverError sparse solve failure
/// \throw CancelledError the progress callback returned false
DiskParamResult continue_disk_param(const TriMesh& disk, DiskParamState& state,
                                    const DiskParamResult& previous, const DiskParamOptions& options);

}  // namespace adaptex
