// Closed-form reference solutions for lines of bodies (docs/methods.md,
// "Exact solutions for lines"): two free rods colliding (Saint-Venant), a
// rigid mass striking a clamped bar (Saint-Venant and Boussinesq), a step
// force wave through a welded junction of two bars.
//
// Conventions, those of the line: x along the line, bodies listed from
// x = 0 outward; u and v along +x; strain u_x, tension positive; axial
// force N = E A u_x (tension positive); a link's force p is a compression
// (p > 0 while the faces push on each other) and its opening is the
// clearance between the faces (upper face's position minus the lower's);
// c = sqrt(E / rho), impedance Z = rho c A = A sqrt(E rho). Every bar here
// is elastic (no viscosity) and unloaded (no body force, no gravity).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/exact/exact.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace barimpact::exact {

/// A uniform elastic bar's data: length, Young's modulus E, density rho
/// (per unit volume) and cross-section area A.
struct Rod {
  double length = 1.0;
  double modulus = 1.0;
  double density = 1.0;
  double area = 1.0;

  [[nodiscard]] double wave_speed() const;  ///< c = sqrt(E / rho)
  [[nodiscard]] double impedance() const;   ///< Z = A sqrt(E rho)
  [[nodiscard]] double mass() const { return density * area * length; }
  [[nodiscard]] double transit() const;  ///< L / c
};

/// One body's fields at one point.
struct LineFields {
  double u = 0.0;            ///< displacement along +x
  double v = 0.0;            ///< velocity along +x
  double strain = 0.0;       ///< u_x, tension positive (0 for a mass)
  double axial_force = 0.0;  ///< N = E A u_x, tension positive (0 for a mass)
};

/// A reference solution for a line of bodies.
class LineSolution {
 public:
  virtual ~LineSolution() = default;

  /// The bodies, in line order.
  [[nodiscard]] virtual std::size_t bodies() const = 0;
  /// Body i's reference span [near, far] on x (a mass: near == far).
  [[nodiscard]] virtual double body_near(std::size_t i) const = 0;
  [[nodiscard]] virtual double body_far(std::size_t i) const = 0;
  /// Body i's fields at x (in its span) and t (0 <= t <= valid_until()).
  /// On a wave front the strain and the velocity are one of the one-sided
  /// values; u is continuous.
  [[nodiscard]] virtual LineFields fields(std::size_t body, double x, double t) const = 0;
  /// The body holding x: where two bodies meet, the lower one; bodies()
  /// when x lies in no body (a gap, or off the line).
  [[nodiscard]] std::size_t body_at(double x) const;

  /// The fields at x, read on body_at(x); NaN when x lies in no body.
  [[nodiscard]] virtual double u(double x, double t) const;
  [[nodiscard]] virtual double v(double x, double t) const;
  [[nodiscard]] virtual double strain(double x, double t) const;
  [[nodiscard]] virtual double axial_force(double x, double t) const;

  /// The links (the unilateral laws), in the line's order: the near end's
  /// (when its law is unilateral), the joints' in line order, the far end's.
  [[nodiscard]] virtual std::size_t links() const = 0;
  /// Link i's force p >= 0 (a compression) and its opening (>= 0).
  [[nodiscard]] virtual double link_force(std::size_t i, double t) const = 0;
  [[nodiscard]] virtual double link_opening(std::size_t i, double t) const = 0;

  /// The solution is exact on [0, valid_until()] (infinity: for all t).
  [[nodiscard]] virtual double valid_until() const = 0;
  /// Kinetic + strain energy of the line at t, = energy(0) + work(t) (the
  /// rigid links store none and dissipate none).
  [[nodiscard]] virtual double energy(double t) const = 0;
  /// Work done on the line by the ends' prescribed forces over (0, t).
  [[nodiscard]] virtual double work(double /*t*/) const { return 0.0; }
  /// The whole budget at t where the solution knows it in closed form
  /// (an elastic-plastic bar's plastic work, say); none: the tabulation
  /// integrates kinetic and elastic strain energy over the bodies.
  [[nodiscard]] virtual std::optional<Energies> energies(double /*t*/) const { return std::nullopt; }
  /// Body i's plastic strain at x, t (0 in an elastic body).
  [[nodiscard]] virtual double plastic_strain(std::size_t /*body*/, double /*x*/, double /*t*/) const { return 0.0; }
  /// One line naming the solution, for summaries.
  [[nodiscard]] virtual const char* name() const = 0;
};

