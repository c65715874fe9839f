// The configuration table alone (io/config): typed reads with file, line and key in every error,
// defaults, ranges, choices, unknown keys with suggestions, and --set overrides.
#include "io/config/toml_reader.h"

#include <gtest/gtest.h>

using namespace talus;

namespace {

const char* kText = R"(top = 1
[a]
x = 2.5
n = 3
flag = true
name = "rock"
v = [1, 2, 3]
[[items]]
name = "first"
k = 1
[[items]]
name = "second"
k = 2
)";

/// Runs f, expects an InputError at `line` about `key` whose message contains `part`.
template <class F> void expectError(F&& f, int line, const std::string& key, const std::string& part) {
  try {
    f();
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "t.toml");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

} // namespace

TEST(ConfigTable, TypedReadsAndDefaults) {
  auto root = readTomlString(kText, "t.toml");
  const ConfigTable& a = *root->table("a");
  EXPECT_EQ(a.number("x"), 2.5);
  EXPECT_EQ(a.integer("n", 0, 0, 10), 3);
  EXPECT_TRUE(a.boolean("flag", false));
  EXPECT_EQ(a.string("name"), "rock");
  EXPECT_EQ(a.vec3("v"), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(a.number("absent", 7.0), 7.0);
  EXPECT_EQ(a.choice("name", "", {"rock", "ice"}), "rock");
  EXPECT_EQ(a.lineOf("n"), 4);
  EXPECT_EQ(a.keyPath("x"), "a.x");
  const auto items = root->tables("items");
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[1]->integer("k", 0, 0, 9), 2);
  EXPECT_EQ(items[1]->keyPath("k"), "items[1].k");
}

TEST(ConfigTable, ErrorsNameFileLineAndKey) {
  auto root = readTomlString(kText, "t.toml");
  const ConfigTable& a = *root->table("a");
  expectError([&] { a.positive("x", 0); a.inRange("x", 0, 0, 1); }, 3, "a.x", "must be in [0, 1] (got 2.5)");
  expectError([&] { a.number("name"); }, 6, "a.name", "expected a number, got a string");
  expectError([&] { a.integer("x", 0, 0, 9); }, 3, "a.x", "expected an integer");
  expectError([&] { a.choice("name", "", {"ice", "water"}); }, 6, "a.name", "'rock' is not one of: ice, water");
  expectError([&] { a.choice("name", "", {"rocks", "ice"}); }, 6, "a.name", "did you mean 'rocks'");
  expectError([&] { a.vec3("v"); a.number("n"); a.boolean("n", false); }, 4, "a.n", "expected true or false");
  expectError([&] { a.string("missing"); }, 2, "a", "missing required key 'missing'");
}

TEST(ConfigTable, UnknownKeysAreReportedWithTheClosestAskedName) {
  auto root = readTomlString("[s]\ndensity = 1\ndensty = 2\n", "t.toml");
  root->table("s")->number("density");
  expectError([&] { root->checkAllUsed(); }, 3, "s.densty", "did you mean 'density'");
}

TEST(ConfigTable, AMissingKeyBlamesItsLikelyMisspelling) {
  auto root = readTomlString("[s]\nyoungs_modulos = 1\n", "t.toml");
  expectError([&] { root->table("s")->positive("youngs_modulus"); }, 2, "s.youngs_modulos", "did you mean 'youngs_modulus'");
}

TEST(ConfigTable, OverridesReplaceValuesByPathAndByName) {
  auto root = readTomlString(kText, "t.toml");
  applyOverride(*root, "a.x=4");
  applyOverride(*root, "items.second.k=5");
  applyOverride(*root, "a.name=ice");
  EXPECT_EQ(root->table("a")->number("x"), 4);
  EXPECT_EQ(root->tables("items")[1]->integer("k", 0, 0, 9), 5);
  EXPECT_EQ(root->table("a")->string("name"), "ice");
  // An error about an overridden value says where it came from.
  applyOverride(*root, "a.x=-1");
  try {
    root->table("a")->positive("x");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("given with --set"), std::string::npos) << e.what();
  }
}
