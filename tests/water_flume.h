// A water column 0.6 m long and 0.4 m deep collapsing along a 2.4 m flume with slip walls
// (dx 4 cm, sound speed 20 m/s): a short water scene for the run-on-ranks and step-parts tests.
#pragma once

namespace talus::test {

inline const char* kWaterFlumeScene = R"(
[simulation]
dx = 0.04
end_time = 0.6
[domain]
min = [0, 0, 0]
max = [2.4, 0.16, 0.6]
walls = "slip"
[[materials]]
name = "water"
model = "water"
density = 1000
sound_speed = 20
[[bodies]]
material = "water"
shape = "box"
min = [0, 0, 0]
max = [0.6, 0.16, 0.4]
)";

} // namespace talus::test
