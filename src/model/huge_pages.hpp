// Line-sized arrays on transparent huge pages (internal to src/): at 10^6
// nodes each is megabytes, and faulting them in 4 KiB at a time is most of
// a run's start-up. A hint (Linux's madvise), given before the first touch;
// elsewhere, or where the system does not allow it, nothing changes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace barimpact::detail {

/// The whole 2 MiB pages inside [data, data + bytes), advised.
inline void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
  const auto at = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (at + huge - 1) & ~(huge - 1), last = (at + bytes) & ~(huge - 1);
  if (last > first) (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

/// v.reserve(n), its storage advised before anything touches it.
template <class T>
void reserve_huge(std::vector<T>& v, std::size_t n) {
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

/// v.assign(n, value) on advised storage.
template <class T>
void assign_huge(std::vector<T>& v, std::size_t n, const T& value) {
  if (v.capacity() < n) {
    v.clear();
    reserve_huge(v, n);
  }
  v.assign(n, value);
}

}  // namespace barimpact::detail
