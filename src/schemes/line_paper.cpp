#include "barimpact/schemes/line_paper.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include "barimpact/schemes/penalty_links.hpp"
#include "half_step_terms.hpp"

namespace barimpact {

namespace {
// h_i . x: the change of link i's opening that x gives (its direction's entries).
double along(const Line& line, std::size_t i, const double* x) {
  return line.opening(i, x) - line.links[i].gap;
}
// (h_i)_j: +1 on the link's node b, -1 on a.
double entry(const Link& l, std::size_t j) {
  return j == l.b ? 1.0 : j == l.a ? -1.0 : 0.0;
}
}  // namespace

LinePaper::LinePaper(const Case& c, Line line)
    : LineScheme(c, std::move(line)), alpha_(c.time.alpha), lambda_(c.time.lambda) {
  assemble();
  plan_rows();
  respond_links();
  allocate();
}

// S = lambda^2 M + K + lambda C + sum_i (k_i/2) h_i h_i^T, D = 2 lambda M + C,
// A = M/dt^2 + alpha S + D/(2 dt) (held rows the identity) factored once,
// B1 and B0; the plastic and soil iterations' responses through A.
void LinePaper::assemble() {
  mass_ = line_.mass(true);
  stiff_ = line_.stiffness();
  visc_ = line_.viscosity();

  // S = lambda^2 M + K + lambda C + sum_i (k_i/2) h_i h_i^T, D = 2 lambda M + C.
  Tridiagonal S = Tridiagonal::combine(lambda_ * lambda_, mass_, 1.0, stiff_);
  S = Tridiagonal::combine(1.0, std::move(S), lambda_, visc_);
  for (const auto& l : line_.links) {
    if (l.law.kind == LawKind::smith) continue;  // soil_'s
    const double half = 0.5 * l.law.stiffness;
    if (l.a != Link::ground) S.diag[l.a] += half;
    if (l.b != Link::ground) S.diag[l.b] += half;
    if (l.a != Link::ground && l.b != Link::ground) S.off[std::min(l.a, l.b)] -= half;
  }
  const Tridiagonal D = Tridiagonal::combine(2.0 * lambda_, mass_, 1.0, visc_);
  const double inv_dt2 = 1.0 / (dt_ * dt_), half_inv_dt = 0.5 / dt_;
  Tridiagonal A = Tridiagonal::combine(1.0, Tridiagonal::combine(inv_dt2, mass_, alpha_, S), half_inv_dt, D);
  b1_ = Tridiagonal::combine(2.0 * inv_dt2, mass_, -(1.0 - 2.0 * alpha_), S);
  b0_ = Tridiagonal::combine(1.0, Tridiagonal::combine(-inv_dt2, mass_, -alpha_, S), half_inv_dt, D);
  held_ = hold_rows(line_, A);
  factor_ = TwistedTridiagonal(A);
  // A load at t_{m+1} enters with weight alpha / exp(lambda t_{m+1}): u^{m+1} moves by alpha A^{-1} g.
  set_plastic_levels(A, held_nodes(held_), alpha_);
  // Smith's soil: Phi^m / exp(lambda t_m) moves u^{m+1} = exp(lambda t_{m+1}) z^{m+1}
  // by exp(lambda dt) A^{-1} Phi^m, and the centred velocity by 1/(2 dt) of that.
  const double shift = lambda_ == 0.0 ? 1.0 : std::exp(lambda_ * dt_);
  soil_ = SoilIteration(line_, A, held_nodes(held_), shift, half_inv_dt);
  soil_.use_levels({alpha_ / shift, 1.0 - 2.0 * alpha_, alpha_ * shift});
}

// Which rows take a uniform stretch's constant stencil and which the
// general row, and the blocks of row pairs the two-ended sweeps take.
void LinePaper::plan_rows() {
  const std::size_t n = line_.nodes();
  // Link faces and force ends take forces besides the bonds': general rows.
  std::vector<unsigned char> special(n, 0);
  for (const auto& l : line_.links)
    for (std::size_t j : {l.a, l.b})
      if (j != Link::ground) special[j] = 1;
  for (const End* e : {&line_.near, &line_.far})
    if (e->kind == EndKind::force) special[e->node] = 1;
  for (std::size_t j = 0; j < n; ++j)
    if (special[j]) extra_nodes_.push_back(j);
  // Inside each uniform stretch of a bar a row is the single bar's stencil,
  // its four coefficients one stretch's constants.
  stencil_of_.assign(n, general);
  for (const Stretch& st : uniform_stretches(line_, special, held_)) {
    const std::size_t j = st.first;
    for (std::size_t i = st.first; i < st.last; ++i) stencil_of_[i] = static_cast<std::uint32_t>(stencils_.size());
    stencils_.push_back({b1_.diag[j], b1_.off[j], b0_.diag[j], b0_.off[j]});
  }
  // The sweeps inwards take rows in pairs, j from the top and one from the
  // bottom: runs of pairs whose two stencils stay the same are one block.
  const std::size_t last = n - 1, k = last / 2;
  for (std::size_t j = 0, jb = last - (last - 2 * k); j < k; ++j, --jb) {
    const std::uint32_t top = stencil_of_[j], bottom = stencil_of_[jb];
    if (top != general && bottom != general && !blocks_.empty() && blocks_.back().top == top &&
        blocks_.back().bottom == bottom)
      ++blocks_.back().count;
    else
      blocks_.push_back({1, top, bottom});
  }
  extra_.assign(n, 0.0);
  // Runs of bonds with the same kind, mass and stiffness (a bar body's elements).
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const Bond &b = line_.bonds[j], *a = j > 0 ? &line_.bonds[j - 1] : nullptr;
    if (a && a->kind == b.kind && a->mass == b.mass && a->stiffness == b.stiffness)
      bond_runs_.back().last = j + 1;
    else
      bond_runs_.push_back({j, j + 1});
  }
  for (BondRun& run : bond_runs_)
    for (std::size_t j = run.first; j < run.last && !run.point_masses; ++j)
      run.point_masses = line_.point_mass[j] != 0.0;
}

