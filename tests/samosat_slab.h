// An elastic snow slab under samosAT with gravity turned 30 degrees, on a terrain plane: the
// thickness-law scenes of the MPI tests (tests/mpi/test_ranks.cpp, tests/test_run_on_ranks.cpp).
#pragma once

#include <string>

namespace talus::test {

/// The scene with the terrain plane through `point` with `normal` and the snow box [min, max]
/// (TOML arrays).
inline std::string samosAtScene(const std::string& point, const std::string& normal, const std::string& min,
                                const std::string& max) {
  return R"(
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
plane = { point = )" + point + ", normal = " + normal + R"( }
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
min = )" + min + "\nmax = " + max + "\n";
}

/// The slab sliding down the flat floor (gravity turned 30 degrees), whose flow-thickness lines
/// cross the ranks' ranges.
inline const std::string kSamosAtSlab = samosAtScene("[0, 0, 0.1]", "[0, 0, 1]", "[0.2, 0.1, 0.1]", "[1.4, 0.7, 0.35]");

/// The same snow pressed by the turned gravity against a steep slope (60 degrees, its normal
/// closest to x): the contact nodes read the thickness lines along x, which cross the ranks'
/// ranges (the ranks split the tree along x first). The floor is a slip wall.
inline const std::string kSamosAtSteepSlope =
    samosAtScene("[2.0, 0, 0]", "[-0.8660254, 0, 0.5]", "[1.0, 0.1, 0.02]", "[2.3, 0.7, 0.4]");

} // namespace talus::test
