// Closed-form solutions used as references.
#pragma once

namespace barimpact::exact {

/// The paper's Example 1 (Section 8), for any L, a, rho: an elastic bar at
/// rest and undeformed, moving with uniform velocity v0 < 0 at t = 0 towards
/// a rigid obstacle at x = 0, f = 0, far end free. With c = sqrt(a/rho), the
/// end stays on the obstacle for 0 < t < 2L/c with R = rho c |v0|; then the
/// bar, undeformed again, leaves with velocity |v0|. Inside the contact phase
/// u(x, t) = (G(x + ct) - G(x - ct)) |v0| L / (2c), G the even 4-periodic
/// triangle wave with G(s) = -s on [0, 2] (arguments in units of L).
/// With v0 >= 0 there is no contact: u = v0 t.
class Example1 {
 public:
  Example1(double length, double stiffness, double density, double v0);

  [[nodiscard]] double wave_speed() const { return c_; }
  /// 2L/c, when the bar leaves the obstacle (0 without contact).
  [[nodiscard]] double contact_end() const;
  [[nodiscard]] double u(double x, double t) const;
  [[nodiscard]] double v(double x, double t) const;
  /// du/dx.
  [[nodiscard]] double strain(double x, double t) const;
  [[nodiscard]] double U(double t) const { return u(0.0, t); }
  [[nodiscard]] double V(double t) const { return v(0.0, t); }
  /// The obstacle's force; on the contact interval's ends the mean of the
  /// one-sided values.
  [[nodiscard]] double R(double t) const;
  /// Kinetic + strain energy, rho L v0^2 / 2 at every t.
  [[nodiscard]] double energy() const { return 0.5 * rho_ * L_ * v0_ * v0_; }

 private:
  double L_, a_, rho_, v0_, c_;
};

}  // namespace barimpact::exact
