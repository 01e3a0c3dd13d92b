// What every scheme of a line of bodies shares (model/line.hpp): the line,
// the step, the compiled loads and end histories, the links' state (force,
// largest compression, what they dissipated) and the answers the run layer
// asks for. Derived classes own their levels and their step.
//
// The near end's reaction R (history.csv) is the near link's force, the
// applied force of a force end, or for a held end (clamped, driven at a
// velocity) the support's force on node 0 from that node's equation of
// motion; all are compressions (> 0 pushing along +x into the line).
#pragma once

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/expression.hpp"
#include "barimpact/model/line.hpp"
#include "barimpact/schemes/plastic_iteration.hpp"
#include "barimpact/schemes/scheme.hpp"
#include "barimpact/schemes/soil_iteration.hpp"
#include "barimpact/schemes/state.hpp"

namespace barimpact {

/// A three-level scheme's budget (central differences, Paoli-Schatzman,
/// characteristic): level m's increments of W_ext, D_visc and D_contact,
/// each force at t_m tested with (u^{m+1} - u^{m-1}) / 2, summed from the
/// first half step's share (dt/2 times the rates at t = 0); the row at t_n
/// reports the sums to t_{n+1/2} less half of level n's.
struct CentredBudget {
  double work_half = 0.0, dissipation_half = 0.0, contact_half = 0.0;  // sums up to t_{n+1/2}
  double work_last = 0.0, dissipation_last = 0.0, contact_last = 0.0;  // level n's
  /// The first half step's share from the rates at t = 0.
  void start(double dt, double power, double viscous, double contact) {
    work_half = 0.5 * dt * power;
    dissipation_half = 0.5 * dt * viscous;
    contact_half = 0.5 * dt * contact;
    work_last = dissipation_last = contact_last = 0.0;
  }
  /// Level n's increments.
  void book(double dw, double dd, double dc) {
    work_last = dw;
    dissipation_last = dd;
    contact_last = dc;
    work_half += dw;
    dissipation_half += dd;
    contact_half += dc;
  }
  [[nodiscard]] double work() const { return work_half - 0.5 * work_last; }
  [[nodiscard]] double dissipation() const { return dissipation_half - 0.5 * dissipation_last; }
  [[nodiscard]] double contact() const { return contact_half - 0.5 * contact_last; }
};

class LineScheme : public Scheme {
 public:
  [[nodiscard]] long long step() const override { return n_; }
  [[nodiscard]] double time() const override { return static_cast<double>(n_) * dt_; }
  [[nodiscard]] std::size_t nodes() const override { return line_.nodes(); }
  [[nodiscard]] const Line* line() const override { return &line_; }
  [[nodiscard]] double end_displacement() const override { return displacement_at(0); }
  [[nodiscard]] double end_velocity() const override { return velocity_at(0); }
  [[nodiscard]] double reaction() const override { return near_force_; }
  void displacement(std::span<double> out) const override;
  void velocity(std::span<double> out) const override;
  [[nodiscard]] double link_force(std::size_t i) const override { return force_[i]; }
  [[nodiscard]] double link_opening(std::size_t i) const override;
  [[nodiscard]] double link_largest_compression(std::size_t i) const override { return c_max_[i]; }
  /// The far end's force (compression > 0) at t_n.
  [[nodiscard]] double far_force() const override { return far_force_; }
  /// A one-step implicit scheme's elastic-plastic elements (the explicit
  /// schemes keep their own and override these).
  [[nodiscard]] double plastic_strain(std::size_t bond) const override {
    return plastic_iteration_.active() ? plastic_iteration_.strain()[bond] : 0.0;
  }
  [[nodiscard]] double plastic_work(std::size_t body) const override { return plastic_iteration_.body_work(body); }
  [[nodiscard]] std::string failure() const override;
  [[nodiscard]] const PlasticIteration& plastic_iteration() const { return plastic_iteration_; }

