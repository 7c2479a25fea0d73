#pragma once
// Wall-time limits that tests assert (a stage stops within 1 s of Cancel, an analysis runs in
// seconds): a sanitized build (COLONMAP_SANITIZE; GCC and clang define __SANITIZE_ADDRESS__)
// runs 4-5 times slower here, so there the limits are ten times wider, still finite.
namespace colonmap {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr double kTimeLimitScale = 10.0;
#else
inline constexpr double kTimeLimitScale = 1.0;
#endif

}  // namespace colonmap
