#include "barimpact/exact/exact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "barimpact/model/expression.hpp"

namespace barimpact::exact {

namespace {
// G: even, 4-periodic, G(s) = -s on [0, 2]; G' = -1 on (0, 2), +1 on (2, 4) mod 4.
double wrap4(double s) {
  const double r = std::fmod(s, 4.0);
  return r < 0.0 ? r + 4.0 : r;
}
double triangle(double s) {
  const double r = wrap4(std::abs(s));
  return r <= 2.0 ? -r : r - 4.0;
}
double triangle_slope(double s) {
  const double sign = s < 0.0 ? -1.0 : 1.0;  // G is even: G'(-s) = -G'(s)
  const double r = wrap4(std::abs(s));
  if (r == 0.0 || r == 2.0) return 0.0;  // mean of the one-sided slopes at a corner
  return sign * (r < 2.0 ? -1.0 : 1.0);
}
}  // namespace

Example1::Example1(double length, double stiffness, double density, double v0)
    : L_(length), a_(stiffness), rho_(density), v0_(v0), c_(std::sqrt(stiffness / density)) {}

double Example1::contact_end() const {
  return v0_ < 0.0 ? 2.0 * L_ / c_ : 0.0;
}

double Example1::u(double x, double t) const {
  if (v0_ >= 0.0) return v0_ * t;
  const double T = contact_end();
  if (t >= T) return -v0_ * (t - T);  // undeformed, leaving with velocity |v0|
  const double amp = -v0_ * L_ / (2.0 * c_);
  return amp * (triangle((x + c_ * t) / L_) - triangle((x - c_ * t) / L_));
}

double Example1::v(double x, double t) const {
  if (v0_ >= 0.0) return v0_;
  const double T = contact_end();
  if (t > T) return -v0_;
  return -v0_ * 0.5 * (triangle_slope((x + c_ * t) / L_) + triangle_slope((x - c_ * t) / L_));
}

double Example1::strain(double x, double t) const {
  if (v0_ >= 0.0 || t >= contact_end()) return 0.0;
  return -v0_ / (2.0 * c_) * (triangle_slope((x + c_ * t) / L_) - triangle_slope((x - c_ * t) / L_));
}

double Example1::R(double t) const {
  if (v0_ >= 0.0 || t < 0.0 || t > contact_end()) return 0.0;
  const double full = rho_ * c_ * (-v0_);
  return (t == 0.0 || t == contact_end()) ? 0.5 * full : full;
}

}  // namespace barimpact::exact

namespace barimpact::exact {

namespace {

class RigidImpact final : public Solution {
 public:
  RigidImpact(double L, double a, double rho, double V, double gap)
      : bar_(L, a, rho, V), V_(V), gap_(gap), hit_(V < 0 ? gap / -V : 0.0), rho_(rho), L_(L) {}
  double U(double t) const override { return u(0.0, t); }
  double V(double t) const override { return v(0.0, t); }
  double R(double t) const override { return V_ < 0 && t >= hit_ ? bar_.R(t - hit_) : 0.0; }
  double valid_until() const override { return std::numeric_limits<double>::infinity(); }
  bool has_field() const override { return true; }
  double u(double x, double t) const override {
    if (V_ >= 0 || t <= hit_) return V_ * t;
    return -gap_ + bar_.u(x, t - hit_);
  }
  double v(double x, double t) const override { return (V_ >= 0 || t <= hit_) ? V_ : bar_.v(x, t - hit_); }
  double strain(double x, double t) const override { return (V_ >= 0 || t <= hit_) ? 0.0 : bar_.strain(x, t - hit_); }
  double energy() const override { return 0.5 * rho_ * L_ * V_ * V_; }
  const char* name() const override { return "rigid obstacle, uniform approach velocity, gap (exact a)"; }