  /// The state a pile-driving blow leaves in the soil and the next blow
  /// starts from (residual stresses): every node's displacement, the shaft
  /// springs' slips (line order, 0 without soil), each link's largest
  /// compression. Only a scheme that overrides these keeps it.
  struct SoilRest {
    std::vector<double> u, shaft_slip, c_max;
  };
  [[nodiscard]] virtual bool keeps_soil_rest() const { return false; }
  [[nodiscard]] virtual SoilRest soil_rest() const { return {}; }
  /// The next start() begins from `rest` (at rest: the case's velocities).
  virtual void resume_soil(SoilRest /*rest*/) {}
  /// Whether a rest was given (resume_soil) for start() to begin from.
  [[nodiscard]] virtual bool resuming() const { return false; }

 protected:
  LineScheme(const Case& c, Line line);

  /// F^n: body force and gravity at t (end forces are not in it), and the
  /// plastic strains' load G p^k while an elastic-plastic iteration needs it.
  void load_at(double t);

  /// A one-step implicit scheme's elastic-plastic elements: `a` its matrix
  /// (the rows of the nodes `held` the identity) and u^{n+1} += c A^{-1} g for a load g at
  /// t_{n+1}.
  void set_plastic(const Tridiagonal& a, const std::vector<std::size_t>& held, double c);
  /// The same for a three-level scheme that books its plastic work itself
  /// (plastic_bonds.hpp's record) and whose matrix holds its links.
  void set_plastic_levels(const Tridiagonal& a, const std::vector<std::size_t>& held, double c);
  /// Level 0's plastic strains from u0, before the start's loads.
  void start_plastic(const double* u0);
  /// One step of the elastic-plastic iteration (plastic_iteration.hpp):
  /// `step()` is the scheme's elastic step, taken with the plastic strains
  /// of level n; when an element yields, the step is taken again from level
  /// n (the kept state) until the plastic strains it loads with hold. Level n is
  /// kept at every step while the line yields, and at intervals doubling to
  /// 32 steps while it does not: reaching level n may then replay up to 31
  /// steps that did not yield (the same numbers: nothing changed), once per
  /// quiet stretch, so that a quiet step pays the yield check and 1/32 of a
  /// copy of its state.
  template <class Step>
  void advance_plastic(Step&& step, const std::vector<double>& u) {
    (void)advance_plastic_levels(step, [&u] { return std::pair<const double*, double>{u.data(), 1.0}; });
  }
  /// The same for a scheme whose newest level is `newest()`: where it keeps
  /// u^{n+1} and the factor it is kept at (paper's exp(lambda t_{n+1})).
  /// True when the level yielded (its plastic strains are not level n's).
  template <class Step, class Newest>
  bool advance_plastic_levels(Step&& step, Newest&& newest) {
    if (since_kept_ >= keep_interval_) {
      if (!yielded_since_kept_) keep_interval_ = std::min(2 * keep_interval_, 32);
      keep_level();
    }
    plastic_iteration_.begin_step();
    plastic_loads();
    step();
    ++since_kept_;
    std::pair<const double*, double> level = newest();  // u^{n+1} as kept, and its factor
    if (plastic_iteration_.settled(level.first, force_.data(), level.second)) return false;
    // Back to level n, replaying the quiet steps since the level kept.
    const long long n = n_ - 1;
    restore_state();
    n_ = kept_n_;
    plastic_iteration_.begin_step();
    while (n_ < n) {
      plastic_loads();
      step();
    }
    keep_interval_ = 1;
    if (kept_n_ != n) keep_level();
    yielded_since_kept_ = true;
    plastic_iteration_.use_iterate();
    int k = 2;
    for (;; ++k) {
      plastic_loads();
      step();
      level = newest();
      if (plastic_iteration_.settled(level.first, force_.data(), level.second)) break;
      if (k == PlasticIteration::most_iterations) {  // the run stops: finite() turns false
        failed_ = true;
        failed_misfit_ = plastic_iteration_.misfit();
        return false;
      }
      restore_state();
      n_ = n;
    }
    plastic_iteration_.count(k);
    plastic_iteration_.accept(one_step_plastic_ ? kept_displacement() : nullptr, level.first);
    since_kept_ = 1;
    return true;
  }
  /// One step with Smith's soil (soil_iteration.hpp): `step()` is the
  /// scheme's step with the soil's iterate, `holds()` the soil's check at its
  /// answer; the step is taken again from level n (the kept state) until it holds.
  /// False when it did not in SoilIteration::most_iterations steps: the run stops.
  template <class Step, class Holds>
  bool advance_soil_level(SoilIteration& soil, Step&& step, Holds&& holds) {
    const long long n = n_;
    keep_state();
    soil.begin_step();
    for (int k = 1;; ++k) {
      step();
      if (holds()) return true;
      if (k == SoilIteration::most_iterations) {  // finite() turns false
        failed_ = true;
        failed_soil_ = soil.failure();
        return false;
      }
      restore_state();
      n_ = n;
    }
  }
  /// What `soil`'s shaft and its toe's link (R_u times its slip) have slipped away up to t_n.
  [[nodiscard]] double slip_work(const SoilIteration& soil) const {
    const std::size_t toe = soil.toe_link();
    return soil.shaft_slip_work() + (toe == Link::ground ? 0.0 : line_.links[toe].law.hysteresis(c_max_[toe]));
  }
  /// The scheme's state as one value (state.hpp), for the iterations above:
  /// keeps it (level n), copies it back, and u^n as kept (a one-step scheme's,
  /// its state's first member). A scheme that iterates overrides all three.
  virtual void keep_state() {}
  virtual void restore_state() {}
  [[nodiscard]] virtual const double* kept_displacement() const { return nullptr; }
  /// The schemes' loads carry G p^k while it may be nonzero (load_zero_).
  void plastic_loads();
  /// f = the body force and gravity at t, and G p^k while the plastic strains load.
  void load_into(double t, std::vector<double>& f);
  /// E_strain, W_ext and D_plastic of an elastic-plastic line at u = u^n.
  void add_plastic(Energies& e, const double* u) const;
  /// The force end's value at t along +x (0 unless the end is a force end).
  [[nodiscard]] double near_value(double t) const {
    return near_history_ ? near_history_(t) : near_value_ ? (*near_value_)(0.0, t) : 0.0;
  }
  [[nodiscard]] double far_value(double t) const {
    return far_history_ ? far_history_(t) : far_value_ ? (*far_value_)(0.0, t) : 0.0;
  }
  /// The penalty links' forces at u (rates from u_old over dt), c_max updated;
  /// adds them to `r` (-p on node a, +p on node b). Rigid links get 0.
  void penalty_forces(const double* u, const double* u_old, double* r);
  /// Adds link forces `p` to r.
  void add_link_force(std::size_t i, double p, double* r) const;
  /// Energy stored in the penalty links at u, and what their hysteresis dissipated.
  [[nodiscard]] double link_energy(const double* u) const;
  [[nodiscard]] double link_hysteresis() const;
  /// Link i's damping force at compression c (force_[i] less its static
  /// part) times `motion`, a rate or an increment of c: a viscoelastic dashpot's
  /// into `viscous` (D_visc), Smith's soil damping into `contact` (D_contact);
  /// a diesel cylinder's gas force times -motion into `work` (W_ext).
  void book_link_damping(std::size_t i, double c, double motion, double& work, double& viscous, double& contact) const;
  /// A three-level scheme's level-m link terms, each link's force at t_m
  /// tested with (c^{m+1} - c^{m-1}) / 2: a rigid link's into `contact`
  /// (D_contact), a viscoelastic link's beyond its spring into `viscous`, a
  /// diesel gas's into `work`.
  void book_link_work(const double* um, const double* u, const double* up, double& work, double& viscous,
                      double& contact) const;

