/// \file orientation.cpp
/// Consistent face winding by propagation across manifold edges (orientation.h).
#include "adaptex/core/orientation.h"

#include <utility>


namespace adaptex {

namespace {

/// Does face t traverse the edge a -> b (rather than b -> a)?
bool has_directed(const Face& t, int a, int b) {
  for (int k = 0; k < 3; ++k)
    if (t[k] == a && t[(k + 1) % 3] == b) return true;
  return false;
}

}  // namespace

FaceOrientation orient_faces(const TriMesh& mesh) { return orient_faces(mesh, build_edges(mesh)); }

FaceOrientation orient_faces(const TriMesh& mesh, const EdgeConnectivity& ec) {
  const int nf = mesh.num_faces();
  FaceOrientation out;
  out.flip.assign(nf, 0);
  out.non_orientable.assign(nf, 0);
  std::vector<char> seen(nf, 0);
  std::vector<int> piece;
  for (int seed = 0; seed < nf; ++seed) {
    if (seen[seed]) continue;
    // Breadth-first over the piece; flip[f] relative to the seed.
    piece.assign(1, seed);
    seen[seed] = 1;
    bool orientable = true;
    for (size_t head = 0; head < piece.size(); ++head) {
      const int f = piece[head];
      for (int k = 0; k < 3; ++k) {
        const auto& fs = ec.edge_faces[ec.face_edges[f][k]];
        if (fs.size() != 2) continue;
        const int g = fs[0] == f ? fs[1] : fs[0];
        const int a = mesh.faces[f][k], b = mesh.faces[f][(k + 1) % 3];
        // Consistent: g traverses b -> a. Then g keeps f's relative winding.
        const char want = static_cast<char>(out.flip[f] ^ (has_directed(mesh.faces[g], a, b) ? 1 : 0));
        if (!seen[g]) {
          seen[g] = 1;
          out.flip[g] = want;
          piece.push_back(g);
        } else if (out.flip[g] != want) {
          orientable = false;
        }
      }
    }
    long flipped = 0;
    for (int f : piece) flipped += out.flip[f];
    const bool invert = 2 * flipped > static_cast<long>(piece.size());
    for (int f : piece) {
      if (!orientable) {
        out.flip[f] = 0;
        out.non_orientable[f] = 1;
        ++out.num_non_orientable_faces;
        continue;
      }
      out.flip[f] = static_cast<char>(out.flip[f] ^ (invert ? 1 : 0));
      out.num_flipped += out.flip[f];
    }
  }
  return out;
}

void apply_orientation(TriMesh& mesh, const FaceOrientation& orientation) {
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    if (orientation.flip[f]) std::swap(mesh.faces[f][1], mesh.faces[f][2]);
}

}  // namespace adaptex
