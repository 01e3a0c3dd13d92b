// The half-step energies' terms, element by element (internal to
// src/schemes): a history row sums them over the whole line at every step,
// so they are formed four elements at a time and summed in four lanes, in
// an order the nodes fix, and the factors every term shares (1/dt^2 of the
// rates, 1/4 of the means) are left to the sums' ends.
//
// Element e joins nodes e and e + 1 of levels a and b (the levels' values
// scaled by sa and sb); with d = b - a and s = b + a at each node:
//   kinetic  d0 (d0 + d1) + d1^2   (= dt^2 (w0^2 + w0 w1 + w1^2), w = d / dt),
//   rate     (d1 - d0)^2            (= dt^2 (w1 - w0)^2),
//   mean     (s1 - s0)^2            (= 4 (m1 - m0)^2, m = s / 2).
#pragma once

#include <cstddef>
#include <cstring>

namespace barimpact::detail {

// A function of these terms is also compiled for AVX2 and chosen at load
// time when the processor has it (GCC's target clones, left out of sanitized
// builds): four lanes, the same operations (no fused multiply-add), the
// same bits.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define BARIMPACT_ENERGY_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define BARIMPACT_ENERGY_CLONES
#endif

/// Nodes per block of a sum that a solve's sweeps carry (PaperScheme).
inline constexpr std::size_t energy_block = 64;

/// Four doubles, summed lane by lane (GCC's vector extension: one AVX2
/// register, or two SSE2 ones): a sum in four lanes, folded as
/// (0 + 1) + (2 + 3), is a quarter as long a chain as node by node.
using Lanes = double __attribute__((vector_size(32)));

/// The four lanes folded in a fixed order.
inline double fold(const Lanes& l) {
  return (l[0] + l[1]) + (l[2] + l[3]);
}

/// Four doubles from p (unaligned).
inline void load(Lanes& v, const double* p) {
  std::memcpy(&v, p, sizeof v);
}

/// Two levels, each with its scale.
struct LevelPair {
  const double *za, *zb;
  double sa, sb;
};

/// An element's terms (above) and its first node's d0; T is double, or Lanes
/// for four elements.
template <class T>
struct ElementTerms {
  T kinetic, rate, mean, d0;
};

/// The terms from the levels' values at the element's nodes (za0, zb0) and
/// (za1, zb1). By reference: a vector passed by value would change the
/// calling convention between the AVX2 and the default builds.
template <class T>
[[gnu::always_inline]] inline void element_terms(const LevelPair& p, const T& za0, const T& zb0, const T& za1,
                                                 const T& zb1, ElementTerms<T>& t) {
  const T a0 = p.sa * za0, b0 = p.sb * zb0, a1 = p.sa * za1, b1 = p.sb * zb1;
  const T d0 = b0 - a0, d1 = b1 - a1, s0 = b0 + a0, s1 = b1 + a1;
  t.kinetic = d0 * (d0 + d1) + d1 * d1;
  t.rate = (d1 - d0) * (d1 - d0);
  t.mean = (s1 - s0) * (s1 - s0);
  t.d0 = d0;
}

/// Elements e and e + 1..e + 3 (four lanes) on unit stride.
[[gnu::always_inline]] inline void element_terms(const LevelPair& p, std::size_t e, ElementTerms<Lanes>& t) {
  Lanes za0, zb0, za1, zb1;
  load(za0, p.za + e), load(zb0, p.zb + e), load(za1, p.za + e + 1), load(zb1, p.zb + e + 1);
  element_terms(p, za0, zb0, za1, zb1, t);
}

}  // namespace barimpact::detail
