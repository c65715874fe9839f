// Inflow hydrographs (engine/inflow_source.h, [[inflows]]): material entering through a
// cross-section at Q(t) holds the hydrograph's volume (its integral) at every time within one row
// of particles, and at the end within 0.1 %; it enters at the hydrograph's speed, normal to the
// section; bad hydrograph files are one line naming the file and line.
#include "engine/inflow_source.h"
#include "test_support.h"

#include <cmath>
#include <fstream>
#include <gtest/gtest.h>

using namespace talus;

namespace {

/// A flat slip channel 4 m long; the section across it at x = 0.3; `hydrograph` as given.
std::string scene(const std::string& hydrograph) {
  return R"(
[simulation]
dx = 0.05
end_time = 10
[domain]
min = [0, 0, -0.2]
max = [4.0, 0.4, 0.6]
walls = "slip"
[terrain]
plane = { point = [0, 0, 0], normal = [0, 0, 1] }
boundary = "slip"
[[materials]]
name = "debris"
model = "elastic"
density = 2000
youngs_modulus = 1e6
[[bodies]]
material = "debris"
shape = "box"
min = [3.5, 0.05, 0]
max = [3.6, 0.15, 0.05]
[[inflows]]
name = "torrent"
material = "debris"
section = [[0.3, 0.05], [0.3, 0.35]]
direction = [1, 0]
)" + hydrograph + "\n";
}

const InflowSource* inflow(const Simulation& sim) {
  for (const auto& s : sim.sources())
    if (auto* f = dynamic_cast<const InflowSource*>(s.get())) return f;
  return nullptr;
}

} // namespace

TEST(Inflow, TheMassThatEntersIsTheHydrographsIntegralAtEveryTime) {
  // A triangle: 0 -> 0.03 m3/s at 0.5 s -> 0 at 1 s, at 2 m/s: 0.015 m3 in all; over the 0.3 m
  // section (12 slots of 0.025 m) the peak layer is Q / (v w) = 0.05 m thick.
  auto sim = test::makeSimulation(scene("hydrograph = [[0, 0], [0.5, 0.03], [1.0, 0]]\nspeed = 2.0"));
  const InflowSource* f = inflow(*sim);
  ASSERT_NE(f, nullptr);
  EXPECT_EQ(f->slots(), 12u);
  EXPECT_NEAR(f->hydrographVolume(1.0), 0.015, 1e-15);
  EXPECT_NEAR(f->hydrographVolume(0.25), 0.5 * 0.25 * 0.015, 1e-15);
  const double rho = 2000, initial = sim->totalMass();
  const double rowTime = 0.025 / 2.0; // a row every spacing / speed
  for (double t : {0.2, 0.4, 0.5, 0.7, 0.9, 1.2}) {
    sim->advanceTo(t);
    const double entered = (sim->totalMass() - initial) / rho, expected = f->hydrographVolume(t);
    std::printf("  t = %.1f s: entered %.6f m3, hydrograph %.6f m3 (%+.2f %%)\n", t, entered, expected,
                expected > 0 ? 100 * (entered / expected - 1) : 0.0);
    // Within one row: what entered since the last row waits for the next (at most Q_max s / v).
    EXPECT_NEAR(entered, expected, 0.03 * rowTime + 1e-9) << "t = " << t;
    EXPECT_NEAR(entered, f->emittedVolume(), 1e-6 * expected + 1e-12);
  }
  EXPECT_NEAR((sim->totalMass() - initial) / rho, 0.015, 0.001 * 0.015) << "the whole hydrograph, within 0.1 %";
  // Entered at the hydrograph's speed along +x, and downstream of the section.
  const auto& P = sim->groups()[0]->particles;
  double minX = 1e9;
  for (size_t p = 0; p < P.size(); ++p)
    if (P.x[p].x() < 3.4) minX = std::min(minX, double(P.x[p].x()));
  EXPECT_GT(minX, 0.3 - 0.05) << "nothing upstream of the section (beyond a cell's splat)";
}

TEST(Inflow, BadHydrographsAreOneLineNamingTheFileAndLine) {
  const std::string dir = test::tempDir("inflow_bad");
  std::ofstream(dir + "/q.csv") << "time_s,discharge_m3_s,speed_m_s\n0,0,2\n0.5,abc,2\n";
  auto errorOf = [](const std::string& text) {
    try {
      test::makeSimulation(text);
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(errorOf(scene("hydrograph = \"" + dir + "/q.csv\"")).find("q.csv:3"), std::string::npos);
  EXPECT_NE(errorOf(scene("hydrograph = [[0, 0], [0, 1]]\nspeed = 2")).find("times must increase"), std::string::npos);
  EXPECT_NE(errorOf(scene("hydrograph = [[0, 0], [1, 1]]")).find("speed"), std::string::npos);
  EXPECT_NE(errorOf(scene("hydrograph = [[0, 0], [1, -1]]\nspeed = 2")).find(">= 0"), std::string::npos);
}
