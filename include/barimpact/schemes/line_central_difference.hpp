// `central-difference`: lumped mass, explicit, with per-bond coefficients
// (a bar with its obstacle is a line of one body):
//
//   m_j (u_j^{n+1} - 2 u_j^n + u_j^{n-1}) / dt^2 = F_j^n + N_j^n - N_{j-1}^n + P_j^n,
//   N_j = k_j (u_{j+1} - u_j)^n + c_j ((u_{j+1} - u_j)^n - (u_{j+1} - u_j)^{n-1}) / dt,
//
// N_j the tension in bond j (viscosity by a backward difference, so that the
// step stays explicit), P the link and end forces at t_n: penalty laws as
// forces (their rate by a backward difference), a force end's value. A rigid
// link is a kinematic constraint on the prediction: the openings at t_{n+1}
// are made >= 0 by impulses along M^{-1} (projected Gauss-Seidel over the
// links, exact for links that share no node), the force reported as
// impulse / dt^2. A clamped node stays at 0; a node driven at v(t) moves by
// dt v(t_{n+1/2}).
//
// Budget: tested with (u^{n+1} - u^{n-1}) / 2 the step gives
// H^{n+1/2} - H^{n-1/2} = (F + P)^n . (u^{n+1} - u^{n-1}) / 2 - (viscous),
// H^{n+1/2} = |w|_M^2 / 2 + (u^n)^T K u^{n+1} / 2, w = (u^{n+1} - u^n) / dt:
// the row at t_n reports the mean of H^{n -/+ 1/2}, the springs' share in
// E_obstacle. The rigid links' work is D_contact (exact by this identity);
// a penalty link's stored energy is its law's at u^n, so its share of the
// budget closes to O(dt^2); a cushion's hysteresis is D_contact.
//
// Elastic-plastic bodies (plastic_bonds.hpp): N_j = A sigma_j + viscous,
// sigma_j = E (eps_j - p_j) with p^n from the return map at u^n, so the
// step stays explicit and p^{n+1} is computed as soon as u^{n+1} is; the
// elastic stencil carries the plastic strains as forces A E (p_{j-1} - p_j),
// and the budget's identity gains D_plastic (closing as the elastic one).
//
// Smith's soil (model/line.hpp's Shaft, contact_law.hpp's smith toe): the
// resistance at t_n from u^n, its slip s^n = clamp(s^{n-1}, w^n - q, w^n + q)
// (w = -u the penetration) and its damping from the backward rate, as
// Smith's own recurrence does; it stores k (w - s)^2 / 2 (E_obstacle), its
// slip dissipates R_u |s^n - s^{n-1}| and its damping R_d^n (w^{n+1} - w^{n-1}) / 2
// (both D_contact), so that the budget closes as the penalty links' does.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "barimpact/schemes/line_scheme.hpp"
#include "barimpact/schemes/plastic_bonds.hpp"

namespace barimpact {

class LineCentralDifference final : public LineScheme {
 public:
  LineCentralDifference(const Case& c, Line line);

  void start() override;
  void advance() override;
  [[nodiscard]] double displacement_at(std::size_t j) const override { return cur_[j]; }
  /// The near end's probe read directly (not through displacement_at's virtual call).
  [[nodiscard]] double end_displacement() const override { return cur_[0]; }
  [[nodiscard]] double velocity_at(std::size_t j) const override {
    return n_ == 0 ? v0_[j] : (next_[j] - prev_[j]) / (2.0 * dt_);
  }
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool finite() const override;
  [[nodiscard]] double plastic_strain(std::size_t bond) const override {
    return plastic_.active() ? plastic_.current()[bond] : 0.0;
  }
  [[nodiscard]] double plastic_work(std::size_t body) const override { return plastic_.body_work(body); }
  [[nodiscard]] double soil_slip_work() const override;
  [[nodiscard]] bool keeps_soil_rest() const override { return true; }
  [[nodiscard]] SoilRest soil_rest() const override;
  void resume_soil(SoilRest rest) override { resume_ = std::move(rest); }
  [[nodiscard]] bool resuming() const override { return resume_.has_value(); }

