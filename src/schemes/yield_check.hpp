// The read-only yield checks the elastic-plastic elements' schemes share
// (plastic_bonds.hpp, plastic_iteration.hpp): whether any element of bonds
// [first, last) yields at a new level from the last one's state, in the
// return map's own arithmetic (material.hpp), so that it yields exactly
// where the map would. Loops without stores or branches: they vectorise.
#pragma once

#include <cmath>
#include <cstddef>

#include "barimpact/model/material.hpp"

namespace barimpact::detail {

// From level m's plastic strains pm and accumulated strains am, at up.
template <bool isotropic>
[[gnu::always_inline]] inline bool yields(std::size_t first, std::size_t last, const Plasticity& law, double inv_h,
                                          const double* __restrict up, const double* __restrict pm,
                                          const double* __restrict am) {
  const double e = law.modulus, hm = law.plastic_modulus, sy = law.yield_stress;
  int any = 0;
  for (std::size_t j = first; j < last; ++j) {
    const double trial = e * ((up[j + 1] - up[j]) * inv_h - pm[j]);
    const double over = isotropic ? trial : trial - hm * pm[j];
    const double radius = isotropic ? sy + hm * am[j] : sy;
    any |= std::abs(over) > radius ? 1 : 0;
  }
  return any != 0;
}

// While nothing has yielded (p = alpha = 0): |E (u_{j+1} - u_j) / h| >
// sigma_y, in the return map's own arithmetic (so that it yields exactly
// where the map would).
[[gnu::always_inline]] inline bool yields_from_rest_loop(std::size_t first, std::size_t last, const Plasticity& law,
                                                         double inv_h, const double* __restrict up) {
  const double e = law.modulus, sy = law.yield_stress;
  int any = 0;
  for (std::size_t j = first; j < last; ++j) any |= std::abs(e * ((up[j + 1] - up[j]) * inv_h)) > sy ? 1 : 0;
  return any != 0;
}

// The loops above as compiled for one processor path (yield_check.cpp).
struct YieldLoops {
  bool (*from_rest)(std::size_t, std::size_t, const Plasticity&, double, const double*);
  bool (*isotropic)(std::size_t, std::size_t, const Plasticity&, double, const double*, const double*, const double*);
  bool (*kinematic)(std::size_t, std::size_t, const Plasticity&, double, const double*, const double*, const double*);
};

// Any x86-64's loops (`wide` false), or AVX2's (nullptr where the build or
// the processor has none): the tests compare them.
const YieldLoops* yield_loops(bool wide);

// The widest this processor runs, chosen once.
const YieldLoops& chosen_yield_loops();

// Whether any element of the bodies `ranges` (plastic_body.hpp) yields at
// up = `scale` times the array (scale 1 is exact), from the state p, a
// (every p and a 0 while `pristine`).
template <class Ranges>
inline bool any_yields(const Ranges& ranges, bool pristine, double scale, const double* up, const double* p,
                       const double* a) {
  for (const auto& r : ranges) {
    const double inv_h = r.inv_h * scale;
    const YieldLoops& loops = chosen_yield_loops();
    if (pristine ? loops.from_rest(r.first, r.last, r.law, inv_h, up)
                 : (r.law.isotropic ? loops.isotropic : loops.kinematic)(r.first, r.last, r.law, inv_h, up, p, a))
      return true;
  }
  return false;
}

}  // namespace barimpact::detail
