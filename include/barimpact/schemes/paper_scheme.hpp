// The alpha-scheme of Do, Raupp & Feijoo (1979), eq. (6.3), in matrix form
// (docs/methods.md states it and the two misprints it corrects). With
// z = exp(-lambda t) u and the split
// k U^- = (k/2)|U| - (k/2) U (linear half implicit, |.| explicit):
//
//   M (z^{n+1} - 2 z^n + z^{n-1}) / dt^2 + S z^{n,alpha} + D (z^{n+1} - z^{n-1}) / (2 dt)
//       = F^{n,alpha} + (k/2) |z^n_0| e_0,
//   S = lambda^2 M + K_a + lambda K_b + (k/2) e_0 e_0^T,   D = 2 lambda M + K_b,
//
// so that A z^{n+1} = B1 z^n + B0 z^{n-1} + (load and contact), with
// A = M/dt^2 + alpha S + D/(2 dt) factored once (it is symmetric positive
// definite) and B1 = 2M/dt^2 - (1 - 2 alpha) S, B0 = -M/dt^2 - alpha S + D/(2 dt).
// A gap g shifts the contact variable: z_0 + g exp(-lambda t) replaces z_0 in
// the obstacle terms, its constant part treated as a load.
//
// Viscoelastic obstacle (l > 0): its dashpot, l (dz_0/dt + lambda z_0) in
// z-variables, joins the implicit side, centred like D and alpha-averaged
// like S, while the contact status is explicit (d^n > 0 and k d^n + l dd/dt^n
// > 0): A + sigma e0 e0^T is solved by Sherman-Morrison with w = A^{-1} e0
// computed once, so the matrix is still factored once. Where the law clips
// (d^n > 0, k d^n + l dd/dt^n <= 0, R = 0) the spring's split is cancelled
// too, its share of A by sigma = -alpha k/2: no obstacle force acts.
// Large bars (partition_threshold nodes and more, outside a batch) solve A
// by Wang's partition method instead (model/partitioned_tridiagonal.hpp):
// the right-hand side in a pass of its own, then P chunks' chains side by
// side, which escape the latency of the two-ended solve's two chains; the
// dashpot's Sherman-Morrison term then enters as a force at row 0.
// Start: z^1 by Taylor with the initial acceleration, second order.
// Clamped far end: the last row of A becomes the identity, u_M = 0.
//
// Velocity and energies at t_n (docs/methods.md): V^n = (u^{n+1} - u^{n-1}) / (2 dt);
// E_kin, E_strain are the means of the scheme's half-step energies at
// n -/+ 1/2, E_obstacle = k ((U^n + g)^-)^2 / 2.
#pragma once

#include <array>
#include <memory>
#include <new>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/expression.hpp"
#include "barimpact/model/line.hpp"
#include "barimpact/model/partitioned_tridiagonal.hpp"
#include "barimpact/model/tridiagonal.hpp"
#include "barimpact/schemes/scheme.hpp"
#include "barimpact/schemes/simd.hpp"

namespace barimpact {

class PaperBatch;

class PaperScheme final : public Scheme {
 public:
  /// Preconditions: `c` validated, a line of one elastic bar (Case::one_bar),
  /// `line` the case's built line, which the scheme keeps (Scheme::line).
  PaperScheme(const Case& c, Line line);
  /// The same, building the line.
  explicit PaperScheme(const Case& c);

  void start() override;
  void advance() override;

  [[nodiscard]] long long step() const override { return n_; }
  [[nodiscard]] double time() const override { return static_cast<double>(n_) * dt_; }
  [[nodiscard]] std::size_t nodes() const override { return line_.nodes(); }
  [[nodiscard]] const Line* line() const override { return &line_; }
  [[nodiscard]] double end_displacement() const override;
  [[nodiscard]] double end_velocity() const override;
  [[nodiscard]] double reaction() const override { return end_force(end_displacement(), end_velocity()); }
  void displacement(std::span<double> out) const override;
  void velocity(std::span<double> out) const override;
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool begin_energies(Energies& e) const override;
  void finish_energies(Energies& e) const override;
  [[nodiscard]] bool finite() const override;
  [[nodiscard]] double displacement_at(std::size_t j) const override;
  [[nodiscard]] double velocity_at(std::size_t j) const override;
  [[nodiscard]] double link_opening(std::size_t /*i*/) const override { return end_displacement() + gap_; }

