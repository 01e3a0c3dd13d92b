// Elastic-plastic cases shared by the tests of plasticity: a bilinear
// material, and von Karman's problem as a case file.
#pragma once

#include <fmt/format.h>

#include <string>

#include "barimpact/model/material.hpp"

namespace barimpact::testing {

// Bilinear hardening: yield stress sigma_y, slope E_t past yield.
inline MaterialData bilinear(double sigma_y, double e_t, Hardening h) {
  MaterialData m;
  m.kind = MaterialKind::plastic;
  m.yield_stress = sigma_y;
  m.hardening_modulus = e_t;
  m.hardening = h;
  return m;
}

// A bar of length 1 (E = rho = 1, c0 = 1) driven into at V = 0.3, sigma_y =
// 0.1, E_t = 0.25 (c1 = 0.5): the precursor (sigma = -0.1, v = 0.1) and the
// plastic front (sigma = -0.2, v = 0.3, eps_p = -0.3) at t = 0.8 stand at x =
// 0.8 and 0.4.
// `wall`: the same bar moving at -0.3 onto a rigid wall instead.
inline std::string von_karman_case(int elements, double courant, const char* hardening = "kinematic",
                                   const char* scheme = "central-difference", bool wall = false) {
  return fmt::format(R"toml([[body]]
name = "rod"
length = 1.0
elements = {}
{}material = "plastic"
yield_stress = 0.1
hardening_modulus = 0.25
hardening = "{}"
[near_end]
{}
[time]
scheme = "{}"
step = {}
end = 0.8
[output]
fields_at = [0.8]
)toml",
                     elements, wall ? "velocity = \"-0.3\"\n" : "", hardening,
                     wall ? "law = \"rigid\"" : "law = \"velocity\"\nvalue = \"0.3\"", scheme, courant / elements);
}

}  // namespace barimpact::testing
