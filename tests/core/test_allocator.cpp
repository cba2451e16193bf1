// core/allocator.h: after keep_freed_memory_in_process(), a large block comes from the heap (not
// from its own mmap) and stays in the process when freed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#include "adaptex/core/allocator.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

// AddressSanitizer replaces malloc: glibc's settings and counters do not apply there.
#if defined(__SANITIZE_ADDRESS__)
#define ADAPTEX_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ADAPTEX_TEST_ASAN 1
#endif
#endif

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
#else
TEST(Allocator, DoesNothingWithoutGlibc) { EXPECT_FALSE(keep_freed_memory_in_process()); }
#endif

}  // namespace
}  // namespace adaptex