/// Two free rods of one material (E, rho, A), the lower on [0, L1], the
/// upper on [L1 + gap, L1 + gap + L2], undeformed, moving rigidly at v1
/// (lower) and v2 (upper); a rigid unilateral joint between them (one
/// link), both outer ends free.
///
/// With v1 > v2 the gap closes at t0 = gap / (v1 - v2); the rods then push
/// on each other with p = Z (v1 - v2) / 2 for 2 Lmin / c (Lmin the shorter
/// rod), and part undeformed-or-travelling: with L1 == L2 they exchange
/// velocities; otherwise the shorter rod leaves rigidly at the longer rod's
/// initial velocity and the longer one keeps the rest of the momentum as a
/// compression pulse 2 Lmin long bouncing between its free ends. The
/// opening never decreases after that (the lower face moves at most as
/// fast as the upper one), so the solution holds for all t. With v1 <= v2
/// the rods never meet.
class SaintVenant final : public LineSolution {
 public:
  SaintVenant(double length1, double length2, double modulus, double density, double area, double v1, double v2,
              double gap = 0.0);
  ~SaintVenant() override;

  [[nodiscard]] double wave_speed() const { return c_; }
  [[nodiscard]] double impedance() const { return Z_; }
  /// The contact interval [t0, t1] (empty, both infinite, without contact).
  [[nodiscard]] double contact_start() const { return t0_; }
  [[nodiscard]] double contact_end() const { return t1_; }
  /// Z (v1 - v2) / 2, the force while in contact (0 without contact).
  [[nodiscard]] double contact_force() const;
  /// rho A (L1 v1 + L2 v2), conserved.
  [[nodiscard]] double momentum() const;

  std::size_t bodies() const override { return 2; }
  double body_near(std::size_t i) const override;
  double body_far(std::size_t i) const override;
  LineFields fields(std::size_t body, double x, double t) const override;
  std::size_t links() const override { return 1; }
  /// p on (t0, t1), half of it at t0 and t1 (the mean of the one-sided values), else 0.
  double link_force(std::size_t i, double t) const override;
  double link_opening(std::size_t i, double t) const override;
  double valid_until() const override;
  double energy(double t) const override;
  const char* name() const override { return "two free rods colliding through a rigid joint (Saint-Venant)"; }

 private:
  class Rods;
  double L1_, L2_, E_, rho_, A_, v1_, v2_, gap_;
  double c_, Z_;
  double t0_, t1_;
  std::unique_ptr<const Rods> rods_;  // the d'Alembert states: in contact, then apart
};

/// A rigid mass m at x = L + gap, moving at v0 along +x (v0 < 0: towards
/// the bar), strikes the free end x = L of a bar on [0, L] clamped at
/// x = 0, at rest and undeformed, through a rigid unilateral joint (one
/// link). The bar is body 0, the mass body 1.
///
/// After the impact (t_hit = gap / |v0|), with tau = m / Z and T = 2L/c,
/// p = Z |v0| exp(-(t - t_hit) / tau) for T > t - t_hit > 0; each return of
/// the wave reflected at the clamped end adds 2 Z |v0| to p at t_hit + k T
/// and, on each interval [k T, (k + 1) T), V and p are exp(-s / tau) times a
/// polynomial of degree k in s, their coefficients from an exact recursion
/// (in double: V and p agree with the same recursion in 80-bit arithmetic
/// to 4e-15 of |v0| and of Z |v0| sqrt(m / bar's mass) over 500 intervals).
/// Contact ends at the first zero of p (found by sampling each interval,
/// 32 points plus 16 per m / Z, and bisecting); then the mass flies at its
/// velocity then, and the bar vibrates clamped-free. valid_until() is the
/// first time the bar's end catches the mass again (infinity if never), or
/// the end of the last computed interval when contact outlasts 1000 of them
/// (contact spans about (pi / 2) sqrt(m / bar's mass) intervals: m above
/// some 400 000 bar masses).
///
/// The mass's velocity V is along +x: m dV/dt = p while in contact.
class DropMass final : public LineSolution {
 public:
  DropMass(const Rod& bar, double mass, double v0, double gap = 0.0);
  ~DropMass() override;

  /// The time of impact, gap / |v0| (infinite when v0 >= 0).
  [[nodiscard]] double impact_time() const { return t_hit_; }
  /// The time the mass leaves the bar (infinite without contact, or when
  /// contact outlasts what is computed).
  [[nodiscard]] double separation_time() const;
  /// The mass's velocity after separation.
  [[nodiscard]] double separation_velocity() const { return Vs_; }
  /// The mass's displacement and velocity (along +x).
  [[nodiscard]] double mass_u(double t) const;
  [[nodiscard]] double mass_v(double t) const;
  /// The force between the mass and the bar's end (right-continuous at the jumps).
  [[nodiscard]] double force(double t) const;

