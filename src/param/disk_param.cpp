/// \file disk_param.cpp
/// Floater embedding + Yoshizawa stretch minimization of one disk (thesis §2.2, §3.3).
#include "adaptex/param/disk_param.h"

#include <chrono>
#include <cmath>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/topology.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/yoshizawa.h"

namespace adaptex {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

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

DiskParamResult parameterize_disk(const TriMesh& disk, const std::vector<int>& boundary_loop,
                                  const DiskParamOptions& options) {
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
  ConvexWeights weights = compute_embedding_weights(disk, is_boundary, options.weights);
  TutteSolver solver(weights, is_boundary, options.backend);
  solver.set_max_iterations(options.max_solver_iterations);
  solver.solve(weights, res.uv);
  StretchStats st = measure_stretch(disk, res.uv);
  res.floater_l2 = res.final_l2 = st.l2;
  res.floater_linf = res.final_linf = st.linf;
  res.time_floater = seconds_since(t0);
  report_progress(options.progress, "floater", 1.0);
  res.solver_fallbacks = solver.fallbacks();
  if (!options.yoshizawa || options.max_iterations <= 0 || !std::isfinite(st.l2)) return res;

  // Yoshizawa–Belyaev–Seidel: λ_vw ← λ_vw / σ_w^η, re-solve, keep the best iterate. When an iterate
  // does not lower L2 by min_improvement, restart from the best weights with η halved (a damped step);
  // stop after max_halvings failed halvings or max_iterations solves.
  const auto t1 = std::chrono::steady_clock::now();
  const int nf = disk.num_faces();
  std::vector<double> face_areas(nf), face_l2;
  for (int f = 0; f < nf; ++f) face_areas[f] = face_area(disk, f);
  measure_stretch(disk, res.uv, face_l2);
  std::vector<double> sigma = vertex_stretch(disk, face_l2, face_areas);  // of the best iterate
  std::vector<Vec2> cur = res.uv;
  ConvexWeights best_weights = weights;
  double eta = options.eta;
  int halvings = 0;
  for (int it = 1; it <= options.max_iterations; ++it) {
    report_progress(options.progress, "yoshizawa",
                    static_cast<double>(it - 1) / options.max_iterations);
    yoshizawa_reweight(weights, sigma, eta);
    cur = res.uv;
    solver.solve(weights, cur);
    st = measure_stretch(disk, cur, face_l2);
    res.iterations = it;
    const double prev_l2 = res.final_l2;
    const bool better = st.flipped == 0 && st.degenerate == 0 && st.l2 < res.final_l2;
    if (better) {
      res.uv.swap(cur);
      res.final_l2 = st.l2;
      res.final_linf = st.linf;
      best_weights = weights;
      if (it < options.max_iterations) sigma = vertex_stretch(disk, face_l2, face_areas);
    } else {
      weights = best_weights;
    }
    if (!better || st.l2 > prev_l2 * (1.0 - options.min_improvement)) {
      if (++halvings > options.max_halvings) break;
      eta *= 0.5;
    }
  }
  res.time_yoshizawa = seconds_since(t1);
  res.solver_fallbacks = solver.fallbacks();
  report_progress(options.progress, "yoshizawa", 1.0);
  return res;
}

}  // namespace adaptex
