// `paper` on a line of bodies: the alpha-scheme of Do, Raupp & Feijoo
// (paper_scheme.hpp) with per-bond coefficients, its treatment of the
// elastic obstacle given to every penalty link. With z = exp(-lambda t) u,
// M the consistent mass (point masses on the diagonal), K and C the bonds'
// stiffness and viscosity (bar elements and spring joints), and for each link
// i its direction h_i = e_b - e_a and opening y_i = h_i . u + g_i:
//
//   M (z^{n+1} - 2 z^n + z^{n-1}) / dt^2 + S z^{n,alpha} + D (z^{n+1} - z^{n-1}) / (2 dt)
//       = F^{n,alpha} + sum_i s_i^n h_i,
//   S = lambda^2 M + K + lambda C + sum_i (k_i/2) h_i h_i^T,   D = 2 lambda M + C,
//
// F the body force, gravity and the force ends' values. Each penalty force
// is split as the paper splits k U^-: p = k c^+ = (k/2)|y| - (k/2) y (c = -y),
// the linear half implicit (in S: links join neighbouring nodes or a node and
// the ground, so S stays tridiagonal) and the |.| half explicit:
// s_i = (k/2)(|h_i . z^n + g_i e^{-lambda t_n}| - g_i (e^{-lambda t})^{n,alpha}).
// So A = M/dt^2 + alpha S + D/(2 dt), symmetric positive definite, is
// factored once. Laws with a status decide it explicitly from level n and
// change A by sigma_i h_i h_i^T while it holds:
//
//   viscoelastic, c^n > 0 and k c^n + l dc/dt^n > 0 (the rate by a backward
//     difference): its dashpot l (dz/dt + lambda z) joins the implicit side,
//     centred like D and alpha-averaged like S: sigma = l (alpha lambda + 1/(2 dt));
//   viscoelastic, c^n > 0 and k c^n + l dc/dt^n <= 0 (the law clips, p = 0):
//     the spring's split is cancelled too, sigma = -alpha k/2;
//   cushion, the branch from c^n and c_max: loading along k while c^n >= c_max
//     (or never compressed), the factored split as it is; unloading and
//     reloading along k/e^2 while c_off < c^n < c_max, c_off = (1 - e^2) c_max
//     where the law reaches 0: (k/2e^2)|y + g + c_off| - (k/2e^2)(y + g + c_off),
//     its implicit half sigma = alpha (k/e^2 - k)/2 beyond the factored k/2;
//     clipped at 0 (c^n <= c_off): the factored k/2 with its kink at c_off,
//     whose force is ~0 there as the elastic law's apart (A unchanged).
//
// The single bar's Sherman-Morrison becomes Woodbury's: with the responses
// w_i = A^{-1} h_i and W_ij = h_i . w_j of the links that can change A,
// computed once, z^{n+1} = y - sum mu_i w_i, (I + Sigma W_JJ) mu = Sigma H_J^T y over
// the links J changed this step (y = A^{-1} r); a step with none is one solve.
//
// Held ends (line_rigid.hpp): a clamped node's z is 0, a node driven at v(t)
// moves by dt v(t_{n+1/2}); their rows become the identity and the support's
// force is the original row's residual. The solve is two-ended, as the
// single bar's (tridiagonal.hpp's TwistedTridiagonal), each row's right-hand side
// formed as the sweeps inwards reach it: the single bar's constant stencils
// inside each uniform stretch of a bar, the general row at body ends,
// joints, masses and held ends.
//
// Start: z^1 by Taylor with the initial acceleration (second order), as the
// single bar's. Reported at t_n: u^n = exp(lambda t_n) z^n, v^n = (u^{n+1} -
// u^{n-1}) / (2 dt), each link's law at (c^n, dc/dt^n). Budget (docs/methods.md):
// E_kin, E_strain (bar elements) and the springs' share of E_obstacle are the
// means of the scheme's half-step energies at n -/+ 1/2; each force of
// level m tested with (u^{m+1} - u^{m-1}) / 2 gives W_ext (loads, end forces,
// supports) and D_visc (C, the viscoelastic links' dashpots, and while a
// link clips the spring's energy released); E_obstacle holds each law's
// energy at u^n and D_contact the cushions' hysteresis. Without links and
// lambda = 0 it closes to round-off; the explicit halves close at O(dt^2).
//
// Elastic-plastic bodies: sigma = E (eps - p) makes the internal force
// K u - G p, so the plastic strains are a load G p, alpha-averaged over the
// three levels as F is. p^{m+1} depends on z^{m+1} through the return map:
// the step is taken again from level m with Newton's update of p^{m+1}
// (plastic_iteration.hpp, weight alpha, tangent A - alpha K_loss) until it
// holds. The budget (plastic_bonds.hpp's record): E_strain the half-step
// energies of the elastic strains, D_plastic the centred plastic work,
// W_ext without the plastic load's work. The Taylor start takes p^1 from
// the return map at u^1.
//
// Smith's soil (soil_iteration.hpp's three-level form): its springs
// alpha-averaged over the three levels as a load, its damping centred at
// t_m with level m's dashpot; the step is taken again from level m with
// Newton's update of the soil's force (weight exp(lambda dt), tangent
// A + exp(lambda dt) K_soil, the links' changes of A left out) until it
// holds. The toe's link then has no spring in S and no explicit half.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "barimpact/schemes/line_rigid.hpp"
#include "barimpact/schemes/line_scheme.hpp"
#include "barimpact/schemes/plastic_bonds.hpp"
#include "barimpact/schemes/soil_iteration.hpp"