// The responses w = A^{-1} h of the links whose status changes A, and W
// among them (Woodbury's correction).
void LinePaper::respond_links() {
  const std::size_t n = line_.nodes(), links = line_.links.size();
  for (std::size_t i = 0; i < links; ++i) {
    const ContactLaw& law = line_.links[i].law;
    if (law.kind != LawKind::viscoelastic && !(law.kind == LawKind::cushion && law.restitution < 1.0)) continue;
    std::vector<double> w(n, 0.0);
    for (std::size_t j : {line_.links[i].a, line_.links[i].b})
      if (j != Link::ground && !line_.fixed(j)) w[j] = entry(line_.links[i], j);
    factor_.solve(w.data());
    modifiable_.push_back(i);
    response_.push_back(std::move(w));
  }
  const std::size_t m = modifiable_.size();
  delassus_.assign(m * m, 0.0);
  for (std::size_t r = 0; r < m; ++r)
    for (std::size_t s = 0; s < m; ++s) delassus_[r * m + s] = along(line_, modifiable_[r], response_[s].data());
  capacitance_.assign(m * m, 0.0);
  mu_.assign(m, 0.0);
  changed_.reserve(m);
  sigma_.assign(links, 0.0);
  status_.assign(links, Status::base);
  link_c_.assign(links, 0.0);
}

// The levels, the loads and the iterations' state, allocated once: the
// time loop allocates nothing.
void LinePaper::allocate() {
  const std::size_t n = line_.nodes();
  for (const auto& b : line_.bonds) {
    viscosity_.push_back(b.viscosity);
    viscous_ = viscous_ || b.viscosity != 0.0;
  }
  for (auto& l : levels_) l.assign(n, 0.0);
  load_mode_ = load_zero_ ? LoadMode::zero : load_steady_ ? LoadMode::steady : LoadMode::unsteady;
  step_mode_ = load_mode_;
  if (load_mode_ != LoadMode::zero || plastic_iteration_.active() || soil_.active())
    for (auto& f : loads_) f.assign(n, 0.0);
  if (soil_.active())  // the misfit refuses elastic-plastic bodies with it
    for (auto* x : {&soil_rhs_, &soil_u_, &soil_old_, &soil_v_}) x->assign(n, 0.0);
  if (plastic_iteration_.active()) {
    plastic_ = PlasticBonds(line_, alpha_);
    if (lambda_ != 0.0)
      for (auto& u : scaled_) u.assign(n, 0.0);
  }
  // A kept level's loads are kept with it: they are overwritten three steps on.
  if (soil_.active() || plastic_iteration_.active()) kept_.keep(state());  // primed: keeping never allocates
}

double LinePaper::scale(long long m) const {
  return lambda_ == 0.0 ? 1.0 : std::exp(lambda_ * static_cast<double>(m) * dt_);
}

std::array<double, 3> LinePaper::load_weights(long long m) const {
  return {alpha_ / scale(m + 1), (1.0 - 2.0 * alpha_) / scale(m), alpha_ / scale(m - 1)};
}

void LinePaper::start() {
  start_loads();
  std::vector<HeldRow> rows;
  double viscous = 0.0;
  const std::vector<double> a0 = initial_acceleration(rows, viscous);
  taylor_start(a0, rows);
  if (plastic_iteration_.active()) start_plastic_level();
  book_start(viscous);
}

// Level 0's pointers and loads: F(0), F(dt) when it moves, the force ends' values.
void LinePaper::start_loads() {
  prev_ = levels_[2].data();
  cur_ = levels_[0].data();
  next_ = levels_[1].data();
  n_ = 0;
  cached_ = {};
  for (auto& f : loads_) std::fill(f.begin(), f.end(), 0.0);  // no plastic load of an earlier run
  start_plastic(u0_.data());                                  // p^0 from u0
  if (load_mode_ != LoadMode::zero) line_.load(*body_force_, 0.0, loads_[0]);
  if (load_mode_ == LoadMode::unsteady) line_.load(*body_force_, dt_, loads_[1]);
  if ((plastic_iteration_.active() || soil_.active()) && load_mode_ == LoadMode::steady)
    loads_[1] = loads_[2] = loads_[0];  // the levels the first unsteady step reads (the plastic or soil mode's)
  if (plastic_iteration_.loading()) plastic_iteration_.add_load(loads_[0].data());
  near_f_ = {near_value(0.0), near_value(dt_), 0.0};
  far_f_ = {far_value(0.0), far_value(dt_), 0.0};
}

