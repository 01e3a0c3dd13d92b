#include "barimpact/schemes/scheme.hpp"

#include <limits>

namespace barimpact {

double Scheme::far_force() const {
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace barimpact
