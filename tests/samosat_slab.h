// An elastic snow slab sliding down a 30-degree plane (gravity turned) under samosAT, whose
// flow-thickness lines cross the ranks' ranges: the thickness-law scene of the MPI tests
// (tests/mpi/test_ranks.cpp, tests/test_run_on_ranks.cpp).
#pragma once

#include <string>

namespace talus::test {

inline const std::string kSamosAtSlab = R"(
[simulation]
dx = 0.05
particles_per_cell = 8
end_time = 1
gravity = [4.905, 0, -8.4957]
[domain]
min = [0, 0, 0]
max = [3.2, 0.8, 0.8]
walls = "slip"
[terrain]
plane = { point = [0, 0, 0.1], normal = [0, 0, 1] }
boundary = "samosat"
[[materials]]
name = "snow"
model = "elastic"
density = 300
youngs_modulus = 1e6
poisson_ratio = 0.3
[[bodies]]
material = "snow"
shape = "box"
min = [0.2, 0.1, 0.1]
max = [1.4, 0.7, 0.35]
)";

// The same snow pressed by the turned gravity against a steep samosAT slope (60 degrees, its
// normal closest to x): the contact nodes read the thickness lines along x, which cross the
// ranks' ranges (the ranks split the tree along x first). The floor is a slip wall.
inline const std::string kSamosAtSteepSlope = R"(
[simulation]
dx = 0.05
particles_per_cell = 8
end_time = 1
gravity = [4.905, 0, -8.4957]
[domain]
min = [0, 0, 0]
max = [3.2, 0.8, 0.8]
walls = "slip"
[terrain]
plane = { point = [2.0, 0, 0], normal = [-0.8660254, 0, 0.5] }
boundary = "samosat"
[[materials]]
name = "snow"
model = "elastic"
density = 300
youngs_modulus = 1e6
poisson_ratio = 0.3
[[bodies]]
material = "snow"
shape = "box"
min = [1.0, 0.1, 0.02]
max = [2.3, 0.7, 0.4]
)";

} // namespace talus::test
