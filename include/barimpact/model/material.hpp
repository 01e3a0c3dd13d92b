// A bar's material: elastic (the paper's) or elastic-plastic with bilinear
// hardening, in one dimension (Simo & Hughes, Computational Inelasticity,
// 1998, Sections 1.2-1.4).
//
// Stress sigma = E (eps - eps_p), yield function f = |sigma - q| - (sigma_y +
// H alpha), H = E E_t / (E - E_t) the plastic modulus that makes the slope
// past yield E_t (E_t = 0: perfectly plastic, H = 0). Kinematic hardening
// moves the centre q = H eps_p (alpha stays 0); isotropic hardening grows the
// radius (q = 0, alpha the accumulated plastic strain). The return map is
// backward Euler, exact for a bilinear law along any strain path that is
// monotone within a step: trial sigma_tr = E (eps - eps_p), and while
// f_tr > 0, dgamma = f_tr / (E + H), eps_p += dgamma sign(sigma_tr - q).
// Per unit volume, the plastic work dissipated is sigma_y dgamma and the
// hardening stores H alpha^2 / 2 (isotropic) or H eps_p^2 / 2 (kinematic).
#pragma once

#include <algorithm>
#include <cmath>

namespace barimpact {

enum class MaterialKind { elastic, plastic };
enum class Hardening { kinematic, isotropic };

/// The case's material keys on a bar body (or today's [bar]).
struct MaterialData {
  MaterialKind kind = MaterialKind::elastic;
  double yield_stress = 1.0;       ///< sigma_y > 0
  double hardening_modulus = 0.0;  ///< E_t in [0, E): the slope past yield
  Hardening hardening = Hardening::kinematic;
};

/// The state of one element: plastic strain, accumulated plastic strain
/// (isotropic hardening's alpha; tracked for both), the plastic work
/// dissipated per unit volume so far.
struct PlasticState {
  double strain = 0.0;       ///< eps_p, tension positive
  double accumulated = 0.0;  ///< sum of |d eps_p|
};

/// One elastic-plastic material with its modulus: the return map.
struct Plasticity {
  double modulus = 1.0;          ///< E
  double yield_stress = 1.0;     ///< sigma_y
  double plastic_modulus = 0.0;  ///< H = E E_t / (E - E_t)
  bool isotropic = false;

  Plasticity() = default;
  Plasticity(double e, const MaterialData& m)
      : modulus(e),
        yield_stress(m.yield_stress),
        plastic_modulus(e * m.hardening_modulus / (e - m.hardening_modulus)),
        isotropic(m.hardening == Hardening::isotropic) {}

  /// The stress at total strain `eps`, updating the element's state;
  /// `dgamma` is the plastic strain increment's size (0 while elastic).
  double stress(double eps, PlasticState& s, double& dgamma) const {
    const double trial = modulus * (eps - s.strain);
    const double inv = 1.0 / (modulus + plastic_modulus);
    dgamma = isotropic ? return_map<true>(trial, plastic_modulus, yield_stress, inv, s.strain, s.accumulated)
                       : return_map<false>(trial, plastic_modulus, yield_stress, inv, s.strain, s.accumulated);
    return modulus * (eps - s.strain);
  }

  /// The return map's core, branch-free so that loops over elements
  /// vectorise: from the trial stress E (eps - p), the new p and alpha in
  /// place; returns dgamma (inv = 1 / (E + H)).
  template <bool iso>
  static double return_map(double trial, double h, double sigma_y, double inv, double& p, double& alpha) {
    const double over = iso ? trial : trial - h * p;
    const double radius = iso ? sigma_y + h * alpha : sigma_y;
    const double dgamma = std::max(std::abs(over) - radius, 0.0) * inv;
    p += std::copysign(dgamma, over);
    alpha += dgamma;
    return dgamma;
  }

  /// The energy the hardening stores per unit volume.
  [[nodiscard]] double hardening_energy(const PlasticState& s) const {
    const double a = isotropic ? s.accumulated : s.strain;
    return 0.5 * plastic_modulus * a * a;
  }
};

}  // namespace barimpact
