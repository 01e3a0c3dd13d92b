// From the case's bodies, joints, ends and gauges to the line the schemes
// step (model/line.hpp): bodies become node ranges (a mass is one node), a
// welded joint shares its node, a spring joint is a bond, a unilateral
// joint or end law is a link.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/line.hpp"

namespace barimpact {

/// The line of `c` (validated). A single-bar case gives one uniform bar.
[[nodiscard]] Line build_line(const Case& c);

/// The consistent nodal shares R_j += int r(xi) phi_j(xi) dxi of a resistance
/// per unit length r, linear on [a, b] (coordinates from node r.first), over
/// the elements of nodes r.first..r.last (2-point Gauss per element piece,
/// exact: r and phi_j are linear), which add up to int r: a shaft's
/// resistance on the nodes.
template <class Density>
void add_shares(const Line& line, const BodyRange& r, double a, double b, Density density,
                std::vector<double>& ultimate) {
  const double x0 = line.x[r.first], g = 0.5 / std::sqrt(3.0);
  for (std::size_t j = r.first; j < r.last; ++j) {
    const double xa = line.x[j] - x0, xb = line.x[j + 1] - x0;
    const double lo = std::max(a, xa), hi = std::min(b, xb);
    if (hi <= lo) continue;
    for (const double w : {0.5 - g, 0.5 + g}) {
      const double xi = lo + w * (hi - lo), f = 0.5 * (hi - lo) * density(xi);
      const double phi_b = (xi - xa) / (xb - xa);  // node j + 1's hat function
      ultimate[j] += f * (1.0 - phi_b);
      ultimate[j + 1] += f * phi_b;
    }
  }
}

/// The restitution a rigid link uses: its own if given, else time.restitution.
[[nodiscard]] double rigid_restitution(const Case& c, const LawData& law);

}  // namespace barimpact
