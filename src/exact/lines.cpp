#include "barimpact/exact/lines.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <queue>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>

#include "barimpact/model/expression.hpp"
#include "barimpact/model/input_error.hpp"

namespace barimpact::exact {

namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

void check_rod(const Rod& r) {
  require(r.length > 0.0 && r.modulus > 0.0 && r.density > 0.0 && r.area > 0.0,
          "a bar needs a positive length, modulus, density and area");
}

void check_link(std::size_t i, std::size_t links) {
  if (i >= links) throw std::out_of_range("no such link");
}

void check_body(std::size_t i, std::size_t bodies) {
  if (i >= bodies) throw std::out_of_range("no such body");
}

// A step function of period P: values[i] on [starts[i], starts[i + 1]) in
// [0, P), starts[0] = 0; with its integral from 0, exact up to rounding.
class PeriodicSteps {
 public:
  PeriodicSteps() = default;
  PeriodicSteps(double period, const std::vector<double>& starts, const std::vector<double>& values) : period_(period) {
    for (std::size_t i = 0; i < starts.size(); ++i) {
      const double end = i + 1 < starts.size() ? starts[i + 1] : period;
      if (end <= starts[i]) continue;  // an empty piece
      starts_.push_back(starts[i]);
      values_.push_back(values[i]);
    }
    starts_.front() = 0.0;
    cumulative_.resize(starts_.size());
    double sum = 0.0;
    for (std::size_t i = 0; i < starts_.size(); ++i) {
      cumulative_[i] = sum;
      const double end = i + 1 < starts_.size() ? starts_[i + 1] : period_;
      sum += values_[i] * (end - starts_[i]);
    }
    total_ = sum;
  }
  [[nodiscard]] double operator()(double s) const {
    double k = 0.0, r = 0.0;
    return values_[locate(s, k, r)];
  }
  /// The integral over (0, s) (negative for s < 0).
  [[nodiscard]] double integral(double s) const {
    double k = 0.0, r = 0.0;
    const std::size_t i = locate(s, k, r);
    return k * total_ + cumulative_[i] + values_[i] * (r - starts_[i]);
  }
  [[nodiscard]] const std::vector<double>& starts() const { return starts_; }
  [[nodiscard]] double period() const { return period_; }

 private:
  std::size_t locate(double s, double& k, double& r) const {
    k = std::floor(s / period_);
    r = s - k * period_;
    if (r >= period_) {  // rounding
      r -= period_;
      k += 1.0;
    }
    r = std::max(r, 0.0);
    return static_cast<std::size_t>(std::upper_bound(starts_.begin(), starts_.end(), r) - starts_.begin()) - 1;
  }
  double period_ = 1.0;
  std::vector<double> starts_, values_, cumulative_;
  double total_ = 0.0;
};

// A piece of a bar's state: strain and velocity constant on [start, next start).
struct Piece {
  double start;
  double strain;
  double velocity;
};

struct State {
  std::vector<Piece> pieces;  // starts from 0, ascending
  double u_near = 0.0;        // u at s = 0
};

// A uniform bar on [0, L] with both ends free, from a piecewise-constant
// state at tau = 0: u = u0 + F(s - c tau) + G(s + c tau), F' and G'
// 2L-periodic step functions (the free ends' reflections
// F'(-r) = -G'(r), G'(L + r) = -F'(L - r) make them so).
class FreeRod {
 public:
  FreeRod() = default;
  FreeRod(double length, double c, const State& state) : L_(length), c_(c), u0_(state.u_near) {
    const auto& p = state.pieces;
    const std::size_t n = p.size();
    auto end = [&](std::size_t i) { return i + 1 < n ? p[i + 1].start : L_; };
    std::vector<double> starts, f, g;
    for (std::size_t i = 0; i < n; ++i) {
      starts.push_back(p[i].start);
      f.push_back(0.5 * (p[i].strain - p[i].velocity / c_));
      g.push_back(0.5 * (p[i].strain + p[i].velocity / c_));
    }
    for (std::size_t i = n; i-- > 0;) {  // the reflections, on [L, 2L)
      starts.push_back(2.0 * L_ - end(i));
      f.push_back(-0.5 * (p[i].strain + p[i].velocity / c_));
      g.push_back(-0.5 * (p[i].strain - p[i].velocity / c_));
    }
    Fp_ = PeriodicSteps(2.0 * L_, starts, f);
    Gp_ = PeriodicSteps(2.0 * L_, starts, g);
  }
  /// u, v, strain at s in [0, L], tau >= 0 (axial force left at 0).
  [[nodiscard]] LineFields at(double s, double tau) const {
    const double xi = s - c_ * tau, eta = s + c_ * tau;
    const double f = Fp_(xi), g = Gp_(eta);
    return {u0_ + Fp_.integral(xi) + Gp_.integral(eta), c_ * (g - f), f + g, 0.0};
  }
  /// The state on [from, to] at tau, its starts measured from `from`.
  [[nodiscard]] State state(double tau, double from, double to) const {
    const double P = 2.0 * L_, tol = 1e-12 * L_;
    std::vector<double> cuts;
    auto add = [&](const PeriodicSteps& w, double shift) {
      for (const double b : w.starts()) {
        const double base = b + shift;
        for (double k = std::ceil((from - base) / P); base + k * P <= to; k += 1.0) cuts.push_back(base + k * P);
      }
    };
    add(Fp_, c_ * tau);   // F'(s - c tau) jumps where s - c tau is a start
    add(Gp_, -c_ * tau);  // G'(s + c tau) likewise
    std::sort(cuts.begin(), cuts.end());
    std::vector<double> bounds{from};
    for (const double s : cuts)
      if (s > bounds.back() + tol && s < to - tol) bounds.push_back(s);
    bounds.push_back(to);
    State out;
    for (std::size_t i = 0; i + 1 < bounds.size(); ++i) {
      const LineFields mid = at(0.5 * (bounds[i] + bounds[i + 1]), tau);
      out.pieces.push_back({bounds[i] - from, mid.strain, mid.v});
    }
    out.u_near = at(from, tau).u;
    return out;
  }

