// Assignments written into a scene's text (the calibrated scene of `talus calibrate`): the
// edited text, read back, holds the assigned values where `--set` would put them, and every
// other line as the author wrote it.
#include "io/config/scene_text_edit.h"
#include "io/config/toml_reader.h"
#include "io/config/config_table.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace talus;

namespace {
const char* kScene = R"(# A scene as a user writes it
[simulation]
end_time = 10.0   # seconds
dx = 2.0

[[materials]]
name = "snow"
density = 200.0

[[materials]]
name = "rock"
density = 2500.0  # granite
friction_angle = 35.0

[basal]
law = "samosat"
)";
} // namespace

TEST(SceneTextEdit, AssignedValuesReadBackWhereSetPutsThemAndTheRestIsUnchanged) {
  const SceneTextEdit e = assignInSceneText(kScene, {"simulation.end_time=12.5", "materials.rock.friction_angle=31.25",
                                                     "materials.0.density=250", "basal.mu=0.155", "output.maps=true",
                                                     "basal.law=voellmy"});
  EXPECT_TRUE(e.unplaced.empty());
  auto edited = readTomlString(e.text, "edited");
  auto expected = readTomlString(kScene, "expected");
  for (const char* a : {"simulation.end_time=12.5", "materials.rock.friction_angle=31.25", "materials.0.density=250",
                        "basal.mu=0.155", "output.maps=true", "basal.law=voellmy"})
    applyOverride(*expected, a);
  EXPECT_DOUBLE_EQ(edited->table("simulation")->number("end_time"), 12.5);
  EXPECT_DOUBLE_EQ(edited->table("simulation")->number("dx"), 2.0);
  EXPECT_DOUBLE_EQ(edited->tables("materials")[1]->number("friction_angle"), 31.25);
  EXPECT_DOUBLE_EQ(edited->tables("materials")[1]->number("density"), 2500.0);
  EXPECT_DOUBLE_EQ(edited->tables("materials")[0]->number("density"), 250.0);
  EXPECT_DOUBLE_EQ(edited->table("basal")->number("mu"), expected->table("basal")->number("mu"));
  EXPECT_EQ(edited->table("basal")->string("law"), "voellmy");
  EXPECT_TRUE(edited->table("output")->boolean("maps", false));
  // Comments stay with their lines.
  EXPECT_NE(e.text.find("end_time = 12.5  # seconds"), std::string::npos) << e.text;
  EXPECT_NE(e.text.find("density = 2500.0  # granite"), std::string::npos);
  EXPECT_EQ(e.text.rfind("# A scene as a user writes it", 0), 0u);
}

TEST(SceneTextEdit, KeysItCannotPlaceSafelyAreReportedNotGuessed) {
  const SceneTextEdit e = assignInSceneText("[[bodies]]\nname = \"a\"\nlines = [\n 1,\n 2]\n",
                                            {"bodies.a.lines=3", "bodies.a.sub.x=1"});
  EXPECT_EQ(e.unplaced.size(), 2u);
  EXPECT_THROW(assignInSceneText(kScene, {"no_equals"}), std::invalid_argument);
}

TEST(SceneTextEdit, RelativeFilesBecomeAbsoluteSoTheTextCanLiveElsewhere) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "talus_test_scene_text_edit";
  fs::create_directories(dir / "terrain");
  std::ofstream(dir / "terrain" / "dem.asc") << "x";
  const SceneTextEdit e = assignInSceneText("[terrain]\ndem = \"terrain/dem.asc\"  # DEM\nkind = \"plane\"\n", {}, dir.string());
  EXPECT_NE(e.text.find("dem = \"" + (dir / "terrain" / "dem.asc").string() + "\"  # DEM"), std::string::npos) << e.text;
  EXPECT_NE(e.text.find("kind = \"plane\""), std::string::npos); // not a file: unchanged
  fs::remove_all(dir);
}
