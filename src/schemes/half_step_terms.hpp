// The half-step energies' node values in blocks (internal to src/schemes):
// a history row sums them over the whole line at every step, so the rates
// w = (u^b - u^a) / dt and means m = (u^b + u^a) / 2, then each element's
// terms, are formed in loops free of reductions, which the compiler
// vectorises, and summed in four lanes (Lanes) in an order the nodes fix.
#pragma once

#include <cstddef>

namespace barimpact::detail {

// A function of these blocks is also compiled for AVX2 and chosen at load
// time when the processor has it (GCC's target clones, left out of sanitized
// builds): four lanes, the same operations (no fused multiply-add), the
// same bits.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define BARIMPACT_ENERGY_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define BARIMPACT_ENERGY_CLONES
#endif

/// Nodes per block: its rates, means and terms stay in the first-level cache.
inline constexpr std::size_t energy_block = 64;

/// Four doubles, summed lane by lane (GCC's vector extension: one AVX2
/// register, or two SSE2 ones): a sum over a block in four lanes, folded as
/// (0 + 1) + (2 + 3), is four times as short a chain as node by node.
using Lanes = double __attribute__((vector_size(32)));

/// The four lanes folded in a fixed order.
inline double fold(const Lanes& l) {
  return (l[0] + l[1]) + (l[2] + l[3]);
}

/// w[i], m[i] of nodes i = 0..count (count + 1 of them) of levels a and b,
/// scaled by sa and sb, as the schemes' own sums form them.
inline void rates_and_means(const double* __restrict za, double sa, const double* __restrict zb, double sb,
                            double inv_dt, std::size_t count, double* __restrict w, double* __restrict m) {
  for (std::size_t i = 0; i <= count; ++i) {
    const double a = sa * za[i], b = sb * zb[i];
    w[i] = (b - a) * inv_dt;
    m[i] = 0.5 * (b + a);
  }
}

}  // namespace barimpact::detail