 private:
  double L_ = 1.0, c_ = 1.0, u0_ = 0.0;
  PeriodicSteps Fp_, Gp_;
};

}  // namespace

double Rod::wave_speed() const {
  return std::sqrt(modulus / density);
}
double Rod::impedance() const {
  return area * std::sqrt(modulus * density);
}
double Rod::transit() const {
  return length / wave_speed();
}

std::size_t LineSolution::body_at(double x) const {
  for (std::size_t i = 0; i < bodies(); ++i)
    if (body_near(i) <= x && x <= body_far(i)) return i;
  return bodies();
}

double LineSolution::u(double x, double t) const {
  const std::size_t i = body_at(x);
  return i == bodies() ? not_a_number : fields(i, x, t).u;
}
double LineSolution::v(double x, double t) const {
  const std::size_t i = body_at(x);
  return i == bodies() ? not_a_number : fields(i, x, t).v;
}
double LineSolution::strain(double x, double t) const {
  const std::size_t i = body_at(x);
  return i == bodies() ? not_a_number : fields(i, x, t).strain;
}
double LineSolution::axial_force(double x, double t) const {
  const std::size_t i = body_at(x);
  return i == bodies() ? not_a_number : fields(i, x, t).axial_force;
}

// ---------------------------------------------------------------------------
// SaintVenant

class SaintVenant::Rods {
 public:
  FreeRod joined;        // both rods as one, from t0 (equal impedances: the joint transmits all)
  FreeRod lower, upper;  // each on its own, from t1
};

SaintVenant::SaintVenant(double length1, double length2, double modulus, double density, double area, double v1,
                         double v2, double gap)
    : L1_(length1), L2_(length2), E_(modulus), rho_(density), A_(area), v1_(v1), v2_(v2), gap_(gap) {
  check_rod({length1, modulus, density, area});
  check_rod({length2, modulus, density, area});
  require(gap >= 0.0 && std::isfinite(v1) && std::isfinite(v2), "the gap must be >= 0 and the velocities finite");
  c_ = std::sqrt(E_ / rho_);
  Z_ = A_ * std::sqrt(E_ * rho_);
  auto rods = std::make_unique<Rods>();
  if (v1_ > v2_) {
    t0_ = gap_ / (v1_ - v2_);
    t1_ = t0_ + 2.0 * std::min(L1_, L2_) / c_;
    // At t0 the faces meet: with the upper rod's displacement shifted by the
    // gap the joined rod's u is continuous (v1 t0 on both sides).
    State start;
    start.pieces = {{0.0, 0.0, v1_}, {L1_, 0.0, v2_}};
    start.u_near = v1_ * t0_;
    rods->joined = FreeRod(L1_ + L2_, c_, start);
    const double tau = t1_ - t0_;
    rods->lower = FreeRod(L1_, c_, rods->joined.state(tau, 0.0, L1_));
    State up = rods->joined.state(tau, L1_, L1_ + L2_);
    up.u_near -= gap_;
    rods->upper = FreeRod(L2_, c_, up);
  } else {
    t0_ = t1_ = infinity;
  }
  rods_ = std::move(rods);
}

SaintVenant::~SaintVenant() = default;

double SaintVenant::contact_force() const {
  return v1_ > v2_ ? 0.5 * Z_ * (v1_ - v2_) : 0.0;
}
double SaintVenant::momentum() const {
  return rho_ * A_ * (L1_ * v1_ + L2_ * v2_);
}

double SaintVenant::body_near(std::size_t i) const {
  return i == 0 ? 0.0 : L1_ + gap_;
}
double SaintVenant::body_far(std::size_t i) const {
  return i == 0 ? L1_ : L1_ + gap_ + L2_;
}

LineFields SaintVenant::fields(std::size_t body, double x, double t) const {
  check_body(body, bodies());
  const bool lower = body == 0;
  const double s = lower ? x : x - (L1_ + gap_);
  LineFields f;
  if (t <= t0_) {
    const double v = lower ? v1_ : v2_;
    f = {v * t, v, 0.0, 0.0};
  } else if (t <= t1_) {
    f = rods_->joined.at(lower ? s : L1_ + s, t - t0_);
    if (!lower) f.u -= gap_;
  } else {
    f = (lower ? rods_->lower : rods_->upper).at(s, t - t1_);
  }
  f.axial_force = E_ * A_ * f.strain;
  return f;
}

