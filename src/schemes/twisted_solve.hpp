// The two-ended ("twisted") solve shared by PaperScheme and the batch
// kernels (internal to src/schemes).
#pragma once

#include <cstddef>

namespace barimpact::detail {

// The two-ended ("twisted") solve of the symmetric tridiagonal A with the
// factors of PaperScheme: rows 0..k-1 eliminated from row 0 down, rows
// k+1..M from row M up, row k = M/2 last. Each sweep then carries two
// independent chains, one per half, which a latency-bound solve runs in the
// time of one. T is double, or four lanes (PaperBatch): the same operations
// in the same order. r0, rl: rows 0 and M of the right-hand side; rhs(j) an
// interior row's; get/put read and write the solution, row by row.
template <class T, class Rhs, class Inv, class Up, class Get, class Put>
inline void twisted_solve(std::size_t last, T a, T r0, T rl, Rhs rhs, Inv inv, Up up, Get get, Put put) {
  const std::size_t k = last / 2;
  const std::size_t top = k > 0 ? k - 1 : 0;  // interior rows of the upper half: 1..k-1
  const std::size_t bottom = last - 1 - k;    // of the lower half: k+1..M-1 (top or top + 1)
  T yt{};
  if (k > 0) {
    yt = r0 * inv(0);
    put(0, yt);
  }
  T yb = rl * inv(last);
  put(last, yb);
  std::size_t jb = last;
  for (std::size_t e = top; e < bottom; ++e) {  // the lower half's extra row
    --jb;
    yb = rhs(jb) * inv(jb) - up(jb) * yb;
    put(jb, yb);
  }
  for (std::size_t j = 1; j <= top; ++j) {
    --jb;
    yt = rhs(j) * inv(j) - up(j) * yt;
    put(j, yt);
    yb = rhs(jb) * inv(jb) - up(jb) * yb;
    put(jb, yb);
  }
  T x = ((k > 0 ? rhs(k) : r0) - a * (yt + yb)) * inv(k);  // row k meets both halves
  put(k, x);
  T xt = x, xb = x;
  for (std::size_t i = 1; i <= k; ++i) {
    xt = get(k - i) - up(k - i) * xt;
    put(k - i, xt);
    xb = get(k + i) - up(k + i) * xb;
    put(k + i, xb);
  }
  for (std::size_t j = 2 * k + 1; j <= last; ++j) {  // the lower half's extra row
    xb = get(j) - up(j) * xb;
    put(j, xb);
  }
}

}  // namespace barimpact::detail
