#include "barimpact/hopkinson/dispersion.hpp"

#include <fmt/format.h>
#include <kissfft/kissfft.hh>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "barimpact/model/input_error.hpp"

namespace barimpact {

namespace {

// x J1(x a), J1(x a) / x and J0(x a) as functions of x^2, real on both
// sides of 0 (a = 1; J becomes I for imaginary x).
double h1(double x2) {
  if (x2 > 0) {
    const double x = std::sqrt(x2);
    return std::cyl_bessel_j(1.0, x) / x;
  }
  if (x2 < 0) {
    const double x = std::sqrt(-x2);
    return std::cyl_bessel_i(1.0, x) / x;
  }
  return 0.5;
}

double g1(double x2) {
  if (x2 >= 0) {
    const double x = std::sqrt(x2);
    return x * std::cyl_bessel_j(1.0, x);
  }
  const double x = std::sqrt(-x2);
  return -x * std::cyl_bessel_i(1.0, x);
}

double j0(double x2) {
  return x2 >= 0 ? std::cyl_bessel_j(0.0, std::sqrt(x2)) : std::cyl_bessel_i(0.0, std::sqrt(-x2));
}

// Rayleigh's equation (2 - xi^2)^2 = 4 sqrt(1 - xi^2 cs2/cd2) sqrt(1 - xi^2), xi = c_R / c_s.
double rayleigh_over_shear(double cs2_over_cd2) {
  auto f = [&](double xi) {
    const double x2 = xi * xi;
    return (2 - x2) * (2 - x2) - 4 * std::sqrt(1 - x2 * cs2_over_cd2) * std::sqrt(1 - x2);
  };
  double lo = 0.5, hi = 1.0;  // f(lo) < 0 < f(hi) = 1 for every nu in [0, 0.5)
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

constexpr double table_ka_max = 20.0;  // omega a / c0 ~ 11.5: far past any gauge's useful band
constexpr int table_points = 400;

}  // namespace

PochhammerChree::PochhammerChree(double poisson) : nu_(poisson) {
  cs2_ = 1.0 / (2.0 * (1.0 + nu_));
  cd2_ = (1.0 - nu_) / ((1.0 + nu_) * (1.0 - 2.0 * nu_));
  rayleigh_ = rayleigh_over_shear(cs2_ / cd2_) * std::sqrt(cs2_);
  for (int i = 0; i <= table_points; ++i) {
    const double ka = table_ka_max * std::pow(static_cast<double>(i) / table_points, 2.0);  // dense at low ka
    const double r = ratio_at_wavenumber(ka);
    table_omega_.push_back(ka * r);
    table_ratio_.push_back(r);
  }
}

double PochhammerChree::frequency_function(double ka, double ratio) const {
  const double k2 = ka * ka, w2 = k2 * ratio * ratio;
  const double p2 = w2 / cd2_ - k2, q2 = w2 / cs2_ - k2;
  const double gp = g1(p2), hq = h1(q2);
  return 2.0 * (q2 + k2) * gp * hq - (q2 - k2) * (q2 - k2) * j0(p2) * hq - 4.0 * k2 * gp * j0(q2);
}

double PochhammerChree::ratio_at_wavenumber(double ka) const {
  if (ka < 1e-6) return 1.0 - nu_ * nu_ * ka * ka / 4.0;  // Rayleigh's long-wave limit (Love 1944, sec. 278)
  // At one wavenumber the modes' frequencies, and so their phase velocities,
  // are ordered: the first mode is the lowest root. It nears c_R at short
  // wavelengths (from just below it: the surface is curved), so the scan
  // goes up from 0.9 c_R to c0, then bisects.
  constexpr int scan = 400;  // steps of 0.0012 c0: the next mode lies 0.04 c0 or more above
  const double from = 0.9 * rayleigh_, to = 1.0 - 1e-15;
  double lo = from, f_lo = frequency_function(ka, lo);
  for (int i = 1; i <= scan; ++i) {
    const double hi = from + (to - from) * i / scan;
    const double f_hi = frequency_function(ka, hi);
    if ((f_lo > 0) != (f_hi > 0)) {
      double a = lo, b = hi, fa = f_lo;
      for (int it = 0; it < 100 && b - a > 1e-15; ++it) {
        const double m = 0.5 * (a + b), fm = frequency_function(ka, m);
        if ((fm > 0) == (fa > 0)) {
          a = m;
          fa = fm;
        } else {
          b = m;
        }
      }
      return 0.5 * (a + b);
    }
    lo = hi;
    f_lo = f_hi;
  }
  return 1.0;  // no root between c_R and c0: a plane wave (nu = 0 makes the mode c0 at every k)
}

double PochhammerChree::ratio_at_frequency(double w) const {
  if (w >= table_omega_.back()) return table_ratio_.back();
  const auto it = std::upper_bound(table_omega_.begin(), table_omega_.end(), w);
  const auto j = static_cast<std::size_t>(it - table_omega_.begin());
  const double f = (w - table_omega_[j - 1]) / (table_omega_[j] - table_omega_[j - 1]);
  return table_ratio_[j - 1] + f * (table_ratio_[j] - table_ratio_[j - 1]);
}

DispersionCorrection::DispersionCorrection(const HopkinsonBar& bar)
    : curve_(bar.poisson), radius_(bar.diameter / 2.0), wave_speed_(bar.wave_speed) {}

int DispersionCorrection::apply(GaugeSignal& s, double distance) const {
  const std::size_t n = s.t.size();
  const double dt = (s.t.back() - s.t.front()) / static_cast<double>(n - 1);
  for (std::size_t k = 1; k < n; ++k)
    if (std::abs(s.t[k] - s.t[k - 1] - dt) > 0.01 * dt)
      throw InputError(
          fmt::format("{}: bar.dispersion needs uniformly spaced samples (t = {} follows {}, the mean "
                      "interval is {})",
                      s.label, s.t[k], s.t[k - 1], dt));
  // Padded to a power of two at least twice as long, the padding a ramp from
  // the last sample back to the first: the periodic record has no step.
  std::size_t size = 1;
  while (size < 2 * n) size *= 2;
  std::vector<std::complex<double>> x(size), spectrum(size);
  for (std::size_t k = 0; k < n; ++k) x[k] = s.strain[k];
  for (std::size_t k = n; k < size; ++k)
    x[k] = s.strain.back() +
           (s.strain.front() - s.strain.back()) * static_cast<double>(k - n + 1) / static_cast<double>(size - n + 1);
  kissfft<double>(size, false).transform(x.data(), spectrum.data());
  for (std::size_t k = 1; k < size; ++k) {
    const double index = k <= size / 2 ? static_cast<double>(k) : static_cast<double>(k) - static_cast<double>(size);
    const double omega = 2.0 * std::numbers::pi * index / (static_cast<double>(size) * dt);
    const double c = wave_speed_ * curve_.ratio_at_frequency(std::abs(omega) * radius_ / wave_speed_);
    spectrum[k] *= std::polar(1.0, -omega * distance * (1.0 / c - 1.0 / wave_speed_));
  }
  kissfft<double>(size, true).transform(spectrum.data(), x.data());
  for (std::size_t k = 0; k < n; ++k) s.strain[k] = x[k].real() / static_cast<double>(size);
  return static_cast<int>(size);
}

}  // namespace barimpact
