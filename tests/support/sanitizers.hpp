// Whether the test executable is built with AddressSanitizer: CLMARCH_UNDER_ASAN. GCC defines
// __SANITIZE_ADDRESS__; clang 14 tells it through __has_feature only.
#pragma once

#if defined(__SANITIZE_ADDRESS__)
#define CLMARCH_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CLMARCH_UNDER_ASAN 1
#endif
#endif
