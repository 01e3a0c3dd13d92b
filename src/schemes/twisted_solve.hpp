// The two-ended ("twisted") solve shared by PaperScheme and the batch
// kernels (internal to src/schemes).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>

namespace barimpact::detail {

// The two-ended ("twisted") solve of the symmetric tridiagonal A with the
// factors of PaperScheme: rows 0..k-1 eliminated from row 0 down, rows
// k+1..M from row M up, row k = M/2 last. Each sweep then carries two
// independent chains, one per half, which a latency-bound solve runs in the
// time of one. T is double, or four lanes (PaperBatch): the same operations
// in the same order. r0, rl: rows 0 and M of the right-hand side; rhs(j) an
// interior row's; get/put read and write the solution, row by row.
// visit(j) sees rows 1..M in order (the upper half's as the sweep in reaches
// them, the lower half's as the sweep out does), each run of at most
// Visit::block of them announced first by visit.ahead(first, end): a sum in
// node order carried beside the sweeps' chains, its terms formed a block
// ahead outside the loops that carry them.
struct NoVisit {
  static constexpr std::size_t block = std::numeric_limits<std::size_t>::max();
  void ahead(std::size_t /*first*/, std::size_t /*end*/) const {}
  void operator()(std::size_t /*j*/) const {}
};
template <class T, class Rhs, class Inv, class Up, class Get, class Put, class Visit = NoVisit>
inline void twisted_solve(std::size_t last, T a, T r0, T rl, Rhs rhs, Inv inv, Up up, Get get, Put put,
                          Visit visit = {}) {
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
  for (std::size_t j0 = 1; j0 <= top;) {
    const std::size_t j1 = j0 + std::min(Visit::block, top + 1 - j0);
    visit.ahead(j0, j1);
    for (std::size_t j = j0; j < j1; ++j) {
      --jb;
      yt = rhs(j) * inv(j) - up(j) * yt;
      put(j, yt);
      yb = rhs(jb) * inv(jb) - up(jb) * yb;
      put(jb, yb);
      visit(j);
    }
    j0 = j1;
  }
  if (k > 0) {
    visit.ahead(k, k + 1);
    visit(k);
  }
  T x = ((k > 0 ? rhs(k) : r0) - a * (yt + yb)) * inv(k);  // row k meets both halves
  put(k, x);
  T xt = x, xb = x;
  for (std::size_t i0 = 1; i0 <= k;) {
    const std::size_t i1 = i0 + std::min(Visit::block, k + 1 - i0);
    visit.ahead(k + i0, k + i1);
    for (std::size_t i = i0; i < i1; ++i) {
      xt = get(k - i) - up(k - i) * xt;
      put(k - i, xt);
      xb = get(k + i) - up(k + i) * xb;
      put(k + i, xb);
      visit(k + i);
    }
    i0 = i1;
  }
  for (std::size_t j = 2 * k + 1; j <= last; ++j) {  // the lower half's extra row
    xb = get(j) - up(j) * xb;
    put(j, xb);
    visit.ahead(j, j + 1);
    visit(j);
  }
}

}  // namespace barimpact::detail