double SaintVenant::link_force(std::size_t i, double t) const {
  check_link(i, links());
  if (!(v1_ > v2_) || t < t0_ || t > t1_) return 0.0;
  return (t == t0_ || t == t1_) ? 0.5 * contact_force() : contact_force();
}

double SaintVenant::link_opening(std::size_t i, double t) const {
  check_link(i, links());
  if (t <= t0_) return gap_ + (v2_ - v1_) * t;
  if (t <= t1_) return 0.0;
  return gap_ + rods_->upper.at(0.0, t - t1_).u - rods_->lower.at(L1_, t - t1_).u;
}

double SaintVenant::valid_until() const {
  return infinity;
}

double SaintVenant::energy(double /*t*/) const {
  return 0.5 * rho_ * A_ * (L1_ * v1_ * v1_ + L2_ * v2_ * v2_);
}

// ---------------------------------------------------------------------------
// DropMass

namespace {

using Poly = std::vector<double>;  // coefficients of 1, s, s^2, ...

double eval(const Poly& p, double s) {
  double r = 0.0;
  for (std::size_t i = p.size(); i-- > 0;) r = r * s + p[i];
  return r;
}

// The sum of p and its derivatives: the integral of exp(-s) p(s) over (0, s)
// is S(0) - exp(-s) S(s).
Poly derivative_sum(const Poly& p) {
  Poly s(p.size(), 0.0);
  for (std::size_t j = p.size(); j-- > 0;)
    s[j] = p[j] + (j + 1 < p.size() ? static_cast<double>(j + 1) * s[j + 1] : 0.0);
  return s;
}

double exp_integral(const Poly& S, double s) {
  return eval(S, 0.0) - std::exp(-s) * eval(S, s);
}

// C = A - B: w_out = v0 exp(-sigma) C on an interval.
Poly outgoing_wave(const Poly& A, const Poly& B) {
  Poly C(A.size(), 0.0);
  for (std::size_t j = 0; j < C.size(); ++j) C[j] = A[j] - (j < B.size() ? B[j] : 0.0);
  return C;
}

// A - 2 B: the contact force p = Z |v0| exp(-sigma) (A - 2 B) on an interval.
Poly force_polynomial(const Poly& A, const Poly& B) {
  Poly q = A;
  for (std::size_t j = 0; j < B.size(); ++j) q[j] -= 2.0 * B[j];
  return q;
}

// The first zero of q on (0, theta], if any. q varies on the scale of
// sigma ~ 1 (m / Z) at the fastest: 32 samples, and 16 per unit of sigma,
// then the first sign change bisected.
std::optional<double> first_zero(const Poly& q, double theta) {
  const int samples = 32 + static_cast<int>(std::min(1e5, std::ceil(16.0 * theta)));
  double lo = 0.0;
  for (int i = 1; i <= samples; ++i) {
    const double hi = theta * i / samples;
    if (eval(q, hi) > 0.0) {
      lo = hi;
      continue;
    }
    double a = lo, b = hi;
    for (int it = 0; it < 200 && b - a > 0.0; ++it) {
      const double mid = 0.5 * (a + b);
      if (mid <= a || mid >= b) break;
      (eval(q, mid) > 0.0 ? a : b) = mid;
    }
    return b;
  }
  return std::nullopt;
}

// The next interval's B: w_in(s) = w_in(s - T) - V(s - T).
Poly next_incoming_wave(const Poly& A, const Poly& B) {
  Poly next = B;
  next.resize(A.size(), 0.0);
  for (std::size_t j = 0; j < A.size(); ++j) next[j] -= A[j];
  return next;
}

// The next interval's A from its B: V continuous across the interval's
// start; m dV/dt = Z (2 w_in - V), i.e. A' = 2 B.
Poly next_velocity(const Poly& A, const Poly& next_B, double theta) {
  Poly next(next_B.size() + 1, 0.0);
  next[0] = std::exp(-theta) * eval(A, theta);
  for (std::size_t j = 0; j < next_B.size(); ++j) next[j + 1] = 2.0 * next_B[j] / static_cast<double>(j + 1);
  return next;
}

constexpr int max_intervals = 1000;

}  // namespace

// On the contact's interval k (time since impact in [k T, (k + 1) T)), with
// sigma = (time - k T) Z / m: V = v0 exp(-sigma) A(sigma) and
// w_in = v0 exp(-sigma) B(sigma), A and B polynomials of degree k.
struct DropMass::Interval {
  Poly A, B;
  Poly SA, SC;      // derivative sums of A and of C = A - B (w_out = v0 exp(-sigma) C)
  double W0 = 0.0;  // W_out at the interval's start
  double U0 = 0.0;  // the integral of V from the impact to the interval's start
};

