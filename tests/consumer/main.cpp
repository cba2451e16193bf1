// Downstream use of the installed library: build a mesh in code, unwrap it, check the result.
#include <adaptex/core/shapes.h>
#include <adaptex/param/unwrap.h>

#include <cstdio>

int main() {
  const adaptex::TriMesh mesh = adaptex::shapes::sphere(24, 12);
  const adaptex::UnwrapResult r = adaptex::unwrap(mesh);
  std::printf("consumer: %d faces, %d charts, L2 stretch %.4f\n", mesh.num_faces(),
              r.param.num_charts, r.report.final_l2);
  return r.param.uv_faces.size() == mesh.faces.size() && r.report.final_l2 >= 1.0 ? 0 : 1;
}
