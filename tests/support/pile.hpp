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

}  // namespace barimpact::testing
