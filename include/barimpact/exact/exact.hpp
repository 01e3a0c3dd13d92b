// Closed-form solutions used as references (docs/methods.md derives each).
//
// All are for a uniform elastic bar (b = 0) of length L, stiffness a and
// mass per unit length rho, wave speed c = sqrt(a/rho), written with the
// d'Alembert decomposition u = F(x - ct) + G(x + ct) and the boundary
// relations at x = 0 and x = L.
#pragma once

#include <memory>
#include <optional>

#include "barimpact/case/case.hpp"
#include "barimpact/schemes/scheme.hpp"

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

/// A reference solution at x = 0 (and, where known, in the bar).
class Solution {
 public:
  virtual ~Solution() = default;
  [[nodiscard]] virtual double U(double t) const = 0;
  [[nodiscard]] virtual double V(double t) const = 0;
  [[nodiscard]] virtual double R(double t) const = 0;
  /// The solution is known on [0, valid_until()].
  [[nodiscard]] virtual double valid_until() const = 0;
  /// u, v and du/dx inside the bar, where the solution gives them.
  [[nodiscard]] virtual bool has_field() const { return false; }
  [[nodiscard]] virtual double u(double /*x*/, double /*t*/) const { return 0.0; }
  [[nodiscard]] virtual double v(double /*x*/, double /*t*/) const { return 0.0; }
  [[nodiscard]] virtual double strain(double /*x*/, double /*t*/) const { return 0.0; }
  /// Total energy (kinetic + strain + obstacle), conserved.
  [[nodiscard]] virtual double energy() const = 0;
  /// One line naming the solution, for summaries.
  [[nodiscard]] virtual const char* name() const = 0;
};

/// (a) A free bar, at rest and undeformed, moving at V < 0 towards a rigid
/// wall a gap g >= 0 away: free flight until g/|V|, then Example 1 (contact
/// for 2L/c with R = rho c |V|), then flight at +|V|.
[[nodiscard]] std::unique_ptr<Solution> rigid_impact(double length, double stiffness, double density, double V,
                                                     double gap);

/// (b) The same, no gap, under a constant uniform body force f: while in
/// contact R = rho c |V| S(t) - f c T(t), S the square wave (+1 on (0, 2L/c),
/// -1 on (2L/c, 4L/c)) and T the triangle wave (T(t) = t, then 4L/c - t);
/// known until lift-off, the first zero of R (for the paper's Example 2
/// data: R = 1 + t, then 3 - t, lift-off at t = 3).
[[nodiscard]] std::unique_ptr<Solution> rigid_impact_with_load(double length, double stiffness, double density,
                                                               double V, double f);

/// (c) The free bar of (a), no gap, against the elastic obstacle k: with
/// tau = rho c / k, rho c dU/dt + k U = 2 rho c^2 G'(ct) gives
/// U = V tau (1 - exp(-t/tau)), R = -k U on (0, 2L/c); then the reflected
/// wave pulls the end off at 2L/c + sigma tau, (2 sigma + 1 + y0) e^-sigma = 1
/// (sigma = 1.6783 when tau << L/c), and the end flies with
/// dU/dt = -V + 2 V exp(-(t - 2L/c)/tau). Known until 4L/c.
[[nodiscard]] std::unique_ptr<Solution> elastic_impact(double length, double stiffness, double density, double V,
                                                       double k);

/// (d) The periodic benchmark: bar clamped at x = L, u0 = kappa (L - x),
/// v0 = 0, rigid obstacle at x = 0 (no gap). Period 3L/c: the end falls to
/// the obstacle at speed kappa c, rests on it for L/c with R = a kappa, and
/// comes back; energy a kappa^2 L / 2 (1/8 for L = a = rho = 1, kappa = 1/2).
[[nodiscard]] std::unique_ptr<Solution> clamped_periodic(double length, double stiffness, double density, double kappa);

/// The exact solution the case admits, if any: (a), (b), (c) or (d) above,
/// recognised from the case's data (expressions evaluated at the nodes).
[[nodiscard]] std::unique_ptr<Solution> for_case(const Case& c);

/// The solution seen through the Scheme interface on the case's time grid
/// and mesh, so that the ordinary loop and observers tabulate it. Energies
/// by the midpoint rule on 20000 cells where u(x, t) is known (the
/// integrands are piecewise constant: error below 1e-4 of the total), NaN
/// where it is not.
[[nodiscard]] std::unique_ptr<Scheme> as_scheme(const Case& c, std::shared_ptr<const Solution> solution);

}  // namespace barimpact::exact