DropMass::DropMass(const Rod& bar, double mass, double v0, double gap) : bar_(bar), m_(mass), v0_(v0), gap_(gap) {
  check_rod(bar);
  require(mass > 0.0 && gap >= 0.0 && std::isfinite(v0), "the mass must be positive, the gap >= 0, v0 finite");
  c_ = bar_.wave_speed();
  Z_ = bar_.impedance();
  T_ = 2.0 * bar_.length / c_;
  nu_ = Z_ / m_;
  theta_ = nu_ * T_;  // 2 (bar's mass) / m
  valid_until_ = infinity;
  ts_ = infinity;
  if (!(v0_ < 0.0)) {
    t_hit_ = infinity;
    return;
  }
  t_hit_ = gap_ / -v0_;
  Interval I;
  I.A = {1.0};
  I.B = {0.0};
  for (int k = 0; k < max_intervals; ++k) {
    I.SA = derivative_sum(I.A);
    I.SC = derivative_sum(outgoing_wave(I.A, I.B));
    intervals_.push_back(I);
    // Separation: the first zero of the contact force on (0, theta].
    if (const auto b = first_zero(force_polynomial(I.A, I.B), theta_)) {
      ts_ = k * T_ + *b / nu_;
      Vs_ = v0_ * std::exp(-*b) * eval(I.A, *b);
      us_ = -gap_ + I.U0 + v0_ / nu_ * exp_integral(I.SA, *b);
    }
    if (std::isfinite(ts_)) break;
    // The next interval: W_out and the mass's displacement carried across its start.
    Interval next;
    next.W0 = I.W0 + v0_ / nu_ * exp_integral(I.SC, theta_);
    next.U0 = I.U0 + v0_ / nu_ * exp_integral(I.SA, theta_);
    next.B = next_incoming_wave(I.A, I.B);
    next.A = next_velocity(I.A, next.B, theta_);
    I = std::move(next);
  }
  if (!std::isfinite(ts_)) {
    valid_until_ = t_hit_ + max_intervals * T_;
    return;
  }
  W_ts_ = W_out(ts_);
  W_ts_T_ = W_out(ts_ - T_);
  find_recontact();
}

DropMass::~DropMass() = default;

double DropMass::separation_time() const {
  return t_hit_ + ts_;
}

double DropMass::w_out(double s) const {
  if (s < 0.0) return 0.0;
  double sign = 1.0;
  if (s >= ts_) {  // free end: w_out(s) = w_in(s) = -w_out(s - T)
    const double j = std::floor((s - ts_) / T_) + 1.0;
    s -= j * T_;
    if (std::fmod(j, 2.0) != 0.0) sign = -1.0;
    if (s >= ts_) {  // rounding
      s -= T_;
      sign = -sign;
    }
  }
  const auto k = std::min(static_cast<std::size_t>(std::max(0.0, std::floor(s / T_))), intervals_.size() - 1);
  const Interval& I = intervals_[k];
  const double sigma = nu_ * (s - static_cast<double>(k) * T_);
  return sign * v0_ * std::exp(-sigma) * (eval(I.A, sigma) - eval(I.B, sigma));
}

double DropMass::W_out(double s) const {
  if (s <= 0.0 || intervals_.empty()) return 0.0;
  auto contact = [&](double r) {
    const auto k = std::min(static_cast<std::size_t>(std::floor(r / T_)), intervals_.size() - 1);
    const Interval& I = intervals_[k];
    return I.W0 + v0_ / nu_ * exp_integral(I.SC, nu_ * (r - static_cast<double>(k) * T_));
  };
  if (s <= ts_) return contact(s);
  // Beyond ts, w_out is T-antiperiodic: with I(r) its integral over
  // (ts - T, ts - T + r), W_out(ts + j T + r) = W_out(ts) - [j odd] I(T) + (-1)^(j+1) I(r).
  const double j = std::floor((s - ts_) / T_);
  const double r = std::min(s - ts_ - j * T_, T_);
  const double I_r = contact(ts_ - T_ + r) - W_ts_T_, I_T = W_ts_ - W_ts_T_;
  const bool odd = std::fmod(j, 2.0) != 0.0;
  return W_ts_ - (odd ? I_T : 0.0) + (odd ? I_r : -I_r);
}

double DropMass::mass_u_after(double s) const {
  if (s >= ts_) return us_ + Vs_ * (s - ts_);
  const auto k = std::min(static_cast<std::size_t>(std::floor(s / T_)), intervals_.size() - 1);
  const Interval& I = intervals_[k];
  return -gap_ + I.U0 + v0_ / nu_ * exp_integral(I.SA, nu_ * (s - static_cast<double>(k) * T_));
}

double DropMass::mass_u(double t) const {
  if (!(t > t_hit_)) return v0_ * t;
  return mass_u_after(t - t_hit_);
}

double DropMass::mass_v(double t) const {
  if (!(t > t_hit_)) return v0_;
  const double s = t - t_hit_;
  if (s >= ts_) return Vs_;
  const auto k = std::min(static_cast<std::size_t>(std::floor(s / T_)), intervals_.size() - 1);
  const double sigma = nu_ * (s - static_cast<double>(k) * T_);
  return v0_ * std::exp(-sigma) * eval(intervals_[k].A, sigma);
}

double DropMass::force(double t) const {
  if (!(t >= t_hit_)) return 0.0;
  const double s = t - t_hit_;
  if (s >= ts_) return 0.0;
  const auto k = std::min(static_cast<std::size_t>(std::floor(s / T_)), intervals_.size() - 1);
  const Interval& I = intervals_[k];
  const double sigma = nu_ * (s - static_cast<double>(k) * T_);
  return std::max(0.0, -Z_ * v0_ * std::exp(-sigma) * (eval(I.A, sigma) - 2.0 * eval(I.B, sigma)));
}

