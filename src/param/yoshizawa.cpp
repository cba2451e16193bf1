/// \file yoshizawa.cpp
/// Yoshizawa–Belyaev–Seidel 2004 re-weighting (thesis §2.2, §3.3).
#include "adaptex/param/yoshizawa.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "adaptex/param/stretch.h"

namespace adaptex {

std::vector<double> vertex_stretch(const TriMesh& mesh, const std::vector<Vec2>& uv) {
  const int nf = mesh.num_faces();
  std::vector<double> areas(nf);
  for (int f = 0; f < nf; ++f) areas[f] = face_area(mesh, f);
  return vertex_stretch(mesh, face_l2_stretch(mesh, uv), areas);  // normalized: ΣA₂ = ΣA₃ scale
}

std::vector<double> vertex_stretch(const TriMesh& mesh, const std::vector<double>& l2,
                                   const std::vector<double>& face_areas) {
  const int nv = mesh.num_vertices(), nf = mesh.num_faces();
  std::vector<double> num(nv, 0.0), den(nv, 0.0);
  for (int f = 0; f < nf; ++f) {
    const double a3 = face_areas[f];
    if (!(a3 > 0)) continue;  // zero-area 3-D face (scan artefact): no say in the stretch
    const double s2 = std::isfinite(l2[f]) ? l2[f] * l2[f] : std::numeric_limits<double>::infinity();
    for (int v : mesh.faces[f]) {
      num[v] += a3 * s2;
      den[v] += a3;
    }
  }
  std::vector<double> sigma(nv, 1.0);
  for (int v = 0; v < nv; ++v)
    if (den[v] > 0) sigma[v] = std::sqrt(num[v] / den[v]);
  return sigma;
}

void yoshizawa_reweight(ConvexWeights& w, const std::vector<double>& sigma, double eta) {
  const int nv = w.num_vertices();
  std::vector<double> factor(sigma.size());
  for (size_t v = 0; v < sigma.size(); ++v) {
    // Regularized: a stretch of 0 or inf (degenerate elements) must not zero or blow up a weight.
    const double sg = std::isfinite(sigma[v]) ? std::clamp(sigma[v], 1e-8, 1e8) : 1e8;
    factor[v] = eta == 1.0 ? 1.0 / sg : std::pow(sg, -eta);
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, nv, 4096), [&](const tbb::blocked_range<int>& r) {
    for (int v = r.begin(); v != r.end(); ++v) {
      const int b = w.offsets[v], e = w.offsets[v + 1];
      if (b == e) continue;
      double sum = 0;
      for (int k = b; k < e; ++k) {
        w.values[k] *= factor[w.neighbors[k]];
        sum += w.values[k];
      }
      for (int k = b; k < e; ++k) w.values[k] /= sum;
    }
  });
}

}  // namespace adaptex
