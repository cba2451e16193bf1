#pragma once
/// \file allocator.h
/// Process-wide allocator settings for programs that build and free large buffers over and over
/// (a texel map, a painter, a density raster per re-parameterization).

namespace adaptex {

/// Which heaps the threads allocate from under keep_freed_memory_in_process().
enum class ArenaPolicy {
  /// One heap for all threads (M_ARENA_MAX 1): a block a worker thread freed is reused by any
  /// thread, at the price of one lock for all (programs that build and free large buffers in
  /// worker threads: the painter, the each-stroke adaptation).
  Shared,
  /// glibc's own arenas, up to 8 per core: no lock shared by the threads, but a worker thread's
  /// large blocks live in heaps that are unmapped when they empty (many small allocations from
  /// every thread: the scan unwrap, docs/decisions.md, "Scans: unwrap and paint allocate from
  /// per-thread heaps").
  PerThread,
};

/// With glibc, keeps freed memory in the process instead of returning it to the system after every
/// large free: blocks up to 32 MiB come from the heap (M_MMAP_THRESHOLD; glibc's default starts at
/// 128 KiB, so a 1024² texel map is mapped and unmapped at each use) and up to 1 GiB of free heap
/// top is kept (M_TRIM_THRESHOLD), and with ArenaPolicy::Shared every thread allocates from that
/// one heap (M_ARENA_MAX 1; call it before starting threads). Without it, each fresh buffer is paid in page faults: half of
/// building a 1024² Painter (94 -> 44 ms, `bench_paint --benchmark_filter=PainterSetup`,
/// docs/history/benchmarks.md, the allocator). The price is that the resident size stays at its peak until
/// the process ends. Called by the adaptex programs (CLI, studio, benchmarks) at the start of
/// main(); a program that embeds the library decides for itself. Other C libraries: no effect.
/// \param arenas ArenaPolicy::Shared (default) or ArenaPolicy::PerThread.
/// \return true if the settings were applied (glibc).
bool keep_freed_memory_in_process(ArenaPolicy arenas = ArenaPolicy::Shared);

/// keep_freed_memory_in_process() unless the environment variable ADAPTEX_DEFAULT_MALLOC is set
/// (to anything): the adaptex programs call this, so that glibc's defaults can be measured against.
/// ADAPTEX_MALLOC_ARENAS=shared or per-thread overrides \p arenas (other values are ignored).
/// \param arenas as in keep_freed_memory_in_process().
/// \return true if the settings were applied.
bool keep_freed_memory_in_process_unless_disabled(ArenaPolicy arenas = ArenaPolicy::Shared);

}  // namespace adaptex
