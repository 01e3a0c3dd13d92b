// A line of bodies, as the schemes see it: nodes on one axis joined by bonds
// (a bar's P1 elements, linear springs), point masses on nodes, links
// (unilateral laws between two neighbouring nodes, or a node and the ground)
// and the two ends' conditions. It knows no time step and no file.
//
// Every matrix of a line is tridiagonal: bond j joins nodes j and j + 1 and
// adds its stiffness k_j, viscosity c_j and mass m_j as
//   K += k_j (e_{j+1} - e_j)(e_{j+1} - e_j)^T,  C likewise with c_j,
//   M_h += (m_j / 6) [[2, 1], [1, 2]] on nodes j, j + 1 (consistent), m_j / 2 each (lumped);
// a unilateral link is not assembled (its bond is empty), so that the
// schemes decide its force. Loads: the body force f(x, t) per unit length on
// bar elements, gravity g towards -x on every mass, the end forces.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "barimpact/model/contact_law.hpp"
#include "barimpact/model/material.hpp"
#include "barimpact/model/sampled_history.hpp"
#include "barimpact/model/tridiagonal.hpp"

namespace barimpact {

/// What joins node j to node j + 1.
enum class BondKind {
  element,  ///< a bar's P1 element: k = E A / h, c = eta A / h, m = rho A h
  spring,   ///< a bilateral spring joint and its dashpot, no mass
  open      ///< nothing assembled: a unilateral link decides the force, or two bodies apart
};

class Expression;

struct Bond {
  BondKind kind = BondKind::element;
  double h = 0.0;          ///< element length (0 for a spring or open bond)
  double stiffness = 0.0;  ///< k_j: E A / h, or the spring's k
  double viscosity = 0.0;  ///< c_j: eta A / h, or the dashpot's
  double mass = 0.0;       ///< m_j = rho A h
  double area = 1.0;       ///< A, to turn a force into a stress
  std::size_t body = 0;    ///< the body the element belongs to (elements only)
  double axial = 0.0;      ///< E A (elements), so that stresses read (E A du + eta A dv) / h / A
  double damping = 0.0;    ///< eta A (elements)
  friend bool operator==(const Bond&, const Bond&) = default;
};

/// The bonds of a line in order, bond j joining nodes j and j + 1. A bar's
/// elements are one bond repeated, so each run of equal bonds keeps it once
/// and every position holds an index: 4 bytes an element instead of a
/// Bond's 72 (at 10^6 elements, 4 MB instead of 72 MB faulted in at start-up).
class Bonds {
 public:
  class const_iterator {
   public:
    using value_type = Bond;
    using difference_type = std::ptrdiff_t;
    const_iterator() = default;
    const_iterator(const Bonds* bonds, std::size_t j) : bonds_(bonds), j_(j) {}
    const Bond& operator*() const { return (*bonds_)[j_]; }
    const Bond* operator->() const { return &(*bonds_)[j_]; }
    const_iterator& operator++() {
      ++j_;
      return *this;
    }
    const_iterator operator++(int) { return {bonds_, j_++}; }
    friend bool operator==(const const_iterator& a, const const_iterator& b) { return a.j_ == b.j_; }

   private:
    const Bonds* bonds_ = nullptr;
    std::size_t j_ = 0;
  };

  /// Appends bond b (kept once while it repeats the last one appended).
  void push_back(const Bond& b) {
    if (distinct_.empty() || !(distinct_.back() == b)) distinct_.push_back(b);
    which_.push_back(static_cast<std::uint32_t>(distinct_.size() - 1));
  }
  /// Appends bond b `count` times (a bar's elements).
  void append(const Bond& b, std::size_t count) {
    if (count == 0) return;
    push_back(b);
    which_.insert(which_.end(), count - 1, which_.back());
  }
  void reserve(std::size_t n) { which_.reserve(n); }
  [[nodiscard]] const Bond& operator[](std::size_t j) const { return distinct_[which_[j]]; }
  [[nodiscard]] const Bond& back() const { return distinct_[which_.back()]; }
  [[nodiscard]] std::size_t size() const { return which_.size(); }
  [[nodiscard]] bool empty() const { return which_.empty(); }
  [[nodiscard]] const_iterator begin() const { return {this, 0}; }
  [[nodiscard]] const_iterator end() const { return {this, which_.size()}; }
  /// How many bonds are kept: one per run of equal bonds.
  [[nodiscard]] std::size_t kept() const { return distinct_.size(); }

