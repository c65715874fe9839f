// The `talus` command line: run scenes, check them, and (later) prepare terrain and benchmarks.
#include "io/common/input_error.h"
#include "io/common/write_error.h"
#include "io/terrain/dem_raster.h"
#include "engine/mpi_communicator.h"
#include "io/run/run_driver.h"
#include "io/run/run_signals.h"
#include "io/scene/avaframe_scene.h"
#include "io/scene/scene.h"
#include "io/config/toml_reader.h"
#include "tools/analysis_commands.h"
#include "tools/animate_command.h"
#include "tools/render_command.h"
#include "tools/benchmark.h"
#include "tools/calibrate_command.h"
#include "tools/ensemble_command.h"
#include "tools/work_precision.h"
#include "tools/terrain_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>

using namespace talus;

namespace {

// Exit status: 0 done, 1 other failure, 2 bad input, 3 numerical failure, 4 an output could not
// be written (disk full, quota, read-only or removed folder), 128 + signal when interrupted.
constexpr int kExitWriteFailure = 4;

SceneSetup load(const std::string& scene, const std::vector<std::string>& sets, const SeedSlice& part = {}) {
  if (scene.empty()) return loadSceneString(defaultSceneText(), "<default scene>", sets, part);
  return loadSceneFile(scene, sets, part);
}

/// MPI ranks when started by mpirun/srun (null otherwise); only rank 0 prints.
std::shared_ptr<Communicator> gRanks;
bool isRoot() { return !gRanks || gRanks->rank() == 0; }

int cmdRun(const std::string& scene, const std::string& out, int threads, const std::vector<std::string>& sets,
           bool quiet, const std::string& resume) {
  quiet = quiet || !isRoot();
  if (!resume.empty() && !out.empty() && out != resume)
    throw InputError("--out", 0, "", "--resume continues in its own directory; do not give a different --out");
  // Under mpirun each rank seeds its part (a resumed run reads its particles from the checkpoint).
  SeedSlice part;
  if (gRanks && resume.empty()) part.part = gRanks->rank(), part.parts = gRanks->size();
  SceneSetup setup = load(scene, sets, part);
  if (!quiet)
    for (const auto& n : setup.notes) std::fprintf(stderr, "talus: %s\n", n.c_str());
  RunOptions opt;
  opt.outDir = resume.empty() ? out : resume;
  opt.resume = !resume.empty();
  opt.threads = threads;
  opt.progress = !quiet;
  opt.handleSignals = true;
  if (gRanks && gRanks->size() > 1) opt.ranks = gRanks;
  const size_t n = setup.seededParticles();
  if (!quiet)
    std::fprintf(stderr, "talus: %s: %zu particles, dx %g m, end time %g s\n", setup.file.c_str(), n,
                 setup.settings.dx, setup.endTime);
  const RunResult r = runScene(std::move(setup), opt);
  // How to continue: the same scene and overrides (the checkpoint is refused otherwise).
  std::string again = "talus run" + (scene.empty() ? std::string() : " " + scene);
  for (const auto& s : sets) again += " --set " + s;
  again += " --resume " + r.outDir;
  char at[96];
  std::snprintf(at, sizeof at, "t = %.6g s", r.checkpointTime);
  if (!isRoot() && r.status != RunStatus::Completed) // rank 0 reports; every rank exits alike
    return r.status == RunStatus::Interrupted ? 128 + r.signal : r.status == RunStatus::WriteFailure ? kExitWriteFailure : 3;
  switch (r.status) {
  case RunStatus::Completed: break;
  case RunStatus::NumericalFailure:
    std::fprintf(stderr, "talus: run stopped: %s\n", r.error.c_str());
    return 3;
  case RunStatus::WriteFailure:
    std::fprintf(stderr, "talus: error: %s; files written before are intact%s\n", r.error.c_str(),
                 r.checkpointTime >= 0 ? ("; continue from the checkpoint of " + std::string(at) + ": " + again).c_str() : "");
    return kExitWriteFailure;
  case RunStatus::Interrupted:
    std::fprintf(stderr, "talus: interrupted by %s at step %llu, %s; checkpoint written; continue with: %s\n",
                 signalName(r.signal).c_str(), (unsigned long long)r.steps, at, again.c_str());
    return 128 + r.signal;
  }
  if (!quiet) {
    std::fprintf(stderr, "talus: done in %.1f s, results in %s/\n", r.wallSeconds, r.outDir.c_str());
    const auto first = filesToOpenFirst(r);
    if (!first.empty()) std::fprintf(stderr, "talus: open first %s/%s\n", r.outDir.c_str(), first[0].c_str());
    std::string also;
    for (size_t i = 1; i < first.size(); ++i) also += (i > 1 ? ", " : "") + first[i];
    if (!also.empty()) std::fprintf(stderr, "talus: then %s (maps/*.tif beside the PNGs open in GIS)\n", also.c_str());
  }
  return 0;
}

int cmdCheck(const std::string& scene, const std::vector<std::string>& sets) {
  SceneSetup s = load(scene, sets);
  std::printf("%s: ok\n", s.file.c_str());
  for (const auto& n : s.notes) std::printf("  %s\n", n.c_str());
  for (const auto& b : s.bodies)
    if (b.fieldMass > 0) // a cover made an erodible field (io/scene/erodible_cover_reader.h)
      std::printf("  %-16s %-10s %-8s erodible field of %.6g kg, geometric %.6g m3\n", b.label.c_str(),
                  b.material.c_str(), b.kind.c_str(), b.fieldMass, b.geometricVolume);
    else
      std::printf("  %-16s %-10s %-8s %9zu particles, seeded %.6g m3 / geometric %.6g m3%s\n", b.label.c_str(),
                  b.material.c_str(), b.kind.c_str(), b.particles, b.seededVolume, b.geometricVolume,
                  b.massScale != 1 ? (", masses x " + std::to_string(b.massScale).substr(0, 6) + " to hold it").c_str() : "");
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"Talus: 3D material point method for alpine mass movements and process cascades"};
  app.require_subcommand(1);