double DropMass::opening_after(double s) const {
  return gap_ + mass_u_after(s) - bar_end_u(s);
}

double DropMass::link_opening(std::size_t i, double t) const {
  check_link(i, links());
  if (!(t > t_hit_)) return gap_ + v0_ * t;
  const double s = t - t_hit_;
  return s <= ts_ ? 0.0 : opening_after(s);
}

void DropMass::find_recontact() {
  // After separation the bar's end moves T-periodically from ts + T on
  // (clamped-free, period 2T): y(s + 2T) = y(s) + 2 T Vs there. Scan
  // [ts, ts + 3T] on a grid fine against T and m / Z; past it, with Vs < 0,
  // the first grid point where y(s) + 2 T Vs j <= 0; then bisect.
  const int n = static_cast<int>(std::min(1e6, std::max(128.0, std::ceil(128.0 * theta_))));
  const double h = T_ / n;
  auto y = [&](double s) { return opening_after(s); };
  double hit = infinity;
  std::vector<double> period;  // y on (ts + T, ts + 3T]
  for (int i = 1; i <= 3 * n && !std::isfinite(hit); ++i) {
    const double s = ts_ + i * h, yi = y(s);
    if (yi <= 0.0) hit = s;
    if (i > n) period.push_back(yi);
  }
  if (!std::isfinite(hit) && Vs_ < 0.0) {
    const double drop = 2.0 * T_ * -Vs_;
    for (std::size_t i = 0; i < period.size(); ++i) {
      const double j = std::ceil(period[i] / drop);
      hit = std::min(hit, ts_ + static_cast<double>(n + 1 + static_cast<int>(i)) * h + 2.0 * T_ * j);
    }
  }
  if (!std::isfinite(hit)) return;
  double a = hit - h, b = hit;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (a + b);
    if (mid <= a || mid >= b) break;
    (y(mid) > 0.0 ? a : b) = mid;
  }
  valid_until_ = t_hit_ + b;
}

double DropMass::body_near(std::size_t i) const {
  return i == 0 ? 0.0 : bar_.length + gap_;
}
double DropMass::body_far(std::size_t i) const {
  return i == 0 ? bar_.length : bar_.length + gap_;
}

LineFields DropMass::fields(std::size_t body, double x, double t) const {
  check_body(body, bodies());
  if (body == 1) return {mass_u(t), mass_v(t), 0.0, 0.0};
  if (!(t > t_hit_)) return {};
  const double s = t - t_hit_, d = (bar_.length - x) / c_;
  const double wR = w_in(s + d), wL = w_out(s - d);
  const double strain = (wL - wR) / c_;
  return {W_in(s + d) + W_out(s - d), wR + wL, strain, bar_.modulus * bar_.area * strain};
}

double DropMass::energy(double /*t*/) const {
  return 0.5 * m_ * v0_ * v0_;
}

// ---------------------------------------------------------------------------
// Junction

double Junction::Steps::value(double t) const {
  const auto i = static_cast<std::size_t>(std::lower_bound(time.begin(), time.end(), t) - time.begin());
  return i == 0 ? 0.0 : sum[i - 1];
}

double Junction::Steps::integral(double t) const {
  const auto i = static_cast<std::size_t>(std::lower_bound(time.begin(), time.end(), t) - time.begin());
  return i == 0 ? 0.0 : t * sum[i - 1] - moment[i - 1];
}

namespace {

// The velocity jumps of the fronts at one node of the lattice of times
// n1 tau1 + n2 tau2: a at x = 0, b and d at the junction (in bar 1 and in
// bar 2), e at the far end.
struct NodeJumps {
  double a = 0.0, b = 0.0, d = 0.0, e = 0.0;
};

using JumpList = std::vector<std::pair<double, double>>;  // (time, jump), in time order

// Every front's jumps up to the horizon, by where they happen; valid_until
// is the horizon, or the time the events ran out.
struct FrontHistory {
  JumpList a, b, d, e;
  double valid_until;
};

// Velocity coefficients at the junction: r reflected, t transmitted, for a
// wave from bar 1 (12) or from bar 2 (21).
struct JunctionRatios {
  double r12, t12, r21, t21;
};

JunctionRatios junction_ratios(double Z1, double Z2) {
  const double sum = Z1 + Z2;
  return {(Z1 - Z2) / sum, 2.0 * Z1 / sum, (Z2 - Z1) / sum, 2.0 * Z2 / sum};
}

// The lattice's nodes that fronts have reached but that are not yet
// passed on, in time order (then level n1 + n2).
class FrontLattice {
 public:
  using Entry = std::tuple<double, std::uint64_t, std::uint64_t, std::uint64_t>;  // time, level, n1, n2

  FrontLattice(double tau1, double tau2) : tau1_(tau1), tau2_(tau2) {}

  // A node's jumps; a node new to the lattice is queued at its time.
  NodeJumps& at(std::uint64_t n1, std::uint64_t n2) {
    auto [it, fresh] = pending_.try_emplace(key(n1, n2));
    if (fresh) queue_.emplace(static_cast<double>(n1) * tau1_ + static_cast<double>(n2) * tau2_, n1 + n2, n1, n2);
    return it->second;
  }
  [[nodiscard]] bool empty() const { return queue_.empty(); }
  [[nodiscard]] const Entry& next() const { return queue_.top(); }
  // The earliest node's jumps, the node taken off the lattice.
  NodeJumps take() {
    const auto [time, level, n1, n2] = queue_.top();
    queue_.pop();
    const auto node = pending_.extract(key(n1, n2));
    return node.mapped();
  }

