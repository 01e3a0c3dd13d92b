// The explicit schemes' elastic-plastic elements (plastic_bonds.hpp): their
// branch-free pass and the yield checks it starts from, against the return
// map of material.hpp element by element.
#include "barimpact/schemes/plastic_bonds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "../../src/schemes/yield_check.hpp"
#include "../support/plastic_cases.hpp"
#include "../support/run_case.hpp"
#include "barimpact/case/line_builder.hpp"
#include "barimpact/model/material.hpp"

namespace barimpact {
namespace {

using testing::bilinear;
using testing::case_from;

// The schemes' pass (plastic_bonds.cpp, branch-free so that it vectorises)
// is the return map above, bit for bit, along random strain histories.
TEST(ReturnMap, TheSchemesPassIsTheReturnMap) {
  for (Hardening h : {Hardening::kinematic, Hardening::isotropic}) {
    const Case c = case_from(fmt::format(R"toml([[body]]
name = "b"
elements = 20
modulus = 3.0
material = "plastic"
yield_stress = 0.01
hardening_modulus = 0.7
hardening = "{}"
[time]
scheme = "central-difference"
step = 0.001
)toml",
                                         h == Hardening::kinematic ? "kinematic" : "isotropic"));
    const Line line = build_line(c);
    PlasticBonds bonds(line);
    const Plasticity law = *line.plasticity[0];
    std::vector<PlasticState> states(line.bonds.size());
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> step(-0.004, 0.004);
    std::vector<double> u(line.nodes(), 0.0), up(line.nodes(), 0.0);
    bonds.start(u.data());
    for (int n = 0; n < 400; ++n) {
      for (std::size_t j = 1; j < up.size(); ++j) up[j] = up[j - 1] + (u[j] - u[j - 1]) + step(rng) * 0.05;
      bonds.advance(u.data(), up.data());
      for (std::size_t j = 0; j < line.bonds.size(); ++j) {
        double dgamma = 0.0;
        (void)law.stress((up[j + 1] - up[j]) * (1.0 / line.bonds[j].h), states[j], dgamma);
        ASSERT_EQ(bonds.next()[j], states[j].strain) << "step " << n << " bond " << j;
      }
      u = up;
    }
  }
}

// The yield checks on each processor path (yield_check.cpp: any x86-64,
// and AVX2 where the processor has it) against the return map element by
// element, right at the yield stress and one ulp past it.
TEST(YieldCheck, AgreesWithTheReturnMapAtTheYieldStress) {
  std::mt19937 random(17);
  std::uniform_real_distribution<double> strain(-0.9, 0.9);
  for (const Hardening h : {Hardening::kinematic, Hardening::isotropic}) {
    const Plasticity law(2.0, bilinear(1.0, 0.5, h));
    for (int trial = 0; trial < 200; ++trial) {
      const std::size_t bonds = 3 + static_cast<std::size_t>(trial % 37);
      // Bond `at` strained exactly to sigma_y / E (u[at] = 0), or one ulp
      // past it; the bonds before it elastic, after it unstrained.
      std::vector<double> u(bonds + 1, 0.0), p(bonds, 0.0), a(bonds, 0.0);
      const std::size_t at = static_cast<std::size_t>(trial) % bonds;
      for (std::size_t j = at; j-- > 0;) u[j] = u[j + 1] - strain(random) / law.modulus;
      const double edge = law.yield_stress / law.modulus;
      for (std::size_t j = at + 1; j <= bonds; ++j) u[j] = trial % 2 == 0 ? edge : std::nextafter(edge, 1.0);
      bool reference = false;
      for (std::size_t j = 0; j < bonds; ++j) {
        PlasticState state;
        double dgamma = 0.0;
        (void)law.stress(u[j + 1] - u[j], state, dgamma);
        reference = reference || dgamma > 0.0;
      }
      for (const bool wide : {false, true}) {
        const detail::YieldLoops* loops = detail::yield_loops(wide);
        if (loops == nullptr) continue;  // no AVX2 here
        EXPECT_EQ(loops->from_rest(0, bonds, law, 1.0, u.data()), reference) << trial << " wide " << wide;
        const auto from_state = h == Hardening::isotropic ? loops->isotropic : loops->kinematic;
        EXPECT_EQ(from_state(0, bonds, law, 1.0, u.data(), p.data(), a.data()), reference) << trial;
      }
    }
  }
}

}  // namespace
}  // namespace barimpact
