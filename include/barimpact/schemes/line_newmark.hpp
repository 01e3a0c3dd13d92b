// `newmark`: Newmark (beta, gamma) with consistent mass, every penalty link
// solved at t_{n+1}:
//
//   M a^{n+1} + C v^{n+1} + K u^{n+1} = F^{n+1} + sum_i p_i^{n+1} h_i,
//   u^{n+1} = u^* + beta dt^2 a^{n+1},  v^{n+1} = v^* + gamma dt a^{n+1},
//
// h_i = e_b - e_a the link's direction, p_i its law at (u^{n+1}, v^{n+1}).
// A = M + gamma dt C + beta dt^2 K is factored once, from the far end
// towards x = 0, with the rows of held nodes replaced by their prescribed
// accelerations. Penalty links are not in A, so A falls apart into blocks
// (the bodies joined by welded and spring joints), and a link joins the
// last row a of one block to the first row b of the next (or a block's end
// to the ground). A step is two passes, as the single bar's: towards x = 0,
// the predictors, the right-hand side and the first sweep together; then,
// the links' laws at t_{n+1} solved exactly together from the free
// accelerations at their nodes (penalty_links.hpp: an active-set iteration
// over the laws' branches with the Delassus matrix W_ij = h_i . A^{-1} h_j),
// away from x = 0, the back substitution with a, u, v and the budget. The
// free acceleration at a block's first row is known when the first sweep
// ends there, and a link's force enters that row's eliminated right-hand
// side alone; at a block's last row it is a dot product of the first
// sweep's values with precomputed weights (taken on the blocks that end in
// a link only), and the force's answer there, A^{-1} e_a on that block, is
// added during the back substitution (only while the link pushes).
// Budget of the trapezoidal rule: E_kin = v^T M v / 2, E_strain = u^T K u / 2
// (bar elements; springs in E_obstacle with the links' stored energy),
// dW = (u^{n+1} - u^n) . (F^n + F^{n+1}) / 2 with the end forces and the
// supports', dD = dt vbar^T C vbar plus the viscoelastic links' force beyond
// their spring's, trapezoidal; a cushion's hysteresis is D_contact.
// Elastic-plastic bodies: the plastic strains' load G p at t_{n+1}, found
// by the Newton iteration of plastic_iteration.hpp around this step.
// Smith's soil likewise: its forces at t_{n+1} a load found by the Newton
// iteration of soil_iteration.hpp (the toe's link then has no law in the
// active set), booked apart from W_ext.
// A large line of one block, free of held rows and links but at x = 0,
// solves A in P chunks side by side (model/partitioned_tridiagonal.hpp):
// the predictors and r are passes of their own (vectorised loops without
// viscosity), the chunks' eliminations give the free acceleration at node
// 0, the near link's force enters through the reduced system, and a, u, v
// follow the back substitution in a pass of their own.
#pragma once

#include <vector>

#include "barimpact/model/partitioned_tridiagonal.hpp"
#include "barimpact/schemes/line_scheme.hpp"
#include "barimpact/schemes/penalty_links.hpp"
#include "barimpact/schemes/soil_iteration.hpp"

namespace barimpact {

class LineNewmark final : public LineScheme {
 public:
  LineNewmark(const Case& c, Line line);

  void start() override;
  void advance() override;
  [[nodiscard]] double displacement_at(std::size_t j) const override { return u_[j]; }
  [[nodiscard]] double velocity_at(std::size_t j) const override { return v_[j]; }
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool finite() const override;
  [[nodiscard]] double soil_slip_work() const override;
  /// The nodes from which a line that can (one block, no held rows, no
  /// soil or plasticity, links only at node 0) takes the partitioned solve.
  /// It is faster from 100 nodes (BM_NewmarkStep: 2.9 against 3.6 ns per
  /// node-step); below 2000 the sequential solve stays, so that the pinned
  /// examples keep their bits.
  static constexpr std::size_t partition_threshold = barimpact::partition_threshold;
  /// The chunks the solve takes by default (bench/tridiagonal_benchmark.cpp).
  static constexpr std::size_t default_partitions = barimpact::default_partitions;
  /// Solve A in `p` chunks from now on (0: the sequential solve), where the
  /// line can; returns the chunks used. For tests and benchmarks: the
  /// constructor takes time.partitions, else chooses by the line's size.
  std::size_t use_partitions(std::size_t p);
  /// The chunks the solve takes (0: the sequential solve).
  [[nodiscard]] std::size_t partitions() const { return partitioned_.partitions(); }