namespace barimpact {

class LinePaper final : public LineScheme {
 public:
  LinePaper(const Case& c, Line line);

  void start() override;
  void advance() override;
  [[nodiscard]] double displacement_at(std::size_t j) const override { return scale(n_) * cur_[j]; }
  [[nodiscard]] double velocity_at(std::size_t j) const override;
  [[nodiscard]] Energies energies() const override;
  [[nodiscard]] bool finite() const override;
  [[nodiscard]] double plastic_strain(std::size_t bond) const override {
    return plastic_.active() ? plastic_.current()[bond] : 0.0;
  }
  [[nodiscard]] double plastic_work(std::size_t body) const override { return plastic_.body_work(body); }
  [[nodiscard]] double soil_slip_work() const override;

 private:
  /// `soil`: F moves, and Smith's soil's force joins it.
  enum class LoadMode { zero, steady, unsteady, soil };
  /// How a link enters level m's step: the factored split spring alone, the
  /// viscoelastic dashpot beside it, the law clipped, a cushion unloading.
  enum class Status : unsigned char { base, pushing, clipped, unloading };

  /// The constructor's phases: the matrices and A's factors; the rows'
  /// stencils and sweep blocks; the links' responses through A; the state.
  void assemble();
  void plan_rows();
  void respond_links();
  void allocate();
  /// start()'s phases: level 0's loads; a0 and the held rows (the links'
  /// dissipation rate at t = 0 into `viscous`); z^0 and z^1 by Taylor; the
  /// plastic strains of level 1; the first half step's budget.
  void start_loads();
  [[nodiscard]] std::vector<double> initial_acceleration(std::vector<HeldRow>& rows, double& viscous);
  void taylor_start(const std::vector<double>& a0, const std::vector<HeldRow>& rows);
  void start_plastic_level();
  void book_start(double viscous);
  [[nodiscard]] double scale(long long m) const;
  /// F^{m,alpha}'s weights (z-units) on F(t_{m+1}), F(t_m), F(t_{m-1}).
  [[nodiscard]] std::array<double, 3> load_weights(long long m) const;
  /// Each link's status, explicit forces and sigma at level m; the force ends'
  /// values; the held rows' known z^{m+1}.
  void prepare(long long m);
  template <LoadMode mode>
  std::array<const double*, 3> level_loads(long long m);
  void link_row(std::size_t i, const double* zc, const double* zo, double em1, double e0, double ebar);
  void end_rows(long long m, const double* zc, double e0, double ep1);
  /// The elastic step: z^{m+1} from levels m and m - 1 (m = n + 1), loads
  /// with the plastic strains' iterate.
  void advance_elastic();
  /// Keeps the level a plastic or soil step starts again from.
  /// A step with Smith's soil: taken again from level n until the soil's
  /// force at level n holds (soil_iteration.hpp).
  void advance_soil();
  /// u^{m+1}, u^{m-1} and the centred velocity at t_m into soil_u_, soil_old_, soil_v_.
  void soil_levels();
  /// Level m + 1's plastic strains into plastic_, level m's plastic work booked.
  void record_plastic(long long m, bool yielded);
  /// u at levels first, first + 1, first + 2 (z scaled into scaled_ when lambda != 0).
  void displacements(long long first, const double* (&u)[3]) const;
  template <LoadMode mode>
  void sweeps(long long m);
  /// A row outside the stretches: B1 z^m + B0 z^{m-1} + F + extra, the held rows.
  [[nodiscard]] double special_row(std::size_t j, double load);
  /// Woodbury's correction for the links whose sigma is not 0.
  void correct(double* zn);
  void supports(const double* zn);
  void book_level(long long m);
  /// The links' reported forces and the ends' at the current level n.
  void report();
  /// The half-step energies between levels a and b (z scaled by sa, sb):
  /// kinetic, strain (bar elements), springs.
  /// The shaft's springs (E_obstacle), its slip and the soil's damping
  /// (D_contact) at level n, u^n = s u_kept.
  void add_soil(Energies& e, const double* u_kept, double s) const;
  void half_step(const double* za, double sa, const double* zb, double sb, double (&e)[3]) const;

