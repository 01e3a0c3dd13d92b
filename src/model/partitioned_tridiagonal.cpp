#include "barimpact/model/partitioned_tridiagonal.hpp"

#include "barimpact/model/setup_polling.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace barimpact {
namespace {

// Chunks swept together, their carries in registers: enough independent
// multiply-subtract chains to cover the chain's latency (about 6 cycles)
// at two floating-point operations per cycle; more spill registers.
constexpr std::size_t group = 8;

// Below this the spike's product of couplings is taken as zero: its terms
// are then 10^-30 of its largest, 14 decades below rounding, and the sweeps
// skip reading it on the rows past it (in a diagonally dominant M + dt^2 K
// it decays geometrically, within tens or hundreds of rows).
constexpr double spike_floor = 1e-30;

using detail::UniformRows;

// Rows i_end - 1 down to i_begin of G chunks (row first_q + i), carries in
// y and acc: y_j = r_j - coupling_{j+1} y_{j+1}, acc += g_j y_j while spiked;
// `uniform`: coupling_{j+1} is cu on every row.
template <std::size_t G, bool spiked, bool uniform = false>
inline void eliminate_rows(double* __restrict x, const double* __restrict c, const double* __restrict g,
                           const std::array<std::size_t, G>& at, std::array<double, G>& y, std::array<double, G>& acc,
                           std::size_t i_begin, std::size_t i_end, double cu = 0.0) {
  for (std::size_t i = i_end; i-- > i_begin;)
    for (std::size_t q = 0; q < G; ++q) {
      const std::size_t j = at[q] + i;
      y[q] = x[j] - (uniform ? cu : c[j + 1]) * y[q];
      x[j] = y[q];
      if constexpr (spiked) acc[q] += g[j] * y[q];
    }
}

// The chunks' elimination towards row 0 (Wang's step 1), G chains at once,
// from each chunk's last row; the local solution's last entry, bottom =
// sum_j g_j y_j, beside it on the rows i >= cut where some g_j is not zero.
template <std::size_t G>
void eliminate_group(double* x, const double* c, const double* g, const std::size_t* first, std::size_t common,
                     std::size_t longer, std::size_t cut, const UniformRows& u, double* bottom) {
  std::array<double, G> y{}, acc{};
  std::array<std::size_t, G> at{};
  for (std::size_t q = 0; q < G; ++q) {
    at[q] = first[q];
    if (q < longer) {  // the chunk's extra row, its last
      const std::size_t j = at[q] + common;
      y[q] = x[j] - c[j + 1] * y[q];
      x[j] = y[q];
      acc[q] = g[j] * y[q];
    }
  }
  eliminate_rows<G, true>(x, c, g, at, y, acc, cut, common);
  const std::size_t hi = std::min(u.end, cut), lo = std::min(u.begin, hi);
  eliminate_rows<G, false>(x, c, g, at, y, acc, hi, cut);
  eliminate_rows<G, false, true>(x, c, g, at, y, acc, lo, hi, u.coupling);
  eliminate_rows<G, false>(x, c, g, at, y, acc, 0, lo);
  for (std::size_t q = 0; q < G; ++q) bottom[q] = acc[q];
}

// Rows i_begin..i_end - 1 of G chunks' back substitution: x_j = (y_j inv_j
// - t g_j) - coupling_j x_{j-1}, the chain the last multiply-subtract alone.
template <std::size_t G, bool spiked, bool uniform = false>
inline void substitute_rows(double* __restrict x, const double* __restrict inv, const double* __restrict c,
                            const double* __restrict g, const std::array<std::size_t, G>& at, std::array<double, G>& xv,
                            const double* t, std::size_t i_begin, std::size_t i_end, const UniformRows& u = {}) {
  for (std::size_t i = i_begin; i < i_end; ++i)
    for (std::size_t q = 0; q < G; ++q) {
      const std::size_t j = at[q] + i;
      if constexpr (spiked)
        xv[q] = (x[j] * inv[j] - t[q] * g[j]) - c[j] * xv[q];
      else if constexpr (uniform)
        xv[q] = x[j] * u.inv - u.coupling * xv[q];
      else
        xv[q] = x[j] * inv[j] - c[j] * xv[q];
      x[j] = xv[q];
    }
}

// The chunks' back substitution (Wang's step 3) from the separator above
// (x_{a-1}, `above`), t = off_b x_{b+1} the separator below's term.
template <std::size_t G>
void substitute_group(double* x, const double* inv, const double* c, const double* g, const std::size_t* first,
                      std::size_t common, std::size_t longer, std::size_t cut, const UniformRows& u,
                      const double* above, const double* t) {
  std::array<double, G> xv{};
  std::array<std::size_t, G> at{};
  for (std::size_t q = 0; q < G; ++q) {
    at[q] = first[q];
    xv[q] = above[q];
  }
  const std::size_t hi = std::min(u.end, cut), lo = std::min(u.begin, hi);
  substitute_rows<G, false>(x, inv, c, g, at, xv, t, 0, lo);
  substitute_rows<G, false, true>(x, inv, c, g, at, xv, t, lo, hi, u);
  substitute_rows<G, false>(x, inv, c, g, at, xv, t, hi, cut);
  substitute_rows<G, true>(x, inv, c, g, at, xv, t, cut, common);
  for (std::size_t q = 0; q < std::min(G, longer); ++q) {
    const std::size_t j = at[q] + common;
    x[j] = (x[j] * inv[j] - t[q] * g[j]) - c[j] * xv[q];
  }
}

// Calls f.template operator()<G>(k, G) over the chunks 0..P-1 in groups of
// at most `group`, the last group's width a compile-time constant too.
template <class F>
void for_groups(std::size_t chunks, F&& f) {
  std::size_t k = 0;
  for (; k + group <= chunks; k += group) f.template operator()<group>(k);
  switch (chunks - k) {
    case 1:
      f.template operator()<1>(k);
      break;
    case 2:
      f.template operator()<2>(k);
      break;
    case 3:
      f.template operator()<3>(k);
      break;
    case 4:
      f.template operator()<4>(k);
      break;
    case 5:
      f.template operator()<5>(k);
      break;
    case 6:
      f.template operator()<6>(k);
      break;
    case 7:
      f.template operator()<7>(k);
      break;
    default:
      break;
  }
}

}  // namespace

