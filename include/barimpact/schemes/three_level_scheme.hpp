// What the explicit central-difference family shares: three displacement
// levels u^{n-1}, u^n, u^{n+1} (the row at t_n is read once u^{n+1} is
// known), the load, and the discrete energy of central differences.
//
//   M (u^{n+1} - 2 u^n + u^{n-1}) / dt^2 + K_a u^n + K_b (u^n - u^{n-1}) / dt = F^n + R^n e_0
//
// (viscosity by a backward difference, so that lumped mass keeps the step
// explicit). Testing with (u^{n+1} - u^{n-1})/2 conserves, for b = 0, f = 0
// and no contact, H^{n+1/2} = |w|_M^2 / 2 + (u^n)^T K_a u^{n+1} / 2 with
// w = (u^{n+1} - u^n)/dt; the row at t_n reports the mean of H^{n-1/2} and
// H^{n+1/2}. W_ext and D_visc sum level m's increments (tested likewise)
// from the first half step's, dt/2 times the rates at t = 0. Derived
// classes decide M (lumped or consistent) and R^n.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/expression.hpp"
#include "barimpact/model/mesh.hpp"
#include "barimpact/model/obstacle.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace barimpact {

class ThreeLevelScheme : public Scheme {
 public:
  void start() override;
  void advance() override;

  [[nodiscard]] long long step() const override { return n_; }
  [[nodiscard]] double time() const override { return static_cast<double>(n_) * dt_; }
  [[nodiscard]] std::size_t nodes() const override { return mesh_.nodes(); }
  [[nodiscard]] double end_displacement() const override { return cur_[0]; }
  [[nodiscard]] double end_velocity() const override;
  [[nodiscard]] double reaction() const override { return reaction_; }
  void displacement(std::span<double> out) const override;
  void velocity(std::span<double> out) const override;
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool finite() const override;
  [[nodiscard]] double displacement_at(std::size_t j) const override { return cur_[j]; }
  [[nodiscard]] double velocity_at(std::size_t j) const override {
    return j == 0 ? end_velocity() : n_ == 0 ? v0_[j] : (next_[j] - prev_[j]) / (2.0 * dt_);
  }
  [[nodiscard]] double link_opening(std::size_t /*i*/) const override { return cur_[0] + law_.gap(); }

 protected:
  /// `consistent_mass`: M_h; else the lumped (row-sum) mass.
  ThreeLevelScheme(const Case& c, bool consistent_mass);

  /// Writes M^{-1} r into r (r has the clamped row zeroed by the caller).
  virtual void apply_inverse_mass(std::span<double> r) const = 0;
  /// The factored consistent mass; required of every scheme built with
  /// consistent_mass (the step fuses its right-hand side into its sweeps).
  [[nodiscard]] virtual const FactoredTridiagonal* mass_factor() const { return nullptr; }
  /// Enforces the obstacle on `next` (u^{n+1}) given the free prediction;
  /// returns R^n, the force (impulse / dt) the obstacle put on the bar.
  /// `prev` is u^{n-1}, `cur` u^n. In a lumped step only next[0] is written
  /// when it is called (the interior rows follow), and only next[0] may change.
  virtual double enforce_contact(const double* prev, const double* cur, double* next) = 0;
  /// Whether enforce_contact's force is an impulse's (a correction of the
  /// predicted u^{n+1}); false where it is the obstacle's exact reaction.
  [[nodiscard]] virtual bool impulsive_contact() const { return true; }
  /// The rigid obstacle's clamp of lumped central differences:
  /// u_0^{n+1} = max(prediction, -g); returns the force behind it.
  double clamp_end(double* next) const;
  /// How a lumped step treats node 0 once predicted: nothing more (no
  /// obstacle, or a penalty, already in the force), the clamp (inline: no
  /// virtual call in the step), or the scheme's enforce_contact.
  enum class LumpedEnd { free, clamp, scheme };
  LumpedEnd lumped_end_ = LumpedEnd::scheme;
  /// With consistent mass, the step asks between its two sweeps for the
  /// displacement impulse mu at node 0 (u^{n+1} += mu M^{-1} e_0) given
  /// u^{n-1}_0 and the free u^{n+1}_0; 0 when none.
  [[nodiscard]] virtual double end_impulse(double /*prev0*/, double /*next0*/) const { return 0.0; }

  Mesh mesh_;
  ObstacleLaw law_;
  double dt_, inv_dt_, a_;
  bool clamped_;
  Tridiagonal mass_, stiffness_a_, stiffness_b_;
  std::vector<double> lumped_;   // row sums of M_h (used by the lumped variant)
  Tridiagonal kinetic_mass_;     // the M of the scheme: M_h, or diag(lumped_)
  std::vector<double> u0_, v0_;  // the initial data at the nodes
  bool lumped_step_ = false;     // M = diag(lumped_): the update is fused into one pass
  bool kb_positive_ = false;
  std::vector<double> inverse_lumped_;

 private:
  template <bool viscous, bool loaded>
  [[gnu::always_inline]] inline double step_rows(const double* um, const double* u, double* up, double penalty);
  void load_at(long long n);
  /// W_ext and D_visc of (0, t_{1/2}), from the start's rates (`viscous` = K_b v^0).
  void book_first_half_step(std::span<const double> viscous);
  /// Adds the level's load work and the bar's viscous dissipation to dw, dd.
  void bar_budget(double& dw, double& dd) const;
  void half_step_energy(const double* a, const double* b, double& kinetic, double& strain) const;

  std::array<std::vector<double>, 3> levels_;
  double* prev_ = nullptr;
  double* cur_ = nullptr;
  double* next_ = nullptr;
  std::vector<double> rhs_, load_;
  std::unique_ptr<Expression> body_force_, initial_displacement_, initial_velocity_;
  bool load_zero_ = true, load_steady_ = true;
  long long n_ = 0;
  double reaction_ = 0.0;  // R^n
  double work_half_ = 0.0, dissipation_half_ = 0.0, work_last_ = 0.0, dissipation_last_ = 0.0;
  double contact_half_ = 0.0, contact_last_ = 0.0;  // D_contact, booked as W_ext and D_visc
};

}  // namespace barimpact