// The links at t = 0, and a0 = M^{-1} (F(0) - K u0 - C v0 + links + end
// forces), held rows at their ends' accelerations: 0, or a driven node's
// 2 (v(dt/2) - v(0)) / dt, which makes the Taylor step its dt v(dt/2).
// `rows` the held rows; `viscous` the links' dissipation rate at t = 0.
std::vector<double> LinePaper::initial_acceleration(std::vector<HeldRow>& rows, double& viscous) {
  const std::size_t n = line_.nodes();
  std::vector<double> r(n, 0.0), cv(n, 0.0);
  stiff_.multiply(u0_, r);
  visc_.multiply(v0_, cv);
  for (std::size_t j = 0; j < n; ++j) r[j] = (load_zero_ ? 0.0 : loads_[0][j]) - r[j] - cv[j];
  if (line_.near.kind == EndKind::force) r[line_.near.node] += near_f_[0];
  if (line_.far.kind == EndKind::force) r[line_.far.node] += far_f_[0];
  viscous = 0.0;
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const ContactLaw& law = line_.links[i].law;
    const double c = -line_.opening(i, u0_.data()), rate = -along(line_, i, v0_.data());
    link_c_[i] = c;
    c_max_[i] = std::max(0.0, c);
    force_[i] = law.force(c, rate, c_max_[i]);
    add_link_force(i, force_[i], r.data());
    if (law.kind != LawKind::smith)
      viscous += law.damping_part(force_[i], c, c_max_[i]) * rate;  // soil_ books the toe's
  }
  if (soil_.active()) {
    soil_.start(u0_.data(), v0_.data());
    soil_.add_start_forces(r.data());
  }
  Tridiagonal m = mass_;
  rows = hold_rows(line_, m);
  for (auto& h : rows) {
    const double v_half = h.near ? near_value(0.5 * dt_) : far_value(0.5 * dt_);
    h.value = h.driven ? 2.0 * (v_half - v0_[h.node]) / dt_ : 0.0;
    h.rhs = r[h.node];
    r[h.node] = h.value;
    if (h.neighbour != HeldRow::none) r[h.neighbour] -= h.coupling * h.value;
  }
  FactoredTridiagonal(m, false).solve(r);
  for (std::size_t k = 0; k < rows.size(); ++k) held_[k].support = rows[k].residual(r.data());
  return r;
}

// z^0 = u0 and, by Taylor, z^1 = z(0) + dt z'(0) + (dt^2/2) z''(0) with
// z' = v0 - lambda u0, z'' = a0 - 2 lambda v0 + lambda^2 u0.
void LinePaper::taylor_start(const std::vector<double>& a0, const std::vector<HeldRow>& rows) {
  const std::size_t n = line_.nodes();
  const double half_dt2 = 0.5 * dt_ * dt_, l = lambda_;
  for (std::size_t j = 0; j < n; ++j) {
    cur_[j] = prev_[j] = u0_[j];
    next_[j] = u0_[j] + dt_ * (v0_[j] - l * u0_[j]) + half_dt2 * (a0[j] - 2.0 * l * v0_[j] + l * l * u0_[j]);
  }
  for (const auto& h : rows)  // a held node moves as every step will move it, exactly
    next_[h.node] =
        h.driven ? (u0_[h.node] + dt_ * (h.near ? near_value(0.5 * dt_) : far_value(0.5 * dt_))) / scale(1) : 0.0;
  if (soil_.active()) {
    for (std::size_t j = 0; j < n; ++j) soil_u_[j] = scale(1) * next_[j];
    soil_.start_levels(soil_u_.data(), v0_.data(), dt_);
  }
}

// p^1 from the return map at u^1, its load in F(t_1); the start's share of
// the plastic work and load work at level "-1" = u^1 - dt v0.
void LinePaper::start_plastic_level() {
  const std::size_t n = line_.nodes();
  const bool yielded = plastic_iteration_.take(next_, scale(1));
  plastic_loads();
  if (plastic_iteration_.loading()) plastic_iteration_.add_load(loads_[1].data());  // F(t_1) + G p^1
  plastic_.start(u0_.data());
  std::vector<double> u1(n), before(n);
  for (std::size_t j = 0; j < n; ++j) {
    u1[j] = scale(1) * next_[j];
    before[j] = u1[j] - dt_ * v0_[j];
  }
  plastic_.record(plastic_iteration_.strain(), plastic_iteration_.accumulated(), yielded, before.data(), u0_.data(),
                  u1.data(), {0.0, 1.0, 0.0}, true);
}

