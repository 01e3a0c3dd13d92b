#include "barimpact/schemes/line_newmark.hpp"

#include "barimpact/model/setup_polling.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace barimpact {

namespace {

// A's factors from the far end (the single bar's direction): pivots,
// the first sweep's couplings and the back substitution's lower entries.
void factor_from_far_end(const Tridiagonal& a, const std::vector<char>& held, std::vector<double>& coupling,
                         std::vector<double>& inv_pivot, std::vector<double>& lower) {
  const std::size_t n = a.size();
  coupling.assign(n, 0.0);
  inv_pivot.assign(n, 0.0);
  lower.assign(n, 0.0);
  double below = 0.0;  // A_{j+1,j} of the row eliminated before
  for (std::size_t j = n; j-- > 0;) {
    const double up = (j + 1 < n && !held[j]) ? a.off[j] : 0.0;    // A_{j,j+1}
    const double down = (j > 0 && !held[j]) ? a.off[j - 1] : 0.0;  // A_{j,j-1}
    coupling[j] = j + 1 < n ? up * inv_pivot[j + 1] : 0.0;
    const double pivot = (held[j] ? 1.0 : a.diag[j]) - coupling[j] * below;
    inv_pivot[j] = 1.0 / pivot;
    lower[j] = down * inv_pivot[j];
    below = down;
  }
}

void solve_from_far_end(const std::vector<double>& coupling, const std::vector<double>& inv_pivot,
                        const std::vector<double>& lower, std::vector<double>& x) {
  const std::size_t n = x.size();
  for (std::size_t j = n - 1; j-- > 0;) x[j] -= coupling[j] * x[j + 1];
  x[0] *= inv_pivot[0];
  for (std::size_t j = 1; j < n; ++j) x[j] = x[j] * inv_pivot[j] - lower[j] * x[j - 1];
}

}  // namespace

LineNewmark::LineNewmark(const Case& c, Line line)
    : LineScheme(c, std::move(line)), beta_(c.time.beta), gamma_(c.time.gamma) {
  const std::size_t n = line_.nodes(), links = line_.links.size();
  mass_ = line_.mass(true);
  stiff_ = line_.stiffness();
  visc_ = line_.viscosity();
  const Tridiagonal a =
      Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, mass_, gamma_ * dt_, visc_), beta_ * dt_ * dt_, stiff_);
  std::vector<char> held(n, 0);
  for (std::size_t j = 0; j < n; ++j)
    if (line_.fixed(j)) {
      held[j] = 1;
      held_.push_back(j);
    }
  poll_setup();  // each phase is line-sized: a study's case polls its interrupt between them
  factor_from_far_end(a, held, coupling_, inv_pivot_, lower_);
  poll_setup();
  for (const auto& b : line_.bonds) {
    stiff_bond_.push_back(b.stiffness);
    visc_bond_.push_back(b.viscosity);
    viscous_ = viscous_ || b.viscosity != 0.0;
  }
  poll_setup();
  build_blocks();
  poll_setup();
  // The links' Delassus matrix from their responses A^{-1} h_i (none on held rows).
  // Sized row by row: GCC 12 misreads the nested fill constructor here
  // (a false -Wfree-nonheap-object).
  std::vector<std::vector<double>> response(links);
  for (std::size_t i = 0; i < links; ++i) {
    response[i].assign(n, 0.0);
    const Link& l = line_.links[i];
    if (l.a != Link::ground && !held[l.a]) response[i][l.a] = -1.0;
    if (l.b != Link::ground && !held[l.b]) response[i][l.b] = 1.0;
    solve_from_far_end(coupling_, inv_pivot_, lower_, response[i]);
  }
  std::vector<double> delassus(links * links, 0.0);
  std::vector<ContactLaw> laws;
  for (std::size_t i = 0; i < links; ++i) {
    // Smith's toe is soil_'s: in the active set it is a law that never pushes.
    laws.push_back(line_.links[i].law.kind == LawKind::smith ? ContactLaw{} : line_.links[i].law);
    for (std::size_t j = 0; j < links; ++j)
      delassus[i * links + j] = line_.opening(i, response[j].data()) - line_.links[i].gap;
  }
  penalty_ = PenaltyLinks(std::move(laws), std::move(delassus), beta_ * dt_ * dt_, gamma_ * dt_);
  for (auto* x : {&u_, &v_, &acc_, &rhs_, &work_, &load_old_}) x->assign(n, 0.0);
  for (auto* x : {&p_old_, &c_old_, &c_free_, &rate_free_, &a_free_last_}) x->assign(links, 0.0);
  set_plastic(a, held_, beta_ * dt_ * dt_);  // a load at t_{n+1} moves u^{n+1} by beta dt^2 A^{-1}
  soil_ = SoilIteration(line_, a, held_, beta_ * dt_ * dt_, gamma_ / (beta_ * dt_));  // and v^{n+1} by gamma dt A^{-1}
  if (soil_.active()) soil_load_.assign(n, 0.0);  // the misfit refuses elastic-plastic bodies with it
  if (soil_.active() || plastic_iteration_.active()) kept_.keep(state());  // primed: keeping never allocates
  // time.partitions, or by the line's size and the run's length; one chunk is the sequential solve.
  if (const std::size_t chunks = chunks_for(c.time.partitions, n, c.step_count()); chunks > 1) use_partitions(chunks);
}

