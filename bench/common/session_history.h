#pragma once
/// \file session_history.h
/// The long painting history the session benchmarks replay (adaptex_bench_session,
/// adaptex_bench_studio_live): `mixed` sets of kSessionBatch strokes (each: 1/8 blobs, then lines in
/// one region) with seeds S, S+1, ..., concatenated to the wanted count. One mixed set of 1,000 would
/// be 125 blobs then 875 lines, so strokes 10 and 100 would both be blobs; batches keep the mix the
/// same along the history.
#include <cstdint>

#include "adaptex/core/mesh.h"
#include "adaptex/paint/generate.h"
#include "adaptex/paint/strokes.h"

namespace adaptex::bench {

constexpr int kSessionBatch = 40;

/// \p count strokes on \p mesh, the first batch with seed \p first_seed.
inline StrokeFile session_history(const TriMesh& mesh, int count, int first_seed) {
  StrokeFile out;
  for (int b = 0; static_cast<int>(out.strokes.size()) < count; ++b) {
    GenerateOptions go;
    go.kind = StrokeKind::Mixed;
    go.count = kSessionBatch;
    go.seed = static_cast<std::uint64_t>(first_seed + b);
    const StrokeFile f = generate_strokes(mesh, go);
    if (b == 0) out.background = f.background;
    for (const Stroke& st : f.strokes)
      if (static_cast<int>(out.strokes.size()) < count) out.strokes.push_back(st);
  }
  return out;
}

}  // namespace adaptex::bench
