// A measured blow on a pile (`barimpact pda RECORD.toml`): the pile below
// the gauges, the record's CSV file and its channels, read from TOML and
// validated; and the record's force and velocity at the gauges in the
// analysers' convention (compression and downward velocity positive), with
// the foot, the impact, the offsets removed and the integrals.
//
// This header owns the record-file contract: [pile] (or [[segment]]),
// [record], [case_method], their keys, defaults and rules (ASTM D4945: force
// from strain times E A at the gauges, velocity from acceleration).
// The wave quantities are case_method.hpp's.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "barimpact/hopkinson/signal.hpp"
#include "barimpact/model/contact_law.hpp"
#include "barimpact/run/output_directory.hpp"

namespace barimpact {

/// A stretch of the pile below the gauges with uniform properties.
struct PileSegment {
  double length = 0.0;      ///< m
  double area = 0.0;        ///< m^2
  double modulus = 0.0;     ///< Pa
  double density = 0.0;     ///< kg/m^3 (E / c^2 when the wave speed is given)
  double wave_speed = 0.0;  ///< m/s, sqrt(E / rho) unless given

  /// Z = E A / c, N s/m.
  [[nodiscard]] double impedance() const { return modulus * area / wave_speed; }
};

/// [match]: signal matching's settings (`barimpact match`), SI units.
struct MatchSettings {
  /// The unknowns a match may fit, in this order.
  static const std::vector<std::string>& all_unknowns();
  int segments = 10;               ///< shaft resistances along the embedded length (equal lengths)
  std::optional<double> embedded;  ///< m of pile in the soil up from the toe (none: all of it)
  std::optional<double> window;    ///< s after t2 matched (none: 0.020, or to the record's end)
  DampingLaw damping_law = DampingLaw::smith;
  std::vector<std::string> unknowns = all_unknowns();
  double shaft_quake = 0.00254, toe_quake = 0.00254;  ///< m: start values, or the values kept when not unknowns
  /// s/m: start values, or kept; none: J_c Z over the Case method's capacity
  std::optional<double> shaft_damping, toe_damping;
  int starts = 4;  ///< starting points of the fit (the first the Case method's estimate)
  /// Hz: the channels' zero-phase low-pass before the match (0: none), as
  /// analysers filter records: it keeps the blow (its rise lasts about a
  /// millisecond) and removes the gauges' noise above it.
  double low_pass = 5000.0;
  /// The weight w of the penalty on the shaft's curvature, w (R_{i-1} - 2
  /// R_i + R_{i+1}) / F_max per inner segment beside the force residuals
  /// (Tikhonov regularisation; 0: none). It is zero on any linear
  /// distribution and settles what the record barely tells apart: the
  /// deepest shaft from the toe.
  double smoothing = 10.0;

  [[nodiscard]] bool fits(std::string_view unknown) const;
};

/// RECORD.toml as read: the pile below the gauges, the CSV file, the channels.
struct PileRecord {
  std::filesystem::path origin;               ///< the record file, for messages
  std::filesystem::path file;                 ///< the record file read (from_file), empty for text
  std::filesystem::path csv;                  ///< [record] file
  std::vector<PileSegment> segments;          ///< from the gauges down; one for a uniform [pile]
  CsvLayout layout;                           ///< time column, delimiter, skip_rows
  std::vector<std::string> force_columns;     ///< force (N) or, with `strain`, strain
  bool strain = false;                        ///< force_columns hold strain (times E A at the gauges)
  std::vector<std::string> velocity_columns;  ///< velocity (m/s) or, with `acceleration`, m/s^2
  bool acceleration = false;
  double damping = 0.5;  ///< [case_method] damping J_c, in [0, 1]
  MatchSettings match;   ///< [match] (defaults when absent)

  /// L, the pile's length below the gauges.
  [[nodiscard]] double length() const;
  /// 2L/c: the wave's travel time from the gauges to the toe and back.
  [[nodiscard]] double travel_time() const;
  /// Z at the gauges (the first segment's).
  [[nodiscard]] double impedance() const;
  /// A at the gauges.
  [[nodiscard]] double area() const;
  /// The depth x below the gauges that a wave reaches and returns from in
  /// `two_way` seconds (2x/c on a uniform pile), clamped to [0, L].
  [[nodiscard]] double depth_at(double two_way) const;
  /// 2 x / c through the segments down to depth x.
  [[nodiscard]] double two_way_time(double x) const;
  /// The segment holding depth x (the upper one at a joint).
  [[nodiscard]] const PileSegment& segment_at(double x) const;

  /// Reads and validates a record file; relative paths in it are relative to
  /// its directory. Throws InputError naming the file, the key and the rule.
  static PileRecord from_file(const std::filesystem::path& path);
  /// The same from TOML text; relative paths are relative to `base`.
  static PileRecord from_string(const std::string& toml, const std::filesystem::path& base,
                                const std::string& origin = "record");
};

/// The record's signals at the gauges, offsets removed (compression and
/// downward velocity positive).
struct PileSignals {
  std::vector<double> t;                               ///< s, strictly increasing
  std::vector<double> force;                           ///< N, the channels' average
  std::vector<double> velocity;                        ///< m/s, the channels' average
  std::vector<double> displacement;                    ///< m, trapezoid integral of velocity from the first sample
  std::vector<double> energy;                          ///< J, trapezoid integral of force times velocity
  std::vector<std::vector<double>> force_channels;     ///< N each, offset removed
  std::vector<std::vector<double>> velocity_channels;  ///< m/s each, offset removed (integrated)
  std::size_t foot = 0;                                ///< first sample above 5% of the averaged force's peak
  std::size_t impact = 0;                              ///< t1: the force's first local maximum from the foot
  std::size_t baseline = 0;  ///< samples more than one rise time before the foot (the offsets' mean)
  bool filtered = false;     ///< the channels were low-passed (read_pile_signals' cutoff)
  double cutoff = 0.0;       ///< Hz, the low-pass applied (the cutoff asked, or a quarter of the sampling rate)
  std::string filter_note;   ///< why a low-pass asked for was not applied (empty: it was, or none was asked)

  [[nodiscard]] double t_foot() const { return t[foot]; }
  [[nodiscard]] double t1() const { return t[impact]; }
};

/// Reads the record's CSV file and makes its signals. Throws InputError (one
/// line naming the file, the column or key and the rule) for a missing file
/// or column, a cell that is not a number, time not increasing, no impact,
/// a record ending before t2, one starting too late for the offsets (fewer
/// than 5 samples more than one rise time before the foot), two channels
/// differing at t1 by more than half the larger (bending), and force and
/// velocity disagreeing at t1 (|F / (Z v) - 1| > 0.3). With `low_pass` > 0
/// (Hz), every channel is first low-passed at zero phase (fourth-order
/// Butterworth response, -6 dB there), at a quarter of the sampling rate
/// when that is lower; an unevenly sampled record is not (filter_note).
[[nodiscard]] PileSignals read_pile_signals(const PileRecord& record, double low_pass = 0.0);

/// What the analysis reads: the record file and its CSV file.
[[nodiscard]] CommandInputs pda_inputs(const PileRecord& record);

}  // namespace barimpact
