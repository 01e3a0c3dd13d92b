// The yield checks' loops compiled twice, for any x86-64 (SSE2) and for
// AVX2, the processor choosing once: a quiet plastic step pays one such
// read-only pass, which with SSE2 alone costs a quarter of an implicit
// step (docs/benchmarks.md). Comparisons of the same IEEE products (no
// contraction, an integer OR): the same answer on either path, which
// tests/unit/plastic_bonds_test.cpp checks on both.
#include "yield_check.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#define BARIMPACT_YIELD_AVX2 1
#endif

namespace barimpact::detail {

namespace {

template <bool isotropic>
bool plastic_baseline(std::size_t first, std::size_t last, const Plasticity& law, double inv_h, const double* up,
                      const double* pm, const double* am) {
  return yields<isotropic>(first, last, law, inv_h, up, pm, am);
}

bool rest_baseline(std::size_t first, std::size_t last, const Plasticity& law, double inv_h, const double* up) {
  return yields_from_rest_loop(first, last, law, inv_h, up);
}

constexpr YieldLoops baseline{rest_baseline, plastic_baseline<true>, plastic_baseline<false>};

#ifdef BARIMPACT_YIELD_AVX2
template <bool isotropic>
[[gnu::target("avx2")]] bool plastic_avx2(std::size_t first, std::size_t last, const Plasticity& law, double inv_h,
                                          const double* up, const double* pm, const double* am) {
  return yields<isotropic>(first, last, law, inv_h, up, pm, am);
}

[[gnu::target("avx2")]] bool rest_avx2(std::size_t first, std::size_t last, const Plasticity& law, double inv_h,
                                       const double* up) {
  return yields_from_rest_loop(first, last, law, inv_h, up);
}

constexpr YieldLoops avx2{rest_avx2, plastic_avx2<true>, plastic_avx2<false>};
#endif

}  // namespace

const YieldLoops* yield_loops(bool wide) {
#ifdef BARIMPACT_YIELD_AVX2
  if (wide) return __builtin_cpu_supports("avx2") ? &avx2 : nullptr;
#else
  if (wide) return nullptr;
#endif
  return &baseline;
}

const YieldLoops& chosen_yield_loops() {
  static const YieldLoops& chosen = yield_loops(true) ? *yield_loops(true) : baseline;
  return chosen;
}

}  // namespace barimpact::detail