std::size_t LineNewmark::use_partitions(std::size_t p) {
  partitioned_ = PartitionedTridiagonal();
  // One block with no far link: A is the whole line's, and every link acts
  // at node 0, a force at row 0 that the reduced system takes.
  // At least two nodes: the elastic step's bond stencil reads node 1.
  const bool can = line_.nodes() >= 2 && blocks_.size() == 1 && blocks_.front().far_link == none && held_.empty() &&
                   !soil_.active() && !plastic_iteration_.active();
  if (!can || p == 0) return 0;
  partitioned_ = PartitionedTridiagonal(
      Tridiagonal::combine(1.0, Tridiagonal::combine(1.0, mass_, gamma_ * dt_, visc_), beta_ * dt_ * dt_, stiff_),
      false, p);
  return partitioned_.partitions();
}

// A's blocks: rows joined by element or spring bonds (a link's bond is
// open, so A has no entry across it). A link's upper node b is the first
// row of its block, its lower node a the last row of its own; on a block
// that ends in a link, the weights of x_a in the first sweep's values and
// the answer A^{-1} e_a.
void LineNewmark::build_blocks() {
  const std::size_t n = line_.nodes();
  last_weight_.assign(n, 0.0);
  last_response_.assign(n, 0.0);
  std::size_t first = 0;
  for (std::size_t j = 0; j < n; ++j) {
    if (j + 1 < n && line_.bonds[j].kind != BondKind::open) continue;
    Block block{first, j, none};
    for (std::size_t i = 0; i < line_.links.size(); ++i)
      if (line_.links[i].a == j && !line_.fixed(j)) block.far_link = i;
    if (block.far_link != none) {
      double product = 1.0;  // prod_{m = k+1}^{last} (-lower_m)
      last_weight_[j] = inv_pivot_[j];
      for (std::size_t k = j; k-- > first;) {
        product *= -lower_[k + 1];
        last_weight_[k] = inv_pivot_[k] * product;
      }
      std::vector<double> e(n, 0.0);
      e[j] = 1.0;
      solve_from_far_end(coupling_, inv_pivot_, lower_, e);
      for (std::size_t k = first; k <= j; ++k) last_response_[k] = e[k];
    }
    blocks_.push_back(block);
    first = j + 1;
  }
}

void LineNewmark::residual(const std::vector<double>& u, const std::vector<double>& v, double t,
                           std::vector<double>& r) {
  const std::size_t n = line_.nodes();
  stiff_.multiply(u, r);
  visc_.multiply(v, work_);
  for (std::size_t j = 0; j < n; ++j) r[j] = (load_zero_ ? 0.0 : load_[j]) - r[j] - work_[j];
  if (line_.near.kind == EndKind::force) r[line_.near.node] += near_value(t);
  if (line_.far.kind == EndKind::force) r[line_.far.node] += far_value(t);
}