  std::size_t bodies() const override { return 2; }
  double body_near(std::size_t i) const override;
  double body_far(std::size_t i) const override;
  LineFields fields(std::size_t body, double x, double t) const override;
  std::size_t links() const override { return 1; }
  double link_force(std::size_t /*i*/, double t) const override { return force(t); }
  double link_opening(std::size_t i, double t) const override;
  double valid_until() const override { return valid_until_; }
  /// m v0^2 / 2, kinetic energy of the mass plus the bar's energy.
  double energy(double t) const override;
  const char* name() const override { return "rigid mass striking a clamped bar (Saint-Venant, Boussinesq)"; }

 private:
  struct Interval;
  // Waves at the struck end, as functions of the time s since impact: the
  // velocity carried by the wave leaving the end (w_out) and by the one
  // arriving (w_in(s) = -w_out(s - T)), and their integrals from 0.
  [[nodiscard]] double w_out(double s) const;
  [[nodiscard]] double W_out(double s) const;
  [[nodiscard]] double w_in(double s) const { return s < T_ ? 0.0 : -w_out(s - T_); }
  [[nodiscard]] double W_in(double s) const { return s < T_ ? 0.0 : -W_out(s - T_); }
  [[nodiscard]] double bar_end_u(double s) const { return W_in(s) + W_out(s); }
  [[nodiscard]] double mass_u_after(double s) const;  // s since impact
  [[nodiscard]] double opening_after(double s) const;
  void find_recontact();

  Rod bar_;
  double m_, v0_, gap_;
  double c_, Z_, T_, nu_, theta_;
  double t_hit_;
  std::vector<Interval> intervals_;   // the contact's, in order
  double ts_ = 0.0;                   // separation, since impact (infinity if none)
  double Vs_ = 0.0, us_ = 0.0;        // mass velocity and displacement then
  double W_ts_ = 0.0, W_ts_T_ = 0.0;  // W_out(ts), W_out(ts - T)
  double valid_until_;
};

/// Two bars welded at x = L1: bar 1 on [0, L1], bar 2 on [L1, L1 + L2], at
/// rest; from t = 0 a constant force F0 along +x on the near end x = 0
/// (F0 > 0 pushes into the bar: N = -F0 there), far end free. No link.
///
/// The incident wave carries N_I = -F0; at the junction a wave from bar 1
/// transmits N_T = 2 Z2 / (Z1 + Z2) N_I and reflects N_R = (Z2 - Z1) /
/// (Z1 + Z2) N_I (force coefficients; the velocity's are 2 Z1 / (Z1 + Z2)
/// and (Z1 - Z2) / (Z1 + Z2)). Every later wave is the sum of the
/// reflections at the junction and at both ends (the force end and the
/// free end reflect velocity unchanged, force with the sign flipped), kept
/// exactly as step fronts up to `horizon`: valid_until() >= horizon unless
/// more than 4 million front events would be needed.
class Junction final : public LineSolution {
 public:
  Junction(const Rod& bar1, const Rod& bar2, double force, double horizon);
  ~Junction() override;

  /// The force coefficients of a wave coming from bar 1.
  [[nodiscard]] double transmitted_ratio() const;  ///< 2 Z2 / (Z1 + Z2)
  [[nodiscard]] double reflected_ratio() const;    ///< (Z2 - Z1) / (Z1 + Z2)
  /// The near end's displacement, velocity and force (F0 along +x for t > 0).
  [[nodiscard]] double U(double t) const;
  [[nodiscard]] double V(double t) const;
  [[nodiscard]] double end_force(double t) const { return t > 0.0 ? F0_ : 0.0; }

  std::size_t bodies() const override { return 2; }
  double body_near(std::size_t i) const override;
  double body_far(std::size_t i) const override;
  LineFields fields(std::size_t body, double x, double t) const override;
  std::size_t links() const override { return 0; }
  double link_force(std::size_t i, double t) const override;
  double link_opening(std::size_t i, double t) const override;
  double valid_until() const override { return valid_until_; }
  /// F0 U(t): all the work goes into the bars.
  double energy(double t) const override { return work(t); }
  double work(double t) const override { return F0_ * U(t); }
  const char* name() const override { return "step force through a welded junction of two bars"; }

 private:
  // A wave's velocity as a step function of its departure time: jumps
  // (time, size) in time order with their running sums.
  struct Steps {
    std::vector<double> time, sum, moment;          // sum = sum of jumps, moment = sum of jump * time
    [[nodiscard]] double value(double t) const;     // the jumps before t
    [[nodiscard]] double integral(double t) const;  // its integral over (0, t)
  };
  Rod bar1_, bar2_;
  double F0_;
  double c1_, c2_, Z1_, Z2_, tau1_, tau2_;
  // a: leaves x = 0 along +x (bar 1); b: leaves the junction along -x (bar 1);
  // d: leaves the junction along +x (bar 2); e: leaves the far end along -x (bar 2).
  Steps a_, b_, d_, e_;
  double valid_until_;
};

