// The elastic-plastic elements of a line (material.hpp) for a one-step
// implicit scheme (newmark, moreau-jean, mass-redistribution): the plastic
// strains of level n + 1 found by a Newton iteration with the consistent
// tangent, each iterate checked by the scheme's own step.
//
// With sigma = E (eps - p), the internal force is K u - G p, where G p puts
// E A p_e on element e's upper node and -E A p_e on its lower one: the
// plastic strains act on an elastic scheme as a load g = G p. A step of
// the scheme takes g^{n+1} = G p^k with the k-th iterate p^k (p^0 = p^n)
// among its loads; the return map at the step's u^{n+1} gives p^; the
// iteration stops when max |p^ - p^k| <= 1e-10 sigma_y / E on every body.
// Otherwise Newton's update: the step answers a load at t_{n+1} by
// u^{n+1} += c A^{-1} g (A the scheme's matrix, c its weight), so the
// residual u - U(G P(u)) has the tangent A^{-1} T, T = A - c K_loss, K_loss
// the stiffness the flowing elements lose (E A / h times E / (E + H), the
// return map's consistent tangent being E_t). T is tridiagonal:
//
//   T du = c G (p^ - p^k),   p^{k+1} = P(u^{n+1} + du),
//
// and the step is taken again from level n with p^{k+1}. T also holds the
// links that push, as springs (a rigid one as a hold). Without links the
// iteration ends as soon as the set of flowing elements repeats (the law is
// piecewise linear); links whose status changes within the step make it
// converge linearly. A step where nothing yields is one step and a
// read-only check.
//
// Budget: the scheme books g's work in W_ext as any load's (trapezoidal,
// du . (g^n + g^{n+1}) / 2 = sum h A E pbar deps); E_strain gains
// sum h A E (p^2 / 2 - eps p) and the hardening's energy, W_ext loses g's
// work and D_plastic is sum over steps of h A sigmabar dp less the
// hardening's energy: all from Q = sum_steps sum_e h A E epsbar dp, which
// only yielding steps change, by summation by parts. The budget then closes
// as the elastic scheme's does.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "barimpact/model/line.hpp"
#include "barimpact/model/tridiagonal.hpp"
#include "barimpact/schemes/plastic_body.hpp"

namespace barimpact {

class PlasticIteration {
 public:
  /// The largest number of steps taken for one level before the run fails.
  static constexpr int most_iterations = 30;

  PlasticIteration() = default;
  explicit PlasticIteration(const Line& line);

  [[nodiscard]] bool active() const { return !ranges_.empty(); }
  /// The scheme's matrix A (the rows of the nodes `held` become the
  /// identity) and weight c:
  /// u^{n+1} answers a load g at t_{n+1} by c A^{-1} g. `links_in_matrix`:
  /// A already holds the links' share of the step's tangent (paper's
  /// implicit halves), so that pushing links are not added again.
  void set_matrix(const Tridiagonal& a, const std::vector<std::size_t>& held, double c, bool links_in_matrix = false);

  /// Level 0 from a virgin material at u0.
  void start(const double* u0);
  /// The iteration's first iterate p^0 = p^n.
  void begin_step();
  /// Steps load again with the iterate Newton's update gave (begin_step():
  /// with level n's plastic strains).
  void use_iterate() {
    iterate_p_ = pk_.data();
    loading_ = true;
  }
  /// Whether g = G p^k may be nonzero (the scheme's loads must carry it).
  [[nodiscard]] bool loading() const { return loading_; }
  /// f += G p^k.
  void add_load(double* f) const;
  /// After the step with p^k reached u^{n+1} = `scale` times `u` with link
  /// forces `force`: true when p^k holds; otherwise p^{k+1} by Newton's
  /// update, and false. (`scale`: paper's exp(lambda t), u kept as z.)
  [[nodiscard]] bool settled(const double* u, const double* force, double scale = 1.0);
  /// Level n + 1 = p^k (k >= 1), its share of Q booked (u_old: u^n;
  /// nullptr: a scheme that books its plastic work itself).
  void accept(const double* u_old, const double* u);
  /// Level n + 1 straight from the return map at u^{n+1} = `scale` times
  /// `u` (a step that does not depend on it: paper's Taylor start); true
  /// when it differs from level n.
  bool take(const double* u, double scale = 1.0);
  /// Accumulated plastic strain per bond at t_n (isotropic hardening's alpha).
  [[nodiscard]] const double* accumulated() const { return alpha_.data(); }
  /// The largest |p^ - p^k| / tolerance of the last check.
  [[nodiscard]] double misfit() const { return misfit_; }
  /// How hard the iteration worked: the levels where something yielded,
  /// the steps taken for them (at least 2 each, besides replays), the most
  /// for one level.
  struct Effort {
    long long yielding_levels = 0, steps = 0;
    int most = 0;
  };
  void count(int steps) {
    if (steps < 2) return;
    ++effort_.yielding_levels;
    effort_.steps += steps;
    effort_.most = std::max(effort_.most, steps);
  }
  [[nodiscard]] const Effort& effort() const { return effort_; }

  /// Plastic strain per bond at t_n (bonds of elastic bodies: 0).
  [[nodiscard]] const double* strain() const { return p_.data(); }
  /// What E_strain gains beyond u^T K u / 2 at u = u^n (hardening included).
  [[nodiscard]] double strain_energy(const double* u) const;
  /// g's work the scheme has booked in W_ext up to t_n.
  [[nodiscard]] double load_work(const double* u) const;
  /// D_plastic up to t_n, of all bodies or of one.
  [[nodiscard]] double work() const;
  [[nodiscard]] double body_work(std::size_t body) const;

 private:
  using Range = PlasticBody;
  // Per body (index into ranges_): the sums the budget's terms are made of,
  // sum h A E p eps (u: nullptr leaves it 0), sum h A E p^2 / 2 and the
  // hardening's energy.
  struct Sums {
    double p_eps = 0.0, p_p = 0.0, hardening = 0.0;
  };
  [[nodiscard]] Sums sums(const Range& r, const double* u) const;
  [[nodiscard]] double range_work(std::size_t i) const;
  /// p^ at u into trial_, flowing_; returns max |p^ - p^k| / tolerance.
  double trial(const double* u, double scale);
  /// p^{k+1} from u by the tangent solve.
  void newton(const double* u, const double* force, double scale);
  /// The links that push (force > 0) in the tangent: a penalty law's c k,
  /// a rigid link as a spring 1e8 times stiffer than its rows (a hold).
  void add_links(const double* force);

  std::vector<Range> ranges_;
  std::vector<Sums> start_;          // at level 0
  std::vector<double> q_;            // per range
  std::vector<double> p_, alpha_;    // level n
  std::vector<double> pk_, alphak_;  // the iterate (k >= 1)
  std::vector<double> trial_p_, trial_alpha_;
  std::vector<unsigned char> flowing_;
  const double* iterate_p_ = nullptr;       // p^k: p_ (k = 0) or pk_
  bool loading_ = false, pristine_ = true;  // pristine: p^n = 0 everywhere
  bool links_in_matrix_ = false;
  double misfit_ = 0.0;
  Effort effort_;
  Tridiagonal a_;
  std::vector<std::size_t> held_;  // rows of A that are the identity
  double c_ = 0.0;
  std::vector<double> diag_, off_, du_;  // the tangent's solve
  struct LinkTangent {
    std::size_t a, b;
    double stiffness;  // k; 0 for a rigid link
  };
  std::vector<LinkTangent> links_;
};

}  // namespace barimpact
