// Geometry-stretch map of thesis §3.5 / Fig. 3.8.
#include "adaptex/adapt/stretch_map.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/param/stretch.h"

namespace adaptex {

std::vector<float> normalized_face_stretch(const TriMesh& mesh, const Parameterization& param, double* reference) {
  const std::vector<double> l2 = face_l2_stretch(mesh, param);
  const int F = mesh.num_faces();
  // Area-weighted 99th percentile of the finite values.
  std::vector<int> order;
  order.reserve(F);
  double total = 0;
  std::vector<double> area(F);
  for (int f = 0; f < F; ++f) {
    area[f] = face_area(mesh, f);
    if (std::isfinite(l2[f])) {
      order.push_back(f);
      total += area[f];
    }
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) { return l2[a] < l2[b]; });
  double ref = 1.0, acc = 0;
  for (int f : order) {
    acc += area[f];
    ref = l2[f];
    if (acc >= 0.99 * total) break;
  }
  if (reference) *reference = ref;
  // Excess stretch: faces at or below the ideal 1 (over-sampled) get 0, the reference gets 1.
  const double span = ref - 1.0;
  std::vector<float> out(F);
  for (int f = 0; f < F; ++f) {
    if (!std::isfinite(l2[f])) out[f] = 1.0f;
    else if (!(span > 1e-9)) out[f] = 0.0f;
    else out[f] = static_cast<float>(std::clamp((l2[f] - 1.0) / span, 0.0, 1.0));
  }
  return out;
}

ImageF rasterize_face_values(const TexelMap& map, const std::vector<float>& values, float outside) {
  ImageF out(map.width, map.height, outside);
  tbb::parallel_for(size_t(0), map.inside.size(), [&](size_t k) {
    const int t = map.inside[k];
    out.data[t] = values[map.face[t]];
  });
  return out;
}

ImageF compute_stretch_map(const TriMesh& mesh, const Parameterization& param, const TexelMap& map) {
  if (map.width <= 0 || map.height <= 0) throw InvalidInputError("compute_stretch_map: empty texel map");
  if (param.uv_faces.size() != mesh.faces.size())
    throw InvalidInputError("compute_stretch_map: parameterization has " + std::to_string(param.uv_faces.size()) +
                            " faces, mesh has " + std::to_string(mesh.faces.size()));
  return rasterize_face_values(map, normalized_face_stretch(mesh, param));
}

}  // namespace adaptex
