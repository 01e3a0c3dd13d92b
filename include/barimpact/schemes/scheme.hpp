// The one interface every time scheme implements: a state that moves from
// step n to n + 1 and answers questions about itself at t_n.
//
// A scheme owns its discrete levels and its discrete energy identity (how
// velocity and energies are read off its levels); it knows nothing of files,
// history or stopping (Odeint's stepper / observer split).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "barimpact/case/case.hpp"

namespace barimpact {

/// The energy budget at t_n. `total()` is constant for an exact solution.
struct Energies {
  double kinetic = 0.0;      ///< E_kin
  double strain = 0.0;       ///< E_strain
  double obstacle = 0.0;     ///< E_obstacle
  double work = 0.0;         ///< W_ext, cumulative work of f
  double dissipation = 0.0;  ///< D_visc, cumulative viscous dissipation (bars and dashpots)
  double contact = 0.0;      ///< D_contact, cumulative: the laws' hysteresis and inelastic impacts
  double plastic = 0.0;      ///< D_plastic, cumulative plastic work dissipated (hardening's share is in E_strain)

  [[nodiscard]] double total() const { return kinetic + strain + obstacle - work + dissipation + contact + plastic; }
};

struct Line;

class Scheme {
 public:
  virtual ~Scheme() = default;

  /// Sets the initial levels: the state is at step 0.
  virtual void start() = 0;
  /// Moves the state from step n to n + 1. Never allocates, never does I/O.
  virtual void advance() = 0;

  [[nodiscard]] virtual long long step() const = 0;
  /// t_n = n dt (never accumulated).
  [[nodiscard]] virtual double time() const = 0;
  [[nodiscard]] virtual std::size_t nodes() const = 0;
  /// U^n = u(0, t_n).
  [[nodiscard]] virtual double end_displacement() const = 0;
  /// V^n, the velocity of x = 0 at t_n.
  [[nodiscard]] virtual double end_velocity() const = 0;
  /// R^n >= 0, the obstacle's force on the bar at t_n.
  [[nodiscard]] virtual double reaction() const = 0;
  /// u(x_j, t_n) into `out` (size nodes()).
  virtual void displacement(std::span<double> out) const = 0;
  /// v(x_j, t_n) into `out` (size nodes()).
  virtual void velocity(std::span<double> out) const = 0;
  [[nodiscard]] virtual Energies energies() const = 0;
  /// energies() in two parts, for a history row at every step: true when
  /// `e` is whole; false when E_kin and E_strain are left to
  /// finish_energies(e), called at this step or after one advance, which
  /// may form their sums inside its own sweeps. The same bits either way.
  [[nodiscard]] virtual bool begin_energies(Energies& e) const {
    e = energies();
    return true;
  }
  virtual void finish_energies(Energies& /*e*/) const {}
  /// u and v at node j at t_n, in the line's numbering (line.hpp).
  [[nodiscard]] virtual double displacement_at(std::size_t j) const = 0;
  [[nodiscard]] virtual double velocity_at(std::size_t j) const = 0;
  /// Link i of the line (line.hpp; for a single bar, link 0 is the obstacle):
  /// its force p >= 0 (a compression) and its opening y at t_n.
  [[nodiscard]] virtual double link_force(std::size_t /*i*/) const { return reaction(); }
  [[nodiscard]] virtual double link_opening(std::size_t i) const = 0;
  /// Link i's largest compression so far (its law's history, contact_law.hpp), 0 where not kept.
  [[nodiscard]] virtual double link_largest_compression(std::size_t /*i*/) const { return 0.0; }
  /// The force (compression > 0) on a held or loaded far end at t_n, when the
  /// scheme computes it; NaN: read it off the last element instead.
  [[nodiscard]] virtual double far_force() const;
  /// Bond j's plastic strain at t_n (0 in an elastic body, material.hpp).
  [[nodiscard]] virtual double plastic_strain(std::size_t /*bond*/) const { return 0.0; }
  /// The plastic work body b has dissipated up to t_n.
  [[nodiscard]] virtual double plastic_work(std::size_t /*body*/) const { return 0.0; }
  /// What Smith's soil (toe and shaft) has dissipated by slipping up to t_n.
  [[nodiscard]] virtual double soil_slip_work() const { return 0.0; }
  /// Why finite() turned false when the state is finite but failed (an
  /// iteration that did not converge); empty otherwise.
  [[nodiscard]] virtual std::string failure() const { return {}; }
  /// False once a level holds NaN or infinity.
  [[nodiscard]] virtual bool finite() const = 0;
  /// The line the scheme steps, when it holds one (its observers read the
  /// same, rather than building it again); null otherwise.
  [[nodiscard]] virtual const Line* line() const { return nullptr; }
};

/// Why a case does not fit its scheme: the `time` key to blame ("scheme",
/// "step" or a parameter; or a full key such as "joint.gas.law") and the rule, naming the law or body it cannot run
/// and the schemes that can (registry.hpp).
struct SchemeMisfit {
  std::string key;
  std::string rule;
};

}  // namespace barimpact
