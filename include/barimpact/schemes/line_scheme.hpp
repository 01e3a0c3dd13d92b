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

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/expression.hpp"
#include "barimpact/model/line.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace barimpact {

class LineScheme : public Scheme {
 public:
  [[nodiscard]] long long step() const override { return n_; }
  [[nodiscard]] double time() const override { return static_cast<double>(n_) * dt_; }
  [[nodiscard]] std::size_t nodes() const override { return line_.nodes(); }
  [[nodiscard]] double end_displacement() const override { return displacement_at(0); }
  [[nodiscard]] double end_velocity() const override { return velocity_at(0); }
  [[nodiscard]] double reaction() const override { return near_force_; }
  void displacement(std::span<double> out) const override;
  void velocity(std::span<double> out) const override;
  [[nodiscard]] double link_force(std::size_t i) const override { return force_[i]; }
  [[nodiscard]] double link_opening(std::size_t i) const override;
  /// The far end's force (compression > 0) at t_n.
  [[nodiscard]] double far_force() const override { return far_force_; }
  [[nodiscard]] const Line& line() const { return line_; }

 protected:
  LineScheme(const Case& c, Line line);

  /// F^n: body force and gravity at t (end forces are not in it).
  void load_at(double t);
  /// The force end's value at t along +x (0 unless the end is a force end).
  [[nodiscard]] double near_value(double t) const { return near_value_ ? (*near_value_)(0.0, t) : 0.0; }
  [[nodiscard]] double far_value(double t) const { return far_value_ ? (*far_value_)(0.0, t) : 0.0; }
  /// The penalty links' forces at u (rates from u_old over dt), c_max updated;
  /// adds them to `r` (-p on node a, +p on node b). Rigid links get 0.
  void penalty_forces(const double* u, const double* u_old, double* r);
  /// Adds link forces `p` to r.
  void add_link_force(std::size_t i, double p, double* r) const;
  /// Energy stored in the penalty links at u, and what their hysteresis dissipated.
  [[nodiscard]] double link_energy(const double* u) const;
  [[nodiscard]] double link_hysteresis() const;
  /// A three-level scheme's level-m link terms, each link's force at t_m
  /// tested with (c^{m+1} - c^{m-1}) / 2: a rigid link's into `contact`
  /// (D_contact), a viscoelastic link's beyond its spring into `viscous`.
  void book_link_work(const double* um, const double* u, const double* up, double& viscous, double& contact) const;

  Line line_;
  double dt_;
  long long n_ = 0;
  std::vector<double> load_;  // F at the current load time
  bool load_zero_ = true, load_steady_ = true;
  std::vector<double> force_;        // link forces p_i at t_n
  std::vector<double> c_max_;        // largest compression so far, per link
  std::vector<double> restitution_;  // per link
  bool has_penalty_ = false, has_rigid_ = false;
  double near_force_ = 0.0, far_force_ = 0.0;
  std::unique_ptr<Expression> body_force_, near_value_, far_value_;
  std::vector<double> u0_, v0_;
};

/// The scheme `c.time.scheme` names for a line of bodies (c.single_bar false).
[[nodiscard]] std::unique_ptr<Scheme> make_line_scheme(const Case& c);

/// Why `c.time.scheme` cannot run the line of `c`: the `time` key to blame
/// ("scheme" or "step") and the rule, naming the law or body it cannot run.
struct LineMisfit {
  std::string key;
  std::string rule;
};
[[nodiscard]] std::optional<LineMisfit> line_scheme_misfit(const Case& c, const Line& line);

/// The largest stable step of central differences on `line` (lumped mass;
/// `consistent_mass`: M_h, 3 times stiffer at the top of the spectrum), by
/// Gershgorin's bound node by node with every penalty link's k and l.
[[nodiscard]] double line_stable_step(const Line& line, bool consistent_mass);

}  // namespace barimpact
