#pragma once
/// \file bench_shared_mesh.h
/// What the Google Benchmark programs of bench/unwrap share: reading a mesh of ../shared/meshes
/// (skipping the benchmark when it is absent) and registering a benchmark timed in milliseconds
/// of wall time with the process CPU time beside it.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "adaptex/core/allocator.h"
#include "adaptex/core/mesh.h"
#include "adaptex/io/mesh_io.h"

namespace adaptex::bench {

/// ../shared/meshes/\p file, or std::nullopt (and \p state skipped with an error) when it is
/// absent. \throw IoError as read_mesh() when the file exists but cannot be read
inline std::optional<TriMesh> shared_mesh_or_skip(benchmark::State& state, const std::string& file) {
  const std::filesystem::path path = std::filesystem::path(ADAPTEX_SHARED_DIR) / "meshes" / file;
  if (!std::filesystem::exists(path)) {
    state.SkipWithError("mesh not available (../shared/meshes absent)");
    return std::nullopt;
  }
  return read_mesh(path);
}

/// Registers \p fn (void(benchmark::State&)) as benchmark \p name: milliseconds, wall time, process
/// CPU time.
template <class Fn>
void register_ms(const std::string& name, Fn fn) {
  benchmark::RegisterBenchmark(name.c_str(), std::move(fn))
      ->Unit(benchmark::kMillisecond)
      ->MeasureProcessCPUTime()
      ->UseRealTime();
}

/// Google Benchmark's main after the benchmarks are registered.
inline int run_benchmarks(int argc, char** argv) {
  // As the adaptex programs run (core/allocator.h); ADAPTEX_DEFAULT_MALLOC=1 measures glibc's defaults.
  keep_freed_memory_in_process_unless_disabled();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace adaptex::bench