  std::string scene, out, avaframe;
  int threads = 0;
  std::vector<std::string> sets;
  bool quiet = false;
  auto* run = app.add_subcommand("run", "Run a scene (the embedded default scene when none is given)");
  run->add_option("scene", scene, "Scene file (TOML)");
  run->add_option("--out", out, "Output directory (overrides [output].directory)");
  run->add_option("--threads", threads, "Worker threads (default: all)")->check(CLI::PositiveNumber);
  run->add_option("--set", sets, "Override a scene key: --set simulation.dx=0.02");
  run->add_flag("--quiet", quiet, "No progress bar or messages");
  run->add_option("--avaframe", avaframe, "An AvaFrame avalanche folder (DEM, REL/, ENT/, ...): sets avaframe.directory");
  std::string resume;
  run->add_option("--resume", resume, "Continue the run in DIR from DIR/checkpoint.h5 (same scene)");

  auto* check = app.add_subcommand("check", "Validate a scene and report the particles each body seeds");
  check->add_option("scene", scene, "Scene file (TOML)");
  check->add_option("--set", sets, "Override a scene key");
  check->add_option("--avaframe", avaframe, "An AvaFrame avalanche folder: sets avaframe.directory");

  auto* defaults = app.add_subcommand("default-scene", "Print the embedded default scene");

  WorkPrecisionOptions wp;
  std::string single;
  validation::Resolution singleRes{0, 8, 0.4, 0};
  auto* wpCmd = app.add_subcommand("work-precision",
                                   "Refine the validation cases; write docs/performance.md and its error-vs-time plot");
  wpCmd->add_option("--out", wp.markdown, "Markdown report");
  wpCmd->add_option("--image", wp.image, "PNG plot of error against wall time");
  wpCmd->add_option("--shared", wp.sharedDir, "The ../shared directory (dam-break data)");
  wpCmd->add_option("--double", wp.doubleBinary, "A talus built with -DTALUS_DOUBLE=ON");
  wpCmd->add_flag("--quick", wp.quick, "Fewer, coarser runs");
  wpCmd->add_option("--single", single, "Run one case and print: error wall particles steps figures");
  wpCmd->add_option("--cells", singleRes.cells, "Resolution for --single");
  wpCmd->add_option("--ppc", singleRes.particlesPerCell, "Particles per cell for --single (8)")->check(CLI::Range(1, 64));
  wpCmd->add_option("--cfl", singleRes.cfl, "CFL number for --single (0.4)")->check(CLI::Range(0.01, 1.0));
  wpCmd->add_option("--flip", singleRes.flip, "AFLIP blend for --single (0: APIC)")->check(CLI::Range(0.0, 1.0));
  wpCmd->add_flag("--fbar", singleRes.fbar, "F-bar for --single");
  wpCmd->add_option("--bed-offset", singleRes.bedOffset, "Column collapses: bed raised by this many cells (--single)")
      ->check(CLI::Range(0.0, 1.0));
  wpCmd->add_option("--sound-speed", singleRes.soundSpeed, "Water cases: the softened water's c in m/s (--single)")
      ->check(CLI::PositiveNumber);
  bool singleScene = false;
  wpCmd->add_flag("--scene", singleScene, "With --single: print the case's scene file instead of running it (obstacle_impact)");

