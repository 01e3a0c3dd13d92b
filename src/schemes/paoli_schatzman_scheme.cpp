#include "barimpact/schemes/paoli_schatzman_scheme.hpp"

namespace barimpact {

PaoliSchatzmanScheme::PaoliSchatzmanScheme(const Case& c)
    : ThreeLevelScheme(c, true), mass_factor_(mass_, clamped_), restitution_(c.time.restitution) {
  response_ = mass_factor_.response_to_end_force();
}

double PaoliSchatzmanScheme::end_impulse(double prev0, double next0) const {
  if (law_.kind() != ObstacleKind::rigid) return 0.0;
  const double e = restitution_, face = -law_.gap();
  if ((next0 + e * prev0) / (1.0 + e) >= face) return 0.0;
  // next + mu w with w = M^{-1} e0: mu from (next_0 + mu w_0 + e prev_0) = (1 + e) face.
  return ((1.0 + e) * face - e * prev0 - next0) / response_[0];
}

double PaoliSchatzmanScheme::enforce_contact(const double* prev, const double* /*cur*/, double* next) {
  const double mu = end_impulse(prev[0], next[0]);
  if (mu == 0.0) return 0.0;
  for (std::size_t j = 0; j < response_.size(); ++j) next[j] += mu * response_[j];
  return mu / (dt_ * dt_);
}

}  // namespace barimpact
