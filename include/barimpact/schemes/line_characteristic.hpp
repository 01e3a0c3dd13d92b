// `characteristic` on a line of bodies: d'Alembert's solution stepped
// exactly, for elastic bars whose elements all take one step dt = h_i / c_i
// to cross (Courant number 1 in every bar).
//
// Inside a uniform run of one bar the lumped stencil is the method of
// characteristics, u_j^{n+1} = u_{j+1}^n + u_{j-1}^n - u_j^{n-1}, exact for any
// u = F(x - c t) + G(x + c t). Every other node (a port: body ends, welded
// junctions of impedances Z = rho c A, masses, link faces, the two ends) is
// stepped in characteristic variables. Each bar s beside the port splits the
// port's displacement into the wave arriving, in_s, and the wave leaving,
// out_s (u = in_s + out_s, one split per side), and the wave arriving at
// t_{n+1} left the neighbour node one transit earlier:
//
//   in_s^{n+1} = u_nbr^n - out_s^{n-1}                                  (C1)
//
// With u = F + G in bar s, the bar's tension at the port is
// N = +/- Z_s (2 d(in_s)/dt - v), so a port of point mass m, bars Z = sum Z_s
// and an external force P obeys
//
//   m dv/dt + Z v = dq/dt + P,    q = 2 sum_s Z_s in_s.                 (C2)
//
// Integrated over a step (exact), with the trapezoidal rule for u:
//
//   m (v^{n+1} - v^n) + Z (u^{n+1} - u^n) = q^{n+1} - q^n + J^n,
//   u^{n+1} - u^n = (dt / 2) (v^n + v^{n+1}),                            (C3)
//
// J^n the impulse of P over the step; then out_s^{n+1} = u^{n+1} - in_s^{n+1}.
// The start is d'Alembert's for the P1 interpolants of u0 and v0 (u0 split
// evenly at a port; the single bar's Taylor start where v0 is linear).
// Without a mass (C3) is exact: a welded junction moves by
// (2 Z1 d(in_1) + 2 Z2 d(in_2)) / (Z1 + Z2), a step wave transmits the force
// 2 Z2 / (Z1 + Z2) and reflects (Z2 - Z1) / (Z1 + Z2) of it, a free end
// moves by 2 d(in) (and with Z1 = Z2 (C3) is the stencil above, to round-off).
// With a mass it is the trapezoidal rule of m u'' + Z u' = q' + P: second
// order. A force end's J is Simpson's integral of f(t) over the step (exact
// for cubics); a clamped node stays at 0; a node driven at v(t) moves by
// Simpson's integral of v.
//
// Rigid links. The faces first move as if the link were open; if that leaves
// the opening y^{n+1} < 0, impulses I >= 0 (-I on face a, +I on b) close it:
// by (C3) a face moves by w I, w = dt / (2 m + Z dt) (1 / Z without a mass,
// 0 held), so I = -y / (w_a + w_b) (projected Gauss-Seidel when links share a
// mass). In contact two faces act as one welded port that carries only
// compression; they part at the first step whose free motion opens them:
// the single bar's end treatment, at every link. A link's force at t_n is
// the mean impulse of the two steps around it, p^n = (I^{n-1} + I^n) / (2 dt)
// (half the force on the step where contact starts or ends, as the exact
// solutions report it). Its restitution is not used.
//
// Budget. With m_j the lumped masses (Z dt / 2 per bar element end, point
// masses added) and w = (u^{n+1} - u^n) / dt, every node's update is the
// lumped central-difference equation with the external forces
// (J^{n-1} + J^n) / (2 dt) at t_n (at a port, from (C1)-(C3): a mass's
// m (v^{n+1} - v^{n-1}) / (2 dt) tested with (u^{n+1} - u^{n-1}) / 2 is the
// change of m w^2 / 2 under the trapezoidal rule), so central differences'
// identity holds: H^{n+1/2} = |w|_m^2 / 2 + (u^n)^T K u^{n+1} / 2 changes by
// those forces tested with (u^{n+1} - u^{n-1}) / 2. The row at t_n reports the
// mean of H^{n -/+ 1/2}; W_ext books the force ends and the supports (a held
// node's force from its lumped equation of motion), D_contact the rigid
// links. The first half step books each impulse of (0, dt) over dt against
// the mean of the rate at t = 0 and over (0, dt), which closes the budget
// from row 0 when every body starts undeformed and moving rigidly; strained
// data that a free end contradicts lose O(h) there (the single bar's too),
// and from row 1 it closes to round-off whatever the data. Refused
// (characteristic_line_misfit): viscosity, springs, penalty links, body
// forces and gravity.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "barimpact/schemes/line_scheme.hpp"