 private:
  std::optional<SoilRest> resume_;  // where the next start() begins
  /// next = 2 cur - prev + dt^2 r / m on the free nodes (`taylor`: the start's
  /// cur + dt v0 + dt^2 r / 2m), r the forces at level `cur`.
  void predict(const double* um, const double* u, double* up, double t, bool taylor);
  /// The held ends' rows of `up`.
  void hold_ends(const double* u, double* up, double t) const;
  bool held_ends_ = false;                     // an end clamped or driven at a velocity
  bool near_held_ = false, far_held_ = false;  // which (read once: the step's fixed work is a few ns)
  double inv_dt2_ = 1.0 / (dt_ * dt_);         // no division in a step (1 / dt: inv_dt_)
  /// Makes every rigid link's opening at `up` >= 0; returns the impulses' forces in rigid_.
  void project(double* up, double force_scale);
  /// The support forces of held ends, the near and far forces at t_n.
  void end_forces(const double* um, const double* u, const double* up, double t, double scale);
  /// Level m's increments of the budget, booked.
  void book_budget(const double* um, const double* u, const double* up);
  [[nodiscard]] double half_step(const double* a, const double* b, BondKind kind, double& kinetic) const;

  /// The fast step: each uniform stretch of bar nodes in one vectorised pass
  /// with constant stencils (as the single bar's), the other nodes (body
  /// ends, joints, masses, held ends) by the general rows.
  void advance_levels(const double* um, const double* u, double* up, double t);
  template <bool viscous, bool loaded>
  void uniform_rows(const double* um, const double* u, double* up);
  /// Smith's shaft resistance on node j at level u (along +x), its slip and
  /// slip work updated, its damping force kept for the budget.
  double shaft_force(std::size_t j, const double* um, const double* u);
  /// r_j = F_j + N_j - N_{j-1} at node j (bond tensions from u, rates from um).
  [[nodiscard]] double row_force(const double* um, const double* u, std::size_t j) const;

  // A stretch of interior nodes [first, last) of one uniform body: stencils
  // k (2u_j - u_{j-1} - u_{j+1}), the same with c, and one lumped mass.
  // Elastic-plastic stretches add the plastic strains' forces E A (p_{j-1} - p_j),
  // stretches in the soil Smith's resistance (shaft_force, fused).
  /// A stretch's side springs: none, or Smith's J |R_s| v or the viscous J R_u v damping.
  enum class Soil : unsigned char { none, smith, viscous };
  struct Stretch {
    std::size_t first, last;
    double k, c, inv_m;
    double axial;  // E A
    bool plastic;
    Soil soil;
  };
  template <bool viscous, bool loaded, bool plastic, Soil soil>
  void stretch_rows(const Stretch& s, const double* um, const double* u, double* up);
  std::vector<Stretch> stretches_;
  std::vector<std::size_t> special_;       // the nodes outside every stretch
  std::vector<double> k_, c_, inv_m_, m_;  // per bond; per node
  std::vector<double> r_, rigid_;          // forces at the level; rigid links' impulse forces
  std::vector<std::size_t> rigid_links_;   // the rigid links, in line order
  PlasticBonds plastic_;                   // the elastic-plastic elements' state (none: every body elastic)
  // Smith's shaft: per node its slip s^n and damping force at t_n; the
  // special nodes in the soil; the slip's work so far, the damping's this level.
  std::vector<double> slip_, soil_damping_;
  std::vector<std::size_t> special_soil_;
  double slip_work_ = 0.0, soil_damping_work_ = 0.0;
  std::array<std::vector<double>, 3> levels_;
  double* prev_ = nullptr;
  double* cur_ = nullptr;
  double* next_ = nullptr;
  bool viscous_ = false;
  double near_support_ = 0.0, far_support_ = 0.0;  // held ends' forces along +x at t_n
  CentredBudget budget_;
};

}  // namespace barimpact
