// A small Drucker-Prager column (a = 2, 12 800 particles) collapsing on a frictional plane: the
// granular scene of the MPI tests (tests/mpi/test_ranks.cpp, tests/test_run_on_ranks.cpp).
#pragma once

#include <string>

namespace talus::test {

inline const std::string kSmallCollapse = R"(
[simulation]
dx = 0.02
particles_per_cell = 8
end_time = 1
[domain]
min = [0, 0, 0]
max = [1.3, 0.16, 0.5]
walls = "slip"
[terrain]
plane = { point = [0, 0, 0.02], normal = [0, 0, 1] }
boundary = { law = "coulomb", friction = 0.5 }
[[materials]]
name = "sand"
model = "drucker_prager"
density = 1600
youngs_modulus = 1e6
poisson_ratio = 0.3
friction_angle = 30
[[bodies]]
material = "sand"
shape = "box"
center = [0.12, 0.08, 0.22]
size = [0.2, 0.16, 0.4]
)";

} // namespace talus::test
