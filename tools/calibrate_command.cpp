#include "tools/calibrate_command.h"

#include "hazard/calibration.h"
#include "hazard/ensemble_runner.h"
#include "io/common/input_error.h"
#include "io/config/scene_text_edit.h"
#include "io/run/run_signals.h"
#include "io/scene/avaframe_scene.h"
#include "io/scene/scene.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace talus {

namespace fs = std::filesystem;
using namespace calibration;

namespace {

/// The scene with the calibrated values (and the user's --set), paths made absolute, so it runs
/// from the results folder as `talus run calibrated.toml`.
void writeCalibratedScene(const CalibrateOptions& o, const std::vector<std::string>& userSets,
                          const CalibrationResult& r, const fs::path& dir) {
  std::ifstream in(o.scene);
  std::stringstream text;
  text << in.rdbuf();
  std::vector<std::string> sets = userSets;
  sets.insert(sets.end(), r.overrides.begin(), r.overrides.end());
  const SceneTextEdit e = assignInSceneText(text.str(), sets, fs::absolute(o.scene).parent_path().string());
  std::ofstream out(dir / "calibrated.toml");
  out << "# " << fs::absolute(o.scene).string() << " calibrated by `talus calibrate` (" << dir.string()
      << "/result.json):\n";
  for (const auto& s : r.overrides) out << "#   " << s << "\n";
  for (const auto& s : e.unplaced) out << "# not written in place, give it as --set: " << s << "\n";
  out << e.text;
}

} // namespace

CLI::App* addCalibrateCommand(CLI::App& app, CalibrateOptions& o) {
  auto* c = app.add_subcommand("calibrate", "Back-analysis: the parameters whose run best matches an observed event "
                                            "(Morris screening, then a Gaussian-process search)");
  c->add_option("scene", o.scene, "Scene file (TOML)")->required();
  c->add_option("--vary", o.vary, "KEY=LOW:HIGH, a numeric scene key to calibrate (repeatable)")->required();
  c->add_option("--observed", o.observed, "footprint=POLYGONS, runout=X,Y or raster=FILE (repeatable)")->required();
  c->add_option("--weight", o.weights, "KIND=W: weight of that observation's loss term (default 1)");
  c->add_option("--raster-result", o.rasterResult, "Peak field the raster observation is compared with (pft, ppr, pfv)");
  c->add_option("--budget", o.budget, "Members in all")->check(CLI::PositiveNumber);
  c->add_option("--initial", o.initial, "Latin-hypercube members before the search (default 2k + 2)");
  c->add_option("--screen", o.screen, "Morris trajectories of the screening (0: none; one parameter: none)");
  c->add_option("--screen-keep", o.screenKeep, "Keep a parameter whose mu* reaches this fraction of the largest");
  c->add_option("--tolerance", o.tolerance, "Loss above the best within which parameters are plausible");
  c->add_option("--ei-stop", o.eiStop, "Stop when the expected improvement falls below this fraction of the losses' range");
  c->add_option("--seed", o.seed, "Seed of the screening and the initial design");
  c->add_option("--out", o.out, "Calibration folder (members in member_NNN/)");
  c->add_option("--threads", o.threads, "Threads per member")->check(CLI::PositiveNumber);
  c->add_option("--jobs", o.jobs, "Members at a time (default: cores / threads)")->check(CLI::PositiveNumber);
  c->add_option("--set", o.sets, "Override a scene key in every member");
  c->add_option("--avaframe", o.avaframe, "An AvaFrame avalanche folder: sets avaframe.directory");
  return c;
}

int runCalibrateCommand(const CalibrateOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  CalibrationSettings s;
  s.vary = ensemble::parseVaries(o.vary);
  s.budget = o.budget, s.initial = o.initial, s.screen = o.screen, s.screenKeep = o.screenKeep;
  s.tolerance = o.tolerance, s.eiStop = o.eiStop, s.seed = o.seed;
  std::vector<std::string> userSets = o.sets;
  if (!o.avaframe.empty()) userSets.push_back(avaFrameOverride(o.avaframe));
  std::vector<std::string> base = userSets;
  base.push_back("output.peak_files=true"); // members are compared through their peak files
  base.push_back("output.animation=false");
  std::vector<std::string> probe = base;    // the scene at the ranges' low ends: bad keys fail here
  for (const auto& v : s.vary) probe.push_back(v.key + "=" + parameterText(v, 0.0));
  const SceneSetup scene = loadSceneFile(o.scene, probe);
  if (!scene.output.maps.enabled)
    throw InputError(o.scene, "a calibration compares the members' peak files: give [output] maps = true");
  std::vector<Observation> observed;
  for (const auto& t : o.observed) observed.push_back(parseObservation(t));
  for (const auto& w : o.weights) applyWeight(observed, w);
  ObservedEvent event(observed, scene.ensemble, o.rasterResult, scene.dem);

  const fs::path dir = fs::absolute(o.out);
  const int jobs = o.jobs > 0 ? o.jobs : std::max(1, int(std::thread::hardware_concurrency()) / o.threads);
  s.batch = size_t(jobs);
  std::fprintf(stderr, "talus calibrate: up to %zu members of %s (%zu key%s), %d at a time, in %s\n", s.budget,
               o.scene.c_str(), s.vary.size(), s.vary.size() > 1 ? "s" : "", jobs, dir.c_str());
  RunSignals signals(/*announce=*/false);
  ensemble::ProcessLauncher launcher(ensemble::selfProgram());
  const std::string sceneFile = fs::absolute(o.scene).string();
  const MemberRunner runner = [&](const std::vector<MemberRequest>& reqs) {
    std::vector<ensemble::MemberJob> jobsList;
    for (const auto& r : reqs) {
      ensemble::MemberJob j;
      j.index = r.index, j.dir = r.dir;
      j.args = ensemble::memberArguments(sceneFile, j.dir, o.threads, base, r.overrides);
      jobsList.push_back(j);
    }
    const auto rep = ensemble::runMembers(jobsList, ensemble::resumeArguments, // killed members continue
        size_t(jobs), launcher, nullptr, [] { return stopSignalReceived() != 0; });
    return !rep.stopped;
  };
  const CalibrationResult r = calibrate(dir.string(), s, event, runner, stderr);
  if (r.stopped) {
    std::fprintf(stderr, "talus calibrate: interrupted by %s after %zu members; run the same command again to "
                 "continue\n", signalName(stopSignalReceived()).c_str(), r.proposed);
    return 128 + stopSignalReceived();
  }
  writeCalibratedScene(o, userSets, r, dir);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "talus calibrate: best %s, loss %.4g (%s = %s), %zu members, %.0f s wall\n",
               ensemble::memberName(r.best).c_str(), r.terms.total, event.csvHeader().c_str(),
               event.csvValues(r.terms).c_str(), r.members, wall);
  for (size_t p = 0; p < s.vary.size(); ++p)
    std::fprintf(stderr, "  %-40s %.6g  (loss within +%g: %.4g .. %.4g)%s\n", s.vary[p].key.c_str(), r.values[p],
                 s.tolerance, r.low[p], r.high[p], r.kept[p] ? "" : "  fixed by the screening");
  std::fprintf(stderr, "talus calibrate: the calibrated scene is %s/calibrated.toml; see loss_*.png and "
               "best_against_observed.png\n", dir.c_str());
  return 0;
}

} // namespace talus