// The first half step's share of the budget: dt/2 times the rates at t = 0
// (`viscous` the links' share), and the ends' forces reported at t = 0.
void LinePaper::book_start(double viscous) {
  const std::size_t n = line_.nodes();
  double power = 0.0;
  for (std::size_t j = 0; j < n; ++j) power += (load_zero_ ? 0.0 : loads_[0][j]) * v0_[j];
  if (line_.near.kind == EndKind::force) power += near_f_[0] * v0_[line_.near.node];
  if (line_.far.kind == EndKind::force) power += far_f_[0] * v0_[line_.far.node];
  for (const auto& h : held_) power += h.support * v0_[h.node];
  for (std::size_t j = 0; j + 1 < n; ++j) viscous += viscosity_[j] * (v0_[j + 1] - v0_[j]) * (v0_[j + 1] - v0_[j]);
  work_half_ = 0.5 * dt_ * power;
  dissipation_half_ = 0.5 * dt_ * viscous;
  work_last_ = dissipation_last_ = 0.0;
  const EndReport e = end_report(line_, force_, near_f_[0], far_f_[0], held_, 1.0);
  near_force_ = e.near;
  far_force_ = e.far;
}

void LinePaper::advance() {
  if (soil_.active()) {
    advance_soil();
    return;
  }
  if (!plastic_iteration_.active()) {
    advance_elastic();
    return;
  }
  const long long m = n_ + 1;
  const bool yielded = advance_plastic_levels([this] { advance_elastic(); },
                                              [this] {
                                                return std::pair<const double*, double>{next_, scale(n_ + 1)};
                                              });
  if (!failed_) record_plastic(m, yielded);
}

void LinePaper::advance_soil() {
  const bool held = advance_soil_level(
      soil_,
      [this] {
        advance_elastic();
        soil_levels();
      },
      [this] { return soil_.settled(soil_u_.data(), soil_v_.data()); });
  if (held) soil_.accept(soil_old_.data(), soil_u_.data());
}

void LinePaper::soil_levels() {
  const std::size_t n = line_.nodes();
  const double sp = scale(n_ + 1), sm = scale(n_ - 1), inv_2dt = 0.5 / dt_;
  for (std::size_t j = 0; j < n; ++j) {
    soil_u_[j] = sp * next_[j];
    soil_old_[j] = sm * prev_[j];
    soil_v_[j] = (soil_u_[j] - soil_old_[j]) * inv_2dt;
  }
}

double LinePaper::soil_slip_work() const {
  return slip_work(soil_);
}

void LinePaper::displacements(long long first, const double* (&u)[3]) const {
  u[0] = prev_;
  u[1] = cur_;
  u[2] = next_;
  if (lambda_ == 0.0) return;
  const std::size_t n = line_.nodes();
  for (std::size_t k = 0; k < 3; ++k) {
    const double s = scale(first + static_cast<long long>(k));
    for (std::size_t j = 0; j < n; ++j) scaled_[k][j] = s * u[k][j];
    u[k] = scaled_[k].data();
  }
}

void LinePaper::record_plastic(long long m, bool yielded) {
  const double* u[3] = {prev_, cur_, next_};
  if (yielded || !plastic_.pristine()) displacements(m - 1, u);  // else record reads no u
  std::array<double, 3> w = load_weights(m);                     // the weights W_ext's booking gives G p (book_level)
  for (double& x : w) x *= scale(m);
  plastic_.record(plastic_iteration_.strain(), plastic_iteration_.accumulated(), yielded, u[0], u[1], u[2], w);
}

void LinePaper::advance_elastic() {
  const long long m = n_ + 1;
  // The plastic strains' load makes F move (their arrays hold G p, and F if any).
  step_mode_ = soil_.active()                 ? LoadMode::soil
               : load_zero_                   ? LoadMode::zero
               : plastic_iteration_.loading() ? LoadMode::unsteady
                                              : load_mode_;
  prepare(m);
  if (soil_.active()) {
    std::fill(soil_rhs_.begin(), soil_rhs_.end(), 0.0);
    soil_.add_load(soil_rhs_.data());
    if (lambda_ != 0.0)
      for (double& f : soil_rhs_) f /= scale(m);
  }
  switch (step_mode_) {
    case LoadMode::zero:
      sweeps<LoadMode::zero>(m);
      break;
    case LoadMode::steady:
      sweeps<LoadMode::steady>(m);
      break;
    case LoadMode::unsteady:
      sweeps<LoadMode::unsteady>(m);
      break;
    case LoadMode::soil:
      sweeps<LoadMode::soil>(m);
      break;
  }
  correct(prev_);
  supports(prev_);
  double* oldest = prev_;
  prev_ = cur_;
  cur_ = next_;
  next_ = oldest;
  n_ = m;
  book_level(m);
  report();
}

// Level m's explicit terms. For each link, y = h . z (its opening but the
// gap, in z), c^m its compression in u; the split spring's |.| half and its
// gap's share, or what its status puts in place of them, as s_i on h_i; the
// status's change of A as sigma_i. Then the force ends' F^{m,alpha} and the
// held rows' known z^{m+1}.
void LinePaper::prepare(long long m) {
  const double* zc = next_;  // z^m
  const double* zo = cur_;   // z^{m-1}
  const double em1 = 1.0 / scale(m - 1), e0 = 1.0 / scale(m), ep1 = 1.0 / scale(m + 1);
  const double ebar = alpha_ * ep1 + (1.0 - 2.0 * alpha_) * e0 + alpha_ * em1;
  for (std::size_t j : extra_nodes_) extra_[j] = 0.0;
  changed_.clear();
  for (std::size_t i = 0; i < line_.links.size(); ++i) link_row(i, zc, zo, em1, e0, ebar);
  for (std::size_t r = 0; r < modifiable_.size(); ++r)
    if (sigma_[modifiable_[r]] != 0.0) changed_.push_back(r);
  end_rows(m, zc, e0, ep1);
}