 private:
  std::vector<Bond> distinct_;
  std::vector<std::uint32_t> which_;
};

/// A unilateral law on the opening y = u_b - u_a + gap (y < 0: penetrating)
/// between two neighbouring nodes, or a node and the ground (`ground`). Its
/// force p >= 0 is a compression: -p on node a, +p on node b.
struct Link {
  static constexpr std::size_t ground = std::numeric_limits<std::size_t>::max();
  std::string name;  ///< the history's column stem: "joint.<name>", "near_end", "far_end"
  ContactLaw law;    ///< elastic, viscoelastic, cushion or rigid
  std::size_t a = ground, b = ground;
  double gap = 0.0;
  bool is_end = false;  ///< a near- or far-end law (the ground), not a joint
};

/// What holds an end node besides a link.
enum class EndKind { free, clamped, force, velocity };

struct End {
  EndKind kind = EndKind::free;
  std::size_t node = 0;
  std::string value = "0";  ///< force (along +x) or velocity, an expression in t
  /// A sampled force or velocity, used instead of `value` when set (a
  /// measured record; shared, never copied per scheme).
  std::shared_ptr<const SampledHistory> history;
};

/// A bar body: the nodes first..last (inclusive) and its bonds first..last-1.
struct BodyRange {
  std::string name;
  bool is_mass = false;
  std::size_t first = 0, last = 0;
  std::string displacement = "0", velocity = "0";  ///< u0(x), v0(x) (constants for a mass)
};

/// A virtual strain gauge: strain and force read off bonds `left` and
/// `right` (the same bond inside an element; the two beside a node), the
/// velocity interpolated linearly between nodes `node` and `node + 1` with
/// weight `weight` on the second.
struct GaugePoint {
  std::string name;
  std::size_t left = 0, right = 0;
  std::size_t node = 0;
  double weight = 0.0;
};

/// Smith's side springs (the case's [body.shaft]) on the nodes of the line:
/// at node j a resistance to the penetration w = -u_j (into the soil, -x),
///   R_s = k_j (w - s_j) within [-R_u_j, R_u_j] (the slip s_j keeps it there),
///   R = R_s + (J_j |R_s| + D_j) dw/dt,
/// along +x on the node; J_j is Smith's damping (damping_law smith) and D_j =
/// J R_u_j the viscous one, one of them 0, so that the force is branch-free.
struct Shaft {
  std::vector<double> ultimate;    ///< R_u per node (0: no soil there)
  std::vector<double> stiffness;   ///< k = R_u / q
  std::vector<double> quake;       ///< q
  std::vector<double> smith;       ///< J (Smith's damping) or 0
  std::vector<double> viscous;     ///< J R_u (viscous damping) or 0
  std::vector<std::size_t> nodes;  ///< the nodes with soil, ascending
  [[nodiscard]] bool empty() const { return nodes.empty(); }
};

struct Line {
  std::vector<double> x;           ///< reference positions of the nodes
  Bonds bonds;                     ///< x.size() - 1 of them
  std::vector<double> point_mass;  ///< masses lumped on nodes (mass bodies)
  std::vector<BodyRange> bodies;   ///< in line order
  std::vector<Link> links;         ///< near end first, then joints in line order, then far end
  End near, far;
  std::vector<GaugePoint> gauges;
  Shaft shaft;                   ///< Smith's side springs (empty: none)
  std::string body_force = "0";  ///< f(x, t), force per unit length on the bar elements
  double gravity = 0.0;          ///< g, towards -x
  /// Per body (line order): its elastic-plastic material, none if elastic.
  std::vector<std::optional<Plasticity>> plasticity;

  /// Whether any body is elastic-plastic.
  [[nodiscard]] bool plastic() const {
    for (const auto& p : plasticity)
      if (p) return true;
    return false;
  }

  [[nodiscard]] std::size_t nodes() const { return x.size(); }
  /// M_h (consistent) or its row sums (lumped), point masses on the diagonal.
  [[nodiscard]] Tridiagonal mass(bool consistent) const;
  /// K from the bonds' stiffness (elements and springs), or C from their viscosity.
  [[nodiscard]] Tridiagonal stiffness() const;
  [[nodiscard]] Tridiagonal viscosity() const;
  /// The lumped mass of every node (row sums of M_h plus point masses).
  [[nodiscard]] std::vector<double> lumped_mass() const;
  /// Node j's lumped mass: its point mass and half of each element beside it.
  [[nodiscard]] double node_mass(std::size_t j) const {
    double m = point_mass[j];
    if (j > 0) m += 0.5 * bonds[j - 1].mass;
    if (j < bonds.size()) m += 0.5 * bonds[j].mass;
    return m;
  }
  /// F_i = int f phi_i over the elements (3-point Gauss each) minus g times
  /// the node's lumped mass, at time t.
  void load(const Expression& f, double t, std::vector<double>& out) const;
  /// Nodal values of each body's u0 (which = 0) or v0 (which = 1) at t = 0.
  [[nodiscard]] std::vector<double> initial(int which) const;
  /// Sum over bonds of kind `kind` of k_j (a_{j+1} - a_j)(b_{j+1} - b_j)
  /// (or c_j with `viscous`): a^T K b restricted to those bonds, free of cancellation.
  [[nodiscard]] double bond_form(BondKind kind, bool viscous, const double* a, const double* b) const;
  /// The opening of link i for nodal displacements u.
  [[nodiscard]] double opening(std::size_t i, const double* u) const {
    const Link& l = links[i];
    return (l.b == Link::ground ? 0.0 : u[l.b]) - (l.a == Link::ground ? 0.0 : u[l.a]) + l.gap;
  }
  /// Whether node j is held (clamped or driven at a velocity).
  [[nodiscard]] bool fixed(std::size_t j) const {
    return (j == near.node && (near.kind == EndKind::clamped || near.kind == EndKind::velocity)) ||
           (j == far.node && (far.kind == EndKind::clamped || far.kind == EndKind::velocity));
  }
  /// The smallest element length over the bar speeds, min h_j / c_j, and 0 without elements.
  [[nodiscard]] double smallest_transit() const;
};

}  // namespace barimpact
