// Speed of reading and writing a scan-sized mesh as `adaptex unwrap --repair` does: the OBJ text by
// the plain-OBJ reader and by tinyobjloader's path (forced by a `cstype` line the plain reader
// leaves to it), a binary PLY, each with the read-time validation and repair; and write_obj() with
// a layout. The mesh: shapes::synthetic_scan() (966 components, zero-area faces). Arg: target face
// count. docs/bench_unwrap.md, "Scan speed".
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "adaptex/core/shapes.h"
#include "adaptex/io/mesh_io.h"

namespace {

using namespace adaptex;

/// The scan, cached per face count (every benchmark of one count reads the same text).
const TriMesh& scan(int faces) {
  static std::map<int, TriMesh> meshes;
  auto it = meshes.find(faces);
  if (it == meshes.end()) it = meshes.emplace(faces, shapes::synthetic_scan(faces, 966, 1458)).first;
  return it->second;
}

/// The scan as the OBJ text write_obj() writes.
std::string obj_text(int faces) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "adaptex_bench_read.obj";
  write_obj(path, scan(faces), nullptr);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  std::filesystem::remove(path);
  return text.str();
}

/// The scan as a binary little-endian PLY (float positions, uchar + int face lists).
std::string ply_binary(int faces) {
  const TriMesh& m = scan(faces);
  std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(m.num_vertices()) +
                  "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                  std::to_string(m.num_faces()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& p : m.positions)
    for (int k = 0; k < 3; ++k) {
      const float x = static_cast<float>(p[k]);
      s.append(reinterpret_cast<const char*>(&x), sizeof x);
    }
  for (const Face& t : m.faces) {
    s += '\3';
    s.append(reinterpret_cast<const char*>(t.data()), 3 * sizeof(int));
  }
  return s;
}

void read_bench(benchmark::State& state, const std::string& text, const char* format) {
  ReadOptions options;
  options.repair = true;
  int faces = 0;
  for (auto _ : state) faces = read_mesh_from_memory(text, format, "scan", options).num_faces();
  state.counters["faces"] = faces;
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * text.size()));
}

void BM_ReadPlainObj(benchmark::State& state) {
  read_bench(state, obj_text(static_cast<int>(state.range(0))), "obj");
}
void BM_ReadObjTinyobjloader(benchmark::State& state) {
  read_bench(state, obj_text(static_cast<int>(state.range(0))) + "cstype bmatrix\n", "obj");
}
void BM_ReadBinaryPly(benchmark::State& state) {
  read_bench(state, ply_binary(static_cast<int>(state.range(0))), "ply");
}

void BM_WriteObj(benchmark::State& state) {
  const TriMesh& m = scan(static_cast<int>(state.range(0)));
  Parameterization param;  // one wedge per vertex, a layout-sized vt block
  for (int v = 0; v < m.num_vertices(); ++v) {
    param.uv.emplace_back(m.positions[v].x() - std::floor(m.positions[v].x()), 0.5);
    param.wedge_vertex.push_back(v);
  }
  param.uv_faces = m.faces;
  param.face_chart.assign(m.faces.size(), 0);
  param.num_charts = 1;
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "adaptex_bench_write.obj";
  for (auto _ : state) write_obj(path, m, &param);
  std::filesystem::remove(path);
  state.counters["faces"] = m.num_faces();
}

BENCHMARK(BM_ReadPlainObj)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReadObjTinyobjloader)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ReadBinaryPly)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_WriteObj)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