// Link i's terms at level m: its compression and largest compression, its
// law's status, the explicit half of its force into extra_ and its share of
// A (sigma_).
void LinePaper::link_row(std::size_t i, const double* zc, const double* zo, double em1, double e0, double ebar) {
  const ContactLaw& law = line_.links[i].law;
  const double g = line_.links[i].gap, k = law.stiffness;
  const double ym = along(line_, i, zc), yo = along(line_, i, zo);
  const double c = -(ym / e0 + g);
  link_c_[i] = c;
  c_max_[i] = std::max(c_max_[i], c);
  if (law.kind == LawKind::smith) {  // soil_'s force, in soil_rhs_
    status_[i] = Status::base;
    sigma_[i] = 0.0;
    return;
  }
  const double implicit_rest = (1.0 - 2.0 * alpha_) * ym + alpha_ * yo;  // y^{m,alpha} but its z^{m+1} part
  double s = 0.5 * k * (std::abs(ym + g * e0) - g * ebar), sigma = 0.0;
  Status status = Status::base;
  if (law.kind == LawKind::viscoelastic && c > 0.0) {
    const double l = law.viscosity, rate = (c + (yo / em1 + g)) / dt_;  // (c^m - c^{m-1}) / dt
    if (k * c + l * rate > 0.0) {
      status = Status::pushing;
      s += l * (yo * 0.5 / dt_ - lambda_ * implicit_rest);
      sigma = l * (alpha_ * lambda_ + 0.5 / dt_);
    } else {
      status = Status::clipped;
      s = 0.5 * k * implicit_rest;
      sigma = -0.5 * alpha_ * k;
    }
  } else if (law.kind == LawKind::cushion && c_max_[i] > 0.0 && c < c_max_[i]) {
    // Off the loading line: the kink moves to c_off = (1 - e^2) c_max, where
    // the law unloads to 0, as a gap g + c_off. Above it the slope is k/e^2;
    // at or below it (clipped) the factored k/2 is kept, its force ~0 as the
    // elastic law's apart, and A is left alone.
    const double e2 = law.restitution * law.restitution, c_off = (1.0 - e2) * c_max_[i], G = g + c_off;
    if (c > c_off) {
      const double kk = k / e2, delta = 0.5 * (kk - k);
      status = Status::unloading;
      s = 0.5 * kk * (std::abs(ym + G * e0) - G * ebar) - delta * implicit_rest;
      sigma = alpha_ * delta;
    } else {
      s = 0.5 * k * (std::abs(ym + G * e0) - G * ebar);
    }
  }
  status_[i] = status;
  sigma_[i] = sigma;
  if (s != 0.0) add_link_force(i, s, extra_.data());
}

// The force ends' alpha-mean values and the held rows' targets at level m.
void LinePaper::end_rows(long long m, const double* zc, double e0, double ep1) {
  const double t = static_cast<double>(m + 1) * dt_;
  const std::array<double, 3> w = load_weights(m);
  const auto slot = [](long long k) { return static_cast<std::size_t>(k % 3); };
  if (line_.near.kind == EndKind::force) {
    near_f_[slot(m + 1)] = near_value(t);
    extra_[line_.near.node] += w[0] * near_f_[slot(m + 1)] + w[1] * near_f_[slot(m)] + w[2] * near_f_[slot(m - 1)];
  }
  if (line_.far.kind == EndKind::force) {
    far_f_[slot(m + 1)] = far_value(t);
    extra_[line_.far.node] += w[0] * far_f_[slot(m + 1)] + w[1] * far_f_[slot(m)] + w[2] * far_f_[slot(m - 1)];
  }
  for (auto& h : held_) {
    const double v_half = h.near ? near_value(t - 0.5 * dt_) : far_value(t - 0.5 * dt_);
    h.value = h.driven ? (zc[h.node] / e0 + dt_ * v_half) * ep1 : 0.0;
  }
}

double LinePaper::special_row(std::size_t j, double load) {
  const double* zc = next_;
  const double* zo = cur_;
  double r = b1_.diag[j] * zc[j] + b0_.diag[j] * zo[j] + load + extra_[j];
  if (j > 0) r += b1_.off[j - 1] * zc[j - 1] + b0_.off[j - 1] * zo[j - 1];
  if (j + 1 < line_.nodes()) r += b1_.off[j] * zc[j + 1] + b0_.off[j] * zo[j + 1];
  return held_row(held_, j, r);
}