  Line line_;
  double dt_, inv_dt_;
  bool near_link_ = false, far_link_ = false;  // the first link is the near end's, the last the far end's
  PlasticIteration plastic_iteration_;
  bool failed_ = false;  // the plastic iteration did not settle (finite() is then false)
  double failed_misfit_ = 0.0;
  std::string failed_soil_;  // why Smith's soil's iteration did not settle (soil_iteration.hpp)
  long long n_ = 0;
  std::vector<double> load_;  // F at the current load time
  bool load_zero_ = true, load_steady_ = true;
  std::vector<double> force_;        // link forces p_i at t_n
  std::vector<double> c_max_;        // largest compression so far, per link
  std::vector<double> restitution_;  // per link
  bool has_penalty_ = false, has_rigid_ = false;
  double near_force_ = 0.0, far_force_ = 0.0;
  std::unique_ptr<Expression> body_force_, near_value_, far_value_;
  HistoryReader near_history_, far_history_;  // a sampled end's, instead of its expression
  std::vector<double> u0_, v0_;

 private:
  void keep_level();
  void set_plastic_matrix(const Tridiagonal& a, const std::vector<std::size_t>& held, double c, bool links_in_matrix);
  long long kept_n_ = 0;                    // the level the kept state holds
  int since_kept_ = 1, keep_interval_ = 1;  // steps since it, and between two
  bool yielded_since_kept_ = false;
  bool one_step_plastic_ = true;     // accept() books Q from the kept u^n
  bool body_zero_ = true;            // no body force and no gravity
  std::vector<double> steady_body_;  // a steady body force and gravity on a plastic line (else empty)
};

// Once per step each: inline, since a short line's step is a few dozen ns
// and a call into another unit costs a few of them.
inline void LineScheme::load_at(double t) {
  if (load_zero_ || (load_steady_ && t > 0.0)) return;  // zero, or computed at t = 0
  load_into(t, load_);
}

inline void LineScheme::add_link_force(std::size_t i, double p, double* r) const {
  const Link& l = line_.links[i];
  if (l.a != Link::ground) r[l.a] -= p;
  if (l.b != Link::ground) r[l.b] += p;
}

inline void LineScheme::penalty_forces(const double* u, const double* u_old, double* r) {
  const double inv_dt = inv_dt_;
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const Link& l = line_.links[i];
    if (l.law.rigid()) {
      force_[i] = 0.0;
      continue;
    }
    const double c = -line_.opening(i, u);
    const double rate = (line_.opening(i, u_old) - line_.opening(i, u)) * inv_dt;  // dc/dt, backward
    if (c > c_max_[i]) c_max_[i] = c;
    force_[i] = l.law.force(c, rate, c_max_[i]);
    if (force_[i] != 0.0) add_link_force(i, force_[i], r);
  }
}