 private:
  Example1 bar_;
  double V_, gap_, hit_, rho_, L_;
};

class RigidImpactWithLoad final : public Solution {
 public:
  RigidImpactWithLoad(double L, double a, double rho, double V, double f)
      : L_(L), rho_(rho), c_(std::sqrt(a / rho)), V_(V), f_(f) {
    // Lift-off: the first zero of R, found on each linear piece.
    const double T = 2.0 * L_ / c_;
    lift_off_ = std::numeric_limits<double>::infinity();
    for (int piece = 0; piece < 64 && !std::isfinite(lift_off_); ++piece) {
      const double t0 = piece * T, t1 = t0 + T;
      const double r0 = R_contact(t0 + 1e-12 * T), r1 = R_contact(t1 - 1e-12 * T);
      if (r0 <= 0)
        lift_off_ = t0;
      else if (r1 <= 0)
        lift_off_ = t0 + T * r0 / (r0 - r1);
    }
  }
  double R_contact(double t) const {
    const double T = 2.0 * L_ / c_;
    const double phase = std::fmod(t, 2.0 * T);
    const double square = phase < T ? 1.0 : -1.0;
    const double triangle = phase < T ? phase : 2.0 * T - phase;
    return rho_ * c_ * -V_ * square - f_ * c_ * triangle;
  }
  double U(double t) const override { return t <= lift_off_ ? 0.0 : std::numeric_limits<double>::quiet_NaN(); }
  double V(double t) const override { return t <= lift_off_ ? 0.0 : std::numeric_limits<double>::quiet_NaN(); }
  double R(double t) const override { return t <= lift_off_ ? std::max(0.0, R_contact(t)) : 0.0; }
  double valid_until() const override { return lift_off_; }
  double energy() const override { return std::numeric_limits<double>::quiet_NaN(); }
  const char* name() const override { return "rigid obstacle under a constant load, until lift-off (exact b)"; }

 private:
  double L_, rho_, c_, V_, f_;
  double lift_off_;
};

class ElasticImpact final : public Solution {
 public:
  ElasticImpact(double L, double a, double rho, double V, double k)
      : rho_(rho), c_(std::sqrt(a / rho)), V_(V), k_(k), L_(L) {
    tau_ = rho_ * c_ / k_;
    T_ = 2.0 * L_ / c_;
    y0_ = 1.0 - std::exp(-T_ / tau_);
    // (2 s + 1 + y0) e^-s = 1 by Newton from s = 1.7.
    double s = 1.7;
    for (int i = 0; i < 50; ++i) {
      const double g = (2.0 * s + 1.0 + y0_) * std::exp(-s) - 1.0;
      const double dg = (1.0 - 2.0 * s - y0_) * std::exp(-s);
      s -= g / dg;
    }
    separation_ = T_ + s * tau_;
  }
  double separation() const { return separation_; }
  double U(double t) const override {
    if (V_ >= 0) return V_ * t;
    if (t <= T_) return V_ * tau_ * (1.0 - std::exp(-t / tau_));
    if (t <= separation_) {
      const double s = (t - T_) / tau_;
      return V_ * tau_ * (-1.0 + (2.0 * s + y0_ + 1.0) * std::exp(-s));
    }
    // Flight: dU/dt = -V + 2 V exp(-(t - 2L/c)/tau), U(separation) = 0.
    auto primitive = [&](double tt) { return -V_ * tt - 2.0 * V_ * tau_ * std::exp(-(tt - T_) / tau_); };
    return primitive(t) - primitive(separation_);
  }
  double V(double t) const override {
    if (V_ >= 0) return V_;
    if (t <= T_) return V_ * std::exp(-t / tau_);
    if (t <= separation_) {
      const double s = (t - T_) / tau_;
      return V_ * (2.0 - 2.0 * s - y0_ - 1.0) * std::exp(-s);
    }
    return -V_ + 2.0 * V_ * std::exp(-(t - T_) / tau_);
  }
  double R(double t) const override { return t <= separation_ ? std::max(0.0, -k_ * U(t)) : 0.0; }
  double valid_until() const override { return 2.0 * T_; }
  double energy() const override { return 0.5 * rho_ * L_ * V_ * V_; }
  const char* name() const override { return "elastic obstacle, uniform approach velocity (exact c)"; }

