// Whether the tests run under AddressSanitizer, whose allocator reports and
// aborts on a failed allocation instead of throwing std::bad_alloc: tests
// of a memory limit skip there.
#pragma once

namespace relight::test {

#if defined(__SANITIZE_ADDRESS__)
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
