// Colliders as a scene gives them: per-face laws of the domain, [[structures]] with their laws
// and motions, and one-line errors for what does not make sense.
#include "test_support.h"

#include <algorithm>
#include <gtest/gtest.h>

using namespace talus;

namespace {

std::string scene(const std::string& domainExtra, const std::string& structures = "") {
  return R"(
[simulation]
dx = 0.1
end_time = 1
[domain]
min = [0, 0, 0]
max = [2, 1, 1]
)" + domainExtra + R"(
[[materials]]
name = "sand"
model = "drucker_prager"
density = 1600
youngs_modulus = 1e6
friction_angle = 30
[[bodies]]
material = "sand"
shape = "box"
min = [0.2, 0.2, 0.0]
max = [0.8, 0.8, 0.4]
)" + structures;
}

std::vector<std::string> colliderNames(const std::string& text) {
  auto sim = test::makeSimulation(text);
  std::vector<std::string> n;
  for (const auto& c : sim->colliders()) n.push_back(c->name() + ":" + c->law().name());
  return n;
}

void expectError(const std::string& text, const std::string& key, const std::string& part) {
  try {
    loadSceneString(text, "test.toml");
    FAIL() << "no error for " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

const char* kDam = R"(
[[structures]]
name = "dam"
shape = "box"
min = [1.2, 0.0, 0.0]
max = [1.5, 1.0, 0.5]
law = "friction"
friction = 0.4
)";

} // namespace

TEST(StructuresInput, EachFaceTakesTheWallsLawUnlessItHasItsOwn) {
  using V = std::vector<std::string>;
  EXPECT_EQ(colliderNames(scene("walls = \"slip\"")), (V{"x_min:slip", "x_max:slip", "y_min:slip", "y_max:slip", "z_min:slip", "z_max:slip"}));
  EXPECT_EQ(colliderNames(scene("x_max = \"open\"\nz_min = { law = \"friction\", friction = 0.3 }\nz_max = \"sticky\"")),
            (V{"x_min:slip", "y_min:slip", "y_max:slip", "z_min:coulomb", "z_max:sticky"}));
  EXPECT_EQ(colliderNames(scene("walls = \"friction\"\nwall_friction = 0.2\ny_min = \"open\"")),
            (V{"x_min:coulomb", "x_max:coulomb", "y_max:coulomb", "z_min:coulomb", "z_max:coulomb"}));
}

TEST(StructuresInput, AStructureIsACollider) {
  auto names = colliderNames(scene("", kDam));
  EXPECT_EQ(names.front(), "dam:coulomb"); // structures at rest act before the faces
  // A moving one acts last, so its prescribed motion wins where it overlaps a face.
  names = colliderNames(scene("", std::string(kDam) + "motion = { velocity = [0, 0, 1], start = 0.5 }\n"));
  EXPECT_EQ(names.back(), "dam:coulomb");
}

TEST(StructuresInput, APanelIsPartOfItsFaceAndActsJustBeforeIt) {
  const std::string panel = "[[panels]]\nname = \"gauge\"\nface = \"x_max\"\nmin = [0, 0.2, 0.1]\nmax = [0, 0.4, 0.2]\n";
  using V = std::vector<std::string>;
  EXPECT_EQ(colliderNames(scene("x_max = \"sticky\"", panel)),
            (V{"x_min:slip", "gauge:sticky", "x_max:sticky", "y_min:slip", "y_max:slip", "z_min:slip", "z_max:slip"}));
  expectError(scene("x_max = \"open\"", panel), "panels[0].face", "x_max is open or periodic");
  expectError(scene("", std::string(kDam) + panel + "[[panels]]\nname = \"dam\"\nface = \"x_min\"\nmin = [0, 0, 0]\nmax = [0, 1, 1]\n"),
              "panels[1].name", "'dam' already names a collider");
  expectError(scene("", "[[panels]]\nface = \"z_min\"\nmin = [0.31, 0, 0]\nmax = [0.39, 1, 0]\n"), "panels[0].max",
              "holds no grid node along x");
  expectError(scene("", "[[panels]]\nface = \"top\"\nmin = [0, 0, 0]\nmax = [1, 1, 0]\n"), "panels[0].face", "not one of");
}