// z^{m+1} into prev_: the right-hand side B1 z^m + B0 z^{m-1} + F^{m,alpha} +
// extra formed row by row as the two-ended solve's sweeps inwards reach it
// (the single bar's constant stencils in each stretch), then the sweep out.
// F at t_{m+1}, t_m, t_{m-1} (a steady load's in the middle; an unsteady
// load's newest formed here, into the slot three levels old).
template <LinePaper::LoadMode mode>
std::array<const double*, 3> LinePaper::level_loads(long long m) {
  if constexpr (mode == LoadMode::steady) {
    return {nullptr, loads_[0].data(), nullptr};
  } else if constexpr (mode == LoadMode::unsteady || mode == LoadMode::soil) {
    auto& newest = loads_[static_cast<std::size_t>((m + 1) % 3)];
    load_into(static_cast<double>(m + 1) * dt_, newest);
    return {newest.data(), loads_[static_cast<std::size_t>(m % 3)].data(),
            loads_[static_cast<std::size_t>((m - 1) % 3)].data()};
  }
  return {nullptr, nullptr, nullptr};
}

template <LinePaper::LoadMode mode>
void LinePaper::sweeps(long long m) {
  const double* __restrict zc = next_;
  const double* __restrict zo = cur_;
  const std::array<double, 3> w = load_weights(m);
  const std::array<const double*, 3> f = level_loads<mode>(m);  // not a structured binding: lambdas capture these
  const double* fp = f[0];
  const double* f0 = f[1];
  const double* fm = f[2];
  const double wbar = w[0] + w[1] + w[2];
  const double* soil = soil_rhs_.data();
  auto load = [=](std::size_t j) {
    if constexpr (mode == LoadMode::zero) {
      (void)j;
      return 0.0;
    } else if constexpr (mode == LoadMode::steady) {
      return wbar * f0[j];
    } else if constexpr (mode == LoadMode::unsteady) {
      return w[0] * fp[j] + w[1] * f0[j] + w[2] * fm[j];
    } else {
      return w[0] * fp[j] + w[1] * f0[j] + w[2] * fm[j] + soil[j];
    }
  };
  auto stencil_row = [&](const Stencil& t, std::size_t j) {
    const double r = t.b1d * zc[j] + t.b1o * (zc[j - 1] + zc[j + 1]) + t.b0d * zo[j] + t.b0o * (zo[j - 1] + zo[j + 1]);
    if constexpr (mode == LoadMode::zero) return r;  // not even the + 0.0 IEEE would keep
    return r + load(j);
  };
  auto row = [&](std::size_t j) {
    const std::uint32_t s = stencil_of_[j];
    return s == general ? special_row(j, load(j)) : stencil_row(stencils_[s], j);
  };
  double* x = prev_;
  const std::size_t last = line_.nodes() - 1, k = last / 2;
  double yt = 0.0, yb = 0.0;
  std::size_t j = 0, jb = last;
  if (last > 2 * k) {  // the lower half's extra row
    factor_.inward(row(jb), jb, yb, x);
    --jb;
  }
  for (const Block& b : blocks_) {
    if (b.top == general || b.bottom == general) {
      factor_.inward(row(j), j, yt, x);
      factor_.inward(row(jb), jb, yb, x);
      ++j, --jb;
      continue;
    }
    const Stencil top = stencils_[b.top], bottom = stencils_[b.bottom];  // constants of the loop
    for (std::uint32_t c = 0; c < b.count; ++c, ++j, --jb) {
      factor_.inward(stencil_row(top, j), j, yt, x);
      factor_.inward(stencil_row(bottom, jb), jb, yb, x);
    }
  }
  factor_.outward(row(k), yt, yb, x);
}

// (A + sum_J sigma_i h_i h_i^T)^{-1} r = y - sum_J mu_i w_i with
// (I + Sigma W_JJ) mu = Sigma H_J^T y, y = A^{-1} r in zn.
void LinePaper::correct(double* zn) {
  const std::size_t nj = changed_.size(), nm = modifiable_.size();
  if (nj == 0) return;
  for (std::size_t a = 0; a < nj; ++a) {
    const std::size_t i = modifiable_[changed_[a]];
    const double sigma = sigma_[i];
    for (std::size_t b = 0; b < nj; ++b)
      capacitance_[a * nj + b] = (a == b ? 1.0 : 0.0) + sigma * delassus_[changed_[a] * nm + changed_[b]];
    mu_[a] = sigma * along(line_, i, zn);
  }
  (void)solve_dense(nj, capacitance_.data(), mu_.data());  // I + Sigma W: A + Sigma changes stays positive definite
  const std::size_t n = line_.nodes();
  for (std::size_t a = 0; a < nj; ++a) {
    const double c = mu_[a];
    const double* __restrict w = response_[changed_[a]].data();
    for (std::size_t j = 0; j < n; ++j) zn[j] -= c * w[j];
  }
}

// Each held row's residual in its original equation, the links' implicit
// change sigma_i h_i (h_i . z^{m+1}) on it included: the support's force (z-units).
void LinePaper::supports(const double* zn) {
  for (auto& h : held_) {
    h.support = h.residual(zn);
    for (std::size_t r : changed_) {
      const std::size_t i = modifiable_[r];
      h.support += sigma_[i] * entry(line_.links[i], h.node) * along(line_, i, zn);
    }
  }
}

