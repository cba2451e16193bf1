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
TEST(Allocator, LargeBlocksComeFromTheHeapAndStayInTheProcess) {
#if defined(ADAPTEX_TEST_ASAN)
  GTEST_SKIP() << "AddressSanitizer's allocator replaces glibc's";
#endif
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

TEST(Allocator, AWorkerThreadsFreedBlockIsReusedByTheMainThread) {
#if defined(ADAPTEX_TEST_ASAN)
  GTEST_SKIP() << "AddressSanitizer's allocator replaces glibc's";
#endif
  // One arena (M_ARENA_MAX 1): a block that another thread allocated and freed goes back to the
  // heap the main thread allocates from, so the same request gets (nearly) the same memory. With glibc's
  // thread arenas the thread's block lives in its own arena's heap and the main thread's request
  // is served elsewhere. (CTest runs this test in a process of its own: threads that earlier tests
  // of the same program started could already own arenas.)
  ASSERT_TRUE(keep_freed_memory_in_process());
  const size_t bytes = 16u << 20;
  void* in_thread = nullptr;
  std::thread([&] {
    in_thread = std::malloc(bytes);
    ASSERT_NE(in_thread, nullptr);
    std::memset(in_thread, 1, bytes);
    std::free(in_thread);
  }).join();
  void* in_main = std::malloc(bytes);
  ASSERT_NE(in_main, nullptr);
  // The two blocks overlap (the thread's own bookkeeping may shift the start by a few hundred bytes).
  const auto a = reinterpret_cast<std::uintptr_t>(in_main), b = reinterpret_cast<std::uintptr_t>(in_thread);
  EXPECT_LT(a > b ? a - b : b - a, bytes);
  std::free(in_main);
}
#else
TEST(Allocator, DoesNothingWithoutGlibc) { EXPECT_FALSE(keep_freed_memory_in_process()); }
#endif

}  // namespace
}  // namespace adaptex
