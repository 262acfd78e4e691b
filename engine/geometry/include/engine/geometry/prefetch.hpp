#pragma once
/// @file Asking for memory before it is needed, for passes that go through a mesh in order
/// but reach their vertices' data at random.
///
/// Meshes whose triangles come in no spatial order (some exporters, shuffled or merged scans)
/// number their vertices in no useful order either, so each triangle's corners, counters and
/// set parents are cache misses. The addresses are known many triangles ahead, and a prefetch a
/// few triangles early overlaps those misses: on a shuffled million-triangle torus the integrals
/// went from 82-131 to 32-42 ms and the parts from 16-22 to 16-17 ms, for ~1 ms more on the
/// same torus in order (docs/performance.md). The edge counts and the weld gained nothing from it
/// (measured), so they go without.

#include <cstddef>

namespace tumble::engine::detail {

/// How many triangles ahead the passes ask for what they will need.
inline constexpr std::size_t kPrefetchDistance = 16;

/// Hints the processor to bring `address` into the cache (for reading, or for writing when
/// `for_write`). Only a hint: it never faults, and compilers without it ignore it.
template <bool for_write = false, typename T>
inline void prefetch(const T* address) {
#if defined(__GNUC__)
  __builtin_prefetch(address, for_write ? 1 : 0);
#else
  (void)address;
#endif
}

}  // namespace tumble::engine::detail
