/// \file disk_param.cpp
/// Floater embedding + Yoshizawa stretch minimization of one disk (thesis §2.2, §3.3).
#include "adaptex/param/disk_param.h"

#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/timer.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/yoshizawa.h"

namespace adaptex {

namespace {


/// The boundary loop of a disk, checking that the mesh is a disk.
std::vector<int> disk_boundary_loop(const TriMesh& disk) {
  const MeshTopology topo = analyze_topology(disk);
  if (!topo.is_manifold())
    throw TopologyError("parameterize_disk: mesh is not manifold (" +
                        std::to_string(topo.nonmanifold_edges.size()) + " non-manifold edges, " +
                        std::to_string(topo.nonmanifold_vertices.size()) + " non-manifold vertices)");
  if (topo.num_components != 1 || topo.boundary_loops.size() != 1 || topo.total_genus() != 0)
    throw TopologyError("parameterize_disk: mesh is not a disk (" + std::to_string(topo.num_components) +
                        " components, " + std::to_string(topo.boundary_loops.size()) +
                        " boundary loops, genus " + std::to_string(topo.total_genus()) + ")");
  return topo.boundary_loops.front();
}

}  // namespace

/// The Yoshizawa loop's variables between runs (see DiskParamState in disk_param.h).
struct DiskParamState {
  ConvexWeights weights;       ///< Current weights (= those of the best iterate between runs).
  /// Factorized for the weights of the last iterate; shared with the runs of sub-disks
  /// (parameterize_subdisk()).
  std::shared_ptr<TutteSolver> solver;
  /// False: the solver was built for this disk. True: this disk is a sub-disk of the solver's
  /// (TutteSolver::solve_subdisk() with sub_map).
  bool subdisk = false;
  /// The Floater weights of the solver's disk (before Yoshizawa), shared along sub-disks.
  std::shared_ptr<const ConvexWeights> pattern_weights;
  TutteSolver::SubdiskMap sub_map;  ///< See subdisk.
  int fallbacks0 = 0;          ///< solver->fallbacks() when this run started.
  bool floater_ok = false;     ///< The Floater embedding has finite L2 (else Yoshizawa never runs).
  bool started = false;        ///< face_areas / face_l2 / sigma initialized.
  bool done = false;           ///< Stopped by the η halvings: no further iteration would run.
  bool sigma_stale = false;    ///< sigma not yet updated to the best iterate (whose face_l2 is kept).
  int iterations = 0;          ///< Yoshizawa iterations done.
  int halvings = 0;            ///< Halvings of η so far.
  double eta = 0;              ///< Current η.
  /// Solves the Tutte system of the current weights into \p uv.
  void solve(std::vector<Vec2>& uv) {
    if (subdisk) solver->solve_subdisk(weights, sub_map, uv);
    else solver->solve(weights, uv);
  }
  std::vector<double> face_areas;  ///< F 3-D face areas.
  std::vector<double> face_l2;     ///< F face L2 stretch of the last iterate (Floater before any).
  std::vector<double> sigma;       ///< V vertex stretch of the best iterate (vertex_stretch()).
};

void DiskParamStateDeleter::operator()(DiskParamState* s) const { delete s; }

namespace {

/// Runs Yoshizawa iterations iterations+1 .. options.max_iterations on \p res (thesis §3.3).
void run_yoshizawa(const TriMesh& disk, DiskParamState& s, const DiskParamOptions& options,
                   DiskParamResult& res) {
  if (!options.yoshizawa || !s.floater_ok || s.done || s.iterations >= options.max_iterations)
    return;
  // Yoshizawa–Belyaev–Seidel: λ_vw ← λ_vw / σ_w^η, re-solve, keep the best iterate. When an iterate
  // does not lower L2 by min_improvement, restart from the best weights with η halved (a damped step);
  // stop after max_halvings failed halvings or max_iterations solves.
  const auto t1 = std::chrono::steady_clock::now();
  if (!s.started) {
    const int nf = disk.num_faces();
    s.face_areas.resize(nf);
    for (int f = 0; f < nf; ++f) s.face_areas[f] = face_area(disk, f);
    s.sigma = vertex_stretch(disk, s.face_l2, s.face_areas);  // of the best iterate
    s.eta = options.eta;
    s.started = true;
  } else if (s.sigma_stale) {
    s.sigma = vertex_stretch(disk, s.face_l2, s.face_areas);
  }
  s.sigma_stale = false;
  std::vector<Vec2> cur;
  ConvexWeights best_weights = s.weights;
  for (int it = s.iterations + 1; it <= options.max_iterations; ++it) {
    report_progress(options.progress, "yoshizawa",
                    static_cast<double>(it - 1) / options.max_iterations);
    yoshizawa_reweight(s.weights, s.sigma, s.eta);
    cur = res.uv;
    s.solve(cur);
    const StretchStats st = measure_stretch(disk, cur, s.face_l2);
    res.iterations = s.iterations = it;
    const double prev_l2 = res.final_l2;
    const bool better = st.flipped == 0 && st.degenerate == 0 && st.l2 < res.final_l2;
    if (better) {
      res.uv.swap(cur);
      res.final_l2 = st.l2;
      res.final_linf = st.linf;
      res.flipped = res.degenerate = 0;
      best_weights = s.weights;
      if (it < options.max_iterations) s.sigma = vertex_stretch(disk, s.face_l2, s.face_areas);
      else s.sigma_stale = true;
    } else {
      s.weights = best_weights;
    }
    if (!better || st.l2 > prev_l2 * (1.0 - options.min_improvement)) {
      if (++s.halvings > options.max_halvings) {
        s.done = true;
        break;
      }
      s.eta *= 0.5;
    }
  }
  res.time_yoshizawa += seconds_since(t1);
  res.solver_fallbacks = s.solver->fallbacks() - s.fallbacks0;
  report_progress(options.progress, "yoshizawa", 1.0);
}

/// The Floater embedding of \p disk into res; the weights and solver into \p s. With \p parent,
/// the disk is a sub-disk of the solver of \p parent (see parameterize_subdisk()); without it,
/// \p keep_pattern keeps a copy of the weights for later sub-disks.
DiskParamResult floater_embedding(const TriMesh& disk, const std::vector<int>& boundary_loop,
                                  const DiskParamOptions& options, DiskParamState& s,
                                  const DiskParamState* parent, const std::vector<int>* to_pattern,
                                  bool keep_pattern) {
  if (disk.num_faces() == 0) throw TopologyError("parameterize_disk: mesh has no faces");
  const auto t0 = std::chrono::steady_clock::now();
  report_progress(options.progress, "floater", 0.0);
  const std::vector<int> loop = boundary_loop.empty() ? disk_boundary_loop(disk) : boundary_loop;
  for (int v : loop)
    if (v < 0 || v >= disk.num_vertices())
      throw TopologyError("parameterize_disk: boundary loop vertex " + std::to_string(v) +
                          " out of range");
  const DiskBoundary boundary = map_boundary_to_square(disk, loop);
  const int nv = disk.num_vertices();
  std::vector<char> is_boundary(nv, 0);
  DiskParamResult res;
  res.on_square = boundary.on_square;
  res.uv.assign(nv, Vec2(0.5, 0.5));
  for (size_t i = 0; i < boundary.loop.size(); ++i) {
    is_boundary[boundary.loop[i]] = 1;
    res.uv[boundary.loop[i]] = boundary.uv[i];
  }
  if (parent && parent->pattern_weights) {
    s.weights = compute_subdisk_weights(disk, is_boundary, options.weights,
                                        *parent->pattern_weights, *to_pattern);
    s.solver = parent->solver;
    s.pattern_weights = parent->pattern_weights;
    s.sub_map = s.solver->map_subdisk(s.weights, *to_pattern);
    s.subdisk = true;
  } else {
    s.weights = compute_embedding_weights(disk, is_boundary, options.weights);
    s.solver = std::make_shared<TutteSolver>(s.weights, is_boundary, options.backend);
    // Kept for sub-disks only when they can use this solver (a state is returned, direct backend).
    if (keep_pattern && s.solver->backend() != TutteSolver::Backend::Multigrid)
      s.pattern_weights = std::make_shared<const ConvexWeights>(s.weights);
  }
  s.solver->set_max_iterations(options.max_solver_iterations);
  s.fallbacks0 = s.solver->fallbacks();
  s.solve(res.uv);
  const StretchStats st = measure_stretch(disk, res.uv, s.face_l2);  // face_l2: for Yoshizawa
  res.floater_l2 = res.final_l2 = st.l2;
  res.floater_linf = res.final_linf = st.linf;
  res.flipped = st.flipped;
  res.degenerate = st.degenerate;
  s.floater_ok = std::isfinite(st.l2);
  res.time_floater = seconds_since(t0);
  report_progress(options.progress, "floater", 1.0);
  res.solver_fallbacks = s.solver->fallbacks() - s.fallbacks0;
  return res;
}

}  // namespace

DiskParamResult parameterize_disk(const TriMesh& disk, const std::vector<int>& boundary_loop,
                                  const DiskParamOptions& options, DiskParamStatePtr* state) {
  DiskParamStatePtr s(new DiskParamState);
  DiskParamResult res =
      floater_embedding(disk, boundary_loop, options, *s, nullptr, nullptr, state != nullptr);
  run_yoshizawa(disk, *s, options, res);
  if (state) *state = std::move(s);
  return res;
}

DiskParamResult parameterize_disk(const TriMesh& disk, const std::vector<int>& boundary_loop,
                                  const DiskParamOptions& options) {
  return parameterize_disk(disk, boundary_loop, options, nullptr);
}

DiskParamResult parameterize_subdisk(const TriMesh& disk, const std::vector<int>& boundary_loop,
                                     const std::vector<int>& to_pattern, const DiskParamState& parent,
                                     const DiskParamOptions& options, DiskParamStatePtr* state) {
  if (static_cast<int>(to_pattern.size()) != disk.num_vertices())
    throw InvalidInputError("parameterize_subdisk: to_pattern has " +
                            std::to_string(to_pattern.size()) + " entries for " +
                            std::to_string(disk.num_vertices()) + " vertices");
  DiskParamStatePtr s(new DiskParamState);
  DiskParamResult res =
      floater_embedding(disk, boundary_loop, options, *s, &parent, &to_pattern, false);
  run_yoshizawa(disk, *s, options, res);
  if (state) *state = std::move(s);
  return res;
}

std::vector<double> result_vertex_stretch(const TriMesh& disk, DiskParamState& state,
                                          const DiskParamResult& result) {
  if (!state.started) return vertex_stretch(disk, result.uv);
  if (state.sigma_stale) {
    state.sigma = vertex_stretch(disk, state.face_l2, state.face_areas);
    state.sigma_stale = false;
  }
  return state.sigma;
}

DiskParamResult continue_disk_param(const TriMesh& disk, DiskParamState& state,
                                    const DiskParamResult& previous,
                                    const DiskParamOptions& options) {
  DiskParamResult res = previous;
  run_yoshizawa(disk, state, options, res);
  return res;
}

}  // namespace adaptex
