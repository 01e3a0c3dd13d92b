// A bar's material (material.hpp): the backward-Euler return map of
// bilinear hardening against the stress-strain curve it must follow, and
// the plastic modulus and the hardening's stored energy by their formulas.
#include "barimpact/model/material.hpp"

#include <gtest/gtest.h>

#include "../support/plastic_cases.hpp"

namespace barimpact {
namespace {

using testing::bilinear;

// Monotone loading follows the bilinear curve sigma = sigma_y + E_t (eps -
// eps_y) past yield whatever the steps; unloading is elastic (slope E). A
// backward-Euler return map is exact for a piecewise-linear law: 1e-15 is
// round-off on stresses of order 1.
TEST(ReturnMap, FollowsTheBilinearCurveAndUnloadsElastically) {
  for (Hardening h : {Hardening::kinematic, Hardening::isotropic}) {
    const Plasticity law(2.0, bilinear(1.0, 0.5, h));  // eps_y = 0.5
    PlasticState s;
    double dgamma = 0.0;
    EXPECT_NEAR(law.stress(0.3, s, dgamma), 0.6, 1e-15);
    EXPECT_EQ(dgamma, 0.0);
    for (double eps : {0.7, 1.0, 1.6}) {
      EXPECT_NEAR(law.stress(eps, s, dgamma), 1.0 + 0.5 * (eps - 0.5), 1e-15) << eps;
      EXPECT_GT(dgamma, 0.0);
    }
    const double p = s.strain;  // sigma = E (eps - p) at 1.55 gives p = 1.6 - 1.55 / 2
    EXPECT_NEAR(p, 1.6 - 1.55 / 2.0, 1e-15);
    EXPECT_NEAR(law.stress(1.2, s, dgamma), 2.0 * (1.2 - p), 1e-15);  // unloading: elastic
    EXPECT_EQ(dgamma, 0.0);
    EXPECT_EQ(s.strain, p);
  }
}

// Reverse yield: kinematic hardening moves the elastic range (reverse yield
// at sigma_max - 2 sigma_y, the Bauschinger effect), isotropic hardening
// grows it (reverse yield at -sigma_max).
TEST(ReturnMap, ReverseYieldDependsOnTheHardening) {
  const double E = 2.0;
  for (Hardening h : {Hardening::kinematic, Hardening::isotropic}) {
    const Plasticity law(E, bilinear(1.0, 0.5, h));
    PlasticState s;
    double dgamma = 0.0;
    const double top = law.stress(1.6, s, dgamma);  // 1.55
    const double p = s.strain;
    const double reverse = h == Hardening::kinematic ? top - 2.0 : -top;
    // Just inside the elastic range, then just beyond it.
    const double inside = p + (reverse + 1e-9) / E, beyond = p + (reverse - 1e-3) / E;
    EXPECT_NEAR(law.stress(inside, s, dgamma), reverse + 1e-9, 1e-14);
    EXPECT_EQ(dgamma, 0.0);
    (void)law.stress(beyond, s, dgamma);
    EXPECT_GT(dgamma, 0.0) << (h == Hardening::kinematic ? "kinematic" : "isotropic");
  }
}

// Perfectly plastic (E_t = 0): the stress never exceeds sigma_y, the plastic
// strain takes the rest.
TEST(ReturnMap, PerfectlyPlasticClipsTheStress) {
  const Plasticity law(1.0, bilinear(0.25, 0.0, Hardening::kinematic));
  PlasticState s;
  double dgamma = 0.0;
  EXPECT_EQ(law.stress(-1.0, s, dgamma), -0.25);
  EXPECT_EQ(s.strain, -0.75);
  EXPECT_EQ(law.hardening_energy(s), 0.0);
}

// E = 2, E_t = 0.5: H = E E_t / (E - E_t) = 2/3, so that the slope past
// yield, E H / (E + H), is E_t. Loaded to eps = 1.6 (p = 0.825, sigma =
// 1.55) and then in one step to eps = -1.6:
//  kinematic: the centre q = H p = 0.55, over = 2 (-1.6 - 0.825) - 0.55 =
//    -5.4, dgamma = (5.4 - 1) / (8/3) = 1.65, p = -0.825, sigma = -1.55;
//    it stores H p^2 / 2 = 0.226875 both times;
//  isotropic: the radius 1 + H alpha = 1.55, dgamma = (4.85 - 1.55) / (8/3)
//    = 1.2375, p = -0.4125, alpha = 2.0625, sigma = -(1 + H alpha) =
//    -2.375; it stores H alpha^2 / 2 = 1.41796875.
// Tolerances: round-off on numbers of order 1.
TEST(Plasticity, HardeningStoresHalfItsModulusTimesItsVariableSquared) {
  for (Hardening h : {Hardening::kinematic, Hardening::isotropic}) {
    const bool iso = h == Hardening::isotropic;
    const Plasticity law(2.0, bilinear(1.0, 0.5, h));
    EXPECT_NEAR(law.plastic_modulus, 2.0 / 3.0, 1e-15);
    EXPECT_EQ(law.isotropic, iso);
    PlasticState s;
    double dgamma = 0.0;
    EXPECT_NEAR(law.stress(1.6, s, dgamma), 1.55, 1e-14);
    EXPECT_NEAR(s.strain, 0.825, 1e-14);
    EXPECT_NEAR(s.accumulated, 0.825, 1e-14);
    EXPECT_NEAR(law.hardening_energy(s), 0.226875, 1e-14);
    EXPECT_NEAR(law.stress(-1.6, s, dgamma), iso ? -2.375 : -1.55, 1e-14);
    EXPECT_NEAR(dgamma, iso ? 1.2375 : 1.65, 1e-14);
    EXPECT_NEAR(s.strain, iso ? -0.4125 : -0.825, 1e-14);
    EXPECT_NEAR(s.accumulated, iso ? 2.0625 : 2.475, 1e-14);
    EXPECT_NEAR(law.hardening_energy(s), iso ? 1.41796875 : 0.226875, 1e-14);
  }
}

}  // namespace
}  // namespace barimpact
