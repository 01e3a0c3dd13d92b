#include "barimpact/schemes/paper_scheme.hpp"

#include "barimpact/model/setup_polling.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <type_traits>

#include <fmt/format.h>

#include "../model/huge_pages.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/schemes/simd.hpp"
#include "half_step_terms.hpp"
#include "twisted_solve.hpp"

namespace barimpact {

using detail::twisted_solve;

namespace {

OneBar one_bar_of(const Case& c) {
  auto v = c.one_bar();
  if (!v) throw InputError("the paper's one-bar kernel runs a line of one elastic bar only");
  return *v;
}

// The element matrix [[p, q], [q, p]] assembled on n nodes of the uniform
// mesh (the mass: p, q = rho h/3, rho h/6), row j's diagonal as assembly
// adds it up; its off-diagonal is q. The start's two uses below read it
// without assembling it: at 10^6 nodes, megabytes the process would fault
// in for one solve.
double uniform_diagonal(std::size_t n, double p, std::size_t j) {
  return j == 0 || j == n - 1 ? p : p + p;
}

// x^T A x, row i's share p_i x_i^2 + 2 q x_i x_{i+1} summed in four lanes
// (half_step_terms.hpp): a history's first row, where a chain of 2n adds
// cost as much as a step at 10^5 nodes.
BARIMPACT_ENERGY_CLONES double uniform_quadratic_form(double p, double q, std::span<const double> x) {
  const std::size_t n = x.size();
  if (n < 2) return n == 1 ? p * x[0] * x[0] : 0.0;
  const double inner = p + p, twice_q = 2.0 * q;
  detail::Lanes lanes{};
  std::size_t i = 1;
  for (; i + 4 < n; i += 4) {  // rows i..i+3, all inner, and their couplings to i+1..i+4
    detail::Lanes a, b;
    detail::load(a, x.data() + i);
    detail::load(b, x.data() + i + 1);
    lanes += inner * a * a + twice_q * a * b;
  }
  for (; i + 1 < n; ++i) lanes[(i - 1) & 3] += inner * x[i] * x[i] + twice_q * x[i] * x[i + 1];
  const double ends = p * x[0] * x[0] + twice_q * x[0] * x[1] + p * x[n - 1] * x[n - 1];
  return ends + detail::fold(lanes);
}

// x <- A^{-1} x as FactoredTridiagonal factors and solves it (the same
// pivots; its couplings q / pivot formed again where used: the same bits),
// the last row the identity when `fix_last`.
void uniform_solve(double p, double q, bool fix_last, std::vector<double>& x) {
  const std::size_t n = x.size();
  // x = +0 everywhere (a bar at rest or moving as one, unloaded): the sweeps
  // below would give +0 again (p, q > 0), at two chained passes' cost.
  if (std::all_of(x.begin(), x.end(), [](double v) { return v == 0.0 && !std::signbit(v); })) return;
  std::vector<double> inv(n, 0.0);
  inv[n - 1] = fix_last ? 0.0 : 1.0 / uniform_diagonal(n, p, n - 1);
  for (std::size_t j = n - 1; j-- > 0;) {
    if (j > 0 && j + 4 <= n && inv[j + 1] == inv[j + 2]) {  // inner rows at the fixed point: see factor()
      std::fill(inv.begin() + 1, inv.begin() + static_cast<std::ptrdiff_t>(j + 1), inv[j + 1]);
      j = 1;
      continue;
    }
    inv[j] = 1.0 / (uniform_diagonal(n, p, j) - q * (q * inv[j + 1]));
  }
  if (inv[n - 1] == 0.0) x[n - 1] = 0.0;
  for (std::size_t j = n - 1; j-- > 0;) x[j] -= q * inv[j + 1] * x[j + 1];
  x[0] *= inv[0];
  for (std::size_t j = 1; j < n; ++j) x[j] = x[j] * inv[j] - q * inv[j] * x[j - 1];
}

// The same on three rows, the first, an inner and the last (the ends' p, the
// inside's p + p, as assembled), and the one off-diagonal: every row of a
// uniform mesh's matrix is one of them.
Tridiagonal three_rows(double p, double q) {
  return Tridiagonal{{p, p + p, p}, {q, q}};
}

// c/h sum_e (a_{e+1} - a_e)(b_{e+1} - b_e): a^T K b element by element,
// free of the cancellation of the assembled form under a large rigid motion.
double stiffness_form(double coefficient, double h, std::span<const double> a, std::span<const double> b) {
  double s = 0.0;
  for (std::size_t e = 0; e + 1 < a.size(); ++e) s += (a[e + 1] - a[e]) * (b[e + 1] - b[e]);
  return coefficient / h * s;
}

// The Taylor start's levels from u0, v0 and a0: the loop in a function of
// its own, its pointers restricted, so that the unit stride's vectorises
// (the same operations, the same bits).
struct TaylorStart {
  const double *u0, *v0, *a0;
  double dt, lambda;
  template <class Stride>
  void write(std::size_t n, Stride st, double* __restrict cur, double* __restrict next, double* __restrict prev) const {
    const double* __restrict u = u0;
    const double* __restrict v = v0;
    const double* __restrict a = a0;
    const double half_dt2 = 0.5 * dt * dt;
    for (std::size_t j = 0; j < n; ++j) {
      cur[j * st] = u[j];
      next[j * st] =
          u[j] + dt * (v[j] - lambda * u[j]) + half_dt2 * (a[j] - 2.0 * lambda * v[j] + lambda * lambda * u[j]);
      prev[j * st] = u[j];
    }
  }
};

// A finite field constant along the bar (a bar at rest, or moving as one):
// every element's difference is +0, so its stiffness_form is +0 without a
// pass over the bar.
bool at_rest_inside(const Expression& initial, const std::vector<double>& values) {
  return !initial.depends_on_x() && std::isfinite(values[0]);
}

// One half step's three energy sums (PaperScheme::half_step_energies) over
// the elements of levels (a, b), element j - 1 added at node j = 1..n-1, in
// an order the nodes alone fix, however a caller splits them: blocks of
// energy_block nodes from node 1, within a block four lanes by (j - 1) mod 4,
// each in node order, a block's lanes folded as (0 + 1) + (2 + 3) into the
// totals block by block. Four lanes are one vector register's adds: the sums
// cost a few instructions per four elements, where three adds chained node
// by node held a history row's step back by a fifth. The sums of the terms
// of half_step_terms.hpp (wm kinetic, wk rate, mk mean), their factors left
// to half_step_of.
struct HalfStepSums {
  double wm = 0.0, wk = 0.0, mk = 0.0;
};

using detail::ElementTerms;
using detail::Lanes;
using detail::LevelPair;

// Elements j - 1 of nodes j0..j1-1 into lanes[sum][(j - 1) mod 4]; j0..j1-1
// inside one block. Four at a time on unit stride (compiled for AVX2 too),
// one at a time otherwise: the same operations lane by lane, the same bits.
BARIMPACT_ENERGY_CLONES void add_elements(const LevelPair& p, std::size_t st, std::size_t j0, std::size_t j1,
                                          double (&lanes)[3][4]) {
  auto one = [&](std::size_t j) {
    ElementTerms<double> t;
    detail::element_terms(p, p.za[(j - 1) * st], p.zb[(j - 1) * st], p.za[j * st], p.zb[j * st], t);
    const std::size_t l = (j - 1) & 3;
    lanes[0][l] += t.kinetic, lanes[1][l] += t.rate, lanes[2][l] += t.mean;
  };
  std::size_t j = j0;
  if (st == 1) {
    for (; j < j1 && ((j - 1) & 3) != 0; ++j) one(j);
    Lanes kinetic, rate, mean;
    detail::load(kinetic, lanes[0]), detail::load(rate, lanes[1]), detail::load(mean, lanes[2]);
    for (; j + 4 <= j1; j += 4) {
      ElementTerms<Lanes> t;
      detail::element_terms(p, j - 1, t);
      kinetic += t.kinetic, rate += t.rate, mean += t.mean;
    }
    std::memcpy(lanes[0], &kinetic, sizeof kinetic);
    std::memcpy(lanes[1], &rate, sizeof rate);
    std::memcpy(lanes[2], &mean, sizeof mean);
  }
  for (; j < j1; ++j) one(j);
}

// HalfStepSums in that order, its nodes added in runs (add), each run
// continuing the last: a whole pass's blocks, or a solve's sweeps' runs
// (twisted_solve's visit), which meet the blocks anywhere.
class LaneSums {
 public:
  static constexpr std::size_t block = detail::energy_block;
  LaneSums(const LevelPair& p, std::size_t stride) : p_(p), stride_(stride) {}
  void add(std::size_t j0, std::size_t j1) {
    while (j0 < j1) {
      const std::size_t end = std::min(j1, block_end_);
      add_elements(p_, stride_, j0, end, lanes_);
      if (end == block_end_) fold();
      j0 = end;
    }
  }
  /// The totals with the block under way folded in.
  [[nodiscard]] HalfStepSums totals() const {
    LaneSums s = *this;
    s.fold();
    return s.totals_;
  }