  BenchOptions bench;
  auto* benchCmd = app.add_subcommand("bench", "Measure particle-steps per second per core, phase times, memory");
  benchCmd
      ->add_option("--case", bench.cases, "Benchmark cases: built-in names, or scene files (*.toml, --scale refines their dx)")
      ->check(CLI::IsMember(benchmarkCaseNames()) | CLI::ExistingFile);
  benchCmd->add_option("--threads", bench.threads, "Thread counts to run (default: 1 2)");
  benchCmd->add_option("--steps", bench.steps, "Timed steps per run")->check(CLI::PositiveNumber);
  benchCmd->add_option("--scale", bench.scale, "Particle count multiplier")->check(CLI::PositiveNumber);
  benchCmd->add_option("--flip", bench.flip, "AFLIP blend of every case (0: APIC)")->check(CLI::Range(0.0, 1.0));
  benchCmd->add_flag("--fbar", bench.fbar, "F-bar in every case");
  bool benchRanks = false;
  benchCmd->add_flag("--ranks", benchRanks,
                     "Under mpirun: distribute each case over the ranks (threads per rank: the first --threads)");

  TerrainCommandOptions terrainOpt;
  auto* terrainCmd = addTerrainCommand(app, terrainOpt);
  SynthDemOptions synthOpt;
  auto* synthCmd = addSynthDemCommand(app, synthOpt);
  EnsembleOptions ensembleOpt;
  auto* ensembleCmd = addEnsembleCommand(app, ensembleOpt);
  CalibrateOptions calibrateOpt;
  auto* calibrateCmd = addCalibrateCommand(app, calibrateOpt);
  AnalysisOptions analysisOpt;
  const AnalysisCommands analysisCmds = addAnalysisCommands(app, analysisOpt);
  AnimateOptions animateOpt;
  auto* animateCmd = addAnimateCommand(app, animateOpt);
  RenderCommandOptions renderOpt;
  auto* renderCmd = addRenderCommand(app, renderOpt);

  CLI11_PARSE(app, argc, argv);
  try {
    if (launchedAsRanks()) gRanks = worldCommunicator(&argc, &argv);
    if (!avaframe.empty()) sets.push_back(avaFrameOverride(avaframe));
    if (*run) return cmdRun(scene, out, threads, sets, quiet, resume);
    if (*check) return cmdCheck(scene, sets);
    if (*benchCmd && benchRanks) {
      if (!gRanks) throw InputError("--ranks", 0, "", "start the benchmark with mpirun: mpirun -np 2 talus bench --ranks --threads 1");
      return runRankBenchmarks(bench, gRanks);
    }
    if (*benchCmd) return runBenchmarks(bench);
    if (*wpCmd) return single.empty() ? runWorkPrecision(wp) : runSingleCase(single, singleRes, wp.sharedDir, singleScene);
    if (*terrainCmd) return runTerrainCommand(terrainOpt);
    if (*synthCmd) return runSynthDemCommand(synthOpt);
    if (*ensembleCmd) return runEnsembleCommand(ensembleOpt);
    if (*calibrateCmd) return runCalibrateCommand(calibrateOpt);
    if (*animateCmd) return runAnimateCommand(animateOpt);
    if (*renderCmd) return runRenderCommand(renderOpt);
    if (const int rc = runAnalysisCommand(analysisCmds, analysisOpt); rc >= 0) return rc;
    if (*defaults) {
      std::cout << defaultSceneText();
      return 0;
    }
  } catch (const InputError& e) {
    // Every rank reads the same inputs and fails alike: rank 0 speaks for them.
    if (isRoot()) std::fprintf(stderr, "talus: error: %s\n", e.what());
    return 2;
  } catch (const WriteError& e) {
    std::fprintf(stderr, "talus: error: %s\n", e.what());
    return kExitWriteFailure;
  } catch (const std::exception& e) {
    if (isRoot()) std::fprintf(stderr, "talus: error: %s\n", e.what());
    else std::fprintf(stderr, "talus: error on rank %d: %s\n", gRanks->rank(), e.what());
    return 1;
  }
  return 0;
}
