// A partitioned solve of a symmetric positive definite tridiagonal system
// (weakly diagonally dominant, as every matrix of a line is: see spike_ below):
// the rows split into P chunks with one separator row between neighbours, so
// that the chunks' recurrences are independent chains a processor runs side
// by side instead of one chain of multiply-subtracts from end to end.
//
// The method is Wang's partition method in its Schur-complement form (H. H.
// Wang, ACM TOMS 7 (1981) 170-183; the SPIKE family, Polizzi & Sameh,
// Parallel Comput. 32 (2006) 177-194), one level, with the spikes folded into
// the two sweeps rather than a third pass:
//   1. each chunk eliminated from its last row towards row 0 (the factors of
//      FactoredTridiagonal, chunk by chunk), and its last row's local
//      solution formed beside the sweep as a dot product with the spike g;
//   2. the separators' values from their Schur complement S, tridiagonal and
//      symmetric positive definite, of size P - 1 and factored once;
//   3. each chunk's back substitution from its first row with the separator
//      above as its start and the one below entering through g.
// Each sweep carries the chunks' chains in groups, their carries in
// registers; the bytes moved are the sequential solve's plus g on each sweep.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "barimpact/model/tridiagonal.hpp"

namespace barimpact {

namespace detail {
/// Rows begin..end - 1 of every chunk of a group where the factors are at
/// their fixed point: a chunk's pivots, factored from its last row up with
/// a matrix's inner rows all alike, repeat exactly within tens of rows (as
/// PaperScheme::factor exploits), so the sweeps there take them from
/// registers instead of two streams of memory: the same values, the same bits.
struct UniformRows {
  std::size_t begin = 0, end = 0;
  double coupling = 0.0, inv = 0.0;
};
}  // namespace detail

/// time.partitions = "auto": the chunks (8: the fastest of 4..256 measured,
/// docs/benchmarks.md) on a line of at least 2000 nodes (which keeps the
/// pinned examples on the sequential solve) whose run is long enough to
/// repay the chunks' factors: at least 32 steps (a run of the paper scheme
/// at 10^5 nodes, whole processes: 0.8 ms more set-up, 0.08 ms less a step).
inline constexpr std::size_t default_partitions = 8, partition_threshold = 2000;
inline constexpr long long partition_min_steps = 32;

/// The chunks a scheme's solve takes: `asked` (time.partitions) when given,
/// else by the rule above; 1 is the sequential solve.
[[nodiscard]] inline std::size_t chunks_for(int asked, std::size_t nodes, long long steps) {
  if (asked > 0) return static_cast<std::size_t>(asked);
  return nodes >= partition_threshold && steps >= partition_min_steps ? default_partitions : 1;
}

class PartitionedTridiagonal {
 public:
  PartitionedTridiagonal() = default;
  /// A's factors in `partitions` chunks (at least 1; fewer when A is too
  /// small to give each chunk a row of its own). With `fix_last` the last row
  /// is replaced by u_{n-1} = 0, as in FactoredTridiagonal. One chunk is the
  /// sequential solve, operation for operation.
  PartitionedTridiagonal(const Tridiagonal& a, bool fix_last, std::size_t partitions);

  /// x <- A^{-1} x, in place: eliminate then substitute.
  void solve(std::span<double> x);
  /// The first phase: the chunks' eliminations and the separators' values.
  /// Returns x_0, the near end's unknown, before the second phase.
  double eliminate(std::span<double> x);
  /// After eliminate: the right-hand side gains f e_0 (a force at row 0) at
  /// O(P) cost. Returns the new x_0.
  double add_end_force(std::span<double> x, double f);
  /// The second phase: x <- A^{-1} b for the b eliminate (and
  /// add_end_force) saw.
  void substitute(std::span<double> x) const;
  /// (A^{-1})_{00}: x_0's answer to a unit force at row 0.
  [[nodiscard]] double end_response() const { return end_response_; }

  [[nodiscard]] std::size_t size() const { return n_; }
  /// The chunks used (at most the partitions asked for).
  [[nodiscard]] std::size_t partitions() const { return first_.size(); }

 private:
  void factor_chunk(const Tridiagonal& a, std::size_t k);
  void factor_separators(const Tridiagonal& a);
  [[nodiscard]] double near_end(std::span<const double> x) const;
  /// The first row (from its chunk's first) where some spike of chunks
  /// k..k+width-1 is not zero.
  [[nodiscard]] std::size_t spike_cut(std::size_t k, std::size_t width) const;
  void find_uniform_rows();

  std::size_t n_ = 0;
  std::size_t rows_ = 0;    // rows solved: n, or n - 1 with the last fixed
  std::size_t common_ = 0;  // rows every chunk has; the first `longer_` have one more
  std::size_t longer_ = 0;
  std::vector<std::size_t> first_;  // chunk k's first row; separator k (k >= 1) is first_[k] - 1
  std::vector<double> inv_;         // 1 / chunk-local pivot (0 on separators and a fixed row)
  std::vector<double> coupling_;    // off_{j-1} inv_j, n + 1 entries, 0 past a chunk's last row
  // g_j = inv_j prod_{i=j+1..b} (-coupling_i), b the chunk's last row; 0 from where the product
  // falls below 1e-30: with |coupling| <= 1 (weak diagonal dominance) it only falls further.
  std::vector<double> spike_;
  std::vector<double> below_;             // off_b, chunk k's coupling to the separator after it (0 for the last)
  std::vector<std::size_t> spiked_from_;  // chunk k's first row (from first_[k]) with g not zero
  // The separators' Schur complement S (rows 1..P-1), factored from row 1:
  // pivots' inverses and S_{i,i-1}.
  std::vector<double> s_inv_, s_lower_;
  std::vector<double> s_end_;                 // S^{-1} applied to a unit force at row 0's effect
  std::vector<double> bottom_;                // workspace: each chunk's last-row local solution
  std::vector<detail::UniformRows> uniform_;  // per group of chunks swept together
  double end_response_ = 0.0;
};

}  // namespace barimpact
