// core/allocator.h: after keep_freed_memory_in_process(), a large block comes from the heap (not
// from its own mmap) and stays in the process when freed.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "adaptex/core/allocator.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "../asan_detect.h"

namespace adaptex {
namespace {

#if defined(__GLIBC__)
// AddressSanitizer's allocator replaces glibc's: the tests of glibc's settings do not apply.
#if defined(ADAPTEX_TEST_ASAN)
#define SKIP_UNDER_ASAN() GTEST_SKIP() << "AddressSanitizer's allocator replaces glibc's"
#else
#define SKIP_UNDER_ASAN() static_cast<void>(0)
#endif

/// The block size of the tests below: over the default mmap threshold, under the kept one.
constexpr size_t kBlock = 16u << 20;

TEST(Allocator, LargeBlocksComeFromTheHeapAndStayInTheProcess) {
  SKIP_UNDER_ASAN();
  ASSERT_TRUE(keep_freed_memory_in_process());
  const size_t bytes = 8u << 20;  // 8 MiB: over glibc's default mmap threshold (128 KiB, dynamic to 32 MiB)
  const struct mallinfo2 before = mallinfo2();
  void* p = std::malloc(bytes);
  ASSERT_NE(p, nullptr);
  std::memset(p, 1, bytes);
  const struct mallinfo2 during = mallinfo2();
  // Not a separate mapping: the number and bytes of mmapped blocks did not grow.
  EXPECT_EQ(during.hblks, before.hblks);
  EXPECT_EQ(during.hblkhd, before.hblkhd);
  std::free(p);
  // Freed, the block is kept as free heap (trim threshold 1 GiB), not returned to the system. (Not
  // asserted: that the heap grew by the block; an earlier test in the same process may have left
  // free heap that the block reused.)
  const struct mallinfo2 after = mallinfo2();
  EXPECT_GE(after.fordblks, bytes);
}

/// How far apart (bytes) a block of kBlock bytes that a worker thread allocated, wrote and freed
/// and a block of the same size that the main thread then allocates are.
std::uintptr_t distance_of_thread_and_main_blocks() {
  std::uintptr_t b = 0;  // the addresses, taken before each free
  std::thread([&] {
    void* in_thread = std::malloc(kBlock);
    if (in_thread) std::memset(in_thread, 1, kBlock);
    b = reinterpret_cast<std::uintptr_t>(in_thread);
    std::free(in_thread);
  }).join();
  void* in_main = std::malloc(kBlock);
  const auto a = reinterpret_cast<std::uintptr_t>(in_main);
  std::free(in_main);
  EXPECT_NE(a, 0u);
  EXPECT_NE(b, 0u);
  return a > b ? a - b : b - a;
}

TEST(Allocator, AWorkerThreadsFreedBlockIsReusedByTheMainThread) {
  SKIP_UNDER_ASAN();
  // One arena (M_ARENA_MAX 1): a block that another thread allocated and freed goes back to the
  // heap the main thread allocates from, so the same request gets (nearly) the same memory. With glibc's
  // thread arenas the thread's block lives in its own arena's heap and the main thread's request
  // is served elsewhere. (CTest runs this test in a process of its own: threads that earlier tests
  // of the same program started could already own arenas.)
  ASSERT_TRUE(keep_freed_memory_in_process());
  // The two blocks overlap (the thread's own bookkeeping may shift the start by a few hundred bytes).
  EXPECT_LT(distance_of_thread_and_main_blocks(), kBlock);
}

TEST(Allocator, PerThreadArenasKeepAWorkerThreadsBlockInItsOwnHeap) {
  SKIP_UNDER_ASAN();
  // ArenaPolicy::PerThread leaves glibc's thread arenas on: the worker's block is in its own
  // arena's heap, so the main thread's request of the same size is served far from it (the
  // opposite of the test above; its own process, as above).
  ASSERT_TRUE(keep_freed_memory_in_process(ArenaPolicy::PerThread));
  EXPECT_GE(distance_of_thread_and_main_blocks(), kBlock);
}

TEST(Allocator, TheEnvironmentChoosesTheHeaps) {
  SKIP_UNDER_ASAN();
  // ADAPTEX_MALLOC_ARENAS=per-thread overrides a program's one heap: as the test above (its own
  // process).
  ASSERT_EQ(unsetenv("ADAPTEX_DEFAULT_MALLOC"), 0);
  ASSERT_EQ(setenv("ADAPTEX_MALLOC_ARENAS", "per-thread", 1), 0);
  ASSERT_TRUE(keep_freed_memory_in_process_unless_disabled(ArenaPolicy::Shared));
  EXPECT_GE(distance_of_thread_and_main_blocks(), kBlock);
}
#else
TEST(Allocator, DoesNothingWithoutGlibc) { EXPECT_FALSE(keep_freed_memory_in_process()); }
#endif

}  // namespace
}  // namespace adaptex
