#include "io/run/run_driver.h"

#include "io/run/run.h"

#include <algorithm>

namespace talus {

std::vector<std::string> filesToOpenFirst(const RunResult& r) {
  std::vector<std::string> out;
  for (const char* f : {"animation.mp4", "report.html", "maps/max_flow_height_vertical.png", "maps/max_speed.png", "maps/max_pressure.png",
                        "plots/kinetic_energy.png", "series.csv", "summary.json"})
    if (std::find(r.files.begin(), r.files.end(), f) != r.files.end()) out.push_back(f);
  return out;
}

RunResult runScene(SceneSetup&& scene, const RunOptions& opt) {
  Run run(std::move(scene), opt);
  while (run.step()) {
  }
  return run.result();
}

} // namespace talus
