// One level of PaperBatch: PaperScheme::solve_level on `width` interleaved
// lanes (internal to src/study). The kernel is compiled once per SIMD
// path (paper_batch_kernel.cpp with BARIMPACT_KERNEL naming it, and the
// path's compiler flags); schemes/simd.hpp chooses one at run time. Every
// path does the same IEEE operations in the same order (no FMA
// contraction), hence the same bits.
#pragma once

#include <cstddef>

namespace barimpact::batch_kernel {

inline constexpr std::size_t width = 4;

/// One level's data for every lane (row-interleaved arrays: node j of lane l
/// at [width j + l]).
struct Level {
  // Per lane: row 0's contact term, the steady load's weight (its alpha-mean
  // exp(-lambda t)), B1's and B0's first, inner and last diagonals, their
  // off-diagonals, and A's off-diagonal.
  double contact[width], load_weight[width];
  double b1_first[width], b1_inner[width], b1_last[width];
  double b0_first[width], b0_inner[width], b0_last[width];
  double b1_off[width], b0_off[width], a_off[width];
  const double* z_now;       // z^m
  const double* z_previous;  // z^{m-1}
  double* z_next;            // z^{m+1}, written over z^{m-2}
  const double* inverse_pivot;
  const double* upper;
  const double* load;  // the steady load (F(0), per lane); null: no load
  std::size_t last;    // M, the last node
};

void advance_scalar(const Level& level);
void advance_sse2(const Level& level);
void advance_avx2(const Level& level);

}  // namespace barimpact::batch_kernel