 private:
  double rho_, c_, V_, k_, L_;
  double tau_ = 0, T_ = 0, y0_ = 0, separation_ = 0;
};

// Integral from 0 to s of the 3-periodic step function with values p[0..2]
// on [0,1), [1,2), [2,3) (s may be negative).
double periodic_integral(const double (&p)[3], double s) {
  const double period = p[0] + p[1] + p[2];
  const double k = std::floor(s / 3.0);
  const double r = s - 3.0 * k;
  double within = 0.0;
  for (int i = 0; i < 3; ++i) within += p[i] * std::clamp(r - i, 0.0, 1.0);
  return k * period + within;
}

double periodic_value(const double (&p)[3], double s) {
  const double r = s - 3.0 * std::floor(s / 3.0);
  return p[std::min(2, static_cast<int>(r))];
}

class ClampedPeriodic final : public Solution {
 public:
  // In units where L = c = 1 and u scales with kappa L: G'(s) = (-1,-1,+1)/4 on
  // the thirds of each period and F'(-s) = (+1,-1,-1)/4, both times 2 kappa;
  // F(0) = G(0) = kappa L / 2.
  ClampedPeriodic(double L, double a, double rho, double kappa)
      : L_(L), a_(a), rho_(rho), c_(std::sqrt(a / rho)), kappa_(kappa) {}
  double G(double s) const {  // s in units of L, value in units of kappa L
    static const double slope[3] = {-0.5, -0.5, 0.5};
    return 0.5 + periodic_integral(slope, s);
  }
  double F(double s) const {                                // F(s) for s in units of L; F(-t) built from F'(-t)
    static const double slope_back[3] = {0.5, -0.5, -0.5};  // F'(-t), t in units
    if (s >= 0) return 0.5 - 0.5 * s;                       // u0 = (1 - x)/2 on [0, 1]: F' = -1/2
    return 0.5 - periodic_integral(slope_back, -s);
  }
  double Fp(double s) const {
    static const double slope_back[3] = {0.5, -0.5, -0.5};
    return s >= 0 ? -0.5 : periodic_value(slope_back, -s);
  }
  double Gp(double s) const {
    static const double slope[3] = {-0.5, -0.5, 0.5};
    return periodic_value(slope, s);
  }
  double u(double x, double t) const override {
    const double X = x / L_, T = c_ * t / L_;
    return kappa_ * L_ * (F(X - T) + G(X + T));
  }
  double v(double x, double t) const override {
    const double X = x / L_, T = c_ * t / L_;
    return kappa_ * c_ * (-Fp(X - T) + Gp(X + T));
  }
  double strain(double x, double t) const override {
    const double X = x / L_, T = c_ * t / L_;
    return kappa_ * (Fp(X - T) + Gp(X + T));
  }
  bool has_field() const override { return true; }
  double U(double t) const override {
    const double T = std::fmod(c_ * t / L_, 3.0);
    if (T <= 1.0) return kappa_ * L_ * (1.0 - T);
    if (T <= 2.0) return 0.0;
    return kappa_ * L_ * (T - 2.0);
  }
  double V(double t) const override {
    const double T = std::fmod(c_ * t / L_, 3.0);
    if (T < 1.0) return -kappa_ * c_;
    if (T < 2.0) return 0.0;
    return kappa_ * c_;
  }
  double R(double t) const override {
    const double T = std::fmod(c_ * t / L_, 3.0);
    return (T > 1.0 && T < 2.0) ? a_ * kappa_ : 0.0;
  }
  double valid_until() const override { return std::numeric_limits<double>::infinity(); }
  double energy() const override { return 0.5 * a_ * kappa_ * kappa_ * L_; }
  const char* name() const override { return "clamped bar released onto a rigid obstacle, period 3L/c (exact d)"; }

 private:
  double L_, a_, rho_, c_, kappa_;
};

}  // namespace

std::unique_ptr<Solution> rigid_impact(double length, double stiffness, double density, double V, double gap) {
  return std::make_unique<RigidImpact>(length, stiffness, density, V, gap);
}
std::unique_ptr<Solution> rigid_impact_with_load(double length, double stiffness, double density, double V, double f) {
  return std::make_unique<RigidImpactWithLoad>(length, stiffness, density, V, f);
}
std::unique_ptr<Solution> elastic_impact(double length, double stiffness, double density, double V, double k) {
  return std::make_unique<ElasticImpact>(length, stiffness, density, V, k);
}
std::unique_ptr<Solution> clamped_periodic(double length, double stiffness, double density, double kappa) {
  return std::make_unique<ClampedPeriodic>(length, stiffness, density, kappa);
}

}  // namespace barimpact::exact

namespace barimpact::exact {

std::unique_ptr<Solution> for_case(const Case& line) {
  const auto one = line.one_bar();
  if (!one) return nullptr;
  const OneBar& c = *one;
  if (c.bar.viscosity != 0.0) return nullptr;
  const Expression u0(c.initial.displacement), v0(c.initial.velocity), f(line.load.body_force);
  const double L = c.bar.length, a = c.bar.stiffness, rho = c.bar.density, g = c.obstacle.gap;
  const int M = c.bar.elements;
  auto at = [&](int j) { return L * j / M; };
  // The value of e when it is the same at every node (and, for f, at all t).
  auto uniform = [&](const Expression& e, double& value) {
    value = e(0.0, 0.0);
    for (int j = 0; j <= M; ++j)
      if (std::abs(e(at(j), 0.0) - value) > 1e-12 * (1.0 + std::abs(value))) return false;
    return !e.depends_on_t();
  };
  double u0c = 0, v0c = 0, fc = 0;
  const bool v_uniform = uniform(v0, v0c), f_uniform = uniform(f, fc);
  if (c.bar.far_end == FarEnd::free && uniform(u0, u0c) && v_uniform && f_uniform && u0c == 0.0 && v0c < 0.0) {
    if (c.obstacle.kind == ObstacleKind::rigid && fc == 0.0) return rigid_impact(L, a, rho, v0c, g);
    if (c.obstacle.kind == ObstacleKind::rigid && g == 0.0) return rigid_impact_with_load(L, a, rho, v0c, fc);
    if (c.obstacle.kind == ObstacleKind::elastic && fc == 0.0 && g == 0.0 && c.obstacle.stiffness > 0)
      return elastic_impact(L, a, rho, v0c, c.obstacle.stiffness);
  }
  if (c.bar.far_end == FarEnd::clamped && c.obstacle.kind == ObstacleKind::rigid && g == 0.0 && v_uniform &&
      v0c == 0.0 && f_uniform && fc == 0.0) {
    const double kappa = u0(0.0, 0.0) / L;
    if (kappa <= 0.0) return nullptr;
    for (int j = 0; j <= M; ++j)
      if (std::abs(u0(at(j), 0.0) - kappa * (L - at(j))) > 1e-12 * kappa * L) return nullptr;
    return clamped_periodic(L, a, rho, kappa);
  }
  return nullptr;
}

}  // namespace barimpact::exact

