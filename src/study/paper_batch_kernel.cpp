// The batch kernel, compiled once per SIMD path (CMakeLists.txt): the
// definition BARIMPACT_KERNEL names it, the path's flags (-mavx2, or the
// x86-64 baseline) choose the instructions. With BARIMPACT_KERNEL_SCALAR
// the lanes are solved one after another in doubles, vectorization off.
// GCC's generic vectors passed by value to inlined helpers (twisted_solve's
// lambdas); their ABI without AVX does not concern us.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "paper_batch_kernel.hpp"

#include <type_traits>

#include "../schemes/twisted_solve.hpp"

namespace barimpact::batch_kernel {

namespace {

// GCC's generic vectors of `width` doubles: one AVX2 register, or two SSE2 ones.
typedef double lanes __attribute__((vector_size(8 * width)));

[[maybe_unused]] inline lanes load_lanes(const double* p) {
  lanes v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
[[maybe_unused]] inline void store_lanes(double* p, lanes v) {
  __builtin_memcpy(p, &v, sizeof v);
}

// PaperScheme::solve_level on T = all lanes at once, or one lane (double):
// the same operations in the same order, so that every lane's result is
// bit-for-bit the scalar kernel's. lane(a) reads a per-lane coefficient,
// get(p, j) node j of an interleaved array, put(j, v) writes z^{m+1}.
template <bool steady, class T, class Lane, class Get, class Put>
void solve(const Level& in, Lane lane, Get get, Put put) {
  const T contact = lane(in.contact), c0 = lane(in.load_weight);
  const T b1d0 = lane(in.b1_first), b1d = lane(in.b1_inner), b1dl = lane(in.b1_last);
  const T b0d0 = lane(in.b0_first), b0d = lane(in.b0_inner), b0dl = lane(in.b0_last);
  const T b1o = lane(in.b1_off), b0o = lane(in.b0_off), a_off = lane(in.a_off);
  const double* __restrict zc = in.z_now;
  const double* __restrict zo = in.z_previous;
  const double* __restrict inv = in.inverse_pivot;
  const double* __restrict up = in.upper;
  const double* __restrict f = in.load;
  const std::size_t last = in.last;
  // The single kernel's operations: a zero load adds nothing.
  auto loaded = [&](T r, std::size_t j) {
    if constexpr (steady) return r + c0 * get(f, j);
    (void)j;
    return r;
  };
  const T r0 = loaded(b1d0 * get(zc, 0) + b1o * get(zc, 1) + b0d0 * get(zo, 0) + b0o * get(zo, 1), 0) + contact;
  const T r_last =
      loaded(b1dl * get(zc, last) + b1o * get(zc, last - 1) + b0dl * get(zo, last) + b0o * get(zo, last - 1), last);
  detail::twisted_solve(
      last, a_off, r0, r_last,
      [&](std::size_t j) {
        return loaded(b1d * get(zc, j) + b1o * (get(zc, j - 1) + get(zc, j + 1)) + b0d * get(zo, j) +
                          b0o * (get(zo, j - 1) + get(zo, j + 1)),
                      j);
      },
      [&](std::size_t j) { return get(inv, j); }, [&](std::size_t j) { return get(up, j); },
      [&](std::size_t j) { return get(in.z_next, j); }, put);
}

template <bool steady>
void advance_lanes(const Level& in) {
  constexpr std::size_t w = width;
#ifdef BARIMPACT_KERNEL_SCALAR
  // One lane after another, each a scalar solve over its stride.
  for (std::size_t l = 0; l < w; ++l)
    solve<steady, double>(
        in, [l](const double(&a)[w]) { return a[l]; }, [l](const double* p, std::size_t j) { return p[w * j + l]; },
        [&in, l](std::size_t j, double v) { in.z_next[w * j + l] = v; });
#else
  solve<steady, lanes>(
      in, [](const double(&a)[w]) { return load_lanes(a); },
      [](const double* p, std::size_t j) { return load_lanes(p + w * j); },
      [&in](std::size_t j, lanes v) { store_lanes(in.z_next + w * j, v); });
#endif
}

}  // namespace

void BARIMPACT_KERNEL(const Level& level) {
  if (level.load != nullptr)
    advance_lanes<true>(level);
  else
    advance_lanes<false>(level);
}

}  // namespace barimpact::batch_kernel
