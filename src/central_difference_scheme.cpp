#include "barimpact/central_difference_scheme.hpp"

namespace barimpact {

void CentralDifferenceScheme::apply_inverse_mass(std::span<double> r) const {
  for (std::size_t j = 0; j < r.size(); ++j) r[j] /= lumped_[j];
}

double CentralDifferenceScheme::enforce_contact(const double* /*prev*/, const double* /*cur*/, double* next) {
  const double face = -law_.gap();
  if (law_.kind() != ObstacleKind::rigid || next[0] >= face) return 0.0;
  const double force = lumped_[0] * (face - next[0]) / (dt_ * dt_);
  next[0] = face;
  return force;
}

}  // namespace barimpact