PartitionedTridiagonal::PartitionedTridiagonal(const Tridiagonal& a, bool fix_last, std::size_t partitions)
    : n_(a.size()) {
  poll_setup();
  assert(n_ > 0 && partitions > 0);
  rows_ = fix_last ? n_ - 1 : n_;
  // Every chunk keeps a row: P chunks and P - 1 separators need 2P - 1 rows.
  const std::size_t p = std::max<std::size_t>(1, std::min(partitions, (rows_ + 1) / 2));
  const std::size_t interior = rows_ - (p - 1);
  common_ = interior / p;
  longer_ = interior % p;
  first_.assign(p, 0);
  for (std::size_t k = 1; k < p; ++k) first_[k] = first_[k - 1] + common_ + (k - 1 < longer_ ? 1 : 0) + 1;
  inv_.assign(n_, 0.0);
  coupling_.assign(n_ + 1, 0.0);
  spike_.assign(n_, 0.0);
  below_.assign(p, 0.0);
  spiked_from_.assign(p, 0);
  bottom_.assign(p, 0.0);
  for (std::size_t k = 0; k < p; ++k) factor_chunk(a, k);
  factor_separators(a);
  find_uniform_rows();
}

// Each group's rows where every chunk's factors equal those at its first
// chunk's middle row: from the middle out, in each chunk, while inv_j,
// coupling_j and coupling_{j+1} (the sweeps' reads) repeat them exactly.
void PartitionedTridiagonal::find_uniform_rows() {
  uniform_.assign((first_.size() + group - 1) / group, {});
  if (rows_ == 0 || common_ < 2) return;
  const std::size_t mid = common_ / 2;
  for (std::size_t k0 = 0; k0 < first_.size(); k0 += group) {
    UniformRows u{0, common_, coupling_[first_[k0] + mid], inv_[first_[k0] + mid]};
    const auto alike = [&](std::size_t j) {
      return inv_[j] == u.inv && coupling_[j] == u.coupling && coupling_[j + 1] == u.coupling;
    };
    for (std::size_t k = k0; k < std::min(k0 + group, first_.size()); ++k) {
      const std::size_t f = first_[k];
      if (!alike(f + mid)) {
        u.begin = u.end = 0;
        break;
      }
      std::size_t lo = mid, hi = mid + 1;
      while (lo > 0 && alike(f + lo - 1)) --lo;
      while (hi < common_ && alike(f + hi)) ++hi;
      u.begin = std::max(u.begin, lo);
      u.end = std::min(u.end, hi);
    }
    uniform_[k0 / group] = u;
  }
}