 private:
  static std::uint64_t key(std::uint64_t n1, std::uint64_t n2) { return (n1 << 32) | n2; }

  double tau1_, tau2_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue_;
  std::unordered_map<std::uint64_t, NodeJumps> pending_;
};

// A node's jumps recorded at its time and passed to the nodes one transit
// later: a reaches the junction, b the force end (which reflects velocity
// unchanged), d the free end (so does it), e the junction from bar 2.
void pass_on(FrontLattice& lattice, std::uint64_t n1, std::uint64_t n2, double time, const NodeJumps& j,
             const JunctionRatios& r, FrontHistory& history) {
  if (j.a != 0.0) {
    history.a.emplace_back(time, j.a);
    NodeJumps& next = lattice.at(n1 + 1, n2);
    if (r.r12 != 0.0) next.b += r.r12 * j.a;
    next.d += r.t12 * j.a;
  }
  if (j.b != 0.0) {
    history.b.emplace_back(time, j.b);
    lattice.at(n1 + 1, n2).a += j.b;
  }
  if (j.d != 0.0) {
    history.d.emplace_back(time, j.d);
    lattice.at(n1, n2 + 1).e += j.d;
  }
  if (j.e != 0.0) {
    history.e.emplace_back(time, j.e);
    NodeJumps& next = lattice.at(n1, n2 + 1);
    next.b += r.t21 * j.e;
    if (r.r21 != 0.0) next.d += r.r21 * j.e;
  }
}

// The fronts from a velocity jump `a0` at x = 0 at t = 0, up to the horizon.
// A node's jumps come from nodes one step earlier, so taking nodes in time
// order completes each before it is used; past 4 million events the
// history ends early.
FrontHistory trace_fronts(double tau1, double tau2, const JunctionRatios& r, double a0, double horizon) {
  FrontHistory history{{}, {}, {}, {}, horizon};
  FrontLattice lattice(tau1, tau2);
  lattice.at(0, 0).a = a0;
  constexpr std::size_t max_events = 4'000'000;
  std::size_t events = 0;
  while (!lattice.empty()) {
    const auto [time, level, n1, n2] = lattice.next();
    if (time > horizon) break;
    if (++events > max_events) {
      history.valid_until = time;
      break;
    }
    const NodeJumps j = lattice.take();
    pass_on(lattice, n1, n2, time, j, r, history);
  }
  return history;
}

}  // namespace

Junction::Junction(const Rod& bar1, const Rod& bar2, double force, double horizon)
    : bar1_(bar1), bar2_(bar2), F0_(force) {
  check_rod(bar1);
  check_rod(bar2);
  require(std::isfinite(force) && !(horizon < 0.0), "the force must be finite and the horizon >= 0");
  c1_ = bar1_.wave_speed();
  c2_ = bar2_.wave_speed();
  Z1_ = bar1_.impedance();
  Z2_ = bar2_.impedance();
  tau1_ = bar1_.transit();
  tau2_ = bar2_.transit();
  valid_until_ = infinity;
  if (F0_ == 0.0) return;
  // Front events on the lattice of times n1 tau1 + n2 tau2, from the jump
  // that makes N = Z1 (b - a) = -F0 at x = 0.
  const FrontHistory history = trace_fronts(tau1_, tau2_, junction_ratios(Z1_, Z2_), F0_ / Z1_, horizon);
  valid_until_ = history.valid_until;
  // Each wave's velocity, its running sum of jumps, and the moment that integrates it.
  auto running_sums = [](const JumpList& jumps) {
    Steps s;
    double sum_j = 0.0, moment = 0.0;
    for (const auto& [t, size] : jumps) {
      sum_j += size;
      moment += size * t;
      s.time.push_back(t);
      s.sum.push_back(sum_j);
      s.moment.push_back(moment);
    }
    return s;
  };
  a_ = running_sums(history.a);
  b_ = running_sums(history.b);
  d_ = running_sums(history.d);
  e_ = running_sums(history.e);
}

Junction::~Junction() = default;

double Junction::transmitted_ratio() const {
  return 2.0 * Z2_ / (Z1_ + Z2_);
}
double Junction::reflected_ratio() const {
  return (Z2_ - Z1_) / (Z1_ + Z2_);
}

double Junction::U(double t) const {
  return a_.integral(t) + b_.integral(t - tau1_);
}
double Junction::V(double t) const {
  return a_.value(t) + b_.value(t - tau1_);
}

double Junction::body_near(std::size_t i) const {
  return i == 0 ? 0.0 : bar1_.length;
}
double Junction::body_far(std::size_t i) const {
  return i == 0 ? bar1_.length : bar1_.length + bar2_.length;
}

