// The table of material models (io/scene/model_table.cpp): every name it lists builds that
// model, and a name it does not list is refused with the valid ones.
#include "io/config/toml_reader.h"
#include "io/scene/model_table.h"

#include <gtest/gtest.h>

using namespace talus;

TEST(ModelTable, EveryListedModelBuildsItsOwnGroup) {
  // Review defect: names and construction branches were two lists, and a name without a branch
  // silently built water. Each name must build a group of that model.
  for (const std::string& model : materialModelNames()) {
    auto root = readTomlString("[m]\nname = \"x\"\nmodel = \"" + model +
                                   "\"\ndensity = 1000\nyoungs_modulus = 1e6\nfriction_angle = 30\n"
                                   "critical_state_slope = 1\npreconsolidation_pressure = 1e4\nhardening = 1\n"
                                   "bulk_modulus = 1e6\n",
                               "t.toml");
    const auto g = createMaterialGroup(*root->table("m"), 0);
    EXPECT_EQ(std::string(g->modelName()), model);
  }
}

TEST(ModelTable, AnUnknownModelNamesTheValidOnes) {
  auto root = readTomlString("[m]\nname = \"x\"\nmodel = \"plasticine\"\ndensity = 1000\n", "t.toml");
  try {
    createMaterialGroup(*root->table("m"), 0);
    FAIL();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.line(), 3);
    for (const std::string& model : materialModelNames()) EXPECT_NE(msg.find(model), std::string::npos) << msg;
  }
}
