// A scene file turned into everything a run needs: settings, seeded material groups, outputs.
#pragma once

#include "io/config/config_table.h"
#include "engine/simulation.h"
#include "io/output/run_context.h"
#include "io/scene/body_seeding.h"
#include "io/scene/ensemble_settings.h"
#include "io/scene/output_reader.h"
#include "io/common/raster_grid.h"

#include <memory>
#include <string>
#include <vector>

namespace talus {

struct SceneSetup {
  std::string file;
  SimulationSettings settings;
  std::vector<std::unique_ptr<MaterialGroup>> groups;
  std::vector<std::string> materialNames;
  std::vector<std::string> materialModels; ///< per material, its model's name ("water", ...)
  double endTime = 1;
  int particlesPerCell = 8;
  double maxParticles = 2e9; ///< [simulation] max_particles, capped by resourceLimits()
  OutputSettings output;
  std::vector<BodyReport> bodies;
  EnsembleSettings ensemble; ///< [ensemble]: used by `talus ensemble` only
  /// The DEM the terrain was built from, when it was built from one (maps use its grid and CRS):
  /// the ground as simulated, i.e. after smoothing, with releases from a post-event DEM carved
  /// out and fixed layers added.
  std::shared_ptr<const DemRaster> dem;
  /// Every key of the scene after --set overrides and AvaFrame expansion, one "key = value" line
  /// each, less those a resumed run may change (simulation.end_time, output.directory, the frame
  /// formats and intervals, plots, series_interval): what decides the state a checkpoint holds.
  std::string stateKeys;
  /// Every key after overrides (ConfigTable::keyLines): what a run records of its configuration.
  std::string keyLines;
  /// 16 hex digits identifying that state: FNV-1a over stateKeys. A checkpoint is resumed only by
  /// a scene with the same hash, so a run can be extended (a later end_time) but not given other
  /// physics.
  std::string hash;
  /// What the reader did that a user may want to know (terrain built or reused, cells filled).
  std::vector<std::string> notes;
  /// Under MPI ranks, the rank's part of the seeding and one process's index of each particle
  /// (io/scene/particle_seeding.h); parts == 1 otherwise.
  SeedSlice seedSlice;
  /// Particles one process seeds (the groups hold fewer when the seeding is split over ranks).
  size_t seededParticles() const;

  /// What the outputs need to know of this scene.
  RunContext runContext() const;
};

/// Reads every section, creates and seeds the material groups, and rejects unknown keys.
/// Throws InputError naming file, line and key.
SceneSetup buildScene(const ConfigTable& root, const SeedSlice& slice = {});

/// Convenience: parse a file (or text) with `--set` overrides and build it.
/// `slice` (part, parts): seed only this rank's part (see SeedSlice).
SceneSetup loadSceneFile(const std::string& path, const std::vector<std::string>& overrides = {},
                         const SeedSlice& slice = {});
SceneSetup loadSceneString(const std::string& text, const std::string& name,
                           const std::vector<std::string>& overrides = {}, const SeedSlice& slice = {});

/// A scene already parsed (the Python module builds `root` from a dict): overrides applied to it,
/// then built. Throws InputError naming root's file and the key.
SceneSetup loadSceneTable(ConfigTable& root, const std::vector<std::string>& overrides = {},
                          const SeedSlice& slice = {});

/// The scene `talus run` uses when no file is given (data/scenes/default.toml, compiled in).
const std::string& defaultSceneText();

} // namespace talus
