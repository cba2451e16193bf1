#pragma once
// ADAPTEX_TEST_ASAN is defined when the test is built with AddressSanitizer (GCC or clang), whose
// allocator and shadow memory change what malloc counters and the resident set show.
#if defined(__SANITIZE_ADDRESS__)
#define ADAPTEX_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ADAPTEX_TEST_ASAN 1
#endif
#endif