 private:
  void fold() {
    double* total[3] = {&totals_.wm, &totals_.wk, &totals_.mk};
    for (std::size_t k = 0; k < 3; ++k) {
      *total[k] += (lanes_[k][0] + lanes_[k][1]) + (lanes_[k][2] + lanes_[k][3]);
      for (double& l : lanes_[k]) l = 0.0;
    }
    block_end_ += block;
  }
  LevelPair p_;
  std::size_t stride_;
  std::size_t block_end_ = 1 + block;
  double lanes_[3][4] = {};
  HalfStepSums totals_;
};

// LaneSums as twisted_solve's visit: each run announced is added at once.
struct HalfStepVisit {
  static constexpr std::size_t block = LaneSums::block;
  LaneSums& sums;
  void ahead(std::size_t j0, std::size_t j1) const { sums.add(j0, j1); }
  void operator()(std::size_t /*j*/) const {}
};

// E_kin and E_strain of one half step from its sums; `c`: PaperScheme::energy_constants().
void half_step_of(const HalfStepSums& s, const std::array<double, 3>& c, double& kinetic, double& strain) {
  kinetic = c[0] * s.wm;
  strain = 0.5 * c[1] * (0.25 * s.mk + c[2] * s.wk);
}

}  // namespace

PaperScheme::PaperScheme(const Case& c) : PaperScheme(c, one_bar_of(c), build_line(c)) {}

PaperScheme::PaperScheme(const Case& c, Line line) : PaperScheme(c, one_bar_of(c), std::move(line)) {}

PaperScheme::PaperScheme(const Case& c, const OneBar& one, Line line)
    : line_(std::move(line)),
      h_(one.bar.length / static_cast<double>(one.bar.elements)),
      dt_(c.time.step),
      alpha_(c.time.alpha),
      lambda_(c.time.lambda),
      density_(one.bar.density),
      a_(one.bar.stiffness),
      b_(one.bar.viscosity),
      clamped_(one.bar.far_end == FarEnd::clamped) {
  if (!line_.links.empty()) {  // the near end's link, elastic or viscoelastic (the table's penalty laws)
    law_ = &line_.links.front().law;
    gap_ = line_.links.front().gap;
    k_ = law_->stiffness;
    l_ = law_->kind == LawKind::viscoelastic ? law_->viscosity : 0.0;
  }
  a_diag_ = form_matrices();
  factor(a_diag_);
  poll_setup();  // each phase is line-sized: a study's case polls its interrupt between them
  if (l_ > 0.0) respond_to_dashpot();
  poll_setup();
  allocate(c, one);
  // time.partitions, or by the bar's size and the run's length; one chunk is the two-ended solve.
  if (const std::size_t chunks = chunks_for(c.time.partitions, line_.nodes(), c.step_count()); chunks > 1)
    use_partitions(chunks);
}

std::array<double, 3> PaperScheme::form_matrices() {
  const double k = k_;
  // On the uniform mesh every matrix has three distinct rows, the first, an
  // inner and the last, and one off-diagonal: A, B1 and B0 are formed on
  // those three rows alone, entry by entry as on the whole (the same bits),
  // rather than as n-row temporaries.
  const Tridiagonal M3 = three_rows(density_ * h_ / 3.0, density_ * h_ / 6.0);
  const Tridiagonal Ka3 = three_rows(a_ / h_, -a_ / h_), Kb3 = three_rows(b_ / h_, -b_ / h_);

  // S = lambda^2 M + K_a + lambda K_b + (k/2) e0 e0^T and D = 2 lambda M + K_b, (6.1)(i).
  Tridiagonal S = Tridiagonal::combine(lambda_ * lambda_, M3, 1.0, Ka3);
  S = Tridiagonal::combine(1.0, S, lambda_, Kb3);
  S.diag[0] += 0.5 * k;
  const Tridiagonal D = Tridiagonal::combine(2.0 * lambda_, M3, 1.0, Kb3);

  const double inv_dt2 = 1.0 / (dt_ * dt_);
  const double half_inv_dt = 0.5 / dt_;
  const Tridiagonal A = Tridiagonal::combine(1.0, Tridiagonal::combine(inv_dt2, M3, alpha_, S), half_inv_dt, D);
  const Tridiagonal B1 = Tridiagonal::combine(2.0 * inv_dt2, M3, -(1.0 - 2.0 * alpha_), S);
  const Tridiagonal B0 = Tridiagonal::combine(1.0, Tridiagonal::combine(-inv_dt2, M3, -alpha_, S), half_inv_dt, D);

  // Every element contributes the same off-diagonal entry on a uniform mesh.
  a_off_ = A.off[0];
  b1_off_ = B1.off[0];
  b0_off_ = B0.off[0];
  b1_diag_ = {B1.diag[0], B1.diag[1], B1.diag[2]};
  b0_diag_ = {B0.diag[0], B0.diag[1], B0.diag[2]};
  return {A.diag[0], A.diag[1], A.diag[2]};
}

void PaperScheme::factor(const std::array<double, 3>& rows) {
  const std::size_t n = line_.nodes();
  // A's row j: the first, an inner or the last (n = 1: the first is the last).
  const auto a_diag = [&](std::size_t j) { return rows[j == 0 ? (n == 1 ? 2 : 0) : j == n - 1 ? 2 : 1]; };

  // The two-ended factorisation of the symmetric positive definite A, once
  // (see twisted_solve): pivots p_j from row 0 down to row k - 1 and from row
  // M up to row k + 1, with up_j = a_off / p_j, and row k = M/2's pivot last.
  const std::size_t last = n - 1, twist = last / 2;
  detail::assign_huge(inv_, n, 0.0);
  detail::assign_huge(upper_, n, 0.0);
  // On the inner rows, all alike, each chain's pivot reaches its fixed point
  // (exactly, in floating point) within a few dozen rows: two equal pivots
  // in a row repeat to the twist, the same bits without the divisions.
  for (std::size_t j = 0; j < twist; ++j) {
    if (j >= 3 && inv_[j - 1] == inv_[j - 2]) {
      std::fill(inv_.begin() + static_cast<std::ptrdiff_t>(j), inv_.begin() + static_cast<std::ptrdiff_t>(twist),
                inv_[j - 1]);
      std::fill(upper_.begin() + static_cast<std::ptrdiff_t>(j), upper_.begin() + static_cast<std::ptrdiff_t>(twist),
                upper_[j - 1]);
      break;
    }
    inv_[j] = 1.0 / (a_diag(j) - (j > 0 ? a_off_ * upper_[j - 1] : 0.0));
    upper_[j] = a_off_ * inv_[j];
  }
  // Clamped: row M reads u_M = 0. A zero pivot inverse makes the sweeps give
  // exactly that, and its zero up removes the column's coupling.
  for (std::size_t j = last; j > twist; --j) {
    if (j + 3 <= last && inv_[j + 1] == inv_[j + 2]) {
      std::fill(inv_.begin() + static_cast<std::ptrdiff_t>(twist + 1),
                inv_.begin() + static_cast<std::ptrdiff_t>(j + 1), inv_[j + 1]);
      std::fill(upper_.begin() + static_cast<std::ptrdiff_t>(twist + 1),
                upper_.begin() + static_cast<std::ptrdiff_t>(j + 1), upper_[j + 1]);
      break;
    }
    inv_[j] = clamped_ && j == last ? 0.0 : 1.0 / (a_diag(j) - (j < last ? a_off_ * upper_[j + 1] : 0.0));
    upper_[j] = a_off_ * inv_[j];
  }
  inv_[twist] = 1.0 / (a_diag(twist) - (twist > 0 ? a_off_ * upper_[twist - 1] : 0.0) - a_off_ * upper_[twist + 1]);
}

// The viscoelastic obstacle's w = A^{-1} e0, once (Sherman-Morrison).
void PaperScheme::respond_to_dashpot() {
  const std::size_t n = line_.nodes();
  dashpot_sigma_ = l_ * (alpha_ * lambda_ + 0.5 / dt_);
  dashpot_response_.assign(n, 0.0);
  double* w = dashpot_response_.data();
  twisted_solve(
      n - 1, a_off_, 1.0, 0.0, [](std::size_t) { return 0.0; }, [&](std::size_t j) { return inv_[j]; },
      [&](std::size_t j) { return upper_[j]; }, [&](std::size_t j) { return w[j]; },
      [&](std::size_t j, double v) { w[j] = v; });
}

void PaperScheme::allocate(const Case& c, const OneBar& one) {
  const std::size_t n = line_.nodes();
  for (auto& level : levels_) detail::assign_huge(level, n, 0.0);
  poll_setup();
  detail::assign_huge(u0_, n, 0.0);
  detail::assign_huge(v0_, n, 0.0);

  body_force_ = std::make_unique<Expression>(c.load.body_force);
  if (body_force_->is_zero()) {
    load_mode_ = LoadMode::zero;
  } else {
    load_mode_ = body_force_->depends_on_t() ? LoadMode::unsteady : LoadMode::steady;
    for (auto& l : loads_) l.assign(n, 0.0);
  }

  initial_displacement_ = std::make_unique<Expression>(one.initial.displacement);
  initial_velocity_ = std::make_unique<Expression>(one.initial.velocity);
}

double PaperScheme::scale(long long m) const {
  return lambda_ == 0.0 ? 1.0 : std::exp(lambda_ * static_cast<double>(m) * dt_);
}

void PaperScheme::start() {
  const std::size_t n = line_.nodes();
  // A constant (the usual bar at rest, or moving as one) fills its values without a call per node.
  for (auto [values, initial] : {std::pair{&u0_, initial_displacement_.get()}, {&v0_, initial_velocity_.get()}}) {
    if (!initial->depends_on_x())
      std::fill(values->begin(), values->end(), (*initial)(0.0, 0.0));
    else
      for (std::size_t j = 0; j < n; ++j) (*values)[j] = (*initial)(line_.x[j], 0.0);
  }
  if (!batched_) {
    prev_ = levels_[2].data();
    cur_ = levels_[0].data();
    next_ = levels_[1].data();
  }
  if (load_mode_ == LoadMode::steady) line_.load(*body_force_, 0.0, loads_[0]);
  if (load_mode_ == LoadMode::unsteady) {
    line_.load(*body_force_, 0.0, loads_[0]);
    line_.load(*body_force_, dt_, loads_[1]);
  }
  // A Taylor start, z^1 = z(0) + dt z'(0) + (dt^2/2) z''(0) with (6.1)
  // z' = v0 - lambda u0 and z'' = a0 - 2 lambda v0 + lambda^2 u0: second
  // order. The paper's z^1 = u0 + dt (v0 - lambda u0) (erratum 2) drops the
  // dt^2 term and is first order when a0 is not zero (a load, u0 strained).
  const std::vector<double> a0 = initial_acceleration();
  const TaylorStart t{u0_.data(), v0_.data(), a0.data(), dt_, lambda_};
  stride_ == 1 ? t.write(n, std::integral_constant<std::size_t, 1>{}, cur_, next_, prev_)
               : t.write(n, stride_, cur_, next_, prev_);
  n_ = 0;
  cached_ = pending_ = {};
  fuse_ = false;
  start_kinetic_ = 0.5 * uniform_quadratic_form(density_ * h_ / 3.0, density_ * h_ / 6.0, v0_);
  start_strain_ = at_rest_inside(*initial_displacement_, u0_) ? 0.0 : 0.5 * stiffness_form(a_, h_, u0_, u0_);
  book_first_half_step();
}

// Level m's increments are centred on t_m and summed from m = 1: the budget
// would start at t_{1/2}. The first half step's share, dt/2 times the rates
// at t = 0 (the load's power, the bar's dissipation, the viscoelastic
// obstacle's (R - k d) dd/dt), is booked here.
void PaperScheme::book_first_half_step() {
  double power = 0.0;
  if (load_mode_ != LoadMode::zero)
    for (std::size_t j = 0; j < v0_.size(); ++j) power += loads_[0][j] * v0_[j];
  double dissipation = at_rest_inside(*initial_velocity_, v0_) ? 0.0 : stiffness_form(b_, h_, v0_, v0_);
  if (dashpot_sigma_ > 0.0) dissipation -= (end_force(u0_[0], v0_[0]) - k_ * penetration(u0_[0])) * v0_[0];
  work_half_ = 0.5 * dt_ * power;
  dissipation_half_ = 0.5 * dt_ * dissipation;
  work_last_ = dissipation_last_ = 0.0;
}

// a0 = M^{-1} (F(0) - K_a u0 - K_b v0 + R(0) e0), R(0) the obstacle's law at
// (u0, v0); F(0) is in loads_[0]. Called by start() only: it may allocate.
std::vector<double> PaperScheme::initial_acceleration() const {
  const std::size_t n = line_.nodes();
  // K_a u0 + K_b v0 by the uniform stencil, row by row as Tridiagonal::multiply
  // (the same bits) without assembling either matrix.
  const double pa = a_ / h_, qa = -a_ / h_, pb = b_ / h_, qb = -b_ / h_;
  auto row = [](double p, double q, std::span<const double> x, std::size_t i) {
    const std::size_t size = x.size();
    double s = (i == 0 || i == size - 1 ? p : p + p) * x[i];
    if (i > 0) s += q * x[i - 1];
    if (i + 1 < size) s += q * x[i + 1];
    return s;
  };
  // A field constant along the bar (at rest, or moving as one) whose three
  // kinds of row (the ends', an inner one) give +0 gives +0 on every row:
  // then the unloaded a = 0 - 0 - 0 is +0 without a pass over the bar.
  auto rows_vanish = [&](double p, double q, const Expression& initial, const std::vector<double>& x) {
    if (initial.depends_on_x()) return false;
    const std::array<double, 3> c{x[0], x[0], x[0]};
    for (std::size_t i = 0; i < 3; ++i)
      if (const double r = row(p, q, c, i); r != 0.0 || std::signbit(r)) return false;
    return true;
  };
  std::vector<double> a(n, 0.0);
  if (load_mode_ != LoadMode::zero || !rows_vanish(pa, qa, *initial_displacement_, u0_) ||
      !rows_vanish(pb, qb, *initial_velocity_, v0_))
    for (std::size_t j = 0; j < n; ++j)
      a[j] = (load_mode_ == LoadMode::zero ? 0.0 : loads_[0][j]) - row(pa, qa, u0_, j) - row(pb, qb, v0_, j);
  a[0] += end_force(u0_[0], v0_[0]);
  if (clamped_) a[n - 1] = 0.0;
  uniform_solve(density_ * h_ / 3.0, density_ * h_ / 6.0, clamped_, a);
  return a;
}

template <PaperScheme::LoadMode mode>
PaperScheme::LevelRows<mode> PaperScheme::level_rows(long long m) {
  const std::size_t last = line_.nodes() - 1;
  const double* zc = next_;
  const double* zo = cur_;
  // exp(-lambda t) at t_{m-1}, t_m, t_{m+1}, and its alpha-mean.
  const double em1 = 1.0 / scale(m - 1), e0 = 1.0 / scale(m), ep1 = 1.0 / scale(m + 1);
  const double ebar = alpha_ * ep1 + (1.0 - 2.0 * alpha_) * e0 + alpha_ * em1;
  const AlphaLoad f = alpha_load<mode>(m, em1, e0, ep1, ebar);
  const double b1o = b1_off_, b0o = b0_off_;
  LevelRows<mode> rows{zc, zo, {f.fp, f.f0, f.fm, f.cp, f.c0, f.cm}, b1_diag_[1], b1o, b0_diag_[1], b0o};

  // The explicit half of the penalty, (k/2)|z_0 + g e^{-lambda t_m}|, and the
  // gap's share of the implicit half, -(k/2) g e^{-lambda t}^{m,alpha}.
  const double k = k_, g = gap_;
  double contact = 0.5 * k * (std::abs(zc[0] + g * e0) - g * ebar);
  rows.sigma = dashpot_sigma_ > 0.0 ? viscoelastic_row(zc, zo, e0, em1, contact) : 0.0;
  rows.r0 = rows.loaded(b1_diag_[0] * zc[0] + b1o * zc[1] + b0_diag_[0] * zo[0] + b0o * zo[1], 0) + contact;
  rows.r_last =
      rows.loaded(b1_diag_[2] * zc[last] + b1o * zc[last - 1] + b0_diag_[2] * zo[last] + b0o * zo[last - 1], last);
  return rows;
}

// One step of (6.3)(iv) at level m: z^{m+1} from z^m (next_) and z^{m-1}
// (cur_), written over z^{m-2} (prev_). The right-hand side is formed row
// by row inside the first sweep of the prefactored two-ended solve, then
// one sweep back: two passes over memory, two chains per pass, no allocation.
template <PaperScheme::LoadMode mode, bool fused>
void PaperScheme::solve_level(long long m) {
  const LevelRows<mode> rows = level_rows<mode>(m);
  double* __restrict zn = prev_;
  const double* __restrict inv = inv_.data();
  const double* __restrict up = upper_.data();
  // fused: the half step (m - 1, m)'s energy sums in node order, inside the
  // sweeps (a history row's, which begin_energies left to this step).
  LaneSums sums(LevelPair{cur_, next_, scale(m - 1), scale(m)}, 1);
  const auto visit = [&] {
    if constexpr (fused)
      return HalfStepVisit{sums};
    else
      return detail::NoVisit{};
  }();
  twisted_solve(
      line_.nodes() - 1, a_off_, rows.r0, rows.r_last, [&](std::size_t j) { return rows(j); },
      [&](std::size_t j) { return inv[j]; }, [&](std::size_t j) { return up[j]; }, [&](std::size_t j) { return zn[j]; },
      [&](std::size_t j, double v) { zn[j] = v; }, visit);
  if (rows.sigma != 0.0) add_dashpot(rows.sigma, zn);
  if constexpr (fused) {
    cached_.n = m - 1;
    half_step_of(sums.totals(), energy_constants(), cached_.kinetic, cached_.strain);
  }
}

namespace {

// Inner rows j0..j1-1 of a level's right-hand side into out, in a loop of
// their own that the compiler vectorises (out restricted, the rows' constants
// in locals), for AVX2 too (half_step_terms.hpp's clones: the same
// operations, no fused multiply-add, the same bits): the partitioned step's
// first pass.
template <class Rows>
BARIMPACT_ENERGY_CLONES void stencil_rows(const Rows& level, double* __restrict out, std::size_t j0, std::size_t j1) {
  const Rows rows = level;
  for (std::size_t j = j0; j < j1; ++j) out[j] = rows(j);
}

}  // namespace

// The partitioned step (Wang's method, model/partitioned_tridiagonal.hpp):
// the right-hand side in a pass of its own, a history row's energy sums
// beside it block by block while the levels are in L1 (LaneSums: any split
// of the nodes gives the same bits), then the chunks' eliminations, the
// dashpot's Sherman-Morrison term as a force f = -sigma x_0 / (1 + sigma
// (A^{-1})_00) at row 0, and the back substitution.
template <PaperScheme::LoadMode mode, bool fused>
void PaperScheme::solve_level_partitioned(long long m) {
  const std::size_t n = line_.nodes(), last = n - 1;
  const LevelRows<mode> rows = level_rows<mode>(m);
  double* zn = prev_;
  LaneSums sums(LevelPair{cur_, next_, scale(m - 1), scale(m)}, 1);
  for (std::size_t j0 = 1; j0 < last; j0 += LaneSums::block) {
    const std::size_t j1 = std::min(last, j0 + LaneSums::block);
    stencil_rows(rows, zn, j0, j1);
    if constexpr (fused) sums.add(j0, j1);
  }
  zn[0] = rows.r0;
  zn[last] = rows.r_last;
  const std::span<double> x(zn, n);
  const double x0 = partitioned_.eliminate(x);
  if (rows.sigma != 0.0)
    partitioned_.add_end_force(x, -rows.sigma * x0 / (1.0 + rows.sigma * partitioned_.end_response()));
  partitioned_.substitute(x);
  if constexpr (fused) {
    sums.add(last, n);
    cached_.n = m - 1;
    half_step_of(sums.totals(), energy_constants(), cached_.kinetic, cached_.strain);
  }
}

std::size_t PaperScheme::use_partitions(std::size_t p) {
  partitioned_ = PartitionedTridiagonal();
  const std::size_t n = line_.nodes();
  if (p == 0 || batched_ || n < 3) return 0;
  Tridiagonal a;
  a.diag.assign(n, a_diag_[1]);
  a.diag.front() = a_diag_[0];
  a.diag.back() = a_diag_[2];
  a.off.assign(n - 1, a_off_);
  partitioned_ = PartitionedTridiagonal(a, clamped_, p);
  return partitioned_.partitions();
}

// Sherman-Morrison: (A + sigma e0 e0^T)^{-1} r = y - sigma y_0 / (1 + sigma w_0) w.
void PaperScheme::add_dashpot(double sigma, double* __restrict y) const {
  const double* __restrict w = dashpot_response_.data();
  const double s = sigma * y[0] / (1.0 + sigma * w[0]);
  for (std::size_t j = 0; j < line_.nodes(); ++j) y[j] -= s * w[j];
}

// Load weights: F^{m,alpha} = cp F(t_{m+1}) + c0 F(t_m) + cm F(t_{m-1}), all
// scaled by exp(-lambda t); an unsteady load's F(t_{m+1}) formed here.
template <PaperScheme::LoadMode mode>
PaperScheme::AlphaLoad PaperScheme::alpha_load(long long m, double em1, double e0, double ep1, double ebar) {
  AlphaLoad f;
  if constexpr (mode == LoadMode::steady) {
    f.f0 = loads_[0].data();
    f.c0 = ebar;
  } else if constexpr (mode == LoadMode::unsteady) {
    auto& newest = loads_[static_cast<std::size_t>((m + 1) % 3)];
    line_.load(*body_force_, static_cast<double>(m + 1) * dt_, newest);
    f.fp = newest.data();
    f.f0 = loads_[static_cast<std::size_t>(m % 3)].data();
    f.fm = loads_[static_cast<std::size_t>((m - 1) % 3)].data();
    f.cp = alpha_ * ep1;
    f.c0 = (1.0 - 2.0 * alpha_) * e0;
    f.cm = alpha_ * em1;
  }
  return f;
}

// The viscoelastic obstacle at level m, its status explicit (d^m and dd/dt^m
// by a backward difference): pushing, the dashpot joins the spring; clipped
// (d > 0, k d + l dd/dt <= 0: R = 0), neither acts, so that the force in the
// equation is the law's. Adjusts row 0's `contact`; returns sigma, the change
// of A's (0, 0) entry, applied by Sherman-Morrison.
double PaperScheme::viscoelastic_row(const double* zc, const double* zo, double e0, double em1, double& contact) {
  const double k = k_, l = l_, g = gap_;
  const double d = -(zc[0] / e0 + g), d_rate = -(zc[0] / e0 - zo[0] / em1) / dt_;
  contact_ = d <= 0.0 ? Contact::apart : k * d + l * d_rate > 0.0 ? Contact::pushing : Contact::clipped;
  if (contact_ == Contact::pushing) {
    contact += l * (zo[0] * 0.5 / dt_ - lambda_ * ((1.0 - 2.0 * alpha_) * zc[0] + alpha_ * zo[0]));
    return dashpot_sigma_;
  }
  if (contact_ == Contact::clipped) {
    // Drop the explicit half and the gap's share; cancel the implicit half
    // (k/2) z_0^{m,alpha}: its z^m, z^{m-1} parts (in B1, B0) here, its
    // alpha z^{m+1} part (in A) by sigma. A - alpha (k/2) e0 e0^T stays
    // positive definite: it is A without the spring.
    contact = 0.5 * k * ((1.0 - 2.0 * alpha_) * zc[0] + alpha_ * zo[0]);
    return -0.5 * alpha_ * k;
  }
  return 0.0;
}

void PaperScheme::advance() {
  const long long m = n_ + 1;
  const bool fused = fuse_;
  fuse_ = false;
  const auto run = [&]<LoadMode mode>() {
    if (partitioned())
      fused ? solve_level_partitioned<mode, true>(m) : solve_level_partitioned<mode, false>(m);
    else
      fused ? solve_level<mode, true>(m) : solve_level<mode, false>(m);
  };
  switch (load_mode_) {
    case LoadMode::zero:
      run.template operator()<LoadMode::zero>();
      break;
    case LoadMode::steady:
      run.template operator()<LoadMode::steady>();
      break;
    case LoadMode::unsteady:
      run.template operator()<LoadMode::unsteady>();
      break;
  }
  finish_level(m);
}

void PaperScheme::finish_level(long long m) {
  double* oldest = prev_;
  prev_ = cur_;
  cur_ = next_;
  next_ = oldest;
  n_ = m;
  if (load_mode_ != LoadMode::zero || b_ > 0.0 || dashpot_sigma_ > 0.0) accumulate_budget(m);
}

// The work and dissipation of level m, from testing (6.3)(iv) with
// (u^{m+1} - u^{m-1}) / 2: dW = F^{m,alpha} . (u^{m+1} - u^{m-1}) / 2 and
// dD = dt |(u^{m+1} - u^{m-1}) / (2 dt)|^2_{K_b}.
void PaperScheme::accumulate_budget(long long m) {
  const std::size_t n = line_.nodes(), st = stride_;
  const double sm = scale(m - 1), sp = scale(m + 1);
  double dw = 0.0;
  if (load_mode_ != LoadMode::zero) {
    const double em1 = 1.0 / sm, e0 = 1.0 / scale(m), ep1 = 1.0 / sp;
    const double back = scale(m);  // F^{m,alpha} is in z-units: times exp(lambda t_m)
    if (load_mode_ == LoadMode::steady) {
      const double w = back * (alpha_ * ep1 + (1.0 - 2.0 * alpha_) * e0 + alpha_ * em1);
      const auto& f = loads_[0];
      for (std::size_t j = 0; j < n; ++j) dw += w * f[j] * 0.5 * (sp * next_[j * st] - sm * prev_[j * st]);
    } else {
      const auto& fp = loads_[static_cast<std::size_t>((m + 1) % 3)];
      const auto& f0 = loads_[static_cast<std::size_t>(m % 3)];
      const auto& fm = loads_[static_cast<std::size_t>((m - 1) % 3)];
      for (std::size_t j = 0; j < n; ++j) {
        const double f = back * (alpha_ * ep1 * fp[j] + (1.0 - 2.0 * alpha_) * e0 * f0[j] + alpha_ * em1 * fm[j]);
        dw += f * 0.5 * (sp * next_[j * st] - sm * prev_[j * st]);
      }
    }
  }
  double dd = 0.0;
  if (b_ > 0.0) {
    const double c = 0.5 / dt_;
    double left = c * (sp * next_[0] - sm * prev_[0]);
    for (std::size_t j = 1; j < n; ++j) {
      const double right = c * (sp * next_[j * st] - sm * prev_[j * st]);
      dd += (right - left) * (right - left);
      left = right;
    }
    dd *= dt_ * b_ / h_;
  }
  if (contact_ == Contact::pushing) {  // the obstacle's dashpot: dt l (du_0/dt)^2
    const double rate = (sp * next_[0] - sm * prev_[0]) / (2.0 * dt_);
    dd += dt_ * l_ * rate * rate;
  } else if (contact_ == Contact::clipped) {
    // The spring lets go unloaded: what k d^2 / 2 loses is dissipated, as
    // k d^m (d^{m-1} - d^{m+1}) / 2, the centred form that telescopes to it.
    const double d = penetration(scale(m) * cur_[0]);
    dd += k_ * d * 0.5 * (sp * next_[0] - sm * prev_[0]);
  }
  work_last_ = dw;
  dissipation_last_ = dd;
  work_half_ += dw;
  dissipation_half_ += dd;
}

double PaperScheme::end_displacement() const {
  return scale(n_) * cur_[0];
}

double PaperScheme::end_velocity() const {
  if (n_ == 0) return v0_[0];
  return (scale(n_ + 1) * next_[0] - scale(n_ - 1) * prev_[0]) / (2.0 * dt_);
}

double PaperScheme::displacement_at(std::size_t j) const {
  return j == 0 ? end_displacement() : scale(n_) * cur_[j * stride_];
}

double PaperScheme::velocity_at(std::size_t j) const {
  if (j == 0) return end_velocity();
  if (n_ == 0) return v0_[j];
  return (scale(n_ + 1) * next_[j * stride_] - scale(n_ - 1) * prev_[j * stride_]) / (2.0 * dt_);
}

void PaperScheme::displacement(std::span<double> out) const {
  const double s = scale(n_);
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = s * cur_[j * stride_];
}

void PaperScheme::velocity(std::span<double> out) const {
  if (n_ == 0) {
    std::copy(v0_.begin(), v0_.end(), out.begin());
    return;
  }
  const double sp = scale(n_ + 1), sm = scale(n_ - 1);
  for (std::size_t j = 0; j < out.size(); ++j)
    out[j] = (sp * next_[j * stride_] - sm * prev_[j * stride_]) / (2.0 * dt_);
}

void PaperScheme::half_step_energies(const double* za, double sa, const double* zb, double sb, const double* zc,
                                     double sc, double (&kinetic)[2], double (&strain)[2]) const {
  const std::size_t n = line_.nodes();
  LaneSums first(LevelPair{za, zb, sa, sb}, stride_), second(LevelPair{zb, zc, sb, sc}, stride_);
  for (std::size_t j0 = 1; j0 < n; j0 += LaneSums::block) {
    const std::size_t j1 = std::min(n, j0 + LaneSums::block);
    first.add(j0, j1);
    if (zc != nullptr) second.add(j0, j1);
  }
  const HalfStepSums ab = first.totals(), bc = second.totals();
  half_step_of(ab, energy_constants(), kinetic[0], strain[0]);
  half_step_of(bc, energy_constants(), kinetic[1], strain[1]);
}

// Element by element: mass rho h/6 [[2,1],[1,2]], stiffness a/h [[1,-1],[-1,1]]:
// (1/2)|w|_M^2 = (rho h/6) sum (w0^2 + w0 w1 + w1^2) with w = d / dt, and
// (1/2)|m|_K^2 + (alpha - 1/4)(dt^2/2)|w|_K^2 with m = s / 2 (HalfStepSums).
std::array<double, 3> PaperScheme::energy_constants() const {
  return {density_ * h_ / 6.0 / (dt_ * dt_), a_ / h_, alpha_ - 0.25};
}

// Row n's terms but E_kin and E_strain, whose half step n + 1/2 the next
// advance sums inside its sweeps (solve_level<mode, true>): the row's own
// pass over the bar, three chained sums, is hidden behind the sweeps'.
bool PaperScheme::begin_energies(Energies& e) const {
  if (n_ == 0 || batched_) {
    e = energies();
    return true;
  }
  e = energies_but_half_steps();
  pending_ = {n_, cached_.kinetic, cached_.strain};
  if (cached_.n != n_ - 1) {
    double k[2], s[2];
    half_step_energies(prev_, scale(n_ - 1), cur_, scale(n_), nullptr, 0.0, k, s);
    pending_.kinetic = k[0];
    pending_.strain = s[0];
  }
  fuse_ = true;
  return false;
}

// The pending row's half step n + 1/2: from the sweeps of the advance since
// (cached_), else summed here from the levels as energies() would.
void PaperScheme::finish_energies(Energies& e) const {
  const long long p = pending_.n;
  if (cached_.n != p) {
    const bool moved = n_ == p + 1;
    double k[2], s[2];
    half_step_energies(moved ? prev_ : cur_, scale(p), moved ? cur_ : next_, scale(p + 1), nullptr, 0.0, k, s);
    cached_ = {p, k[0], s[0]};
  }
  e.kinetic = 0.5 * (pending_.kinetic + cached_.kinetic);
  e.strain = 0.5 * (pending_.strain + cached_.strain);
}

// Row n's terms but E_kin and E_strain (n >= 1).
Energies PaperScheme::energies_but_half_steps() const {
  Energies e;
  e.obstacle = end_energy(end_displacement());
  e.work = work_half_ - 0.5 * work_last_;
  e.dissipation = dissipation_half_ - 0.5 * dissipation_last_;
  return e;
}

Energies PaperScheme::energies() const {
  if (n_ == 0) {
    Energies e;
    e.obstacle = end_energy(end_displacement());
    e.kinetic = start_kinetic_;
    e.strain = start_strain_;
    return e;
  }
  Energies e = energies_but_half_steps();
  double k[2] = {0.0, 0.0}, s[2] = {0.0, 0.0}, k1 = 0.0, s1 = 0.0, k2 = 0.0, s2 = 0.0;
  if (cached_.n == n_ - 1) {  // the previous row's n + 1/2 is this row's n - 1/2
    k1 = cached_.kinetic;
    s1 = cached_.strain;
    half_step_energies(cur_, scale(n_), next_, scale(n_ + 1), nullptr, 0.0, k, s);
    k2 = k[0], s2 = s[0];
  } else {  // both half-steps in one pass
    half_step_energies(prev_, scale(n_ - 1), cur_, scale(n_), next_, scale(n_ + 1), k, s);
    k1 = k[0], s1 = s[0], k2 = k[1], s2 = s[1];
  }
  cached_ = {n_, k2, s2};
  e.kinetic = 0.5 * (k1 + k2);
  e.strain = 0.5 * (s1 + s2);
  return e;
}

bool PaperScheme::finite() const {
  const std::size_t last = line_.nodes() - 1;
  const std::size_t at = last * stride_;
  return std::isfinite(cur_[0]) && std::isfinite(cur_[at]) && std::isfinite(next_[0]) && std::isfinite(next_[at]) &&
         std::isfinite(work_half_) && std::isfinite(dissipation_half_) && std::isfinite(scale(n_ + 1));
}

}  // namespace barimpact