/// The solution the line case admits, if any: SaintVenant (two bars of one
/// material, a rigid joint, free ends, undeformed, uniform velocities),
/// DropMass (a bar clamped at the near end, a rigid joint to a mass, bar at
/// rest) or Junction (two bars, welded, a constant force on the near end,
/// far end free, at rest, valid up to time.end); nullptr otherwise. Every
/// one needs zero body force, zero gravity, zero viscosity and initial
/// data given as constants. A rigid joint's restitution is not read: in
/// the continuum the contact stores and dissipates nothing.
/// Von Karman's problem (von Karman & Duwez, J. Appl. Phys. 21, 1950): an
/// elastic-plastic bar (E, rho, A; yield stress sigma_y, bilinear with
/// tangent modulus E_t > 0, material.hpp) on [0, L], at rest and
/// undeformed, its end x = 0 driven into it at a constant velocity V > 0
/// (V < 0 pulls: the same with tension). Two fronts leave x = 0: the
/// elastic precursor at c0 = sqrt(E / rho), behind it sigma = -sigma_y,
/// v = v_y = c0 eps_y (eps_y = sigma_y / E), and, when V > v_y, the plastic
/// front at c1 = sqrt(E_t / rho), behind it v = V, eps = -(eps_y + (V - v_y)
/// / c1), sigma = -(sigma_y + E_t (|eps| - eps_y)). Loading is monotone, so
/// kinematic and isotropic hardening agree; valid until the precursor
/// reaches x = L. The budget is closed-form: the fronts dissipate nothing
/// beyond the material's plastic work (each jump follows a straight piece
/// of the stress-strain curve).
///
/// With `wall`, the same seen from the bar: the bar moves at -V onto a rigid
/// wall at x = 0 (a rigid near end, one link) that stops it; every velocity
/// and displacement shifts by -V and -V t, the wall's force is the
/// plateau's compression, and the wall does no work (the kinetic energy
/// lost is the strain energy and the plastic work).
class VonKarman final : public LineSolution {
 public:
  VonKarman(const Rod& bar, double yield_stress, double tangent_modulus, double velocity, bool wall = false);

  [[nodiscard]] double elastic_speed() const { return c0_; }
  [[nodiscard]] double plastic_speed() const { return c1_; }
  /// The stresses behind the precursor and behind the plastic front (V's sign: compression for V > 0).
  [[nodiscard]] double precursor_stress() const;
  [[nodiscard]] double plateau_stress() const;
  [[nodiscard]] double plateau_strain() const;
  [[nodiscard]] double plateau_plastic_strain() const;

  std::size_t bodies() const override { return 1; }
  double body_near(std::size_t /*i*/) const override { return 0.0; }
  double body_far(std::size_t /*i*/) const override { return bar_.length; }
  LineFields fields(std::size_t body, double x, double t) const override;
  std::size_t links() const override { return wall_ ? 1 : 0; }
  double link_force(std::size_t i, double t) const override;
  double link_opening(std::size_t i, double t) const override;
  double valid_until() const override { return bar_.length / c0_; }
  /// Driven: the work done so far (the budget starts at 0); against the wall: the kinetic energy at t = 0.
  double energy(double t) const override;
  /// The driven end's work: -N(0) V t.
  double work(double t) const override;
  std::optional<Energies> energies(double t) const override;
  double plastic_strain(std::size_t body, double x, double t) const override;
  const char* name() const override { return "von Karman: an elastic-plastic bar struck at a constant velocity"; }

 private:
  Rod bar_;
  double sigma_y_, E_t_, V_;
  double c0_, c1_, sign_, v_y_, eps_y_;
  double eps_plateau_, sigma_plateau_;  // magnitudes
  bool plastic_ = false;                // V beyond v_y
  bool wall_ = false;                   // seen from the bar, moving at -V onto a rigid wall
};

[[nodiscard]] std::unique_ptr<LineSolution> for_line_case(const Case& c);

}  // namespace barimpact::exact

namespace barimpact::exact {

/// A line solution seen through the Scheme interface on the case's time grid
/// and line (model/line.hpp), so that the ordinary loop and observers
/// tabulate it: nodal u and v, link forces and openings, energies by the
/// midpoint rule on 20000 cells of the bars (a mass's kinetic energy exact).
[[nodiscard]] std::unique_ptr<Scheme> as_line_scheme(const Case& c, std::shared_ptr<const LineSolution> solution);

}  // namespace barimpact::exact

namespace barimpact::exact {

/// The line solution `c` admits (for_line_case) seen at the near end, as a
/// single bar's Solution: U, V and R (the near link's force, the force end's
/// value, or a held end's support force), so that studies measure a line's
/// errors as a bar's. nullptr when the line admits none.
[[nodiscard]] std::unique_ptr<Solution> line_end(const Case& c);

}  // namespace barimpact::exact