// The support's force along +x on a held node at the current state: what
// its equation of motion needs beyond the line's own forces.
double LineNewmark::support(std::size_t j, double t) const {
  const std::size_t n = line_.nodes();
  auto row = [&](const Tridiagonal& m, const std::vector<double>& x) {
    double s = m.diag[j] * x[j];
    if (j > 0) s += m.off[j - 1] * x[j - 1];
    if (j + 1 < n) s += m.off[j] * x[j + 1];
    return s;
  };
  double s = row(mass_, acc_) + row(visc_, v_) + row(stiff_, u_) - (load_zero_ ? 0.0 : load_[j]);
  if (soil_.active()) s -= soil_.load_on(j);
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    if (line_.links[i].a == j) s += force_[i];
    if (line_.links[i].b == j) s -= force_[i];
  }
  (void)t;
  return s;
}

void LineNewmark::start() {
  const std::size_t n = line_.nodes();
  n_ = 0;
  u_ = u0_;
  v_ = v0_;
  std::fill(c_max_.begin(), c_max_.end(), 0.0);
  std::fill(penalty_.branches().begin(), penalty_.branches().end(), PenaltyLinks::Branch::off);
  start_plastic(u_.data());
  // a^0 = M^{-1} (F^0 - K u^0 - C v^0 + links), held rows at their ends' accelerations.
  load_at(0.0);
  residual(u_, v_, 0.0, acc_);
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const ContactLaw& law = line_.links[i].law;
    const double c = -line_.opening(i, u_.data());
    c_max_[i] = std::max(0.0, c);
    force_[i] = law.rigid() ? 0.0 : law.force(c, -(line_.opening(i, v_.data()) - line_.links[i].gap), c_max_[i]);
    add_link_force(i, force_[i], acc_.data());
  }
  if (soil_.active()) {
    soil_.start(u_.data(), v_.data());
    soil_.add_start_forces(acc_.data());
  }
  std::vector<char> held(n, 0);
  for (std::size_t j : held_) held[j] = 1;
  std::vector<double> coupling, inv_pivot, lower;
  factor_from_far_end(mass_, held, coupling, inv_pivot, lower);
  for (const End* e : {&line_.near, &line_.far}) {
    if (e->kind == EndKind::clamped) acc_[e->node] = 0.0;
    if (e->kind == EndKind::velocity)  // the history's slope over the first step
      acc_[e->node] = ((e == &line_.near ? near_value(dt_) : far_value(dt_)) - v_[e->node]) / dt_;
  }
  solve_from_far_end(coupling, inv_pivot, lower, acc_);
  load_old_ = load_;
  for (std::size_t i = 0; i < force_.size(); ++i) {
    p_old_[i] = force_[i];
    c_old_[i] = -line_.opening(i, u_.data());
  }
  support_old_[0] = support(line_.near.node, 0.0);
  support_old_[1] = support(line_.far.node, 0.0);
  near_force_ = !line_.links.empty() && line_.links.front().name == "near_end" ? force_.front()
                : line_.near.kind == EndKind::force                            ? near_value(0.0)
                : line_.fixed(line_.near.node)                                 ? support_old_[0]
                                                                               : 0.0;
  far_force_ = !line_.links.empty() && line_.links.back().name == "far_end" ? force_.back()
               : line_.far.kind == EndKind::force                           ? -far_value(0.0)
               : line_.fixed(line_.far.node)                                ? -support_old_[1]
                                                                            : 0.0;
  ext_work_ = dissipation_ = 0.0;
}