  /// Bars of this many nodes and more take the partitioned solve. Measured
  /// (bench BM_PaperStepPartitioned against BM_PaperStepSequential) it is
  /// already 1.5 times faster at 1001 nodes; the threshold stays above the
  /// pinned examples, which keep the two-ended solve's bits. 8 chunks: 16 and
  /// 32 are no faster at 10^4..10^6 nodes.
  static constexpr std::size_t partition_threshold = barimpact::partition_threshold;
  static constexpr std::size_t default_partitions = barimpact::default_partitions;
  /// Solves A in p chunks from the next step on (0: the sequential two-ended
  /// solve); returns the chunks used.
  std::size_t use_partitions(std::size_t p);
  [[nodiscard]] bool partitioned() const { return partitioned_.size() > 0; }

  /// The level z^{n+1}, node j at [j * stride()] (exposed for tests of the scheme itself).
  [[nodiscard]] const double* next_level() const { return next_; }
  [[nodiscard]] std::size_t stride() const { return stride_; }

 private:
  PaperScheme(const Case& c, const OneBar& one, Line line);
  friend class PaperBatch;
  enum class LoadMode { zero, steady, unsteady };
  /// A row of the right-hand side with the alpha-mean load F^{m,alpha}
  /// added: cp f^{m+1} + c0 f^m + cm f^{m-1} (steady: c0 f^m alone). A zero
  /// load adds nothing, not even the + 0.0 that IEEE rules would keep.
  template <LoadMode mode>
  struct LoadedRow {
    const double* __restrict fp;
    const double* __restrict f0;
    const double* __restrict fm;
    double cp, c0, cm;
    double operator()(double r, std::size_t j) const {
      if constexpr (mode == LoadMode::zero) {
        (void)j;
        return r;
      } else if constexpr (mode == LoadMode::steady) {
        return r + c0 * f0[j];
      } else {
        return r + (cp * fp[j] + c0 * f0[j] + cm * fm[j]);
      }
    }
  };

  /// A, B1 and B0 on their three distinct rows (members) and A's diagonal there.
  [[nodiscard]] std::array<double, 3> form_matrices();
  /// A's two-ended factors from its rows (the first, an inner, the last).
  void factor(const std::array<double, 3>& rows);
  void respond_to_dashpot();
  /// The levels, the loads and the initial values' expressions.
  void allocate(const Case& c, const OneBar& one);
  /// fused: also the half step (m - 1, m)'s energy sums, into cached_.
  template <LoadMode mode, bool fused>
  void solve_level(long long m);
  /// The same by the partitioned solve.
  template <LoadMode mode, bool fused>
  void solve_level_partitioned(long long m);
  /// Level m's right-hand side B1 z^m + B0 z^{m-1} + F^{m,alpha} + contact,
  /// shared by both solves: an inner row's stencil (operator()), the end
  /// rows r0 (with the obstacle's explicit terms) and r_last, and sigma, the
  /// dashpot's change of A's (0, 0) entry.
  template <LoadMode mode>
  struct LevelRows {
    const double* __restrict zc;
    const double* __restrict zo;
    LoadedRow<mode> loaded;
    double b1d, b1o, b0d, b0o;
    double r0 = 0.0, r_last = 0.0, sigma = 0.0;
    double operator()(std::size_t j) const {
      return loaded(b1d * zc[j] + b1o * (zc[j - 1] + zc[j + 1]) + b0d * zo[j] + b0o * (zo[j - 1] + zo[j + 1]), j);
    }
  };
  /// What both solves share at level m: the load, the obstacle's terms and the end rows.
  template <LoadMode mode>
  LevelRows<mode> level_rows(long long m);
  /// F^{m,alpha}'s loads and weights (paper_scheme.cpp).
  struct AlphaLoad {
    const double* fp = nullptr;
    const double* f0 = nullptr;
    const double* fm = nullptr;
    double cp = 0.0, c0 = 0.0, cm = 0.0;
  };
  template <LoadMode mode>
  AlphaLoad alpha_load(long long m, double em1, double e0, double ep1, double ebar);
  /// The viscoelastic obstacle's dashpot added to a solve's y (add_dashpot's Sherman-Morrison).
  void add_dashpot(double sigma, double* y) const;
  /// Rotates the levels and books the budget of level m.
  void finish_level(long long m);
  /// The viscoelastic obstacle's status at level m and its terms in row 0;
  /// returns the change sigma of A's (0, 0) entry.
  double viscoelastic_row(const double* zc, const double* zo, double e0, double em1, double& contact);
  /// The obstacle's penetration d = (-(U + g))^+, its force R(U, V) and
  /// stored energy k d^2 / 2: the near link's law (none: 0).
  [[nodiscard]] double penetration(double U) const {
    const double d = -(U + gap_);
    return law_ != nullptr && d > 0.0 ? d : 0.0;
  }
  [[nodiscard]] double end_force(double U, double V) const {
    return law_ != nullptr ? law_->force(-(U + gap_), -V, 0.0) : 0.0;
  }
  [[nodiscard]] double end_energy(double U) const { return law_ != nullptr ? law_->energy(-(U + gap_), 0.0) : 0.0; }
  /// a0 = M^{-1} (F(0) - K_a u0 - K_b v0 + R(0) e0).
  [[nodiscard]] std::vector<double> initial_acceleration() const;
  /// W_ext and D_visc of (0, t_{1/2}), dt/2 times their rates at t = 0.
  void book_first_half_step();
  /// exp(lambda t_m): u^m = scale(m) z^m (Remark 6.2).
  [[nodiscard]] double scale(long long m) const;
  /// The scheme's energy between levels (a, b) = (n-1, n) or (n, n+1):
  /// (1/2)|w|_M^2 + (1/2)|m|_Ka^2 + (alpha - 1/4)(dt^2/2)|w|_Ka^2, w = (u^b - u^a)/dt,
  /// m = (u^b + u^a)/2; the identity (7.1) makes it telescope when lambda = 0.
  /// Level i is z_i scaled by s_i; with z_c, also the half-step (b, c), in
  /// the same pass over the nodes.
  void half_step_energies(const double* za, double sa, const double* zb, double sb, const double* zc, double sc,
                          double (&kinetic)[2], double (&strain)[2]) const;
  void accumulate_budget(long long m);
  /// A row's energies but E_kin and E_strain (n >= 1): the obstacle's, W and D.
  [[nodiscard]] Energies energies_but_half_steps() const;
  /// The half-step energies' constants: rho h / 6, a / h, (alpha - 1/4) dt^2.
  [[nodiscard]] std::array<double, 3> energy_constants() const;

