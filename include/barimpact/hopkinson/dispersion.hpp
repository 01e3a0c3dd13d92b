// Dispersion in the bars of a Hopkinson test: the first longitudinal mode of
// a solid circular bar (Pochhammer 1876, Chree 1889) travels at a phase
// velocity c(omega) below c0 = sqrt(E / rho) once its wavelength nears the
// bar's diameter, so that a pulse measured at a gauge is not the pulse at the
// specimen's face. The correction (Follansbee & Frantz 1983, Gong, Malvern &
// Jenkins 1990) moves each Fourier component of the record by the distance d
// at its own speed instead of c0: its phase changes by -omega d (1 / c(omega)
// - 1 / c0), amplitudes kept (no radial distribution factors).
//
// The frequency equation, with p^2 = omega^2 / c_d^2 - k^2, q^2 = omega^2 /
// c_s^2 - k^2 (Graff, Wave Motion in Elastic Solids, 1975, sec. 8.2):
//   (2 p / a)(q^2 + k^2) J1(p a) J1(q a) - (q^2 - k^2)^2 J0(p a) J1(q a)
//     - 4 k^2 p q J1(p a) J0(q a) = 0,
// divided by q so that it stays real where p or q is imaginary (J becomes I).
#pragma once

#include <vector>

#include "barimpact/hopkinson/setup.hpp"
#include "barimpact/hopkinson/signal.hpp"

namespace barimpact {

/// c / c0 of the first longitudinal mode in a solid circular bar of Poisson's ratio nu.
class PochhammerChree {
 public:
  explicit PochhammerChree(double poisson);
  /// c / c0 at wavenumber x radius, k a >= 0 (solved).
  [[nodiscard]] double ratio_at_wavenumber(double ka) const;
  /// c / c0 at omega a / c0 >= 0 (from a table of the solved curve; c_R / c0 beyond it).
  [[nodiscard]] double ratio_at_frequency(double omega_a_over_c0) const;
  /// The Rayleigh surface wave's speed over c0: the curve's limit at high frequency.
  [[nodiscard]] double rayleigh_ratio() const { return rayleigh_; }

 private:
  [[nodiscard]] double frequency_function(double ka, double ratio) const;
  double nu_, cs2_, cd2_, rayleigh_;  // (c_s / c0)^2, (c_d / c0)^2, c_R / c0
  std::vector<double> table_omega_, table_ratio_;
};

/// Moves gauge records along one bar at the dispersive speeds, re-referenced
/// to c0 so that the analysis's travel-time shifts still apply.
class DispersionCorrection {
 public:
  explicit DispersionCorrection(const HopkinsonBar& bar);
  /// Corrects the signal in place for `distance` (> 0: the way the wave
  /// travels, gauge to face; < 0: face to gauge); returns the Fourier terms.
  /// Throws InputError when its samples are not uniformly spaced (within
  /// 1%): the Fourier series needs one interval.
  int apply(GaugeSignal& s, double distance) const;

 private:
  PochhammerChree curve_;
  double radius_, wave_speed_;
};

}  // namespace barimpact