// Chunk k's local pivots from its last row b up (FactoredTridiagonal's
// formulas), its coupling to the separator above, and its spike g.
void PartitionedTridiagonal::factor_chunk(const Tridiagonal& a, std::size_t k) {
  const std::size_t first = first_[k], b = first + common_ + (k < longer_ ? 1 : 0) - 1;
  if (rows_ == 0) return;
  inv_[b] = 1.0 / a.diag[b];
  for (std::size_t j = b; j-- > first;) {
    coupling_[j + 1] = a.off[j] * inv_[j + 1];
    inv_[j] = 1.0 / (a.diag[j] - a.off[j] * coupling_[j + 1]);
  }
  if (first > 0) coupling_[first] = a.off[first - 1] * inv_[first];
  spiked_from_[k] = b + 1 - first;
  if (k + 1 == first_.size()) return;  // the last chunk has no separator below
  below_[k] = a.off[b];
  // pi_b = 1, pi_j = -coupling_{j+1} pi_{j+1}; g_j = inv_j pi_j: the local
  // solution's last entry is sum_j g_j y_j, and the separator below enters
  // row j's elimination as off_b pi_j.
  double pi = 1.0;
  for (std::size_t j = b + 1; j-- > first && pi != 0.0;) {
    spike_[j] = inv_[j] * pi;
    spiked_from_[k] = j - first;
    const double next = -coupling_[j] * pi;
    pi = std::abs(next) < spike_floor ? 0.0 : next;
  }
}

// S on the separators s_i = first_i - 1 (i = 1..P-1), the Schur complement
// of the chunks: S_ii = d_s - off_{s-1}^2 U_{i-1} - off_s^2 inv_{a_i},
// S_{i,i+1} = -off_s off_{b_i} g_{a_i}, U the local (A_k^{-1})_{bb} =
// sum_j g_j pi_j of the chunk above; factored by Thomas from row 1.
void PartitionedTridiagonal::factor_separators(const Tridiagonal& a) {
  const std::size_t p = first_.size();
  s_inv_.assign(p, 0.0);
  s_lower_.assign(p, 0.0);
  s_end_.assign(p, 0.0);
  end_response_ = rows_ == 0 ? 0.0 : inv_[0];
  if (p == 1) return;
  for (std::size_t i = 1; i < p; ++i) {
    const std::size_t s = first_[i] - 1, top = first_[i - 1], b = s - 1;
    double u = 0.0;  // (A_{i-1}^{-1})_{bb}: the spike at row j is g_j, pi_j = g_j / inv_j
    for (std::size_t j = top; j <= b; ++j) u += spike_[j] * spike_[j] / inv_[j];
    const double sii = a.diag[s] - below_[i - 1] * below_[i - 1] * u - a.off[s] * coupling_[s + 1];
    if (i > 1) {
      const std::size_t above = first_[i - 1];
      s_lower_[i] = -a.off[above - 1] * below_[i - 1] * spike_[above];
      s_inv_[i] = 1.0 / (sii - s_lower_[i] * s_lower_[i] * s_inv_[i - 1]);
    } else {
      s_inv_[i] = 1.0 / sii;
    }
  }
  // A force f at row 0 adds f g_0 to chunk 0's bottom, so -off_{b_0} g_0 f
  // to separator 1's right-hand side; its answer S^{-1} that, per unit f.
  s_end_[1] = -below_[0] * spike_[0];
  for (std::size_t i = 2; i < p; ++i) s_end_[i] = -s_lower_[i] * s_inv_[i - 1] * s_end_[i - 1];
  s_end_[p - 1] *= s_inv_[p - 1];
  for (std::size_t i = p - 1; i-- > 1;) s_end_[i] = (s_end_[i] - s_lower_[i + 1] * s_end_[i + 1]) * s_inv_[i];
  end_response_ = inv_[0] - below_[0] * s_end_[1] * spike_[0];
}