// The links' compressions and rates at t_{n+1} with every link force 0 (the
// free accelerations at their nodes: a block's first row from the first
// sweep's last value there, its last row by its weights), then their forces
// by the active-set iteration, each entering its upper node's eliminated
// right-hand side.
void LineNewmark::solve_links() {
  const std::size_t links = line_.links.size();
  if (links == 0) return;
  const double bdt2 = beta_ * dt_ * dt_, gdt = gamma_ * dt_;
  const double* __restrict y = rhs_.data();
  for (const Block& b : blocks_) {
    if (b.far_link == none) continue;
    const double* __restrict w = last_weight_.data();
    double x = 0.0;
    for (std::size_t j = b.first; j <= b.last; ++j) x += w[j] * y[j];
    a_free_last_[b.far_link] = x;
  }
  for (std::size_t i = 0; i < links; ++i) {
    const Link& l = line_.links[i];
    double free = 0.0;  // h_i . a_free
    if (l.b != Link::ground && !line_.fixed(l.b)) free += partitioned() ? near_free_ : y[l.b] * inv_pivot_[l.b];
    if (l.a != Link::ground && !line_.fixed(l.a)) free -= a_free_last_[i];
    c_free_[i] = -(line_.opening(i, u_.data()) + bdt2 * free);
    rate_free_[i] = -(line_.opening(i, v_.data()) - l.gap + gdt * free);
  }
  penalty_.solve(c_free_.data(), rate_free_.data(), c_max_.data(), force_.data());
  for (std::size_t i = 0; i < links; ++i) {
    const Link& l = line_.links[i];
    if (l.b == Link::ground || line_.fixed(l.b)) continue;
    if (partitioned())  // l.b is node 0
      near_free_ = partitioned_.add_end_force(rhs_, force_[i]);
    else
      rhs_[l.b] += force_[i];
  }
}

// One step in two passes (the single bar's): towards x = 0, the predictors,
// right-hand side and first sweep; the links; away from x = 0, the back
// substitution with a, u, v and the budget's sums.
void LineNewmark::advance() {
  if (soil_.active())
    advance_soil();
  else if (plastic_iteration_.active())
    advance_plastic([this] { advance_elastic(); }, u_);
  else
    advance_elastic();
}

void LineNewmark::advance_elastic() {
  const double t = static_cast<double>(n_ + 1) * dt_;
  load_at(t);
  const bool loaded = !load_zero_;
  sweep_load_ = load_.data();
  if (soil_.active()) {  // the first sweep reads F^{n+1} + g^k, the budget F alone
    if (loaded)
      std::copy(load_.begin(), load_.end(), soil_load_.begin());
    else
      std::fill(soil_load_.begin(), soil_load_.end(), 0.0);
    soil_.add_load(soil_load_.data());
    sweep_load_ = soil_load_.data();
  }
  if (partitioned()) {
    step_partitioned(loaded);
  } else {
    if (loaded || soil_.active())
      viscous_ ? forward<true, true>(t) : forward<true, false>(t);
    else
      viscous_ ? forward<false, true>(t) : forward<false, false>(t);
    solve_links();
    if (loaded)
      viscous_ ? backward<true, true>() : backward<true, false>();
    else
      viscous_ ? backward<false, true>() : backward<false, false>();
  }
  ++n_;
  book_links(t);
}

// The partitioned step: r alone, the chunks' eliminations (x_0 free), the
// links at node 0, the back substitution, then a, u, v and the budget.
void LineNewmark::step_partitioned(bool loaded) {
  const double t = static_cast<double>(n_ + 1) * dt_;
  if (!viscous_) {
    loaded ? step_elastic<true>(t) : step_elastic<false>(t);
    return;
  }
  if (loaded)
    viscous_ ? forward<true, true, false>(t) : forward<true, false, false>(t);
  else
    viscous_ ? forward<false, true, false>(t) : forward<false, false, false>(t);
  near_free_ = partitioned_.eliminate(rhs_);
  solve_links();
  partitioned_.substitute(rhs_);
  if (loaded)
    viscous_ ? backward<true, true, true>() : backward<true, false, true>();
  else
    viscous_ ? backward<false, true, true>() : backward<false, false, true>();
}