 private:
  void advance_elastic();
  void step_partitioned(bool loaded);
  template <bool loaded>
  void step_elastic(double t);
  [[nodiscard]] bool partitioned() const { return partitioned_.size() > 0; }
  /// A step with Smith's soil: taken again from level n until the soil's
  /// forces at t_{n+1} hold (soil_iteration.hpp).
  void advance_soil();
  /// r = F(t) + end forces - C v - K u at every free row; held rows get `held`.
  void residual(const std::vector<double>& u, const std::vector<double>& v, double t, std::vector<double>& r);
  void build_blocks();
  /// The free accelerations at the links' nodes, then their forces at t_{n+1}.
  void solve_links();
  template <bool loaded, bool viscous, bool eliminated = true>
  void forward(double t);
  /// An end node's right-hand side r, or a held end's prescribed acceleration.
  [[nodiscard]] double end_row(std::size_t j, double r, double t) const;
  template <bool loaded, bool viscous, bool solved = false>
  void backward();
  template <bool loaded, bool viscous, bool pushed, bool solved>
  void backward_block(std::size_t first, std::size_t last, double p, double& x, double& dw, double& dd,
                      double& vbar_below);
  void book_links(double t);
  [[nodiscard]] double support(std::size_t node, double t) const;

  /// A's blocks (rows first..last) and the link on each block's last row.
  struct Block {
    std::size_t first, last;
    std::size_t far_link;  ///< the link whose lower node is `last`, or none
  };
  static constexpr std::size_t none = static_cast<std::size_t>(-1);

  double beta_, gamma_;
  Tridiagonal mass_, stiff_, visc_;
  // A's factors from the far end: y_j = r_j - coupling_j y_{j+1}, then
  // x_j = y_j inv_pivot_j - lower_j x_{j-1}.
  std::vector<double> coupling_, inv_pivot_, lower_;
  std::vector<double> last_weight_;    // x_last = sum_j last_weight_j y_j on a block ending in a link
  std::vector<double> last_response_;  // A^{-1} e_last on that block
  std::vector<Block> blocks_;
  std::vector<std::size_t> held_;       // nodes held by their ends
  PartitionedTridiagonal partitioned_;  // A in chunks, when partitioned_.size() > 0
  double near_free_ = 0.0;              // its x_0 after the chunks' eliminations
  PenaltyLinks penalty_;                // the links' laws and Delassus matrix W_ij = h_i . A^{-1} h_j
  SoilIteration soil_;                  // Smith's toe and shaft, out of penalty_
  std::vector<double> soil_load_;       // F^{n+1} + g^k, what the first sweep reads while the soil acts
  const double* sweep_load_ = nullptr;
  std::vector<double> u_, v_, acc_, rhs_, work_;
  std::vector<double> load_old_, p_old_, c_old_, c_free_, rate_free_, a_free_last_;
  std::vector<double> stiff_bond_, visc_bond_;  // k_j, c_j per bond
  double end_old_[2][2] = {{0, 0}, {0, 0}};     // the ends' v^n and a^n, for u^{n+1} - u^n
  double du_end_[2] = {0, 0};                   // the ends' u^{n+1} - u^n
  double step_work_ = 0.0, step_dissipation_ = 0.0;
  bool viscous_ = false;
  std::array<double, 2> support_old_{};
  double ext_work_ = 0.0, dissipation_ = 0.0;
  // The state a step changes, as one value (state.hpp): u first.
  auto state() {
    return std::tie(u_, v_, acc_, load_, load_old_, p_old_, c_old_, force_, c_max_, support_old_, ext_work_,
                    dissipation_, near_force_, far_force_, penalty_.branches());
  }
  void keep_state() override { kept_.keep(state()); }
  void restore_state() override { kept_.restore(state()); }
  [[nodiscard]] const double* kept_displacement() const override { return kept_.get<0>().data(); }
  KeptState<std::vector<double>, std::vector<double>, std::vector<double>, std::vector<double>, std::vector<double>,
            std::vector<double>, std::vector<double>, std::vector<double>, std::vector<double>, std::array<double, 2>,
            double, double, double, double, std::vector<PenaltyLinks::Branch>>
      kept_;
};

}  // namespace barimpact
