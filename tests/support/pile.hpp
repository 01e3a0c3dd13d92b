// A pile in Smith's soil shared by the tests of the soil (case keys, the
// line built from them, the schemes' step and runs): a steel pile of 10 m
// in 50 elements, its shaft and toe each of one quake, no damping.
#pragma once

namespace barimpact::testing {

constexpr const char* pile_toml = R"(
[[body]]
name = "pile"
length = 10.0
elements = 50
area = 0.006
modulus = 210e9
density = 7850.0
viscosity = 2e6
[body.shaft]
ultimate = 300e3
quake = 0.0025
damping = 0.0
[near_end]
law = "smith"
ultimate = 200e3
quake = 0.0025
damping = 0.0
[time]
end = 0.01
step = "auto"
scheme = "central-difference"
)";

// The pile of the drivability tests: 10 m of steel in 40 elements, no soil
// of its own (a profile gives it one).
constexpr const char* driven_pile_toml = R"(
[[body]]
name = "pile"
length = 10.0
elements = 40
area = 0.006
modulus = 210e9
density = 7850.0
)";

// A 2 t ram on a capblock above it.
constexpr const char* ram_toml = R"(
[[body]]
name = "ram"
kind = "mass"
mass = 2000.0
[[joint]]
between = ["pile", "ram"]
law = "cushion"
stiffness = 2e9
restitution = 0.8
)";

// A blow's time: central differences at their stable step.
constexpr const char* blow_time_toml = R"(
[time]
end = 0.04
step = "auto"
scheme = "central-difference"
)";

// Dropped by hand from 0.8 m.
constexpr const char* drop_toml = R"(
[hammer]
kind = "drop"
ram = "ram"
stroke = 0.8
)";

// Soft clay over sand, depths in m below ground ([drive] apart).
constexpr const char* clay_over_sand_toml = R"(
[[layer]]
top = 0.0
bottom = 4.0
shaft = [10e3, 20e3]
toe = 1e6
shaft_damping = 0.65
setup = 2.0
[[layer]]
top = 4.0
bottom = 10.0
shaft = 30e3
toe = 8e6
shaft_quake = 0.003
toe_quake = 0.004
damping_law = "viscous"
)";

}  // namespace barimpact::testing
