// Scene files: overrides, and bad input reported with file, line and key.
#include "io/config/toml_reader.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <regex>

using namespace talus;

namespace {
const char* kGood = R"([simulation]
dx = 0.1
end_time = 1.0
[domain]
min = [0, 0, 0]
max = [2, 2, 2]
[[materials]]
name = "rock"
model = "elastic"
density = 2700
youngs_modulus = 1e7
poisson_ratio = 0.25
[[bodies]]
material = "rock"
shape = "box"
min = [0.5, 0.5, 0.5]
max = [1.0, 1.0, 1.0]
)";

/// Expects an InputError whose message starts with "test.toml:<line>: <key>" and contains `part`.
void expectError(const std::string& text, int line, const std::string& key, const std::string& part,
                 const std::vector<std::string>& sets = {}) {
  try {
    loadSceneString(text, "test.toml", sets);
    FAIL() << "no error for " << key;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.line(), line) << msg;
    EXPECT_EQ(e.key(), key) << msg;
    EXPECT_NE(msg.find(part), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
  }
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}
} // namespace

TEST(SceneInput, GoodSceneSeedsBodies) {
  SceneSetup s = loadSceneString(kGood, "test.toml");
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].particles, 5u * 5u * 5u * 8u);
  EXPECT_NEAR(s.bodies[0].seededVolume, 0.125, 1e-12);
}

TEST(SceneInput, SetOverridesScalarsVectorsAndNamedMaterials) {
  SceneSetup s = loadSceneString(kGood, "test.toml",
                                 {"simulation.dx=0.05", "simulation.gravity=[1,0,-9.8]", "materials.rock.density=2500"});
  EXPECT_DOUBLE_EQ(s.settings.dx, 0.05);
  EXPECT_DOUBLE_EQ(s.settings.gravity.x(), 1.0);
  EXPECT_DOUBLE_EQ(s.groups[0]->density(), 2500.0);
  EXPECT_EQ(s.bodies[0].particles, 10u * 10u * 10u * 8u);
}

TEST(SceneInput, MalformedTomlNamesTheLine) {
  expectError(replace(kGood, "dx = 0.1", "dx = = 0.1"), 2, "", "");
}

TEST(SceneInput, NegativeAndNonFiniteValuesNameTheKey) {
  expectError(replace(kGood, "density = 2700", "density = -2700"), 10, "materials[0].density", "positive");
  expectError(replace(kGood, "dx = 0.1", "dx = nan"), 2, "simulation.dx", "finite");
  expectError(replace(kGood, "end_time = 1.0", "end_time = 1.0\nflip = 1.5"), 4, "simulation.flip", "[0, 1]");
}

TEST(SceneInput, PoissonRatioOfOneHalfIsRefused) {
  expectError(replace(kGood, "poisson_ratio = 0.25", "poisson_ratio = 0.5"), 12, "materials[0].poisson_ratio", "0.5)");
}

TEST(SceneInput, UnknownKeySuggestsTheClosestValidOne) {
  expectError(replace(kGood, "youngs_modulus", "youngs_modulos"), 11, "materials[0].youngs_modulos",
              "did you mean 'youngs_modulus'");
  expectError(replace(kGood, "end_time", "endtime"), 3, "simulation.endtime", "did you mean 'end_time'");
}

TEST(SceneInput, WrongTypeIsNamed) {
  expectError(replace(kGood, "dx = 0.1", "dx = \"fine\""), 2, "simulation.dx", "expected a number");
  expectError(replace(kGood, "max = [2, 2, 2]", "max = [2, 2]"), 6, "domain.max", "3 numbers");
}

TEST(SceneInput, BodyOutsideTheDomainIsRefused) {
  expectError(replace(kGood, "max = [1.0, 1.0, 1.0]", "max = [1.0, 1.0, 2.5]"), 15, "bodies[0].shape", "outside the domain");
}

TEST(SceneInput, UnknownMaterialAndModelAreNamed) {
  expectError(replace(kGood, "material = \"rock\"", "material = \"granite\""), 14, "bodies[0].material", "granite");
  expectError(replace(kGood, "model = \"elastic\"", "model = \"elastik\""), 9, "materials[0].model", "did you mean 'elastic'");
}

TEST(SceneInput, EmptySceneAndMissingSectionsAreRefused) {
  expectError("", 1, "", "missing [simulation]");
  const std::string noBodies = std::string(kGood).substr(0, std::string(kGood).find("[[bodies]]"));
  expectError(noBodies, 1, "", "no [[bodies]]");
}

TEST(SceneInput, MissingTerrainFileIsNamed) {
  const std::string t = std::string(kGood) + "[terrain]\nsdf = \"nowhere.vdb\"\nboundary = \"slip\"\n";
  expectError(t, 19, "terrain.sdf", "file not found");
}

TEST(SceneInput, ABadValueGivenWithSetSaysSo) {
  expectError(kGood, 0, "simulation.dx", "(given with --set)", {"simulation.dx=-1"});
}

TEST(SceneInput, BadOverrideIsNamed) {
  expectError(kGood, 0, "materials.granite.density", "no element 'granite'", {"materials.granite.density=1"});
}

TEST(SceneInput, ATinyGridSpacingIsRefusedBeforeSeedingBillionsOfParticles) {
  expectError(replace(kGood, "dx = 0.1", "dx = 1e-5"), 13, "bodies[0]", "max_particles");
  // The limit is a scene key too.
  expectError(std::string(kGood), 13, "bodies[0]", "max_particles", {"simulation.max_particles=100"});
}

TEST(SceneInput, FrictionAnglesOutsideZeroToNinetyAreRefused) {
  const std::string dp = replace(replace(kGood, "model = \"elastic\"", "model = \"drucker_prager\"\nfriction_angle = 95"),
                                 "poisson_ratio = 0.25", "poisson_ratio = 0.25");
  expectError(dp, 10, "materials[0].friction_angle", "(0, 90)");
}

// A wall holds the node rows at or beyond its face: a face between rows gives the material up to
// a cell more room, which a user should be told (a half tank 0.5 m wide at dx 0.055 m is 10 %
// wider: docs/convergence.md, "Dam break onto a box").
TEST(SceneInput, AWallBetweenNodeRowsIsNotedWithWhereItActs) {
  auto domainNotes = [](const SceneSetup& s) {
    std::vector<std::string> out;
    for (const auto& n : s.notes)
      if (n.rfind("domain:", 0) == 0) out.push_back(n);
    return out;
  };
  EXPECT_TRUE(domainNotes(loadSceneString(kGood, "test.toml")).empty());
  const auto off = domainNotes(loadSceneString(replace(kGood, "max = [2, 2, 2]", "max = [2.05, 2, 2]"), "test.toml"));
  ASSERT_EQ(off.size(), 1u);
  EXPECT_NE(off[0].find("x_max wall (2.05 m)"), std::string::npos) << off[0];
  EXPECT_NE(off[0].find("acts at the row beyond, 2.1 m"), std::string::npos) << off[0];
  // An open face holds no nodes: nothing to say.
  EXPECT_TRUE(domainNotes(loadSceneString(replace(kGood, "max = [2, 2, 2]", "max = [2.05, 2, 2]\nx_max = \"open\""),
                                          "test.toml")).empty());
}
