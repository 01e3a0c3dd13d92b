// Pochhammer-Chree dispersion (dispersion.hpp): the first mode's speed
// between Rayleigh's long-wave limit and the Rayleigh wave, and a
// correction there and back.
#include "barimpact/hopkinson/dispersion.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "barimpact/hopkinson/signal.hpp"

namespace barimpact {
namespace {

// Pochhammer-Chree: Rayleigh's long-wave limit and the Rayleigh wave at short
// wavelengths; a correction there and back is the identity.
TEST(PochhammerChree, FirstModeRunsFromC0ToTheRayleighWave) {
  for (double nu : {0.1, 0.29, 0.33}) {
    const PochhammerChree pc(nu);
    // c / c0 = 1 - nu^2 (k a)^2 / 4 + O((k a)^4) (Love 1944, sec. 278): at
    // k a = 0.05 the next term is below 1e-6.
    for (double ka : {0.02, 0.05})
      EXPECT_NEAR(pc.ratio_at_wavenumber(ka), 1.0 - nu * nu * ka * ka / 4.0, 2e-6) << nu << " " << ka;
    // At k a = 30 (a wavelength a fifth of the radius) the mode is within 1%
    // of the Rayleigh wave, its limit on a surface of vanishing curvature.
    EXPECT_NEAR(pc.ratio_at_wavenumber(30.0) / pc.rayleigh_ratio(), 1.0, 1e-2) << nu;
    // Falling all the way to about c_R (k a = 6: a wavelength of half the diameter).
    double last = 1.0;
    for (double ka = 0.1; ka < 6; ka += 0.1) {
      const double r = pc.ratio_at_wavenumber(ka);
      EXPECT_LT(r, last) << ka;
      last = r;
    }
  }
  // Steel (nu = 0.29): Rayleigh's c_R / c_s = 0.9258 (Viktorov's fit 0.926).
  EXPECT_NEAR(PochhammerChree(0.29).rayleigh_ratio() * std::sqrt(2 * 1.29), 0.926, 2e-3);
}

TEST(PochhammerChree, CorrectingThereAndBackIsTheIdentity) {
  HopkinsonBar bar;
  bar.wave_speed = 5000.0;
  bar.diameter = 0.02;
  bar.poisson = 0.29;
  GaugeSignal s;
  for (int k = 0; k < 16000; ++k) {  // 1.6 ms: the dispersed tail (< 150 us) stays inside
    s.t.push_back(k * 1e-7);
    s.strain.push_back(-1e-3 * std::exp(-std::pow((k * 1e-7 - 5e-4) / 5e-6, 2)));
  }
  auto moved = s;
  DispersionCorrection(bar).apply(moved, 1.0);
  double change = 0.0;
  for (std::size_t k = 0; k < s.t.size(); ++k) change = std::max(change, std::abs(moved.strain[k] - s.strain[k]));
  EXPECT_GT(change, 1e-5);  // a 5 us pulse in a 20 mm bar disperses over 1 m
  DispersionCorrection(bar).apply(moved, -1.0);
  // 1e-6 of the peak: FFT round-off, the Nyquist term's real part, and what
  // of the tail the record's ends cut (measured 1.2e-10).
  for (std::size_t k = 0; k < s.t.size(); ++k) EXPECT_NEAR(moved.strain[k], s.strain[k], 1e-9);
}

}  // namespace
}  // namespace barimpact