// The partitioned step without viscosity, its passes as loops a compiler
// vectorises: the predictors, r (each bond's tension formed for both its
// rows), the solve, then a, u, v; the operations of forward() and
// backward_block() row by row, hence the same bits as the viscous form.
template <bool loaded>
void LineNewmark::step_elastic(double t) {
  const std::size_t n = line_.nodes(), last = n - 1;
  const double dt = dt_, c1 = (0.5 - beta_) * dt * dt, c2 = (1.0 - gamma_) * dt;
  const double bdt2 = beta_ * dt * dt, gdt = gamma_ * dt;
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  double* __restrict a = acc_.data();
  double* __restrict y = rhs_.data();
  const double* __restrict k = stiff_bond_.data();
  const double* __restrict f = sweep_load_;
  const double* __restrict f_old = load_old_.data();
  for (int e = 0; e < 2; ++e) {
    const std::size_t j = e == 0 ? 0 : last;
    end_old_[e][0] = v[j];
    end_old_[e][1] = a[j];
  }
  for (std::size_t j = 0; j < n; ++j) {
    u[j] += dt * v[j] + c1 * a[j];
    v[j] += c2 * a[j];
  }
  for (std::size_t j = 1; j < last; ++j)
    y[j] = (loaded ? f[j] : 0.0) + k[j] * (u[j + 1] - u[j]) - k[j - 1] * (u[j] - u[j - 1]);
  y[0] = end_row(0, (loaded ? f[0] : 0.0) + k[0] * (u[1] - u[0]), t);
  y[last] = end_row(last, (loaded ? f[last] : 0.0) - k[last - 1] * (u[last] - u[last - 1]), t);
  near_free_ = partitioned_.eliminate(rhs_);
  solve_links();
  partitioned_.substitute(rhs_);
  double work = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    const double anew = y[j];
    if constexpr (loaded) {
      const double vold = v[j] - c2 * a[j];
      work += (dt * vold + c1 * a[j] + bdt2 * anew) * 0.5 * (f_old[j] + f[j]);
    }
    u[j] += bdt2 * anew;
    v[j] += gdt * anew;
    a[j] = anew;
  }
  step_work_ = work;
  step_dissipation_ = 0.0;
  for (int e = 0; e < 2; ++e) {
    const std::size_t j = e == 0 ? 0 : last;
    du_end_[e] = dt * end_old_[e][0] + c1 * end_old_[e][1] + bdt2 * a[j];
  }
}

void LineNewmark::advance_soil() {
  if (!advance_soil_level(
          soil_, [this] { advance_elastic(); }, [this] { return soil_.settled(u_.data(), v_.data()); }))
    return;
  soil_.accept(kept_displacement(), u_.data());
  const std::size_t toe = soil_.toe_link();
  if (toe == Link::ground) return;
  force_[toe] = p_old_[toe] = soil_.toe_force();
  if (line_.links[toe].name == "near_end") near_force_ = force_[toe];
}

// Towards x = 0: u^*, v^* in place (node j - 1's one row ahead, for the
// bond below), r_j = F_j + T_j - T_{j-1} with T_j = k_j (u^*_{j+1} - u^*_j)
// + c_j (v^*_{j+1} - v^*_j), y_j = r_j - coupling_j y_{j+1}. The end rows
// take their end forces or their held accelerations.
// Without `eliminated`, y is r itself (the partitioned solve eliminates).
template <bool loaded, bool viscous, bool eliminated>
void LineNewmark::forward(double t) {
  const std::size_t n = line_.nodes(), last = n - 1;
  const double dt = dt_, c1 = (0.5 - beta_) * dt * dt, c2 = (1.0 - gamma_) * dt;
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  const double* __restrict a = acc_.data();
  double* __restrict y = rhs_.data();
  const double* __restrict k = stiff_bond_.data();
  const double* __restrict c = visc_bond_.data();
  const double* __restrict cp = coupling_.data();
  const double* __restrict f = sweep_load_;
  for (int e = 0; e < 2; ++e) {  // the ends' v^n and a^n, kept for their u^{n+1} - u^n
    const std::size_t j = e == 0 ? 0 : last;
    end_old_[e][0] = v[j];
    end_old_[e][1] = a[j];
  }
  auto predict = [&](std::size_t j) {
    u[j] += dt * v[j] + c1 * a[j];
    v[j] += c2 * a[j];
  };
  auto tension = [&](std::size_t j) {  // bond j, predictors of j and j + 1 in place
    double s = k[j] * (u[j + 1] - u[j]);
    if constexpr (viscous) s += c[j] * (v[j + 1] - v[j]);
    return s;
  };
  auto load = [&](std::size_t j) {
    if constexpr (loaded) return f[j];
    (void)j;
    return 0.0;
  };
  predict(last);
  if (n == 1) {
    y[0] = end_row(0, load(0), t);
    return;
  }
  predict(last - 1);
  double below = tension(last - 1);
  double carry = end_row(last, load(last) - below, t);
  y[last] = carry;
  for (std::size_t j = last - 1; j > 0; --j) {
    const double above = below;
    predict(j - 1);
    below = tension(j - 1);
    if constexpr (eliminated)
      carry = load(j) + above - below - cp[j] * carry;
    else
      carry = load(j) + above - below;
    y[j] = carry;
  }
  y[0] = end_row(0, load(0) + below, t) - (eliminated ? cp[0] * carry : 0.0);
}

