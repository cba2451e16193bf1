// Surface points carried to a conforming refinement of their mesh.
#include "adaptex/paint/point_transfer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <string>

#include "adaptex/core/errors.h"

namespace adaptex {

namespace {
/// Children of every face of the parent mesh, CSR: children[start[f] .. start[f + 1]).
struct ChildLists {
  std::vector<int> start, children;
};

ChildLists child_lists(int parent_faces, const FaceData<int>& parent_face) {
  ChildLists c;
  c.start.assign(static_cast<size_t>(parent_faces) + 1, 0);
  c.children.resize(parent_face.size());
  for (int p : parent_face) {
    if (p < 0 || p >= parent_faces)
      throw InvalidInputError("transfer_points: parent face " + std::to_string(p) + " out of range [0, " +
                              std::to_string(parent_faces) + ")");
    ++c.start[p + 1];
  }
  for (int f = 0; f < parent_faces; ++f) c.start[f + 1] += c.start[f];
  std::vector<int> fill(c.start.begin(), c.start.end() - 1);
  for (size_t k = 0; k < parent_face.size(); ++k) c.children[fill[parent_face[k]]++] = static_cast<int>(k);
  return c;
}

/// The child of \p parent holding the 3-D point \p p (the one it is deepest inside), with clamped
/// barycentrics; a child's centre when every child is degenerate.
SurfacePoint locate(const Vec3& p, int parent, const TriMesh& to, const ChildLists& c) {
  double best = -std::numeric_limits<double>::infinity();
  SurfacePoint out;
  bool found = false;
  for (int q = c.start[parent]; q < c.start[parent + 1]; ++q) {
    const int child = c.children[q];
    const Face& f = to.faces[child];
    const Vec3 e1 = to.positions[f[1]] - to.positions[f[0]], e2 = to.positions[f[2]] - to.positions[f[0]];
    const Vec3 d = p - to.positions[f[0]];
    const double a11 = e1.dot(e1), a12 = e1.dot(e2), a22 = e2.dot(e2), det = a11 * a22 - a12 * a12;
    if (!(det > 0)) continue;
    const double l1 = (a22 * e1.dot(d) - a12 * e2.dot(d)) / det, l2 = (a11 * e2.dot(d) - a12 * e1.dot(d)) / det;
    const double inside = std::min({1 - l1 - l2, l1, l2});
    if (inside > best) {
      best = inside;
      found = true;
      const double c1 = std::clamp(l1, 0.0, 1.0), c2 = std::clamp(l2, 0.0, 1.0 - c1);
      out = SurfacePoint{child, 1 - c1 - c2, c1};
    }
  }
  if (!found)  // only degenerate children: any child's centre (same parent face, same surface)
    out = SurfacePoint{c.start[parent] < c.start[parent + 1] ? c.children[c.start[parent]] : parent, 1.0 / 3, 1.0 / 3};
  return out;
}
}  // namespace

std::vector<SurfacePoint> transfer_points(const std::vector<SurfacePoint>& pts, const TriMesh& from,
                                          const TriMesh& to, const FaceData<int>& parent_face) {
  if (parent_face.size() != to.faces.size())
    throw InvalidInputError("transfer_points: " + std::to_string(parent_face.size()) + " parent indices for " +
                            std::to_string(to.faces.size()) + " faces");
  const ChildLists c = child_lists(from.num_faces(), parent_face);
  std::vector<SurfacePoint> out(pts.size());
  tbb::parallel_for(size_t(0), pts.size(), [&](size_t k) {
    const Vec3 p = point_on_face(from, pts[k].face, pts[k].b0, pts[k].b1);
    out[k] = locate(p, pts[k].face, to, c);
  });
  return out;
}

}  // namespace adaptex
