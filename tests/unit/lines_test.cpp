#include "barimpact/exact/lines.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "../support/plastic_cases.hpp"
#include "../support/run_case.hpp"

namespace barimpact::exact {
namespace {

using barimpact::testing::case_from;
using barimpact::testing::von_karman_case;

// What a body of the line weighs and stores, to integrate its momentum and
// energy: a bar's rho A and E A, or a mass.
struct Weights {
  double rhoA = 0.0, EA = 0.0, mass = 0.0;
};

struct Totals {
  double momentum = 0.0, energy = 0.0;
};

// Momentum and kinetic + strain energy by the midpoint rule on `cells`
// cells per bar. Inside a bar the integrands are piecewise constant or
// smooth: the error comes from the cells a wave front cuts, each at most
// h times the jump.
Totals totals(const LineSolution& s, const std::vector<Weights>& w, double t, int cells = 20000) {
  Totals out;
  for (std::size_t i = 0; i < s.bodies(); ++i) {
    const double a = s.body_near(i), b = s.body_far(i);
    if (w[i].mass > 0.0) {
      const double v = s.fields(i, a, t).v;
      out.momentum += w[i].mass * v;
      out.energy += 0.5 * w[i].mass * v * v;
      continue;
    }
    const double h = (b - a) / cells;
    for (int k = 0; k < cells; ++k) {
      const LineFields f = s.fields(i, a + (k + 0.5) * h, t);
      out.momentum += w[i].rhoA * f.v * h;
      out.energy += 0.5 * (w[i].rhoA * f.v * f.v + w[i].EA * f.strain * f.strain) * h;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------
// SaintVenant: E = 4, rho = 1, A = 0.5, so c = 2 and Z = 1.

constexpr double kE = 4.0, kRho = 1.0, kA = 0.5, kC = 2.0, kZ = 1.0;

TEST(SaintVenant, ContactLastsTwiceTheShorterTransitWithHalfTheImpedanceTimesTheClosingSpeed) {
  // v1 - v2 = 1.5: the gap 0.3 closes at 0.2, contact for 2 L1 / c = 1.
  const SaintVenant s(1.0, 2.5, kE, kRho, kA, 1.0, -0.5, 0.3);
  EXPECT_DOUBLE_EQ(s.wave_speed(), kC);
  EXPECT_DOUBLE_EQ(s.impedance(), kZ);
  EXPECT_DOUBLE_EQ(s.contact_start(), 0.2);
  EXPECT_DOUBLE_EQ(s.contact_end(), 1.2);
  EXPECT_DOUBLE_EQ(s.contact_force(), 0.75);
  for (double t : {0.2001, 0.5, 0.93, 1.1999}) {
    EXPECT_DOUBLE_EQ(s.link_force(0, t), 0.75) << t;
    EXPECT_DOUBLE_EQ(s.link_opening(0, t), 0.0) << t;
    // The same force read off both faces' fields (N = -p), 1e-12: the
    // fields sum two d'Alembert waves, each exact up to rounding.
    EXPECT_NEAR(s.fields(0, 1.0, t).axial_force, -0.75, 1e-12) << t;
    EXPECT_NEAR(s.fields(1, 1.3, t).axial_force, -0.75, 1e-12) << t;
  }
  for (double t : {0.0, 0.1, 1.25, 7.0}) EXPECT_EQ(s.link_force(0, t), 0.0) << t;
  EXPECT_NEAR(s.link_opening(0, 0.1), 0.15, 1e-15);
  // The lower rod leaves unstrained at 1.2, the upper one's face then moves
  // at the same v2 until its far end's reflection returns (0.2 + 2 L2 / c
  // = 2.7): touching without force, then apart.
  EXPECT_EQ(s.link_opening(0, 1.3), 0.0);
  EXPECT_NEAR(s.link_opening(0, 2.69), 0.0, 1e-15);
  EXPECT_GT(s.link_opening(0, 2.71), 0.0);
  EXPECT_EQ(s.valid_until(), std::numeric_limits<double>::infinity());
  EXPECT_THROW((void)s.link_force(1, 0.5), std::out_of_range);
}

TEST(SaintVenant, ConservesMomentumAndEnergyAtAllTimes) {
  // Momentum and energy by the midpoint rule on 20000 cells per rod: a
  // handful of fronts each cut one cell, whose error is at most h |jump|,
  // so 1e-3 of the scale is a wide bound; at t = 0 and in flight it is exact.
  for (const auto& [L1, L2] : {std::pair{1.0, 2.5}, std::pair{2.5, 1.0}, std::pair{1.5, 1.5}, std::pair{1.0, 1.7}}) {
    const double v1 = 1.5, v2 = -0.25;
    const SaintVenant s(L1, L2, kE, kRho, kA, v1, v2, 0.3);
    const std::vector<Weights> w{{kRho * kA, kE * kA, 0.0}, {kRho * kA, kE * kA, 0.0}};
    const double P = kRho * kA * (L1 * v1 + L2 * v2);
    const double En = 0.5 * kRho * kA * (L1 * v1 * v1 + L2 * v2 * v2);
    EXPECT_DOUBLE_EQ(s.momentum(), P);
    EXPECT_DOUBLE_EQ(s.energy(0.0), En);
    const double scale = kRho * kA * (L1 + L2) * 1.5;
    for (double t : {0.0, 0.1, 0.25, 0.7, 1.19, 1.23, 3.7, 17.3, 101.9}) {
      const Totals T = totals(s, w, t);
      EXPECT_NEAR(T.momentum, P, 1e-3 * scale) << L1 << " " << t;
      EXPECT_NEAR(T.energy, En, 1e-3 * En) << L1 << " " << t;
    }
  }
}

TEST(SaintVenant, EqualRodsExchangeVelocities) {
  const double v1 = 1.5, v2 = -0.25;
  const SaintVenant s(1.5, 1.5, kE, kRho, kA, v1, v2, 0.0);
  EXPECT_DOUBLE_EQ(s.contact_end(), 1.5);
  // Both rods uniform and unstrained after 2L/c; 1e-12 for rounding.
  for (double t : {1.5001, 2.0, 9.37})
    for (double x : {0.0, 0.4, 1.1, 1.5}) {
      EXPECT_NEAR(s.fields(0, x, t).v, v2, 1e-12);
      EXPECT_NEAR(s.fields(0, x, t).strain, 0.0, 1e-12);
      EXPECT_NEAR(s.fields(1, 1.5 + x, t).v, v1, 1e-12);
      EXPECT_NEAR(s.fields(1, 1.5 + x, t).strain, 0.0, 1e-12);
    }
}

TEST(SaintVenant, TheShorterRodLeavesRigidlyAtTheLongerRodsInitialVelocity) {
  // Classical result: the shorter rod takes the longer rod's initial
  // velocity; the longer keeps the rest of the momentum as a pulse. 1e-12
  // pointwise (rounding); the longer rod's momentum by the midpoint rule
  // as in ConservesMomentum (1e-3 of the scale).
  const double v1 = 1.5, v2 = -0.25;
  const std::vector<Weights> w{{kRho * kA, kE * kA, 0.0}, {kRho * kA, kE * kA, 0.0}};
  {
    const SaintVenant s(1.0, 2.5, kE, kRho, kA, v1, v2, 0.0);  // lower shorter
    for (double t : {1.0001, 1.7, 12.3})
      for (double x : {0.0, 0.3, 0.77, 1.0}) {
        EXPECT_NEAR(s.fields(0, x, t).v, v2, 1e-12);
        EXPECT_NEAR(s.fields(0, x, t).strain, 0.0, 1e-12);
      }
    const Totals T = totals(s, w, 12.3);
    EXPECT_NEAR(T.momentum - kRho * kA * 1.0 * v2, kRho * kA * (1.0 * (v1 - v2) + 2.5 * v2),
                1e-3 * 3.5 * 1.5 * kRho * kA);
  }
  {
    const SaintVenant s(2.5, 1.0, kE, kRho, kA, v1, v2, 0.0);  // upper shorter
    for (double t : {1.0001, 1.7, 12.3})
      for (double x : {2.5, 2.8, 3.27, 3.5}) {
        EXPECT_NEAR(s.fields(1, x, t).v, v1, 1e-12);
        EXPECT_NEAR(s.fields(1, x, t).strain, 0.0, 1e-12);
      }
  }
}

TEST(SaintVenant, FieldsAreDAlembertWavesWithFreeEnds) {
  const double v1 = 1.5, v2 = -0.25, g = 0.3, L1 = 1.0, L2 = 1.7;
  const SaintVenant s(L1, L2, kE, kRho, kA, v1, v2, g);
  // Riemann invariants: v - c strain is carried along +x, v + c strain
  // along -x, unchanged while the path stays inside a rod (through the
  // contact's start and end too). Rounding only: 1e-12.
  const double points[][2] = {{0.213, 0.05}, {0.41, 0.31}, {0.77, 1.13}, {0.52, 1.91}, {0.35, 7.77}};
  for (std::size_t body : {0u, 1u}) {
    const double a = s.body_near(body), L = body == 0 ? L1 : L2;
    for (const auto& p : points) {
      const double x = a + p[0] * L, t = p[1];
      for (double dt : {0.03, 0.11, 0.19}) {
        if (x + kC * dt < a + L) {
          const LineFields f0 = s.fields(body, x, t), f1 = s.fields(body, x + kC * dt, t + dt);
          EXPECT_NEAR(f0.v - kC * f0.strain, f1.v - kC * f1.strain, 1e-12) << body << " " << x << " " << t;
        }
        if (x - kC * dt > a) {
          const LineFields f0 = s.fields(body, x, t), f1 = s.fields(body, x - kC * dt, t + dt);
          EXPECT_NEAR(f0.v + kC * f0.strain, f1.v + kC * f1.strain, 1e-12) << body << " " << x << " " << t;
        }
      }
    }
  }
  // v = u_t and strain = u_x: u is continuous and piecewise linear, so a
  // central difference lies between the one-sided values (1e-8: u's
  // rounding over h = 1e-6).
  const double h = 1e-6;
  for (std::size_t body : {0u, 1u})
    for (const auto& p : points) {
      const double x = s.body_near(body) + p[0] * (body == 0 ? L1 : L2), t = p[1];
      const double dudt = (s.fields(body, x, t + h).u - s.fields(body, x, t - h).u) / (2 * h);
      const double va = s.fields(body, x, t - h).v, vb = s.fields(body, x, t + h).v;
      EXPECT_GE(dudt, std::min(va, vb) - 1e-8);
      EXPECT_LE(dudt, std::max(va, vb) + 1e-8);
      const double dudx = (s.fields(body, x + h, t).u - s.fields(body, x - h, t).u) / (2 * h);
      const double ea = s.fields(body, x - h, t).strain, eb = s.fields(body, x + h, t).strain;
      EXPECT_GE(dudx, std::min(ea, eb) - 1e-8);
      EXPECT_LE(dudx, std::max(ea, eb) + 1e-8);
    }
  // Free ends: no strain at the outer ends ever, nor at the faces once apart.
  for (double t : {0.1, 0.33, 0.71, 1.05, 2.6, 13.9}) {
    EXPECT_NEAR(s.strain(0.0, t), 0.0, 1e-12) << t;
    EXPECT_NEAR(s.strain(L1 + g + L2, t), 0.0, 1e-12) << t;
    if (t > s.contact_end()) {
      EXPECT_NEAR(s.fields(0, L1, t).strain, 0.0, 1e-12) << t;
      EXPECT_NEAR(s.fields(1, L1 + g, t).strain, 0.0, 1e-12) << t;
    }
  }
  // u is continuous through the contact's start and end (1e-9 over 1e-12 in t).
  for (double t : {s.contact_start(), s.contact_end()})
    for (double x : {0.0, 0.5, 1.0, 1.3, 2.0, 3.0}) EXPECT_NEAR(s.u(x, t - 1e-12), s.u(x, t + 1e-12), 1e-9);
}

TEST(SaintVenant, TheRodsNeverMeetAgain) {
  // The opening after separation never decreases (the lower face is never
  // faster than the upper one); 1e-12 for rounding.
  for (const auto& [L1, L2] : {std::pair{1.0, 2.5}, std::pair{2.5, 1.0}, std::pair{1.0, 1.7}, std::pair{1.7, 1.0}}) {
    const SaintVenant s(L1, L2, kE, kRho, kA, 1.5, -0.25, 0.0);
    double last = 0.0;
    for (int i = 0; i <= 6000; ++i) {
      const double t = s.contact_end() + 0.01 * i;
      const double y = s.link_opening(0, t);
      EXPECT_GE(y, last - 1e-12) << L1 << " " << t;
      last = y;
    }
    EXPECT_GT(last, 1.0);
  }
}

TEST(SaintVenant, WithoutApproachTheRodsFlyApart) {
  const SaintVenant s(1.0, 1.0, kE, kRho, kA, -0.5, 0.5, 0.1);
  EXPECT_EQ(s.contact_force(), 0.0);
  EXPECT_EQ(s.link_force(0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(s.link_opening(0, 2.0), 2.1);
  EXPECT_DOUBLE_EQ(s.u(0.5, 2.0), -1.0);
  EXPECT_DOUBLE_EQ(s.v(1.5, 2.0), 0.5);
  EXPECT_TRUE(std::isnan(s.u(1.05, 2.0)));  // in the gap
  EXPECT_EQ(s.body_at(1.0), 0u);
  EXPECT_EQ(s.body_at(1.1), 1u);
  EXPECT_EQ(s.body_at(1.05), 2u);
}

// ---------------------------------------------------------------------------
// DropMass: a bar with L = E = rho = A = 1 (c = Z = 1, T = 2L/c = 2, its mass 1).

const Rod unit_bar{1.0, 1.0, 1.0, 1.0};

TEST(DropMass, ForceStartsAtZV0AndDecaysAtRateZOverM) {
  const double m = 4.0, v0 = -2.0;  // tau = m / Z = 4
  const DropMass d(unit_bar, m, v0);
  EXPECT_DOUBLE_EQ(d.force(0.0), 2.0);
  // 1e-14 relative: one exp and one polynomial of degree 0.
  for (double t : {1e-9, 0.3, 1.1, 1.999}) EXPECT_NEAR(d.force(t), 2.0 * std::exp(-t / 4.0), 1e-14) << t;
  for (double t : {0.3, 1.1, 1.999}) EXPECT_NEAR(d.mass_v(t), -2.0 * std::exp(-t / 4.0), 1e-14) << t;
  // At 2L/c the wave the mass sent, reflected by the clamped end without
  // change of sign, comes back and doubles at the mass: p jumps by 2 Z |v0|.
  const double before = 2.0 * std::exp(-0.5);
  EXPECT_NEAR(d.force(2.0) - before, 2.0 * 2.0, 1e-13);
  EXPECT_NEAR(d.force(2.0 + 1e-12) - d.force(2.0 - 1e-12), 4.0, 1e-10);
  // The force read off the bar's field at the struck end (N = -p), and the
  // clamped end (u = 0), to rounding.
  for (double t : {0.4, 1.7, 2.3, 3.1, 4.9}) {
    EXPECT_NEAR(-d.fields(0, 1.0, t).axial_force, d.force(t), 1e-12) << t;
    EXPECT_NEAR(d.u(0.0, t), 0.0, 1e-14) << t;
  }
  // Ahead of the first front the bar is at rest.
  EXPECT_EQ(d.v(0.5, 0.3), 0.0);
  EXPECT_EQ(d.u(0.5, 0.3), 0.0);
  // Behind it the strain the end sent when the front left: -p / (E A).
  EXPECT_NEAR(d.strain(0.9, 0.3), -d.force(0.2), 1e-15);
}

TEST(DropMass, TheMassObeysItsEquationAndStaysOnTheBarWhileInContact) {
  const double m = 10.0, v0 = -1.0;  // theta = 0.2: contact over several intervals
  const DropMass d(unit_bar, m, v0);
  ASSERT_GT(d.separation_time(), 6.0);
  // m dV/dt = p by central differences, h = 1e-5 away from the jumps at
  // k T: truncation h^2 |V'''| / 6 and rounding 1e-16 / h, under 1e-9.
  const double h = 1e-5;
  for (double t = 0.37; t < d.separation_time(); t += 0.5) {
    if (std::abs(t - 2.0 * std::round(t / 2.0)) < 2 * h) continue;
    const double dV = (d.mass_v(t + h) - d.mass_v(t - h)) / (2 * h);
    EXPECT_NEAR(m * dV, d.force(t), 1e-8) << t;
    // The mass's displacement (the integral of V) equals the bar end's
    // (the waves' integrals): two closed forms, equal to rounding.
    EXPECT_NEAR(d.mass_u(t), d.u(1.0, t), 1e-12) << t;
    EXPECT_EQ(d.link_opening(0, t), 0.0);
  }
  EXPECT_EQ(d.force(d.separation_time() + 1e-9), 0.0);
  EXPECT_NEAR(d.force(d.separation_time() - 1e-9), 0.0, 1e-7);
}

TEST(DropMass, EqualMassesSeparateInClosedForm) {
  // m = bar's mass: theta = 2, p = Z |v0| e^-s (2 - 2 s + e^-2) on the
  // second interval (s in units of m / Z), zero at s = 1 + e^-2 / 2, where
  // V = 2 |v0| e^-s. To 1e-13 (bisection to the last bits).
  const double v0 = -1.0;
  const DropMass d(unit_bar, 1.0, v0);
  const double s = 1.0 + std::exp(-2.0) / 2.0;
  EXPECT_NEAR(d.separation_time(), 2.0 + s, 1e-13);
  EXPECT_NEAR(d.separation_velocity(), 2.0 * std::exp(-s), 1e-13);
  EXPECT_GT(d.valid_until(), d.separation_time());
}

TEST(DropMass, AgreesWithAnIndependentIntegrationOfTheDelayEquation) {
  // m dV/dt = Z (2 w(t) - V), w(t) = w(t - T) - V(t - T) (w = 0 before T),
  // by the trapezoidal rule on 4000 steps per T (second order: about 1e-7
  // here), against the closed forms: 1e-5.
  const double m = 10.0, v0 = -1.0, T = 2.0, nu = 1.0 / m;
  const DropMass d(unit_bar, m, v0);
  const int n = 4000;
  const double h = T / n;
  const int steps = static_cast<int>(std::ceil(d.separation_time() / h));
  std::vector<double> V(steps + 1), wr(steps + 1), wl(steps + 1);  // w's right and left limits at each node
  V[0] = v0;
  for (int i = 0; i <= steps; ++i) {
    wr[i] = i < n ? 0.0 : wr[i - n] - V[i - n];
    wl[i] = i <= n ? 0.0 : wl[i - n] - V[i - n];
    if (i == steps) break;
    const double wnext = i + 1 <= n ? 0.0 : wl[i + 1 - n] - V[i + 1 - n];
    // V' = nu (2 w - V), implicit trapezoid on (t_i, t_i+1).
    V[i + 1] = (V[i] + 0.5 * h * nu * (2 * wr[i] - V[i] + 2 * wnext)) / (1 + 0.5 * h * nu);
  }
  for (int i = 1; i < steps; i += 97) {
    const double t = i * h;
    EXPECT_NEAR(d.mass_v(t), V[i], 1e-5) << t;
    if (i % n != 0) {
      EXPECT_NEAR(d.force(t), std::max(0.0, 2 * wr[i] - V[i]), 1e-5) << t;
    }
  }
}

TEST(DropMass, ConservesEnergyUpToTheNextImpact) {
  // 1/2 m V^2 + the bar's energy by the midpoint rule on 20000 cells (the
  // fronts' cells and the smooth parts' second-order error: 1e-3 is wide).
  for (double m : {0.5, 1.0, 4.0, 10.0}) {
    const double v0 = -1.5;
    const DropMass d(unit_bar, m, v0);
    const std::vector<Weights> w{{1.0, 1.0, 0.0}, {0.0, 0.0, m}};
    const double E0 = 0.5 * m * v0 * v0;
    EXPECT_DOUBLE_EQ(d.energy(0.0), E0);
    const double end = std::min(d.valid_until(), d.separation_time() + 10.0);
    for (int i = 0; i <= 12; ++i) {
      const double t = end * i / 12.0 * 0.999;
      EXPECT_NEAR(totals(d, w, t).energy, E0, 1e-3 * E0) << m << " " << t;
    }
    // Between separation and the next contact the faces are apart.
    for (int i = 1; i < 200; ++i) {
      const double t = d.separation_time() + (end - d.separation_time()) * i / 200.0;
      EXPECT_GT(d.link_opening(0, t), 0.0) << m << " " << t;
      EXPECT_EQ(d.force(t), 0.0);
    }
    if (std::isfinite(d.valid_until())) {
      EXPECT_NEAR(d.link_opening(0, d.valid_until()), 0.0, 1e-12);
    }
  }
}

TEST(DropMass, FliesAcrossTheGapFirst) {
  const DropMass d(unit_bar, 2.0, -2.0, 0.2);
  EXPECT_DOUBLE_EQ(d.impact_time(), 0.1);
  EXPECT_DOUBLE_EQ(d.mass_u(0.05), -0.1);
  EXPECT_DOUBLE_EQ(d.link_opening(0, 0.05), 0.1);
  EXPECT_EQ(d.force(0.05), 0.0);
  EXPECT_DOUBLE_EQ(d.force(0.1), 2.0);
  EXPECT_NEAR(d.force(0.6), 2.0 * std::exp(-0.25), 1e-14);
  EXPECT_NEAR(d.mass_u(0.9), d.u(1.0, 0.9) - 0.2, 1e-12);
  EXPECT_EQ(d.body_at(1.2), 1u);
  EXPECT_DOUBLE_EQ(d.u(1.2, 0.05), -0.1);
  const DropMass away(unit_bar, 2.0, 1.0);
  EXPECT_EQ(away.force(1.0), 0.0);
  EXPECT_DOUBLE_EQ(away.mass_u(3.0), 3.0);
  EXPECT_EQ(away.valid_until(), std::numeric_limits<double>::infinity());
}

// ---------------------------------------------------------------------------
// Junction: bar 1 with c1 = 2, Z1 = 2, L1 = 1 (tau1 = 0.5); bar 2 with
// c2 = sqrt(1/2), Z2 = 3 sqrt 2, L2 = 1.5 (tau2 = 3 / sqrt 2).

const Rod bar1{1.0, 4.0, 1.0, 1.0};
const Rod bar2{1.5, 1.0, 2.0, 3.0};

TEST(Junction, TransmitsAndReflectsWithTheImpedanceRatios) {
  const double F0 = 3.0;
  for (const bool stiff_second : {true, false}) {
    const Rod& r1 = stiff_second ? bar1 : bar2;
    const Rod& r2 = stiff_second ? bar2 : bar1;
    const double Z1 = r1.impedance(), Z2 = r2.impedance(), c1 = r1.wave_speed(), c2 = r2.wave_speed();
    const double L1 = r1.length, tau1 = r1.transit();
    const Junction j(r1, r2, F0, 20.0);
    EXPECT_DOUBLE_EQ(j.transmitted_ratio(), 2 * Z2 / (Z1 + Z2));
    EXPECT_DOUBLE_EQ(j.reflected_ratio(), (Z2 - Z1) / (Z1 + Z2));
    // The near end before the reflection comes back: V = F0 / Z1.
    for (double t : {0.1 * tau1, 1.9 * tau1}) {
      EXPECT_NEAR(j.V(t), F0 / Z1, 1e-14);
      EXPECT_NEAR(j.U(t), F0 / Z1 * t, 1e-14);
      EXPECT_EQ(j.end_force(t), F0);
    }
    // Incident (ahead of the reflection), reflected + incident in bar 1,
    // transmitted in bar 2, all within one transit of the junction: 1e-12.
    const double t = tau1 + 0.2 * std::min(tau1, r2.transit());
    const double NI = -F0;
    EXPECT_NEAR(j.axial_force(0.1 * L1, t), NI, 1e-12);
    EXPECT_NEAR(j.axial_force(L1 - 0.1 * c1 * (t - tau1), t), NI * (1 + j.reflected_ratio()), 1e-12);
    EXPECT_NEAR(j.axial_force(L1 + 0.5 * c2 * (t - tau1), t), NI * j.transmitted_ratio(), 1e-12);
    EXPECT_EQ(j.axial_force(L1 + 1.5 * c2 * (t - tau1), t), 0.0);  // ahead of the transmitted front
  }
}

TEST(Junction, EnergyEqualsTheWorkAndMomentumTheImpulse) {
  // Kinetic + strain energy against F0 U(t), momentum against F0 t, by the
  // midpoint rule on 100000 cells per bar: the integrands are piecewise
  // constant, each front's cell errs by at most h times its jump; dozens
  // of fronts by t = 23 stay under 1e-3 of the totals.
  const double F0 = 3.0;
  const Junction j(bar1, bar2, F0, 30.0);
  EXPECT_GE(j.valid_until(), 30.0);
  const std::vector<Weights> w{{bar1.density * bar1.area, bar1.modulus * bar1.area, 0.0},
                               {bar2.density * bar2.area, bar2.modulus * bar2.area, 0.0}};
  for (double t : {0.3, 0.7, 1.9, 4.4, 9.7, 23.1}) {
    const Totals T = totals(j, w, t, 100000);
    EXPECT_NEAR(T.energy, j.work(t), 1e-3 * j.work(t)) << t;
    EXPECT_DOUBLE_EQ(j.energy(t), j.work(t));
    EXPECT_NEAR(T.momentum, F0 * t, 1e-3 * F0 * t) << t;
  }
}

TEST(Junction, DisplacementAndForceAreContinuousAtTheJunctionAndTheEndsHold) {
  const double F0 = 3.0;
  const Junction j(bar1, bar2, F0, 40.0);
  // Both sides' fields at x = L1 from their own waves: equal to rounding.
  for (double t : {0.13, 0.77, 2.71, 5.55, 13.3, 37.9}) {
    const LineFields a = j.fields(0, 1.0, t), b = j.fields(1, 1.0, t);
    EXPECT_NEAR(a.u, b.u, 1e-11 * (1 + std::abs(a.u))) << t;
    EXPECT_NEAR(a.v, b.v, 1e-11) << t;
    EXPECT_NEAR(a.axial_force, b.axial_force, 1e-11) << t;
    EXPECT_NEAR(j.axial_force(0.0, t), -F0, 1e-11) << t;  // the force end
    EXPECT_NEAR(j.axial_force(2.5, t), 0.0, 1e-11) << t;  // the free end
    EXPECT_NEAR(j.u(0.0, t), j.U(t), 1e-12 * (1 + std::abs(j.U(t)))) << t;
  }
  EXPECT_EQ(j.links(), 0u);
}

TEST(Junction, EqualImpedancesReflectNothing) {
  const Rod a{1.0, 4.0, 1.0, 1.0}, b{2.0, 1.0, 4.0, 1.0};  // Z = 2 both, c = 2 and 1/2
  const Junction j(a, b, 1.0, 10.0);
  EXPECT_EQ(j.reflected_ratio(), 0.0);
  EXPECT_EQ(j.transmitted_ratio(), 1.0);
  // Until the far end's reflection returns to the junction (0.5 + 8 = 8.5).
  for (double t : {0.7, 3.0, 8.4}) EXPECT_NEAR(j.axial_force(0.5, t), -1.0, 1e-14);
}

// ---------------------------------------------------------------------------
// for_line_case

BodyData bar_body(const char* name, double length, double velocity = 0.0) {
  BodyData b;
  b.name = name;
  b.kind = BodyKind::bar;
  b.length = length;
  b.modulus = 4.0;
  b.area = 0.5;
  b.velocity = std::to_string(velocity);
  return b;
}

Case two_rods() {
  Case c;
  c.bodies = {bar_body("lower", 1.0, 1.0), bar_body("upper", 2.0, -0.5)};
  JointData j;
  j.name = "lower-upper";
  j.lower = "lower";
  j.upper = "upper";
  j.law.law = JointLaw::rigid;
  j.law.gap = 0.1;
  c.joints = {j};
  return c;
}

TEST(ForLineCase, RecognisesTheThreeSolutions) {
  const Case rods = two_rods();
  const auto s = for_line_case(rods);
  ASSERT_NE(s, nullptr);
  const auto* sv = dynamic_cast<const SaintVenant*>(s.get());
  ASSERT_NE(sv, nullptr);
  EXPECT_DOUBLE_EQ(sv->contact_start(), 0.1 / 1.5);

  Case drop = two_rods();
  drop.bodies[0].velocity = "0";
  drop.bodies[1].kind = BodyKind::mass;
  drop.bodies[1].mass = 3.0;
  drop.bodies[1].velocity = "-2";
  drop.joints[0].law.gap = 0.0;
  drop.near_end.law = JointLaw::clamped;
  const auto d = for_line_case(drop);
  ASSERT_NE(d, nullptr);
  ASSERT_NE(dynamic_cast<const DropMass*>(d.get()), nullptr);
  EXPECT_DOUBLE_EQ(d->link_force(0, 0.0), 2.0);  // Z |v0| with Z = A sqrt(E rho) = 1

  Case step = two_rods();
  step.bodies[0].velocity = step.bodies[1].velocity = "0";
  step.bodies[1].modulus = 9.0;
  step.joints.clear();  // welded
  step.near_end.law = JointLaw::force;
  step.near_end.value = "2.5";
  step.time.end = 3.0;
  const auto j = for_line_case(step);
  ASSERT_NE(j, nullptr);
  const auto* junction = dynamic_cast<const Junction*>(j.get());
  ASSERT_NE(junction, nullptr);
  EXPECT_EQ(junction->end_force(1.0), 2.5);
  EXPECT_GE(junction->valid_until(), 3.0);
  step.joints = {JointData{"lower-upper", "lower", "upper", {}, {}}};
  step.joints[0].law.law = JointLaw::welded;
  EXPECT_NE(dynamic_cast<const Junction*>(for_line_case(step).get()), nullptr);
}

TEST(ForLineCase, DeclinesWhatTheSolutionsDoNotCover) {
  auto declined = [](auto change) {
    Case c = two_rods();
    change(c);
    return for_line_case(c) == nullptr;
  };
  EXPECT_TRUE(declined([](Case& c) { c.load.gravity = 9.81; }));
  EXPECT_TRUE(declined([](Case& c) { c.load.body_force = "1"; }));
  EXPECT_TRUE(declined([](Case& c) { c.bodies[1].viscosity = 0.1; }));
  EXPECT_TRUE(declined([](Case& c) { c.bodies[0].velocity = "x"; }));
  EXPECT_TRUE(declined([](Case& c) { c.bodies[0].displacement = "0.1"; }));
  EXPECT_TRUE(declined([](Case& c) { c.bodies[1].density = 2.0; }));
  EXPECT_TRUE(declined([](Case& c) { c.joints[0].law.law = JointLaw::cushion; }));
  EXPECT_TRUE(declined([](Case& c) { c.far_end.law = JointLaw::clamped; }));
  EXPECT_TRUE(declined([](Case& c) { c.bodies.push_back(c.bodies[1]); }));
  EXPECT_TRUE(declined([](Case& c) {
    c.joints.clear();
    c.near_end.law = JointLaw::force;
    c.near_end.value = "sin(t)";
  }));
  EXPECT_FALSE(declined([](Case&) {}));
}

// The tabulated solution's budget (closed form) closes: the driven end's
// work is kinetic + elastic + hardening energy + plastic work, exactly.
TEST(VonKarman, TheExactBudgetCloses) {
  const exact::VonKarman exact({2.0, 3.0, 0.5, 0.2}, 0.4, 0.6, -1.7);  // pulled: tension
  for (double t : {0.1, 0.5, 0.8}) {
    const Energies e = *exact.energies(t);
    EXPECT_NEAR(e.kinetic + e.strain + e.plastic, e.work, 1e-14 * e.work) << t;
    EXPECT_GT(e.plastic, 0.0);
  }
  EXPECT_GT(exact.plateau_stress(), 0.0);
  EXPECT_GT(exact.plateau_plastic_strain(), 0.0);
}

// `barimpact exact` knows the case only while nothing else loads the bar
// before the precursor arrives: a far end driven from t = 0 has no
// closed form here.
TEST(VonKarman, IsTheExactSolutionOnlyOfItsOwnCase) {
  const Case c = case_from(von_karman_case(100, 0.5));
  EXPECT_NE(exact::for_line_case(c), nullptr);
  for (const char* far : {"law = \"force\"\nvalue = \"0.5\"", "law = \"velocity\"\nvalue = \"-0.1\""})
    EXPECT_EQ(exact::for_line_case(case_from(von_karman_case(100, 0.5) + "[far_end]\n" + far + "\n")), nullptr) << far;
  EXPECT_NE(exact::for_line_case(case_from(von_karman_case(100, 0.5) + "[far_end]\nlaw = \"clamped\"\n")), nullptr);
}

}  // namespace
}  // namespace barimpact::exact