  double alpha_, lambda_;
  LoadMode load_mode_ = LoadMode::zero;  // F's own: zero, steady or unsteady
  LoadMode step_mode_ = LoadMode::zero;  // this step's: unsteady while the plastic strains load
  Tridiagonal mass_, stiff_, visc_;      // M, K, C of the line
  Tridiagonal b1_, b0_;                  // B1 = 2M/dt^2 - (1 - 2 alpha) S, B0 = -M/dt^2 - alpha S + D/(2 dt)
  TwistedTridiagonal factor_;            // A, held rows the identity
  std::vector<HeldRow> held_;
  // Each row's stencil: an index into stencils_ (a uniform stretch's
  // constant coefficients of B1 and B0), or `general` (special_row).
  struct Stencil {
    double b1d, b1o, b0d, b0o;
  };
  static constexpr std::uint32_t general = 0xffffffffu;
  std::vector<Stencil> stencils_;
  std::vector<std::uint32_t> stencil_of_;
  // A run of the solve's row pairs (top j, bottom jb) with the same two
  // stencils; a general row is a block of its own.
  struct Block {
    std::uint32_t count, top, bottom;
  };
  std::vector<Block> blocks_;
  // Bonds first..last - 1 alike in kind, mass and stiffness (half_step's runs).
  struct BondRun {
    std::size_t first, last;
    bool point_masses = false;  // whether a node first..last - 1 carries one
  };
  std::vector<BondRun> bond_runs_;
  std::vector<double> viscosity_;  // c_j per bond
  bool viscous_ = false;
  std::vector<double> extra_;  // the links' s_i h_i and the force ends' values, z-units
  std::vector<std::size_t> extra_nodes_;

  // Links whose status can change A (viscoelastic, cushions with e < 1):
  // their index, response w = A^{-1} h (0 on held rows), W among them.
  std::vector<std::size_t> modifiable_;
  std::vector<std::vector<double>> response_;
  std::vector<double> delassus_;
  std::vector<double> sigma_;  // per modifiable link, this step
  std::vector<double> capacitance_, mu_;
  std::vector<std::size_t> changed_;  // the modifiable links with sigma != 0 this step
  std::vector<Status> status_;        // per link, at the last level
  std::vector<double> link_c_;        // per link: c^m

  std::array<std::vector<double>, 3> levels_;
  double* prev_ = nullptr;  // z^{n-1}
  double* cur_ = nullptr;   // z^n
  double* next_ = nullptr;  // z^{n+1}
  // F(t_m) + G p^m at [m % 3] (unscaled; [0] only while a step is steady)
  std::array<std::vector<double>, 3> loads_;
  std::array<double, 3> near_f_{}, far_f_{};  // the force ends' values at t_m, [m % 3]

  // The half-step energies at n + 1/2, kept for the row at n + 1.
  struct HalfStep {
    long long n = -1;
    double e[3] = {0, 0, 0};
  };
  mutable HalfStep cached_;
  double work_half_ = 0.0, dissipation_half_ = 0.0;  // sums up to t_{n+1/2}
  double work_last_ = 0.0, dissipation_last_ = 0.0;  // level n's increments

  SoilIteration soil_;
  std::vector<double> soil_rhs_;                       // Phi^m / exp(lambda t_m), the step's soil force in z-units
  std::vector<double> soil_u_, soil_old_, soil_v_;     // u^{m+1}, u^{m-1}, (u^{m+1} - u^{m-1}) / (2 dt)
  PlasticBonds plastic_;                               // levels n - 1, n, n + 1 of the plastic strains, their work
  mutable std::array<std::vector<double>, 3> scaled_;  // u = exp(lambda t) z, when lambda != 0
  // The state a step changes, as one value (state.hpp): its three levels and their loads, the link forces.
  auto state() {
    return std::tie(levels_, loads_, prev_, cur_, next_, near_f_, far_f_, work_half_, dissipation_half_, work_last_,
                    dissipation_last_, force_, c_max_, near_force_, far_force_);
  }
  void keep_state() override { kept_.keep(state()); }
  void restore_state() override { kept_.restore(state()); }
  KeptState<std::array<std::vector<double>, 3>, std::array<std::vector<double>, 3>, double*, double*, double*,
            std::array<double, 3>, std::array<double, 3>, double, double, double, double, std::vector<double>,
            std::vector<double>, double, double>
      kept_;
};

}  // namespace barimpact
