// Whether the tests run under AddressSanitizer, whose allocator reports and
// aborts on a failed allocation instead of throwing std::bad_alloc: tests
// of a memory limit skip there. The sanitizer build compiles the tests
// themselves uninstrumented (tests/CMakeLists.txt) and says so with
// RELIGHT_ADDRESS_SANITIZER.
#pragma once

namespace relight::test {

#if defined(__SANITIZE_ADDRESS__) || defined(RELIGHT_ADDRESS_SANITIZER)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

}  // namespace relight::test