  Line line_;
  const ContactLaw* law_ = nullptr;  // the near link's (elastic or viscoelastic), null without one
  double gap_ = 0.0;
  double k_ = 0.0, l_ = 0.0;  // the obstacle's stiffness, and its viscosity when viscoelastic
  double h_, dt_, alpha_, lambda_, density_, a_, b_;
  bool clamped_;

  // Constant coefficients of A, B1, B0 on the uniform mesh: the off-diagonal
  // (identical for every element) and the first, inner and last diagonal.
  double a_off_, b1_off_, b0_off_;
  std::array<double, 3> b1_diag_{}, b0_diag_{};
  std::array<double, 3> a_diag_{};        // A's first, inner and last diagonal
  PartitionedTridiagonal partitioned_;    // A in chunks, when partitioned()
  std::vector<double> inv_;               // 1 / pivot of A's two-ended factorisation
  std::vector<double> upper_;             // a_off / pivot: the factors' off-diagonal
  std::vector<double> dashpot_response_;  // w = A^{-1} e0 (viscoelastic obstacle)
  double dashpot_sigma_ = 0.0;            // l (alpha lambda + 1/(2 dt))
  /// The viscoelastic obstacle's status used at the last level: apart (d <= 0,
  /// the split spring alone), pushing (spring and dashpot), clipped (R = 0).
  enum class Contact { apart, pushing, clipped };
  Contact contact_ = Contact::apart;

  std::array<std::vector<double>, 3> levels_;
  std::size_t stride_ = 1;  // node j of a level is at [j * stride_] (PaperBatch::width inside one)
  bool batched_ = false;
  double* prev_ = nullptr;  // z^{n-1}
  double* cur_ = nullptr;   // z^n
  double* next_ = nullptr;  // z^{n+1}

  LoadMode load_mode_ = LoadMode::zero;
  std::unique_ptr<Expression> body_force_, initial_displacement_, initial_velocity_;
  std::array<std::vector<double>, 3> loads_;  // F(t_{m-1}), F(t_m), F(t_{m+1}), unscaled
  std::vector<double> u0_, v0_;

  // The half-step energy at n + 1/2, kept for the row at n + 1.
  struct HalfStep {
    long long n = -1;
    double kinetic = 0.0, strain = 0.0;
  };
  mutable HalfStep cached_;
  mutable HalfStep pending_;   // a history row's half step n - 1/2 while n + 1/2 is summed (begin_energies)
  mutable bool fuse_ = false;  // the next advance sums its half step (m - 1, m) into cached_

  long long n_ = 0;
  double start_kinetic_ = 0.0, start_strain_ = 0.0;  // E_kin, E_strain at t = 0 (the mass matrix is not kept)
  double work_half_ = 0.0, dissipation_half_ = 0.0;  // sums up to t_{n+1/2}
  double work_last_ = 0.0, dissipation_last_ = 0.0;  // increments of level n
};

}  // namespace barimpact