// Level m's increments (the levels m - 1, m, m + 1 are prev_, cur_, next_):
// each force of the step tested with (u^{m+1} - u^{m-1}) / 2.
void LinePaper::book_level(long long m) {
  const std::size_t n = line_.nodes();
  const double sm = scale(m - 1), s0 = scale(m), sp = scale(m + 1);
  auto moved = [&](std::size_t j) { return 0.5 * (sp * next_[j] - sm * prev_[j]); };
  const std::array<double, 3> w = load_weights(m);
  double dw = 0.0;
  if (step_mode_ == LoadMode::steady) {
    const double c = s0 * (w[0] + w[1] + w[2]);
    for (std::size_t j = 0; j < n; ++j) dw += c * loads_[0][j] * moved(j);
  } else if (step_mode_ == LoadMode::unsteady || step_mode_ == LoadMode::soil) {  // F alone: soil_ books the soil
    const auto& fp = loads_[static_cast<std::size_t>((m + 1) % 3)];
    const auto& f0 = loads_[static_cast<std::size_t>(m % 3)];
    const auto& fm = loads_[static_cast<std::size_t>((m - 1) % 3)];
    for (std::size_t j = 0; j < n; ++j) dw += s0 * (w[0] * fp[j] + w[1] * f0[j] + w[2] * fm[j]) * moved(j);
  }
  const auto at = [](const std::array<double, 3>& f, long long k) { return f[static_cast<std::size_t>(k % 3)]; };
  if (line_.near.kind == EndKind::force)
    dw += s0 * (w[0] * at(near_f_, m + 1) + w[1] * at(near_f_, m) + w[2] * at(near_f_, m - 1)) * moved(line_.near.node);
  if (line_.far.kind == EndKind::force)
    dw += s0 * (w[0] * at(far_f_, m + 1) + w[1] * at(far_f_, m) + w[2] * at(far_f_, m - 1)) * moved(line_.far.node);
  for (const auto& h : held_) dw += s0 * h.support * moved(h.node);

  double dd = 0.0;
  if (viscous_) {  // dt |(u^{m+1} - u^{m-1}) / (2 dt)|_C^2
    const double inv_dt = 1.0 / dt_;
    for (std::size_t j = 0; j + 1 < n; ++j) {
      const double d = (moved(j + 1) - moved(j)) * inv_dt;  // the bond's stretching rate
      dd += dt_ * viscosity_[j] * d * d;
    }
  }
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    if (status_[i] != Status::pushing && status_[i] != Status::clipped) continue;
    const Link& l = line_.links[i];
    const double dy = 0.5 * (sp * along(line_, i, next_) - sm * along(line_, i, prev_));  // (y^{m+1} - y^{m-1}) / 2
    if (status_[i] == Status::pushing) {
      const double rate = dy / dt_;
      dd += dt_ * l.law.viscosity * rate * rate;
    } else {
      // The spring lets go unloaded: k c^m (c^{m-1} - c^{m+1}) / 2, which telescopes to what k c^2 / 2 loses.
      dd += l.law.stiffness * link_c_[i] * dy;
    }
  }
  work_last_ = dw;
  dissipation_last_ = dd;
  work_half_ += dw;
  dissipation_half_ += dd;
}

void LinePaper::report() {
  const double sm = scale(n_ - 1), sp = scale(n_ + 1);
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const double rate = -(sp * along(line_, i, next_) - sm * along(line_, i, prev_)) / (2.0 * dt_);
    force_[i] = line_.links[i].law.force(link_c_[i], rate, c_max_[i]);
  }
  const auto k = static_cast<std::size_t>(n_ % 3);
  const EndReport e = end_report(line_, force_, near_f_[k], far_f_[k], held_, scale(n_));
  near_force_ = e.near;
  far_force_ = e.far;
}

double LinePaper::velocity_at(std::size_t j) const {
  if (n_ == 0) return v0_[j];
  return (scale(n_ + 1) * next_[j] - scale(n_ - 1) * prev_[j]) / (2.0 * dt_);
}

namespace {

// A run of equal bonds, nodes first..last: the levels (a, b) with their
// scales, the nodes' point masses, the bonds' mass / 3, stiffness and
// 4 (alpha - 1/4) (the rate term's weight beside the mean's).
struct BondRunTerms {
  detail::LevelPair levels;
  const double* mass;
  double third, stiffness, extra;
  bool open;
};

// The run's kinetic and bond sums (half_step_terms.hpp's terms, times dt^2
// and 4) into the two sums: four elements at a time in four lanes by
// element - first mod 4, each in node order, folded at the run's end.
// Without point masses (a bar's inner nodes) their stream is not read.
template <bool point_masses>
BARIMPACT_ENERGY_CLONES void add_run(const BondRunTerms& r, std::size_t first, std::size_t last, double& kinetic_sum,
                                     double& bond_sum) {
  using detail::Lanes;
  Lanes kinetic{}, rate{}, mean{}, nodes{};
  std::size_t e = first;
  for (; e + 4 <= last; e += 4) {
    detail::ElementTerms<Lanes> t;
    detail::element_terms(r.levels, e, t);
    kinetic += t.kinetic, rate += t.rate, mean += t.mean;
    if constexpr (point_masses) {
      Lanes m;
      detail::load(m, r.mass + e);
      nodes += m * t.d0 * t.d0;
    }
  }
  for (; e < last; ++e) {
    const detail::LevelPair& p = r.levels;
    detail::ElementTerms<double> t;
    detail::element_terms(p, p.za[e], p.zb[e], p.za[e + 1], p.zb[e + 1], t);
    const std::size_t l = (e - first) & 3;
    kinetic[l] += t.kinetic, rate[l] += t.rate, mean[l] += t.mean;
    if constexpr (point_masses) nodes[l] += r.mass[e] * t.d0 * t.d0;
  }
  kinetic_sum += r.third * detail::fold(kinetic);
  if constexpr (point_masses) kinetic_sum += detail::fold(nodes);
  if (!r.open) bond_sum += r.stiffness * (detail::fold(mean) + r.extra * detail::fold(rate));
}

}  // namespace

