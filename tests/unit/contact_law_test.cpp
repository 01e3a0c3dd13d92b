// The laws of a unilateral link (contact_law.hpp) as functions of the
// compression, its rate and c_max, against the formulas the header states:
// the elastic, viscoelastic, cushion and rigid laws' forces, energies and
// hysteresis, Smith's toe and side springs' slip bookkeeping, and a diesel
// cylinder's gas against its polytropes.
#include "barimpact/model/contact_law.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace barimpact {
namespace {

ContactLaw toe(double ultimate, double quake, double damping, DampingLaw law = DampingLaw::smith) {
  ContactLaw l;
  l.kind = LawKind::smith;
  l.soil = {ultimate, quake, damping, law};
  l.stiffness = l.soil.stiffness();
  return l;
}

ContactLaw law_of(LawKind kind, double k, double l = 0.0, double e = 1.0) {
  ContactLaw law;
  law.kind = kind;
  law.stiffness = k;
  law.viscosity = l;
  law.restitution = e;
  return law;
}

// p = k c^+, energy k c^2 / 2, nothing dissipated; no force nor energy
// while open (c <= 0). k = 100 at c = 0.02: p = 2, energy 0.02. The
// tolerances are round-off on numbers of order 1.
TEST(ContactLaw, ElasticIsHookesSpringInCompressionOnly) {
  const ContactLaw law = law_of(LawKind::elastic, 100.0);
  EXPECT_NEAR(law.force(0.02, 7.0, 0.02), 2.0, 1e-15);  // the rate plays no part
  EXPECT_NEAR(law.energy(0.02, 0.02), 0.02, 1e-16);
  EXPECT_EQ(law.force(-0.01, 1.0, 0.02), 0.0);
  EXPECT_EQ(law.energy(-0.01, 0.02), 0.0);
  EXPECT_EQ(law.hysteresis(0.02), 0.0);
  EXPECT_EQ(law.damping_part(2.0, 0.02, 0.02), 0.0);
  EXPECT_EQ(law.largest_stiffness(), 100.0);
  EXPECT_EQ(law.largest_viscosity(), 0.0);
  EXPECT_FALSE(law.rigid());
  EXPECT_EQ(to_string(law.kind), "elastic");
}

// p = max(0, k c + l dc/dt) while c > 0: k = 100, l = 10 at c = 0.01 gives
// 1 + 5 = 6 at a rate of 0.5, nothing (not -4) at -0.5; its static part is
// k c = 1, the dashpot's the rest.
TEST(ContactLaw, ViscoelasticAddsItsDashpotAndNeverPulls) {
  const ContactLaw law = law_of(LawKind::viscoelastic, 100.0, 10.0);
  EXPECT_NEAR(law.force(0.01, 0.5, 0.01), 6.0, 1e-15);
  EXPECT_EQ(law.force(0.01, -0.5, 0.01), 0.0);
  EXPECT_EQ(law.force(-0.001, 5.0, 0.01), 0.0);  // open: the dashpot does not act
  EXPECT_NEAR(law.static_force(0.01, 0.01), 1.0, 1e-15);
  EXPECT_NEAR(law.damping_part(6.0, 0.01, 0.01), 5.0, 1e-15);
  EXPECT_NEAR(law.energy(0.01, 0.01), 0.005, 1e-17);
  EXPECT_EQ(law.largest_viscosity(), 10.0);
  EXPECT_EQ(to_string(law.kind), "viscoelastic");
}

// Smith's capblock, k = 100 and e = 0.5 (k / e^2 = 400), compressed to
// c_max = 0.02: loading along k to p = 2; unloading along k / e^2 from
// there, p = 400 (c - 0.75 c_max), zero below c = 0.015; reloading along
// the same line. It stores (k / 2 e^2)(c - (1 - e^2) c_max)^2 (0.005 at
// c_max) and has dissipated k (1 - e^2) c_max^2 / 2 = 0.015: together the
// loading's work k c_max^2 / 2 = 0.02. Tolerances: round-off.
TEST(ContactLaw, CushionLoadsAlongKAndUnloadsAlongKOverESquared) {
  const ContactLaw law = law_of(LawKind::cushion, 100.0, 0.0, 0.5);
  EXPECT_NEAR(law.force(0.01, 0.0, 0.01), 1.0, 1e-15);  // loading: k c
  EXPECT_NEAR(law.force(0.02, 0.0, 0.02), 2.0, 1e-14);
  EXPECT_NEAR(law.force(0.018, 0.0, 0.02), 1.2, 1e-13);  // unloading: 400 x 0.003
  EXPECT_EQ(law.force(0.014, 0.0, 0.02), 0.0);
  EXPECT_NEAR(law.energy(0.02, 0.02), 0.005, 1e-16);
  EXPECT_NEAR(law.energy(0.018, 0.02), 0.0018, 1e-16);
  EXPECT_EQ(law.energy(0.014, 0.02), 0.0);
  EXPECT_NEAR(law.hysteresis(0.02), 0.015, 1e-16);
  EXPECT_NEAR(law.energy(0.02, 0.02) + law.hysteresis(0.02), 0.5 * 100.0 * 0.02 * 0.02, 1e-16);
  EXPECT_EQ(law.largest_stiffness(), 400.0);
  EXPECT_EQ(to_string(law.kind), "cushion");
}

// A rigid link's force is the scheme's multiplier: the law gives none and stores nothing.
TEST(ContactLaw, RigidHasNoForceOfItsOwn) {
  const ContactLaw law = law_of(LawKind::rigid, 0.0);
  EXPECT_TRUE(law.rigid());
  EXPECT_EQ(law.force(0.01, 1.0, 0.01), 0.0);
  EXPECT_EQ(law.energy(0.01, 0.01), 0.0);
  EXPECT_EQ(law.hysteresis(0.01), 0.0);
  EXPECT_EQ(to_string(law.kind), "rigid");
}

// The side spring's slip keeps k |w - s| <= R_u: unchanged within the
// quake q of w, dragged to w - q or w + q beyond it.
TEST(ContactLaw, SmithSlipKeepsTheSpringWithinItsQuake) {
  const double q = 0.002;
  EXPECT_EQ(smith_slip(0.001, 0.002, q), 0.001);
  EXPECT_EQ(smith_slip(0.0, 0.005, q), 0.005 - q);
  EXPECT_EQ(smith_slip(0.0, -0.005, q), -0.005 + q);
  const SoilSpring smith{500.0, q, 0.4, DampingLaw::smith}, viscous{500.0, q, 0.4, DampingLaw::viscous};
  EXPECT_EQ(smith.stiffness(), 500.0 / q);
  EXPECT_NEAR(smith.damping_force(-100.0, 2.0), 0.4 * 100.0 * 2.0, 1e-13);    // J |R_s| v
  EXPECT_NEAR(viscous.damping_force(-100.0, 2.0), 0.4 * 500.0 * 2.0, 1e-13);  // J R_u v
  EXPECT_EQ(toe(500.0, q, 0.4).largest_viscosity(), 0.4 * 500.0);
  EXPECT_EQ(to_string(LawKind::smith), "smith");
}

// The work of the static force along a path of compressions (trapezoids on
// 1e5 steps a leg: the force is piecewise linear, so only the kinks err, by
// at most k dc^2 = 1e-5 R_u q each) against the stored energy plus the slip's work.
TEST(SmithLaw, ToeSlipBookkeepingIsExactOnLoadingUnloadingReloading) {
  const double ru = 1000.0, q = 0.01;
  const ContactLaw law = toe(ru, q, 0.0);
  double c = 0.0, c_max = 0.0, work = 0.0;
  auto go = [&](double to) {
    const double from = c;
    for (int i = 1; i <= 100'000; ++i) {
      const double f0 = law.force(c, 0.0, c_max);
      const double c1 = from + (to - from) * i / 100'000;
      c_max = std::max(c_max, c1);
      work += 0.5 * (f0 + law.force(c1, 0.0, c_max)) * (c1 - c);
      c = c1;
    }
    EXPECT_NEAR(work, law.energy(c, c_max) + law.hysteresis(c_max), 4e-5 * ru * q) << "at c = " << c;
  };
  go(3 * q);  // yields at q, slips 2 q
  EXPECT_NEAR(law.force(c, 0.0, c_max), ru, 1e-12 * ru);
  EXPECT_NEAR(law.hysteresis(c_max), ru * 2 * q, 1e-12 * ru * q);
  go(1.5 * q);  // unloads: above the slipped position 2 q the toe carries nothing
  EXPECT_EQ(law.force(c, 0.0, c_max), 0.0);
  go(2.5 * q);  // reloads elastically from the slipped position
  EXPECT_NEAR(law.force(c, 0.0, c_max), 0.5 * ru, 1e-9 * ru);
  go(5 * q);  // yields again where it left off, 3 q
  EXPECT_NEAR(law.hysteresis(c_max), ru * 4 * q, 1e-12 * ru * q);
  go(-q);  // pulled out: no tension
  EXPECT_EQ(law.force(c, 0.0, c_max), 0.0);
  go(6 * q);
  EXPECT_NEAR(law.hysteresis(c_max), ru * 5 * q, 1e-12 * ru * q);
}

TEST(SmithLaw, ToeForceIsNeverNegativeAndDampsOnlyWhileInTheSoil) {
  for (const DampingLaw d : {DampingLaw::smith, DampingLaw::viscous}) {
    const ContactLaw law = toe(1000.0, 0.01, 0.5, d);
    const double c_max = 0.03;                        // slipped 0.02
    EXPECT_EQ(law.force(0.015, -5.0, c_max), 0.0);    // above the slipped position, moving up
    EXPECT_EQ(law.force(0.015, 100.0, c_max), 0.0);   // above it, moving down: no damping either
    EXPECT_EQ(law.force(0.025, -100.0, c_max), 0.0);  // rebounding fast: never a pull
    const double rs = law.static_force(0.025, c_max);
    EXPECT_NEAR(rs, 500.0, 1e-12 * 500.0);
    const double expected = d == DampingLaw::smith ? rs * (1 + 0.5 * 2.0) : rs + 0.5 * 1000.0 * 2.0;
    EXPECT_DOUBLE_EQ(law.force(0.025, 2.0, c_max), expected);
  }
}

// Smith's side spring both ways: the stored energy k (w - s)^2 / 2 plus
// R_u sum |ds| is the work of k (w - s) along any path.
TEST(SmithLaw, ShaftSpringSlipsBothWaysWithExactBookkeeping) {
  const double ru = 500.0, q = 0.002, k = ru / q;
  double w = 0.0, s = 0.0, work = 0.0, slipped = 0.0;
  auto go = [&](double to) {  // as the toe's: 1e5 trapezoids a leg
    const double from = w;
    for (int i = 1; i <= 100'000; ++i) {
      const double f0 = k * (w - s);
      const double w1 = from + (to - from) * i / 100'000;
      const double s1 = smith_slip(s, w1, q);
      slipped += ru * std::abs(s1 - s);
      s = s1;
      work += 0.5 * (f0 + k * (w1 - s)) * (w1 - w);
      w = w1;
      ASSERT_LE(std::abs(k * (w - s)), ru * (1 + 1e-12));
    }
    EXPECT_NEAR(work, 0.5 * k * (w - s) * (w - s) + slipped, 4e-5 * ru * q) << "at w = " << w;
  };
  go(4 * q);
  EXPECT_NEAR(s, 3 * q, 1e-12);
  go(-3 * q);  // through zero force to -R_u, slipping back
  EXPECT_NEAR(k * (w - s), -ru, 1e-9 * ru);
  EXPECT_NEAR(s, -2 * q, 1e-12);
  go(q);
  EXPECT_NEAR(slipped, ru * (3 + 5 + 2) * q, 1e-6 * ru * q);  // up to s = 0 at w = q
}

// A diesel cylinder (a small hammer's numbers): bore 0.05 m^2, ports 0.5 m
// above impact, a 0.1 m chamber, 3 MPa after combustion.
ContactLaw diesel() {
  ContactLaw law;
  law.kind = LawKind::diesel;
  law.stiffness = 2e10;
  law.restitution = 0.8;
  law.gas = {0.05, 0.5, 0.1, 3e6};
  return law;
}

// The gas force at openings y = -c between impact and the ports against the
// polytropes written as p V^n = const, V = A (L_ch + y): before impact
// (c_max = 0) from p_atm at the ports, V_0 = A (0.1 + 0.5), n = 1.35; after
// (c_max > 0) from p_comb at V_1 = A 0.1, n = 1.25; none past the ports.
// The tolerances are round-off on forces of order 1e5 N.
TEST(DieselLaw, GasForceFollowsThePolytropes) {
  const ContactLaw law = diesel();
  const double a = 0.05, p_atm = 101325.0, v0 = a * 0.6, v1 = a * 0.1;
  for (const double y : {0.4, 0.25, 0.1, 0.01, 1e-4}) {
    const double v = a * (0.1 + y);
    const double compressed = p_atm * std::pow(v0, 1.35) / std::pow(v, 1.35);
    const double expanded = 3e6 * std::pow(v1, 1.25) / std::pow(v, 1.25);
    EXPECT_NEAR(law.force(-y, 0.0, 0.0), (compressed - p_atm) * a, 1e-9 * p_atm * a) << y;
    EXPECT_NEAR(law.force(-y, 0.0, 1e-3), (expanded - p_atm) * a, 1e-9 * 3e6 * a) << y;
    EXPECT_NEAR(law.gas.pressure(y, true) * std::pow(v, 1.25), 3e6 * std::pow(v1, 1.25), 1e-12 * 3e6 * v1);
  }
  for (const double y : {0.5, 0.7, 3.0}) {  // the ports open: atmospheric
    EXPECT_EQ(law.force(-y, 0.0, 0.0), 0.0);
    EXPECT_EQ(law.force(-y, 0.0, 1e-3), 0.0);
    EXPECT_EQ(law.gas.pressure(y, true), p_atm);
  }
  // Below impact the cushion adds its own force; its energy and hysteresis are a cushion's.
  const ContactLaw cushion = law_of(LawKind::cushion, 2e10, 0.0, 0.8);
  const double c = 1e-4, c_max = 2e-4;
  EXPECT_NEAR(law.force(c, 0.0, c_max), cushion.force(c, 0.0, c_max) + law.gas.force(-c, true), 1e-6);
  EXPECT_EQ(law.energy(c, c_max), cushion.energy(c, c_max));
  EXPECT_EQ(law.hysteresis(c_max), cushion.hysteresis(c_max));
  EXPECT_EQ(law.gas_force(c, c_max), law.gas.force(-c, true));
  EXPECT_EQ(cushion.gas_force(c, c_max), 0.0);
  EXPECT_EQ(to_string(law.kind), "diesel");
}

// W_c and W_e, the gas's works between the ports and impact in closed form,
// against Simpson's rule on the force over 10^4 intervals (its error, of
// order h^4 times the fourth derivative, is far below 1e-9 of the work on
// these smooth polytropes); and their values for this cylinder.
TEST(DieselLaw, CompressionAndExpansionWorksAreTheForcesIntegrals) {
  const ContactLaw law = diesel();
  auto integral = [&](bool fired) {
    const int n = 10'000;
    const double h = 0.5 / n;
    double sum = law.gas.force(0.0, fired) + law.gas.force(0.5 * (1.0 - 1e-15), fired);
    for (int i = 1; i < n; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * law.gas.force(i * h, fired);
    return sum * h / 3.0;
  };
  EXPECT_NEAR(law.gas.compression_work(), integral(false), 1e-9 * law.gas.compression_work());
  EXPECT_NEAR(law.gas.expansion_work(), integral(true), 1e-9 * law.gas.expansion_work());
  EXPECT_NEAR(law.gas.compression_work(), 5041.958, 1e-3);
  EXPECT_NEAR(law.gas.expansion_work(), 19130.289, 1e-3);
}

}  // namespace
}  // namespace barimpact
