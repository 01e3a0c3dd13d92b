// The history's columns beyond the budget: named scalars read off a scheme
// at t_n through the line's numbering (model/line.hpp). In history.csv's
// order: per [[joint]] in line order `joint.<name>.force` (compression > 0)
// and `joint.<name>.opening` (< 0 while penetrating), a diesel cylinder's
// `joint.<name>.pressure` (its gas's, Pa absolute), for a far end with a
// law other than free `far_end.force` and `far_end.opening`, per mass
// `body.<name>.u` and `body.<name>.v`, per gauge `gauge.<name>.strain`
// (tension > 0), `gauge.<name>.velocity` and `gauge.<name>.force` (the axial
// force E A eps + eta A deps/dt, tension > 0).
#pragma once

#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/line.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace barimpact {

/// Bond j's tension at t_n: k (u_{j+1} - u_j) + c (v_{j+1} - v_j) - E A eps_p.
[[nodiscard]] double bond_tension(const Line& line, const Scheme& s, std::size_t j);
/// A gauge's axial force (tension > 0) and its velocity along +x at t_n.
[[nodiscard]] double gauge_force(const Line& line, const Scheme& s, const GaugePoint& g);
[[nodiscard]] double gauge_velocity(const Scheme& s, const GaugePoint& g);

class Probes {
 public:
  Probes() = default;
  /// The columns of `c`'s line; `line` is read at every step, and must outlive the probes.
  Probes(const Case& c, const Line& line);

  [[nodiscard]] const std::vector<std::string>& names() const { return names_; }
  [[nodiscard]] std::size_t size() const { return names_.size(); }
  /// Every column at the scheme's t_n into out[0..size()). Never allocates.
  void read(const Scheme& s, double* out) const;

 private:
  enum class Kind {
    link_force,
    link_opening,
    link_pressure,
    bond_force,
    bond_opening,
    far_force,
    far_opening,
    node_u,
    node_v,
    gauge_strain,
    gauge_velocity,
    gauge_force
  };
  struct Column {
    Kind kind;
    std::size_t index;  // link, bond, node or gauge
  };
  [[nodiscard]] double value(const Scheme& s, const Column& col) const;

  const Line* line_ = nullptr;
  std::vector<std::string> names_;
  std::vector<Column> columns_;
};

}  // namespace barimpact
