// The elements of one elastic-plastic body of a line, as the schemes' plastic
// states (plastic_bonds.hpp, plastic_iteration.hpp) walk them: bonds
// [first, last), one material and one element size throughout.
#pragma once

#include <cstddef>
#include <vector>

#include "barimpact/model/line.hpp"

namespace barimpact {

struct PlasticBody {
  std::size_t first, last, body;
  Plasticity law;
  double inv_h, volume, axial, k;  // 1 / h, A h, E A, E A / h

  /// The yield strain sigma_y / E.
  [[nodiscard]] double yield_strain() const { return law.yield_stress / law.modulus; }
};

/// The line's elastic-plastic bodies that have elements, in line order.
[[nodiscard]] inline std::vector<PlasticBody> plastic_bodies(const Line& line) {
  std::vector<PlasticBody> bodies;
  for (std::size_t b = 0; b < line.bodies.size(); ++b) {
    if (b >= line.plasticity.size() || !line.plasticity[b]) continue;
    const BodyRange& body = line.bodies[b];
    if (body.last == body.first) continue;
    const Bond& e = line.bonds[body.first];
    bodies.push_back({body.first, body.last, b, *line.plasticity[b], 1.0 / e.h, e.area * e.h, e.axial, e.stiffness});
  }
  return bodies;
}

}  // namespace barimpact