std::size_t PartitionedTridiagonal::spike_cut(std::size_t k, std::size_t width) const {
  std::size_t cut = common_;
  for (std::size_t q = k; q < k + width; ++q) cut = std::min(cut, spiked_from_[q]);
  return cut;
}

double PartitionedTridiagonal::near_end(std::span<const double> x) const {
  if (rows_ == 0) return 0.0;
  const double t = first_.size() > 1 ? below_[0] * x[first_[1] - 1] : 0.0;
  return x[0] * inv_[0] - t * spike_[0];
}

double PartitionedTridiagonal::eliminate(std::span<double> x) {
  assert(x.size() == n_);
  if (rows_ < n_) x[n_ - 1] = 0.0;  // the fixed row
  const std::size_t p = first_.size();
  double* xs = x.data();
  for_groups(p, [&]<std::size_t G>(std::size_t k) {
    eliminate_group<G>(xs, coupling_.data(), spike_.data(), first_.data() + k, common_, longer_ > k ? longer_ - k : 0,
                       spike_cut(k, G), uniform_[k / group], bottom_.data() + k);
  });
  if (p > 1) {
    // The separators' right-hand sides, S's forward sweep, then its back
    // substitution, each separator's value in its own row of x.
    double w = 0.0;
    for (std::size_t i = 1; i < p; ++i) {
      const std::size_t s = first_[i] - 1;
      const double r = x[s] - below_[i - 1] * bottom_[i - 1] - coupling_[s + 1] * x[s + 1];
      w = i > 1 ? r - s_lower_[i] * s_inv_[i - 1] * w : r;
      x[s] = w;
    }
    double xs_next = 0.0;
    for (std::size_t i = p; i-- > 1;) {
      const std::size_t s = first_[i] - 1;
      xs_next = (x[s] - (i + 1 < p ? s_lower_[i + 1] * xs_next : 0.0)) * s_inv_[i];
      x[s] = xs_next;
    }
  }
  return near_end(x);
}

double PartitionedTridiagonal::add_end_force(std::span<double> x, double f) {
  if (rows_ == 0) return 0.0;
  x[0] += f;
  for (std::size_t i = 1; i < first_.size(); ++i) x[first_[i] - 1] += f * s_end_[i];
  return near_end(x);
}

void PartitionedTridiagonal::substitute(std::span<double> x) const {
  const std::size_t p = first_.size();
  double* xs = x.data();
  for_groups(p, [&]<std::size_t G>(std::size_t k) {
    std::array<double, G> above{}, t{};
    for (std::size_t q = 0; q < G; ++q) {
      above[q] = k + q > 0 ? xs[first_[k + q] - 1] : 0.0;
      t[q] = k + q + 1 < p ? below_[k + q] * xs[first_[k + q + 1] - 1] : 0.0;
    }
    substitute_group<G>(xs, inv_.data(), coupling_.data(), spike_.data(), first_.data() + k, common_,
                        longer_ > k ? longer_ - k : 0, spike_cut(k, G), uniform_[k / group], above.data(), t.data());
  });
}

void PartitionedTridiagonal::solve(std::span<double> x) {
  eliminate(x);
  substitute(x);
}

}  // namespace barimpact
