#include "tools/ensemble_command.h"

#include "hazard/ensemble_aggregate.h"
#include "hazard/ensemble_plan.h"
#include "hazard/ensemble_runner.h"
#include "io/common/input_error.h"
#include "io/run/run_signals.h"
#include "io/scene/avaframe_scene.h"
#include "io/scene/scene.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace talus {

namespace fs = std::filesystem;
using namespace ensemble;

namespace {

/// The scene as member 0 runs it: bad --vary keys or values fail here, before any member runs,
/// and the error names the --vary it comes from.
SceneSetup validate(const EnsembleOptions& o, const Plan& plan, const std::vector<std::string>& base) {
  std::vector<std::string> sets = base;
  for (const auto& s : plan.overrides(0)) sets.push_back(s);
  try {
    return loadSceneFile(o.scene, sets);
  } catch (const InputError& e) {
    loadSceneFile(o.scene, base); // the scene itself at fault: its own error
    std::string culprit;
    for (const auto& v : plan.vary) {
      const std::string last = v.key.substr(v.key.rfind('.') + 1);
      if (e.key().size() >= last.size() && e.key().compare(e.key().size() - last.size(), last.size(), last) == 0)
        culprit = v.text;
    }
    if (culprit.empty())
      for (const auto& v : plan.vary) culprit += (culprit.empty() ? "" : ", ") + v.text;
    throw InputError("--vary", 0, culprit, e.what());
  }
}

void writePlan(const fs::path& dir, const Plan& plan) {
  const fs::path file = dir / "plan.csv";
  const std::string text = plan.csv();
  if (fs::exists(file)) {
    std::ifstream in(file);
    std::stringstream old;
    old << in.rdbuf();
    if (old.str() != text)
      throw InputError(file.string(), "holds another plan (other --vary, --samples, --method or --seed): "
                                      "give another --out, or remove the folder");
    return;
  }
  fs::create_directories(dir);
  std::ofstream(file) << text;
}

} // namespace

CLI::App* addEnsembleCommand(CLI::App& app, EnsembleOptions& o) {
  auto* c = app.add_subcommand("ensemble", "Run a scene many times over varied keys; probability maps and run-out "
                                           "distributions from the members' peak files");
  c->add_option("scene", o.scene, "Scene file (TOML)")->required();
  c->add_option("--vary", o.vary, "KEY=LOW:HIGH, any numeric scene key (repeatable)")->required();
  c->add_option("--samples", o.samples, "Members (lhs), levels per key (grid) or trajectories (morris)")->required();
  c->add_option("--method", o.method, "lhs, grid or morris");
  c->add_option("--seed", o.seed, "Seed of the lhs and morris sampling");
  c->add_option("--out", o.out, "Ensemble folder (members in member_NNN/)");
  c->add_option("--threads", o.threads, "Threads per member")->check(CLI::PositiveNumber);
  c->add_option("--jobs", o.jobs, "Members at a time (default: cores / threads)")->check(CLI::PositiveNumber);
  c->add_option("--set", o.sets, "Override a scene key in every member");
  c->add_option("--avaframe", o.avaframe, "An AvaFrame avalanche folder: sets avaframe.directory");
  c->add_flag("--aggregate-only", o.aggregateOnly, "Summarise the members present; run none");
  return c;
}

int runEnsembleCommand(const EnsembleOptions& o) {
  const auto vary = parseVaries(o.vary);
  const Plan plan = makePlan(vary, parseMethod(o.method), o.samples, o.seed);
  std::vector<std::string> base = o.sets;
  if (!o.avaframe.empty()) base.push_back(avaFrameOverride(o.avaframe));
  base.push_back("output.peak_files=true"); // members are summarised from their peak files
  base.push_back("output.animation=false"); // and nobody watches a member's film
  const SceneSetup scene = validate(o, plan, base);
  if (!scene.output.maps.enabled)
    throw InputError(o.scene, "an ensemble is summarised from the members' hazard maps: give [output] maps = true");
  const fs::path dir = fs::absolute(o.out);
  writePlan(dir, plan);
  const std::string sceneFile = fs::absolute(o.scene).string();
  const int jobs = o.jobs > 0 ? o.jobs : std::max(1, int(std::thread::hardware_concurrency()) / o.threads);
  std::fprintf(stderr, "talus ensemble: %zu members of %s (%s, %zu key%s), %d at a time with %d thread%s each, in %s\n",
               plan.members(), o.scene.c_str(), o.method.c_str(), vary.size(), vary.size() > 1 ? "s" : "", jobs,
               o.threads, o.threads > 1 ? "s" : "", dir.c_str());

  std::vector<MemberJob> members;
  for (size_t m = 0; m < plan.members(); ++m) {
    MemberJob j;
    j.index = m;
    j.dir = (dir / memberName(m)).string();
    j.args = memberArguments(sceneFile, j.dir, o.threads, base, plan.overrides(m));
    members.push_back(j);
  }
  RunReport run;
  int stoppedBy = 0;
  if (!o.aggregateOnly) {
    // SIGINT/SIGTERM: start no more members and wait for the running ones, which got the signal
    // too (the terminal's process group, a batch job's processes) and stop at a checkpoint.
    RunSignals signals(/*announce=*/false);
    ProcessLauncher launcher(selfProgram());
    run = runMembers(members, resumeArguments, // a killed member continues from its checkpoint
        size_t(jobs), launcher, stderr, [] { return stopSignalReceived() != 0; });
    stoppedBy = run.stopped ? stopSignalReceived() : 0;
  }
  if (stoppedBy) {
    std::fprintf(stderr, "talus ensemble: interrupted by %s; %zu of %zu members completed; run the same command again "
                 "to resume the others from their checkpoints\n", signalName(stoppedBy).c_str(), run.completed, members.size());
    return 128 + stoppedBy;
  }
  const AggregateReport agg = aggregate(dir.string(), plan, scene.ensemble, scene.dem);
  size_t completed = 0;
  for (const auto& m : agg.members) completed += m.completed;
  std::fprintf(stderr, "talus ensemble: %zu of %zu members completed (%zu kept from before)%s, results in %s/\n",
               completed, plan.members(), run.skipped,
               o.aggregateOnly ? "" : (", " + std::to_string(int(run.wallSeconds + 0.5)) + " s wall").c_str(), dir.c_str());
  for (const auto& f : agg.files)
    if (f.rfind("maps/prob_", 0) == 0 && f.size() > 4 && f.compare(f.size() - 4, 4, ".png") == 0) {
      std::fprintf(stderr, "talus ensemble: open first %s/%s, then members.csv%s\n", dir.c_str(), f.c_str(),
                   scene.ensemble.path.empty() ? "" : " and runout.png");
      break;
    }
  if (completed < plan.members()) {
    std::fprintf(stderr, "talus ensemble: %zu member(s) failed; run the same command again to retry them\n",
                 plan.members() - completed);
    return 3;
  }
  return 0;
}

} // namespace talus