// An end node's row: its right-hand side with its end force, or a held
// end's prescribed acceleration (clamped: 0; driven: v^{n+1} = v(t) = v^* +
// gamma dt a^{n+1}).
double LineNewmark::end_row(std::size_t j, double r, double t) const {
  for (const End* e : {&line_.near, &line_.far}) {
    if (e->node != j) continue;
    const double value = e == &line_.near ? near_value(t) : far_value(t);
    if (e->kind == EndKind::clamped) return 0.0;
    if (e->kind == EndKind::velocity) return (value - v_[j]) / (gamma_ * dt_);
    if (e->kind == EndKind::force) r += value;
  }
  return r;
}

// Away from x = 0, block by block: x_j = y_j inv_j - lower_j x_{j-1} (the
// links' forces at the blocks' first rows already in y), plus - p A^{-1} e_a
// on a block whose last-row link pushes; a, u, v from the predictors; the
// step's load work and viscous dissipation from the levels at t_n,
// recovered: v^n = v^* - (1 - gamma) dt a^n, u^{n+1} - u^n = dt v^n +
// (1/2 - beta) dt^2 a^n + beta dt^2 a^{n+1}.
template <bool loaded, bool viscous, bool solved>
void LineNewmark::backward() {
  double x = 0.0, dw = 0.0, dd = 0.0, vbar_below = 0.0;
  for (const Block& b : blocks_) {
    const double p = b.far_link == none ? 0.0 : force_[b.far_link];
    if (p != 0.0)
      backward_block<loaded, viscous, true, solved>(b.first, b.last, p, x, dw, dd, vbar_below);
    else
      backward_block<loaded, viscous, false, solved>(b.first, b.last, 0.0, x, dw, dd, vbar_below);
  }
  step_work_ = dw;
  step_dissipation_ = dd;
  const std::size_t last = line_.nodes() - 1;
  const double dt = dt_, bdt2 = beta_ * dt * dt, c1 = (0.5 - beta_) * dt * dt;
  for (int e = 0; e < 2; ++e) {
    const std::size_t j = e == 0 ? 0 : last;
    const double a_old = end_old_[e][1];
    du_end_[e] = dt * end_old_[e][0] + c1 * a_old + bdt2 * acc_[j];
  }
}