// (1/2)|w|_M^2, and (1/2)|m|_K^2 + (alpha - 1/4)(dt^2/2)|w|_K^2 over the bar
// elements and over the springs, w = (u^b - u^a)/dt, m = (u^b + u^a)/2: the
// identity (7.1) makes their sum telescope (lambda = 0). Run by run of
// equal bonds (add_run), each taking its constants once; the factors 1/dt^2
// and 1/4 the terms share applied at the end.
void LinePaper::half_step(const double* za, double sa, const double* zb, double sb, double (&e)[3]) const {
  const std::size_t n = line_.nodes();
  const double extra = 4.0 * (alpha_ - 0.25);
  const double* mass = line_.point_mass.data();
  double kinetic = 0.0, strain = 0.0, springs = 0.0;
  for (const BondRun& run : bond_runs_) {
    const Bond& b = line_.bonds[run.first];
    const BondRunTerms terms{{za, zb, sa, sb}, mass, b.mass / 3.0, b.stiffness, extra, b.kind == BondKind::open};
    double& bond_sum = b.kind == BondKind::element ? strain : springs;
    run.point_masses ? add_run<true>(terms, run.first, run.last, kinetic, bond_sum)
                     : add_run<false>(terms, run.first, run.last, kinetic, bond_sum);
  }
  const double dl = sb * zb[n - 1] - sa * za[n - 1];
  kinetic += mass[n - 1] * dl * dl;
  e[0] = 0.5 * kinetic / (dt_ * dt_);
  e[1] = 0.125 * strain;
  e[2] = 0.125 * springs;
}

Energies LinePaper::energies() const {
  Energies e;
  for (std::size_t i = 0; i < line_.links.size(); ++i) e.obstacle += line_.links[i].law.energy(link_c_[i], c_max_[i]);
  e.contact = link_hysteresis();
  if (n_ == 0) {
    e.kinetic = 0.5 * mass_.quadratic_form(v0_);
    e.strain = 0.5 * line_.bond_form(BondKind::element, false, u0_.data(), u0_.data());
    e.obstacle += 0.5 * line_.bond_form(BondKind::spring, false, u0_.data(), u0_.data());
    if (plastic_.active()) e.strain += plastic_.strain_energy(u0_.data());
    add_soil(e, u0_.data(), 1.0);
    return e;
  }
  double before[3], after[3];
  if (cached_.n == n_ - 1) {  // the previous row's n + 1/2 is this row's n - 1/2
    std::copy(cached_.e, cached_.e + 3, before);
  } else {
    half_step(prev_, scale(n_ - 1), cur_, scale(n_), before);
  }
  half_step(cur_, scale(n_), next_, scale(n_ + 1), after);
  cached_.n = n_;
  std::copy(after, after + 3, cached_.e);
  e.kinetic = 0.5 * (before[0] + after[0]);
  e.strain = 0.5 * (before[1] + after[1]);
  e.obstacle += 0.5 * (before[2] + after[2]);
  e.work = work_half_ - 0.5 * work_last_;
  e.dissipation = dissipation_half_ - 0.5 * dissipation_last_;
  if (plastic_.active()) {
    const double* u[3];
    displacements(n_ - 1, u);
    e.strain += plastic_.strain_energy(u[0], u[1], u[2]);
    e.work -= plastic_.load_work();
    e.plastic = plastic_.work();
  }
  add_soil(e, cur_, scale(n_));
  return e;
}

void LinePaper::add_soil(Energies& e, const double* u_kept, double s) const {
  if (!soil_.active()) return;
  e.obstacle += soil_.shaft_energy(u_kept, s);
  e.contact += soil_.shaft_slip_work() + soil_.damping_work();
}

bool LinePaper::finite() const {
  const std::size_t last = line_.nodes() - 1;
  return !failed_ && std::isfinite(cur_[0]) && std::isfinite(cur_[last]) && std::isfinite(next_[0]) &&
         std::isfinite(next_[last]) && std::isfinite(work_half_) && std::isfinite(dissipation_half_) &&
         std::isfinite(scale(n_ + 1));
}

}  // namespace barimpact
