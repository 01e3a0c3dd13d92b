// The elastic-plastic elements of a line (material.hpp) for a three-level
// scheme: each element's plastic strain p and accumulated plastic strain at
// levels n - 1, n, n + 1, the return map of a new level, and the scheme's
// energy identity.
//
// A three-level scheme's internal force at level m is the elements' axial
// force N^m = A sigma^m, sigma^m = E (eps^m - p^m). Tested with
// (u^{m+1} - u^{m-1}) / 2, it does the work h A sigma^m (eps^{m+1} -
// eps^{m-1}) / 2 per element, which is exactly
//
//   psi^{m+1/2} - psi^{m-1/2} + h A sigma^m (p^{m+1} - p^{m-1}) / 2,
//   psi^{m+1/2} = h A E (eps^m - p^m)(eps^{m+1} - p^{m+1}) / 2,
//
// so E_strain holds psi (the elastic energy, at the half steps) and the
// second term, summed over the steps, is the plastic work: D_plastic books
// it less the energy the hardening stores (which E_strain holds). The
// budget then closes as the elastic scheme's does. The centred term tends to
// sigma_y |dp| (plus the hardening's share) as dt -> 0; along a monotone
// plastic flow at constant stress it is that exactly.
//
// The paper's alpha-scheme averages its stiffness over three levels, so its
// element force is A sigma~^m, sigma~^m = alpha sigma^{m+1} + (1 - 2 alpha)
// sigma^m + alpha sigma^{m-1}, and with e = eps - p the same algebra gives
//
//   h A sigma~^m (eps^{m+1} - eps^{m-1}) / 2 = psi^{m+1/2} - psi^{m-1/2}
//       + h A sigma~^m (p^{m+1} - p^{m-1}) / 2,
//   psi^{m+1/2} = h A E (e^m e^{m+1} + alpha (e^{m+1} - e^m)^2) / 2,
//
// the paper's half-step energy (7.1) of the elastic strains. Its plastic
// strains come from an iteration (plastic_iteration.hpp) and act as a load
// G p~^m, whose work the scheme books in W_ext: record() books that work
// too, so that W_ext can leave it out.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "barimpact/model/line.hpp"
#include "barimpact/schemes/plastic_body.hpp"

namespace barimpact {

class PlasticBonds {
 public:
  PlasticBonds() = default;
  /// `alpha`: the weight of levels m -/+ 1 in level m's stress (paper's
  /// alpha; 0 for the explicit schemes).
  explicit PlasticBonds(const Line& line, double alpha = 0.0);

  [[nodiscard]] bool active() const { return !ranges_.empty(); }

  /// Level 0 from a virgin material at u0, as level n and in the place of
  /// level n + 1 (the level the next step's forces read).
  void start(const double* u0);
  /// The state at u^{m+1} (`up`) from level m's (`next()`, at `u`), and
  /// level m's plastic work h A sigma^m (p^{m+1} - p^{m-1}) / 2 booked
  /// (p^{m-1}: `current()`); then levels n - 1, n, n + 1 move on by one, as
  /// the scheme's. `first`: the start's step, whose level -1 is level 0
  /// (half its share, as the start's other terms).
  void advance(const double* u, const double* up, bool first = false);
  /// Level m + 1 given by an implicit iteration instead of the return map:
  /// `p`, `a` its plastic and accumulated strains, `yielded` whether they
  /// differ from level m's. Books level m's plastic work h A sigma~^m
  /// (p^{m+1} - p^{m-1}) / 2 and the plastic strains' load's work h A E p~^m
  /// (eps^{m+1} - eps^{m-1}) / 2, both means with the weights `w` of levels
  /// m + 1, m, m - 1 (the scheme's, which the exponential shift tilts),
  /// at displacements um, u, up; then moves on as advance. `first`: the
  /// start's step (w = {0, 1, 0}, um the level that makes (up - um) / 2 the
  /// start's dt v0 / 2).
  void record(const double* p, const double* a, bool yielded, const double* um, const double* u, const double* up,
              const std::array<double, 3>& w, bool first = false);
  /// The work of the plastic strains' load booked by record() up to level n
  /// (its half-step sum, as W_ext's).
  [[nodiscard]] double load_work() const;
  /// No element has yielded yet: every plastic strain is 0 (the schemes'
  /// elastic stencils then hold).
  [[nodiscard]] bool pristine() const { return pristine_; }

  /// Plastic strain per bond (0 in an elastic body): level n + 1 before
  /// advance (the forces' level), level n after it.
  [[nodiscard]] const double* next() const { return p_[next_].data(); }
  [[nodiscard]] const double* current() const { return p_[cur_].data(); }
  [[nodiscard]] const double* previous() const { return p_[prev_].data(); }

  /// What the plastic strains add to an elastic scheme's strain energy at
  /// level n (E_strain's share beyond (1/2) u^T K u): at the start, from u0
  /// alone; later, the mean of the half-step corrections between levels
  /// (u^{n-1}, u^n) and (u^n, u^{n+1}). Both include the hardening's energy.
  [[nodiscard]] double strain_energy(const double* u0) const;
  [[nodiscard]] double strain_energy(const double* um, const double* u, const double* up) const;
  /// D_plastic at level n: the centred plastic work (its half-step sum, as
  /// W_ext's) less the hardening's stored energy; the same for one body.
  [[nodiscard]] double work() const;
  [[nodiscard]] double body_work(std::size_t body) const;

 private:
  using Range = PlasticBody;
  void rotate();
  [[nodiscard]] double hardening_energy(const Range& r) const;
  [[nodiscard]] double hardening_energy() const;
  /// The half-step energy's correction between levels (a, pa) and (b, pb):
  /// sum psi - k da db / 2 over the elastic-plastic elements.
  [[nodiscard]] double energy_correction(const double* a, const double* pa, const double* b, const double* pb) const;
  [[nodiscard]] double body_work(const Range& r) const;

  std::vector<Range> ranges_;
  // Three arrays for levels n - 1, n, n + 1; a level no element yields into
  // shares its predecessor's array (a step where nothing yields, after one
  // where nothing did, writes nothing).
  std::array<std::vector<double>, 3> p_, accumulated_;
  int prev_ = 2, cur_ = 0, next_ = 1, fresh_ = 2;
  bool quiet_ = false;                            // p^{n+1} = p^n: nothing yielded at the last step
  bool pristine_ = true;                          // nothing has ever yielded
  std::vector<double> half_, last_, hardening0_;  // per body: the centred work's sums, the hardening at level 0
  double load_half_ = 0.0, load_last_ = 0.0;      // record()'s load work
  double alpha_ = 0.0;
};

}  // namespace barimpact
