// Whether this build runs under AddressSanitizer (g++ defines __SANITIZE_ADDRESS__, clang has the feature): what
// such a build times is its allocator, and its tests may run shorter cases of the same code paths.
#pragma once

namespace smcbench {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitizedBuild = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kSanitizedBuild = true;
#else
inline constexpr bool kSanitizedBuild = false;
#endif
#else
inline constexpr bool kSanitizedBuild = false;
#endif

}  // namespace smcbench