inline void LineScheme::book_link_work(const double* um, const double* u, const double* up, double& work,
                                       double& viscous, double& contact) const {
  for (std::size_t i = 0; i < line_.links.size(); ++i) {
    const Link& l = line_.links[i];
    const double dcomp = 0.5 * (line_.opening(i, um) - line_.opening(i, up));  // (c^{m+1} - c^{m-1}) / 2
    if (l.law.rigid()) contact += force_[i] * dcomp;
    book_link_damping(i, -line_.opening(i, u), dcomp, work, viscous, contact);
  }
}

inline void LineScheme::book_link_damping(std::size_t i, double c, double motion, double& work, double& viscous,
                                          double& contact) const {
  const ContactLaw& law = line_.links[i].law;
  if (law.kind == LawKind::diesel) {  // the gas pushes the faces apart: its work is -p dc
    work -= law.gas_force(c, c_max_[i]) * motion;
    return;
  }
  const double damping = law.damping_part(force_[i], c, c_max_[i]) * motion;
  (law.kind == LawKind::smith ? contact : viscous) += damping;  // Smith's damping is the soil's
}

/// The largest stable step of central differences on `line` (lumped mass;
/// `consistent_mass`: M_h, 3 times stiffer at the top of the spectrum), by
/// Gershgorin's bound node by node with every penalty link's k and l.
[[nodiscard]] double line_stable_step(const Line& line, bool consistent_mass);

}  // namespace barimpact
