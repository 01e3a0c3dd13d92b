#include "barimpact/schemes/central_difference_scheme.hpp"

namespace barimpact {

void CentralDifferenceScheme::apply_inverse_mass(std::span<double> r) const {
  for (std::size_t j = 0; j < r.size(); ++j) r[j] /= lumped_[j];
}

double CentralDifferenceScheme::enforce_contact(const double* /*prev*/, const double* /*cur*/, double* next) {
  return clamp_end(next);
}

}  // namespace barimpact
