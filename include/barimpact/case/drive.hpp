// A pile driven through a soil profile ([drive] and [[layer]]) by a hammer
// ([hammer]): what the case file says, and the soil a blow meets at one
// penetration. At a penetration d the toe is at depth d and a pile node at
// distance x above the toe at depth d - x; a depth on a layer boundary
// belongs to the layer below it (top <= z < bottom; the last layer includes
// its bottom).
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "barimpact/model/contact_law.hpp"

namespace barimpact {

/// A piece of a shaft given as a profile ([body.shaft] profile): along the
/// body from its near end, the resistance per unit length (N/m) linear from
/// `from` to `to`, with the piece's quake, damping and damping law. A node
/// takes the soil of the first piece with from < x <= to (of the first with
/// from <= x <= to if none): a node on a boundary takes the piece below it.
struct ShaftPiece {
  double from = 0.0, to = 0.0;
  double resistance_from = 0.0, resistance_to = 0.0;  ///< N/m
  SoilSpring soil{0.0, 0.00254, 0.164, DampingLaw::smith};

  [[nodiscard]] double resistance_at(double x) const {
    return to > from ? resistance_from + (resistance_to - resistance_from) * (x - from) / (to - from) : resistance_from;
  }
  /// The piece's total resistance, N.
  [[nodiscard]] double ultimate() const { return 0.5 * (resistance_from + resistance_to) * (to - from); }
};

/// One soil layer of the profile ([[layer]]), depths in m below ground.
struct LayerData {
  double top = 0.0, bottom = 0.0;
  /// Unit shaft resistance during driving (Pa) at the layer's top and bottom, linear between.
  double shaft_top = 0.0, shaft_bottom = 0.0;
  double toe = 0.0;  ///< unit toe resistance during driving (Pa) while the toe is in this layer
  /// Smith's quake and damping along the shaft and at the toe (ultimate unused).
  SoilSpring shaft{0.0, 0.00254, 0.164, DampingLaw::smith};
  SoilSpring toe_soil{0.0, 0.00254, 0.492, DampingLaw::smith};
  double setup = 1.0;  ///< long-term static over driving resistance of the shaft

  /// The unit shaft resistance at depth z within the layer.
  [[nodiscard]] double shaft_at(double z) const {
    return bottom > top ? shaft_top + (shaft_bottom - shaft_top) * (z - top) / (bottom - top) : shaft_top;
  }
};

/// [drive]: the penetrations analysed and how the pile meets the soil.
struct DriveData {
  std::string pile;                ///< the pile body (empty: [blow] pile, else the bar nearest x = 0)
  double perimeter = 0.0;          ///< m
  std::optional<double> toe_area;  ///< m2 (none: the pile's area)
  std::vector<double> depths;      ///< penetrations analysed, ascending, m
  double refusal = 100.0;          ///< blows per 250 mm counted as refusal
  double blow_rate = 40.0;         ///< blows per minute
  int blows = 1;                   ///< blows per depth (> 1: residual stress analysis)
  /// The penetration this case's run analyses (`drive.depth`; none: the deepest).
  std::optional<double> depth;
  std::vector<LayerData> layers;  ///< top to bottom, contiguous from 0

  /// The penetration a run of the case analyses.
  [[nodiscard]] double analysed_depth() const { return depth ? *depth : depths.back(); }
  /// The layer holding depth z (top <= z < bottom; the last includes its bottom).
  [[nodiscard]] const LayerData& layer_at(double z) const;
};

/// The soil a blow meets at one penetration: the shaft as pieces along the
/// pile from its toe (perimeter times the unit resistances), the toe's
/// spring, and the capacities.
struct DriveSoil {
  std::vector<ShaftPiece> shaft;
  SoilSpring toe;
  double shaft_capacity = 0.0, toe_capacity = 0.0;
  double long_term_capacity = 0.0;  ///< toe + the layers' setup x their shaft capacity
};

/// The soil at penetration `depth` of `drive`'s profile, for a pile whose toe bears on `toe_area`.
[[nodiscard]] DriveSoil soil_at(const DriveData& drive, double depth, double toe_area);

/// A hammer's kinds and their default efficiencies (drop 0.67, hydraulic 0.95, air-steam 0.67).
enum class HammerKind { drop, hydraulic, air_steam, diesel };

[[nodiscard]] std::string_view to_string(HammerKind kind);

/// An open-end diesel hammer's data (the gas between ram and anvil).
struct DieselData {
  double anvil_mass = 0.0;
  double cylinder_area = 0.0;        ///< m2
  double compression_length = 0.0;   ///< ports to impact, m
  double chamber_length = 0.0;       ///< the gas column at impact, m
  double combustion_pressure = 0.0;  ///< Pa
  double max_stroke = 0.0;           ///< m
  double impact_stiffness = 2e10;    ///< N/m, ram on anvil
  double impact_restitution = 0.8;
};

/// One hammer of a table (data/hammers.toml, or [hammer] table = "..."):
/// the ram, its rated stroke or energy, the efficiency, the capblock and the helmet.
struct HammerModel {
  std::string name;
  HammerKind kind = HammerKind::drop;
  double ram_mass = 0.0;
  double stroke = 0.0;  ///< m (0: from energy)
  double energy = 0.0;  ///< J, rated (0: from stroke)
  double efficiency = 0.0;
  double cushion_stiffness = 0.0;
  double cushion_restitution = 0.8;
  double helmet_mass = 0.0;
  std::string source;
  DieselData diesel;  ///< kind diesel
};

/// [hammer]: a hammer from a table (`model`) or by hand (`kind`, `ram`).
struct HammerData {
  std::string model;                 ///< a table's name (empty: by hand)
  std::optional<HammerModel> entry;  ///< the table's entry (model only)
  HammerKind kind = HammerKind::drop;
  std::string ram;  ///< the ram body
  /// The stroke: as given, energy / (m g), or the table's; a diesel
  /// hammer's blow's fall height above impact (its first: max_stroke).
  double stroke = 0.0;
  double efficiency = 0.0;
  double ram_mass = 0.0;  ///< a diesel hammer by hand
  DieselData diesel;      ///< kind diesel
  /// The pile cushion between the pile head and the helmet (model only).
  struct Cushion {
    double stiffness = 0.0, restitution = 1.0;
  };
  std::optional<Cushion> pile_cushion;

  /// The ram's speed at impact: sqrt(2 g stroke efficiency).
  [[nodiscard]] double impact_velocity(double g) const { return std::sqrt(2.0 * g * stroke * efficiency); }
};

/// FROM:TO:COUNT as values spaced linearly, from and to included, each to 12
/// significant digits (0.4, not 0.39999999999999997, as a user types it).
[[nodiscard]] std::vector<double> linear_range(double from, double to, long long count);

/// The acceleration of gravity the pile contract uses: the case's, else 9.81 m/s2.
[[nodiscard]] inline double drive_gravity(double case_gravity) {
  return case_gravity > 0.0 ? case_gravity : 9.81;
}

/// The hammers barimpact ships (data/hammers.toml, compiled in).
[[nodiscard]] const std::vector<HammerModel>& shipped_hammers();
/// The text of data/hammers.toml as shipped.
[[nodiscard]] std::string_view shipped_hammers_toml();
/// A table of hammers in data/hammers.toml's layout; `origin` names it in
/// messages. Throws InputError naming the entry and key.
[[nodiscard]] std::vector<HammerModel> read_hammer_table(std::string_view toml, std::string_view origin);

}  // namespace barimpact
