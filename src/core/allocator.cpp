/// \file allocator.cpp
/// See allocator.h.
#include "adaptex/core/allocator.h"

#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace adaptex {

bool keep_freed_memory_in_process(ArenaPolicy arenas) {
#if defined(__GLIBC__)
  // 32 MiB is glibc's largest accepted mmap threshold on 64-bit (DEFAULT_MMAP_THRESHOLD_MAX);
  // setting either value also turns off glibc's dynamic adjustment of both.
  const bool mmap_ok = mallopt(M_MMAP_THRESHOLD, 32 * 1024 * 1024) == 1;
  const bool trim_ok = mallopt(M_TRIM_THRESHOLD, 1024 * 1024 * 1024) == 1;
  // One arena: a worker thread's block then comes from the same kept heap. A thread arena's heaps
  // are at most 64 MiB each and are unmapped when they empty, so the blocks that TBB's workers
  // allocate (a painter's index and padding built side by side) were paid in page faults again
  // (2048² Painter: 314 ms with thread arenas, 196 ms with one).
  const bool arena_ok = arenas == ArenaPolicy::PerThread || mallopt(M_ARENA_MAX, 1) == 1;
  return mmap_ok && trim_ok && arena_ok;
#else
  (void)arenas;
  return false;
#endif
}

bool keep_freed_memory_in_process_unless_disabled(ArenaPolicy arenas) {
  if (const char* a = std::getenv("ADAPTEX_MALLOC_ARENAS")) {
    if (std::strcmp(a, "shared") == 0) arenas = ArenaPolicy::Shared;
    if (std::strcmp(a, "per-thread") == 0) arenas = ArenaPolicy::PerThread;
  }
  return std::getenv("ADAPTEX_DEFAULT_MALLOC") == nullptr && keep_freed_memory_in_process(arenas);
}

}  // namespace adaptex