template <bool loaded, bool viscous, bool pushed, bool solved>
void LineNewmark::backward_block(std::size_t first, std::size_t last, double p, double& x, double& dw, double& dd,
                                 double& vbar_below) {
  const double dt = dt_, bdt2 = beta_ * dt * dt, gdt = gamma_ * dt;
  const double c1 = (0.5 - beta_) * dt * dt, c2 = (1.0 - gamma_) * dt;
  double* __restrict u = u_.data();
  double* __restrict v = v_.data();
  double* __restrict a = acc_.data();
  const double* __restrict y = rhs_.data();
  const double* __restrict inv = inv_pivot_.data();
  const double* __restrict lo = lower_.data();
  const double* __restrict g = last_response_.data();
  const double* __restrict c = visc_bond_.data();
  const double* __restrict f_old = load_old_.data();
  const double* __restrict f = load_.data();
  double work = 0.0, loss = 0.0, vb = vbar_below;
  for (std::size_t j = first; j <= last; ++j) {
    if constexpr (solved)
      x = y[j];
    else
      x = y[j] * inv[j] - lo[j] * x;
    double anew = x;
    if constexpr (pushed) anew -= p * g[j];
    const double vold = v[j] - c2 * a[j];
    if constexpr (loaded) work += (dt * vold + c1 * a[j] + bdt2 * anew) * 0.5 * (f_old[j] + f[j]);
    u[j] += bdt2 * anew;
    v[j] += gdt * anew;
    a[j] = anew;
    if constexpr (viscous) {
      const double vbar = 0.5 * (v[j] + vold);
      if (j > 0) loss += dt * c[j - 1] * (vbar - vb) * (vbar - vb);
      vb = vbar;
    }
  }
  dw += work;
  dd += loss;
  vbar_below = vb;
}

// The links' c_max, the ends' forces and supports, and the budget's end and link terms.
void LineNewmark::book_links(double t) {
  double dw = step_work_, dd = step_dissipation_;
  const double s_near = support(line_.near.node, t), s_far = support(line_.far.node, t);
  if (line_.fixed(line_.near.node)) dw += 0.5 * (support_old_[0] + s_near) * du_end_[0];
  if (line_.fixed(line_.far.node)) dw += 0.5 * (support_old_[1] + s_far) * du_end_[1];
  if (line_.near.kind == EndKind::force) dw += 0.5 * (near_value(t - dt_) + near_value(t)) * du_end_[0];
  if (line_.far.kind == EndKind::force) dw += 0.5 * (far_value(t - dt_) + far_value(t)) * du_end_[1];
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const ContactLaw& law = line_.links[i].law;
    const double c = -line_.opening(i, u_.data());
    c_max_[i] = std::max(c_max_[i], c);
    if (law.kind == LawKind::viscoelastic)  // the force beyond the spring's, trapezoidal (as the single bar's)
      dd += 0.5 *
            ((p_old_[i] - law.stiffness * std::max(0.0, c_old_[i])) + (force_[i] - law.stiffness * std::max(0.0, c))) *
            (c - c_old_[i]);
    p_old_[i] = force_[i];
    c_old_[i] = c;
  }
  ext_work_ += dw;
  dissipation_ += dd;
  if (!load_zero_ && !load_steady_) load_old_ = load_;
  support_old_[0] = s_near;
  support_old_[1] = s_far;
  near_force_ = near_link_                          ? force_.front()
                : line_.near.kind == EndKind::force ? near_value(t)
                : line_.fixed(line_.near.node)      ? s_near
                                                    : 0.0;
  far_force_ = far_link_                          ? force_.back()
               : line_.far.kind == EndKind::force ? -far_value(t)
               : line_.fixed(line_.far.node)      ? -s_far
                                                  : 0.0;
}

Energies LineNewmark::energies() const {
  Energies e;
  e.kinetic = 0.5 * mass_.quadratic_form(v_);
  e.strain = 0.5 * line_.bond_form(BondKind::element, false, u_.data(), u_.data());
  e.obstacle = 0.5 * line_.bond_form(BondKind::spring, false, u_.data(), u_.data()) + link_energy(u_.data());
  e.work = ext_work_;
  e.dissipation = dissipation_;
  e.contact = link_hysteresis();
  if (soil_.active()) {
    e.obstacle += soil_.shaft_energy(u_.data());
    e.contact += soil_.shaft_slip_work() + soil_.damping_work();
  }
  add_plastic(e, u_.data());
  return e;
}

double LineNewmark::soil_slip_work() const {
  return slip_work(soil_);
}

bool LineNewmark::finite() const {
  const std::size_t last = line_.nodes() - 1;
  return !failed_ && std::isfinite(u_[0]) && std::isfinite(u_[last]) && std::isfinite(v_[0]) &&
         std::isfinite(v_[last]) && std::isfinite(ext_work_) && std::isfinite(dissipation_);
}

}  // namespace barimpact