LineFields Junction::fields(std::size_t body, double x, double t) const {
  check_body(body, bodies());
  // Velocity w_R of the wave along +x and w_L of the one along -x:
  // v = w_R + w_L, strain = (w_L - w_R) / c, N = Z (w_L - w_R).
  double wR = 0.0, wL = 0.0, u = 0.0, c = 0.0, Z = 0.0;
  if (body == 0) {
    const double tR = t - x / c1_, tL = t - (bar1_.length - x) / c1_;
    wR = a_.value(tR);
    wL = b_.value(tL);
    u = a_.integral(tR) + b_.integral(tL);
    c = c1_;
    Z = Z1_;
  } else {
    const double xi = x - bar1_.length;
    const double tR = t - xi / c2_, tL = t - (bar2_.length - xi) / c2_;
    wR = d_.value(tR);
    wL = e_.value(tL);
    u = d_.integral(tR) + e_.integral(tL);
    c = c2_;
    Z = Z2_;
  }
  return {u, wR + wL, (wL - wR) / c, Z * (wL - wR)};
}

double Junction::link_force(std::size_t i, double /*t*/) const {
  check_link(i, links());
  return 0.0;
}
double Junction::link_opening(std::size_t i, double /*t*/) const {
  check_link(i, links());
  return 0.0;
}

// ---------------------------------------------------------------------------
// Recognising a line case

namespace {

// The value of an expression that uses neither x nor t.
bool constant(const std::string& text, double& value) {
  try {
    const Expression e(text);
    if (e.depends_on_x() || e.depends_on_t()) return false;
    value = e(0.0, 0.0);
    return std::isfinite(value);
  } catch (const InputError&) {
    return false;
  }
}

Rod rod_of(const BodyData& b) {
  return {b.length, b.modulus, b.density, b.area};
}

}  // namespace

// ---------------------------------------------------------------------------
// VonKarman

VonKarman::VonKarman(const Rod& bar, double yield_stress, double tangent_modulus, double velocity, bool wall)
    : bar_(bar), sigma_y_(yield_stress), E_t_(tangent_modulus), V_(velocity), wall_(wall) {
  check_rod(bar);
  require(yield_stress > 0.0 && tangent_modulus > 0.0 && tangent_modulus < bar.modulus && std::isfinite(velocity),
          "von Karman's problem needs sigma_y > 0, 0 < E_t < E and a finite velocity");
  c0_ = bar_.wave_speed();
  c1_ = std::sqrt(E_t_ / bar_.density);
  sign_ = V_ >= 0.0 ? 1.0 : -1.0;
  eps_y_ = sigma_y_ / bar_.modulus;
  v_y_ = c0_ * eps_y_;
  plastic_ = std::abs(V_) > v_y_;
  eps_plateau_ = plastic_ ? eps_y_ + (std::abs(V_) - v_y_) / c1_ : std::abs(V_) / c0_;
  sigma_plateau_ = plastic_ ? sigma_y_ + E_t_ * (eps_plateau_ - eps_y_) : bar_.modulus * eps_plateau_;
}

double VonKarman::precursor_stress() const {
  return -sign_ * (plastic_ ? sigma_y_ : sigma_plateau_);
}
double VonKarman::plateau_stress() const {
  return -sign_ * sigma_plateau_;
}
double VonKarman::plateau_strain() const {
  return -sign_ * eps_plateau_;
}
double VonKarman::plateau_plastic_strain() const {
  return plastic_ ? -sign_ * (eps_plateau_ - sigma_plateau_ / bar_.modulus) : 0.0;
}

LineFields VonKarman::fields(std::size_t body, double x, double t) const {
  check_body(body, bodies());
  const double front0 = c0_ * t, front1 = plastic_ ? c1_ * t : 0.0;
  const double eps1 = plastic_ ? -sign_ * eps_y_ : plateau_strain(), v1 = plastic_ ? sign_ * v_y_ : V_;
  LineFields f;
  if (x >= front0) {  // ahead of the precursor: at rest (moving at -V towards the wall)
    if (wall_) f = {-V_ * t, -V_, 0.0, 0.0};
    return f;
  }
  if (x >= front1) {
    f = {-(front0 - x) * eps1, v1, eps1, 0.0};
  } else {
    const double eps2 = plateau_strain();
    f = {-(front0 - front1) * eps1 - (front1 - x) * eps2, V_, eps2, 0.0};
  }
  f.axial_force = bar_.area * (x >= front1 ? precursor_stress() : plateau_stress());
  if (wall_) {  // the bar's frame: it moved at -V
    f.u -= V_ * t;
    f.v -= V_;
  }
  return f;
}

double VonKarman::link_force(std::size_t i, double t) const {
  check_link(i, links());
  return t > 0.0 ? -bar_.area * plateau_stress() : 0.0;  // the wall's push: the plateau's compression
}
double VonKarman::link_opening(std::size_t i, double /*t*/) const {
  check_link(i, links());
  return 0.0;
}

double VonKarman::plastic_strain(std::size_t body, double x, double t) const {
  check_body(body, bodies());
  return plastic_ && x < c1_ * t ? plateau_plastic_strain() : 0.0;
}

double VonKarman::work(double t) const {
  return wall_ ? 0.0 : -bar_.area * plateau_stress() * V_ * t;
}

double VonKarman::energy(double t) const {
  return wall_ ? 0.5 * bar_.density * bar_.area * bar_.length * V_ * V_ : work(t);
}

