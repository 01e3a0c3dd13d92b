// The yield checks' loops, compiled for AVX2 as well as for any x86-64 and
// chosen by the processor at load time (GCC's target_clones): a quiet
// plastic step pays one such read-only pass, which on the portable build's
// SSE2 alone costs a quarter of an implicit step (docs/benchmarks.md).
// Comparisons of the same IEEE products (no contraction): the same answer
// on either path.
#include "yield_check.hpp"

namespace barimpact::detail {

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define BARIMPACT_YIELD_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define BARIMPACT_YIELD_CLONES
#endif

BARIMPACT_YIELD_CLONES bool yields_isotropic(std::size_t first, std::size_t last, const Plasticity& law, double inv_h,
                                             const double* __restrict up, const double* __restrict pm,
                                             const double* __restrict am) {
  return yields<true>(first, last, law, inv_h, up, pm, am);
}

BARIMPACT_YIELD_CLONES bool yields_kinematic(std::size_t first, std::size_t last, const Plasticity& law, double inv_h,
                                             const double* __restrict up, const double* __restrict pm,
                                             const double* __restrict am) {
  return yields<false>(first, last, law, inv_h, up, pm, am);
}

BARIMPACT_YIELD_CLONES bool yields_from_rest(std::size_t first, std::size_t last, const Plasticity& law, double inv_h,
                                             const double* __restrict up) {
  const double e = law.modulus, sy = law.yield_stress;
  int any = 0;
  for (std::size_t j = first; j < last; ++j) any |= std::abs(e * ((up[j + 1] - up[j]) * inv_h)) > sy ? 1 : 0;
  return any != 0;
}

}  // namespace barimpact::detail
