#include "barimpact/exact.hpp"

#include <cmath>

namespace barimpact::exact {

namespace {
// G: even, 4-periodic, G(s) = -s on [0, 2]; G' = -1 on (0, 2), +1 on (2, 4) mod 4.
double wrap4(double s) {
  const double r = std::fmod(s, 4.0);
  return r < 0.0 ? r + 4.0 : r;
}
double triangle(double s) {
  const double r = wrap4(std::abs(s));
  return r <= 2.0 ? -r : r - 4.0;
}
double triangle_slope(double s) {
  const double sign = s < 0.0 ? -1.0 : 1.0;  // G is even: G'(-s) = -G'(s)
  const double r = wrap4(std::abs(s));
  if (r == 0.0 || r == 2.0) return 0.0;  // mean of the one-sided slopes at a corner
  return sign * (r < 2.0 ? -1.0 : 1.0);
}
}  // namespace

Example1::Example1(double length, double stiffness, double density, double v0)
    : L_(length), a_(stiffness), rho_(density), v0_(v0), c_(std::sqrt(stiffness / density)) {}

double Example1::contact_end() const {
  return v0_ < 0.0 ? 2.0 * L_ / c_ : 0.0;
}

double Example1::u(double x, double t) const {
  if (v0_ >= 0.0) return v0_ * t;
  const double T = contact_end();
  if (t >= T) return -v0_ * (t - T);  // undeformed, leaving with velocity |v0|
  const double amp = -v0_ * L_ / (2.0 * c_);
  return amp * (triangle((x + c_ * t) / L_) - triangle((x - c_ * t) / L_));
}

double Example1::v(double x, double t) const {
  if (v0_ >= 0.0) return v0_;
  const double T = contact_end();
  if (t > T) return -v0_;
  return -v0_ * 0.5 * (triangle_slope((x + c_ * t) / L_) + triangle_slope((x - c_ * t) / L_));
}

double Example1::strain(double x, double t) const {
  if (v0_ >= 0.0 || t >= contact_end()) return 0.0;
  return -v0_ / (2.0 * c_) * (triangle_slope((x + c_ * t) / L_) - triangle_slope((x - c_ * t) / L_));
}

double Example1::R(double t) const {
  if (v0_ >= 0.0 || t < 0.0 || t > contact_end()) return 0.0;
  const double full = rho_ * c_ * (-v0_);
  return (t == 0.0 || t == contact_end()) ? 0.5 * full : full;
}

}  // namespace barimpact::exact
