// The command's heap on transparent huge pages. A run's start-up is mostly
// the kernel faulting its line-sized arrays in, 4 KiB at a time: a one-step
// run of a 10^5-element bar took 2,700 faults, an elastic-plastic one
// 12,400 (its matrices and their temporaries). Here arrays up to 32 MiB come
// from the heap, grown once by 64 MiB of address space (nothing touched)
// and advised for 2 MiB pages, and what is freed is reused, not returned.
// The price: huge pages count whole, so a small run's resident peak is a
// few MB above what it touches (21 MB instead of 15 at 10^3 elements).
// The library never sets this: its host (Python, another program) owns its
// own heap. Skipped under an address-space limit (ulimit -v), where the
// reservation could crowd out the run, and where the heap is not brk's.
#pragma once

#include <cstdint>
#include <cstdlib>  // first: it defines __GLIBC__

#if defined(__linux__) && defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>
#if __GLIBC_PREREQ(2, 33) && defined(MADV_HUGEPAGE)
#define BARIMPACT_HUGE_HEAP  // mallinfo2, the heap's free top, is glibc 2.33's
#endif
#endif

namespace barimpact_cli {

inline void prefer_huge_pages() {
#if defined(BARIMPACT_HUGE_HEAP)
  rlimit space{};
  if (getrlimit(RLIMIT_AS, &space) != 0 || space.rlim_cur != RLIM_INFINITY) return;
  constexpr std::uintptr_t huge = std::uintptr_t{2} << 20;
  constexpr int largest_from_heap = 32 << 20, reserve = 64 << 20;
  mallopt(M_MMAP_THRESHOLD, largest_from_heap);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_TOP_PAD, reserve);
  // One allocation grows the heap and fills its unaligned head: it ends just
  // below the first 2 MiB boundary past the break, where malloc writes the
  // new top's header, and moves brk by the 64 MiB pad past it. Nothing else
  // is touched, so that every 2 MiB page from that boundary on can be a huge
  // one, the first arrays a run makes (the line's nodes) among them. Kept
  // for the process's life, never touched.
  const auto before = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t top = before - mallinfo2().keepcost;  // the heap's free top
  constexpr std::uintptr_t header = 128;                     // more than malloc's chunk headers
  std::uintptr_t first = (before + huge - 1) & ~(huge - 1);
  if (first < before + header) first += huge;  // the request must outgrow the free top
  static void* head = nullptr;
  head = std::malloc(first - top - header);
  const auto after = reinterpret_cast<std::uintptr_t>(sbrk(0));
  mallopt(M_TOP_PAD, 128 << 10);  // glibc's default: later growth as usual
  const std::uintptr_t last = after & ~(huge - 1);
  if (head != nullptr && last > first) (void)madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#endif
}

}  // namespace barimpact_cli
