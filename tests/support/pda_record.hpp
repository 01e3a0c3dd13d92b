// Pile records for the tests of `barimpact pda`: a record with known waves
// (a half-sine wave down and chosen waves up), written as a CSV file with a
// RECORD.toml beside it, and the waves' values by their formulas.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

namespace barimpact::testing {

// A steel-like uniform pile: c = 5000 m/s, Z = E A / c = 4e5 N s/m, 2L/c = 8 ms.
struct KnownWaves {
  double length = 20.0, area = 0.01, modulus = 200e9, density = 8000.0;
  double peak = 2e6;     // P: Wd's peak, N
  double start = 0.002;  // Wd = P sin(pi (t - start) / width) on [start, start + width]
  double width = 0.002;
  double drop = 0.2;                                     // Wu holds -drop Wd(t - 3 ms): a reflection from 7.5 m
  double toe = 0.3;                                      // and toe Wd(t - 2L/c): the toe's resistance
  double late = 0.4;                                     // and late Wd(t - 2L/c - 1 ms)
  double dt = 1e-4;                                      // samples every 0.1 ms from t = 0
  int samples = 400;                                     // to 40 ms
  double force_offset = 3000.0, velocity_offset = 0.02;  // the channels' offsets (+ and -)

  [[nodiscard]] double wave_speed() const { return std::sqrt(modulus / density); }
  [[nodiscard]] double impedance() const { return modulus * area / wave_speed(); }
  [[nodiscard]] double travel() const { return 2.0 * length / wave_speed(); }
  [[nodiscard]] double t(int k) const { return k * dt; }
  [[nodiscard]] double down(double at) const {
    const double s = (at - start) / width;
    return s > 0.0 && s < 1.0 ? peak * std::sin(std::numbers::pi * s) : 0.0;
  }
  [[nodiscard]] double up(double at) const {
    return -drop * down(at - 0.003) + toe * down(at - travel()) + late * down(at - travel() - 0.001);
  }
  [[nodiscard]] double force(double at) const { return down(at) + up(at); }
  [[nodiscard]] double velocity(double at) const { return (down(at) - up(at)) / impedance(); }

  // The record's CSV: t, two force channels and two velocity channels
  // (their offsets opposite), and the record file naming them.
  void write(const std::filesystem::path& dir, const std::string& extra = "") const {
    std::ofstream csv(dir / "blow.csv");
    csv << "t,F1,F2,V1,V2\n";
    for (int k = 0; k < samples; ++k)
      csv << fmt::format("{},{},{},{},{}\n", t(k), force(t(k)) + force_offset, force(t(k)) - 0.5 * force_offset,
                         velocity(t(k)) + velocity_offset, velocity(t(k)) - 0.5 * velocity_offset);
    std::ofstream toml(dir / "record.toml");
    toml << fmt::format(
        "[pile]\nlength = {}\narea = {}\nmodulus = {}\ndensity = {}\n\n[record]\nfile = \"blow.csv\"\ntime = \"t\"\n"
        "force = [\"F1\", \"F2\"]\nvelocity = [\"V1\", \"V2\"]\n{}",
        length, area, modulus, density, extra);
  }
};

}  // namespace barimpact::testing