namespace barimpact {

class LineCharacteristic final : public LineScheme {
 public:
  /// Preconditions: characteristic_line_misfit(c, line) is empty.
  LineCharacteristic(const Case& c, Line line);

  void start() override;
  void advance() override;
  [[nodiscard]] double displacement_at(std::size_t j) const override { return cur_[j]; }
  /// A free mass's own (trapezoidal) v^n; elsewhere (u^{n+1} - u^{n-1}) / (2 dt).
  [[nodiscard]] double velocity_at(std::size_t j) const override;
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool finite() const override;

 private:
  static constexpr std::size_t none = Link::ground;
  enum class Hold { free, forced, clamped, driven };

  // A bar beside a port: the node across its element, its impedance Z_s,
  // and the port's split of u into arriving and leaving waves.
  struct Side {
    std::size_t neighbour = 0;
    double impedance = 0.0;
    double stiffness = 0.0;       // k = E A / h of its element
    double in = 0.0;              // in^{n+1}
    double in_next = 0.0;         // in^{n+2}, during a step
    std::array<double, 2> out{};  // out^n, out^{n+1}
  };
  struct Port {
    std::size_t node = 0;
    std::array<Side, 2> side{};
    int sides = 0;
    double impedance = 0.0;  // Z = sum Z_s
    double mass = 0.0;       // the point mass m
    double response = 0.0;   // w = d u^{n+1} / d J: dt / (2 m + Z dt), 0 when held
    Hold hold = Hold::free;
    bool near = false;                             // the near end's node (for its force or velocity)
    std::array<double, 2> velocity{};              // v^n, v^{n+1} (a mass's trapezoidal velocity)
    std::array<double, 2> impulse{};               // J^{n-1}, J^n: a force end's or a support's
    double drive = 0.0;                            // q^{n+1} - q^n of this step
    double support = 0.0;                          // a held node's support force at t_n, along +x
    std::array<std::size_t, 2> links{none, none};  // rigid links touching the node
    std::array<double, 2> link_sign{};             // -1 on face a, +1 on face b
  };

  // A run [first, last) of interior nodes of one uniform bar: the stencil.
  struct Stretch {
    std::size_t first, last;
  };

  [[nodiscard]] Port make_port(std::size_t j) const;
  void connect_links();
  /// The waves arriving at t_{n+1}: (C1), or at the start d'Alembert's for
  /// the P1 interpolants of u0 and v0; sets the port's drive.
  void arrive(Port& p, const double* u, bool first);
  /// (C3) without the links (held: the prescribed motion).
  void free_update(Port& p, const double* u, double* up, double t);
  /// Closes every rigid link's opening at up by impulses (impulse_).
  void settle_links(double* up);
  /// The leaving waves, a mass's velocity and a held node's impulse after the links.
  void depart(Port& p, const double* u, const double* up, double t);
  [[nodiscard]] double link_impulse_on(const Port& p) const;
  [[nodiscard]] double step_integral(bool near, double t) const;
  void uniform_rows(const double* um, const double* u, double* up) const;
  void start_rows(double* up) const;
  /// Link forces and the near and far forces at t_n (`first`: n = 0).
  void report_forces(bool first);
  /// A held node's support force at t_n from its lumped equation of motion.
  [[nodiscard]] double support(const Port& p) const;
  void book_first_half_step();
  void book_budget(double& dw, double& dc) const;
  [[nodiscard]] double half_step(const double* a, const double* b, double& kinetic) const;

  std::vector<Stretch> stretches_;
  std::vector<Port> ports_;
  std::vector<std::size_t> port_of_;            // per node: its port, or none
  std::vector<double> m_;                       // lumped masses
  std::vector<double> impulse_, impulse_last_;  // rigid links' I^n, I^{n-1}
  bool coupled_ = false;                        // two rigid links share a node
  std::array<std::vector<double>, 3> levels_;
  double* prev_ = nullptr;
  double* cur_ = nullptr;
  double* next_ = nullptr;
  CentredBudget budget_;  // its dissipation stays 0: the scheme runs no viscosity
};

/// The step `characteristic` takes on `line`: the element transit time
/// h_i / c_i every bar shares (to a relative 1e-9), nullopt when the bars
/// disagree or there is none. scheme_misfit sets time.step to it.
[[nodiscard]] std::optional<double> line_characteristic_step(const Line& line);

/// Why `characteristic` cannot run the line of `c`: the law, joint or body it
/// cannot treat exactly (key "scheme", naming the schemes that can), a bar
/// whose elements' transit time differs from the others' ("scheme"), or
/// time.step not that transit time ("step").
[[nodiscard]] std::optional<SchemeMisfit> characteristic_line_misfit(const Case& c, const Line& line);

}  // namespace barimpact