TEST(StructuresInput, NoParticleIsSeededInsideAStructure) {
  const std::string text = scene("", R"(
[[structures]]
name = "pillar"
shape = "cylinder"
start = [0.5, 0.5, -0.1]
end = [0.5, 0.5, 0.6]
radius = 0.15
)");
  auto sim = test::makeSimulation(text);
  for (const Vec3& x : sim->groups()[0]->particles.x) EXPECT_GT(std::hypot(x.x() - 0.5, x.y() - 0.5), 0.15 - 1e-6);
}

TEST(StructuresInput, AThinStructureIsNoted) {
  const SceneSetup s = loadSceneString(scene("", R"(
[[structures]]
name = "fence"
shape = "box"
min = [1.5, 0.0, 0.0]
max = [1.55, 1.0, 0.5]
)"),
                                       "test.toml");
  bool noted = false;
  for (const auto& n : s.notes) noted |= n.find("'fence' is thinner than two grid cells") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(StructuresInput, BadLawsAndStructuresAreOneLineErrors) {
  expectError(scene("x_min = \"stickey\""), "domain.x_min", "did you mean 'sticky'");
  expectError(scene("walls = \"friction\""), "domain.walls", "'friction' needs 'wall_friction'");
  expectError(scene("z_min = { law = \"friction\" }"), "domain.z_min.law", "'friction' needs 'friction'");
  expectError(scene("", "[[structures]]\nshape = \"box\"\nmin = [0,0,0]\nmax = [1,1,1]\nlaw = \"open\"\n"),
              "structures[0].law", "not one of");
  expectError(scene("", "[[structures]]\nname = \"x_max\"\nshape = \"box\"\nmin = [0,0,0]\nmax = [1,1,1]\n"),
              "structures[0].name", "names a domain face");
  expectError(scene("", std::string(kDam) + kDam), "structures[1].name", "duplicate structure name 'dam'");
  expectError(scene("", "[[structures]]\nshape = \"level_set\"\nfile = \"nowhere.vdb\"\n"), "structures[0].file",
              "file not found");
  expectError(scene("", "[[structures]]\nshape = \"pyramid\"\n"), "structures[0].shape", "not one of");
  expectError(scene("", std::string(kDam) + "motion = { velocity = [1, 0, 0], start = 2, stop = 1 }\n"),
              "structures[0].motion.stop", "later than start");
}

TEST(StructuresInput, BasalLawsPeriodicAxesAndMaterialLawsAreCheckedWhereGiven) {
  // Rate laws take their parameters beside the law or inline; unknown parameters fail by name.
  const auto names = colliderNames(scene("z_min = { law = \"voellmy\", friction = 0.2, xi = 1000 }\n"));
  EXPECT_NE(std::find(names.begin(), names.end(), "z_min:voellmy"), names.end());
  expectError(scene("z_min = { law = \"voellmy\", friction = -1 }\n"), "domain.z_min.friction", "");
  expectError(scene("z_min = { law = \"samosat\", kappa = 0 }\n"), "domain.z_min.kappa", "");
  // 20 cells along x: not whole 8-node blocks.
  expectError(scene("periodic = [\"x\"]\n"), "domain.periodic", "multiple of 8 dx");
  expectError(scene("periodic = [\"w\"]\n"), "domain.periodic", "not an axis");
  // A material's own law: a wrong name is refused with the valid ones.
  std::string text = scene("");
  text.replace(text.find("friction_angle = 30"), 19, "friction_angle = 30\nbasal = { law = \"glue\" }");
  expectError(text, "materials[0].basal.law", "'glue' is not one of: sticky");
}