std::optional<Energies> VonKarman::energies(double t) const {
  const double A = bar_.area, rho = bar_.density, E = bar_.modulus;
  const double l1 = plastic_ ? (c0_ - c1_) * t : c0_ * t, l2 = plastic_ ? c1_ * t : 0.0;  // precursor, plastic zone
  const double s1 = std::abs(precursor_stress()), v1 = plastic_ ? v_y_ : std::abs(V_);
  const double s2 = sigma_plateau_, p2 = std::abs(plateau_plastic_strain());
  const double H = E * E_t_ / (E - E_t_);
  Energies e;
  e.kinetic = 0.5 * rho * A * (v1 * v1 * l1 + V_ * V_ * l2);
  if (wall_) {  // the bar's frame: velocities -V + v, the part ahead still moving at -V
    const double ahead = bar_.length - c0_ * t, w1 = v1 - std::abs(V_);
    e.kinetic = 0.5 * rho * A * (V_ * V_ * ahead + w1 * w1 * l1);
  }
  e.strain = A * (0.5 * s1 * s1 / E * l1 + (0.5 * s2 * s2 / E + 0.5 * H * p2 * p2) * l2);
  e.work = work(t);
  e.plastic = A * sigma_y_ * p2 * l2;
  return e;
}

std::unique_ptr<LineSolution> for_line_case(const Case& c) {
  double f = 0.0;
  if (!constant(c.load.body_force, f) || f != 0.0 || c.load.gravity != 0.0) return nullptr;
  if (c.bodies.size() == 1 && c.bodies[0].kind == BodyKind::bar &&
      c.bodies[0].material.kind == MaterialKind::plastic) {  // von Karman's: driven at a constant velocity
    const BodyData& b = c.bodies[0];
    double v = 0.0, u0 = 0.0, v0 = 0.0;
    // A far end loaded from t = 0 would change the bar before the precursor
    // arrives; a free, held or unilateral one acts only after L / c0.
    const bool far_quiet = c.far_end.law != JointLaw::force && c.far_end.law != JointLaw::velocity;
    if (far_quiet && b.viscosity == 0.0 && b.material.hardening_modulus > 0.0 && c.near_end.law == JointLaw::velocity &&
        constant(c.near_end.value, v) && constant(b.displacement, u0) && constant(b.velocity, v0) && u0 == 0.0 &&
        v0 == 0.0)
      return std::make_unique<VonKarman>(rod_of(b), b.material.yield_stress, b.material.hardening_modulus, v);
    // The bar moving at v0 < 0 onto a rigid wall: von Karman's problem at V = -v0, seen from the bar.
    if (far_quiet && b.viscosity == 0.0 && b.material.hardening_modulus > 0.0 && c.near_end.law == JointLaw::rigid &&
        c.near_end.gap == 0.0 && constant(b.displacement, u0) && constant(b.velocity, v0) && u0 == 0.0 && v0 < 0.0)
      return std::make_unique<VonKarman>(rod_of(b), b.material.yield_stress, b.material.hardening_modulus, -v0, true);
    return nullptr;
  }
  for (const BodyData& b : c.bodies)  // the solutions below are elastic
    if (b.material.kind != MaterialKind::elastic) return nullptr;
  if (c.bodies.size() != 2 || c.joints.size() > 1) return nullptr;
  const BodyData& lower = c.bodies[0];
  const BodyData& upper = c.bodies[1];
  for (const BodyData* b : {&lower, &upper})
    if (b->kind == BodyKind::bar && b->viscosity != 0.0) return nullptr;
  const JointData* joint = c.joints.empty() ? nullptr : &c.joints[0];
  if (joint != nullptr && (joint->lower != lower.name || joint->upper != upper.name)) return nullptr;
  double u1 = 0.0, v1 = 0.0, u2 = 0.0, v2 = 0.0;
  if (!constant(lower.displacement, u1) || !constant(lower.velocity, v1) || !constant(upper.displacement, u2) ||
      !constant(upper.velocity, v2) || u1 != 0.0 || u2 != 0.0)
    return nullptr;
  const bool bars = lower.kind == BodyKind::bar && upper.kind == BodyKind::bar;
  const bool rigid = joint != nullptr && joint->law.law == JointLaw::rigid;
  const bool welded = joint == nullptr || joint->law.law == JointLaw::welded;
  const JointLaw near = c.near_end.law, far = c.far_end.law;

  if (bars && rigid && near == JointLaw::free && far == JointLaw::free && lower.modulus == upper.modulus &&
      lower.density == upper.density && lower.area == upper.area)
    return std::make_unique<SaintVenant>(lower.length, upper.length, lower.modulus, lower.density, lower.area, v1, v2,
                                         joint->law.gap);
  if (lower.kind == BodyKind::bar && upper.kind == BodyKind::mass && rigid && near == JointLaw::clamped &&
      far == JointLaw::free && v1 == 0.0)
    return std::make_unique<DropMass>(rod_of(lower), upper.mass, v2, joint->law.gap);
  double F0 = 0.0;
  if (bars && welded && near == JointLaw::force && far == JointLaw::free && v1 == 0.0 && v2 == 0.0 &&
      constant(c.near_end.value, F0))
    return std::make_unique<Junction>(rod_of(lower), rod_of(upper), F0, c.time.end);
  return nullptr;
}

}  // namespace barimpact::exact