namespace barimpact::exact {

namespace {

class TabulatedSolution final : public Scheme {
 public:
  TabulatedSolution(const Case& line, std::shared_ptr<const Solution> s)
      : TabulatedSolution(line.time.step, *line.one_bar(), std::move(s)) {}
  TabulatedSolution(double dt, const OneBar& c, std::shared_ptr<const Solution> s)
      : s_(std::move(s)),
        dt_(dt),
        L_(c.bar.length),
        a_(c.bar.stiffness),
        rho_(c.bar.density),
        k_(c.obstacle.kind == ObstacleKind::elastic ? c.obstacle.stiffness : 0.0),
        gap_(c.obstacle.gap),
        nodes_(static_cast<std::size_t>(c.bar.elements) + 1) {}
  void start() override { n_ = 0; }
  void advance() override { ++n_; }
  long long step() const override { return n_; }
  double time() const override { return static_cast<double>(n_) * dt_; }
  std::size_t nodes() const override { return nodes_; }
  double end_displacement() const override { return s_->U(time()); }
  double end_velocity() const override { return s_->V(time()); }
  double reaction() const override { return s_->R(time()); }
  void displacement(std::span<double> out) const override {
    fill(out, [&](double x) { return s_->u(x, time()); });
  }
  void velocity(std::span<double> out) const override {
    fill(out, [&](double x) { return s_->v(x, time()); });
  }
  double displacement_at(std::size_t j) const override {
    return j == 0 ? end_displacement() : s_->has_field() ? s_->u(x(j), time()) : nan();
  }
  double velocity_at(std::size_t j) const override {
    return j == 0 ? end_velocity() : s_->has_field() ? s_->v(x(j), time()) : nan();
  }
  double link_opening(std::size_t /*i*/) const override { return end_displacement() + gap_; }
  Energies energies() const override {
    Energies e;
    const double U = end_displacement();
    e.obstacle = U < 0 ? 0.5 * k_ * U * U : 0.0;
    if (!s_->has_field()) {
      e.kinetic = e.strain = std::numeric_limits<double>::quiet_NaN();
      return e;
    }
    constexpr int cells = 20000;
    const double h = L_ / cells, t = time();
    for (int i = 0; i < cells; ++i) {
      const double x = (i + 0.5) * h, v = s_->v(x, t), eps = s_->strain(x, t);
      e.kinetic += 0.5 * rho_ * v * v * h;
      e.strain += 0.5 * a_ * eps * eps * h;
    }
    return e;
  }
  bool finite() const override { return true; }

 private:
  template <class F>
  void fill(std::span<double> out, F f) const {
    for (std::size_t j = 0; j < out.size(); ++j)
      out[j] = s_->has_field() ? f(L_ * static_cast<double>(j) / static_cast<double>(nodes_ - 1))
                               : std::numeric_limits<double>::quiet_NaN();
  }
  double x(std::size_t j) const { return L_ * static_cast<double>(j) / static_cast<double>(nodes_ - 1); }
  static double nan() { return std::numeric_limits<double>::quiet_NaN(); }
  std::shared_ptr<const Solution> s_;
  double dt_, L_, a_, rho_, k_, gap_;
  std::size_t nodes_;
  long long n_ = 0;
};

}  // namespace

std::unique_ptr<Scheme> as_scheme(const Case& c, std::shared_ptr<const Solution> solution) {
  return std::make_unique<TabulatedSolution>(c, std::move(solution));
}

}  // namespace barimpact::exact
