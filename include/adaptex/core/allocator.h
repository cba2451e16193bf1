#pragma once
/// \file allocator.h
/// Process-wide allocator settings for programs that build and free large buffers over and over
/// (a texel map, a painter, a density raster per re-parameterization).

namespace adaptex {

/// With glibc, keeps freed memory in the process instead of returning it to the system after every
/// large free: blocks up to 32 MiB come from the heap (M_MMAP_THRESHOLD; glibc's default starts at
/// 128 KiB, so a 1024² texel map is mapped and unmapped at each use) and up to 1 GiB of free heap
/// top is kept (M_TRIM_THRESHOLD), and every thread allocates from that one heap (M_ARENA_MAX 1;
/// call it before starting threads). Without it, each fresh buffer is paid in page faults: half of
/// building a 1024² Painter (94 -> 44 ms, `bench_paint --benchmark_filter=PainterSetup`,
/// docs/history/benchmarks.md, the allocator). The price is that the resident size stays at its peak until
/// the process ends. Called by the adaptex programs (CLI, studio, benchmarks) at the start of
/// main(); a program that embeds the library decides for itself. Other C libraries: no effect.
/// \return true if the settings were applied (glibc).
bool keep_freed_memory_in_process();

/// keep_freed_memory_in_process() unless the environment variable ADAPTEX_DEFAULT_MALLOC is set
/// (to anything): the adaptex programs call this, so that glibc's defaults can be measured against.
/// \return true if the settings were applied.
bool keep_freed_memory_in_process_unless_disabled();

}  // namespace adaptex
