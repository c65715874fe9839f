// DIR/summary.json: what a run did, for humans and scripts.
#pragma once

#include "engine/simulation.h"
#include "io/common/json_text.h"
#include "io/output/output_set.h"

#include <string>
#include <vector>

namespace talus {

/// What one process holds at the end of a run (summary.json "memory_bytes"), bytes.
struct MemoryFigures {
  uint64_t particles = 0; ///< the engine's particles with their model state (Simulation::particleBytes)
  uint64_t grid = 0;      ///< grid blocks and the colliders' per-block samples (Simulation::gridBytes)
  uint64_t terrain = 0;   ///< the terrain's level set values in memory (Simulation::terrainBytes)
  uint64_t peakResident = 0; ///< the process's peak resident set (getrusage), program and outputs included
};
/// The engine's figures of `sim` and this process's peak resident set.
MemoryFigures memoryFigures(const Simulation& sim);

/// One MPI rank's share of a run (summary.json "ranks").
struct RankFigures {
  uint64_t particles = 0, blocks = 0, bytesSent = 0, rebalances = 0;
  uint64_t collectives = 0;        ///< MPI calls made (reductions, exchanges, gathers)
  double computeSeconds = 0;       ///< the step's phases other than communication
  double communicationSeconds = 0; ///< migration, halo, reductions and gathers (waiting included)
  MemoryFigures memory;            ///< the rank's engine (rank 0's output view only in peakResident)
};

struct RunInfo {
  std::string scene;
  double wallSeconds = 0;
  int threads = 1;
  std::vector<std::string> materialNames;
  std::string status = "completed"; ///< "failed: ...", or "interrupted" by a signal
  std::string signal;               ///< the signal that interrupted the run ("SIGTERM")
  std::vector<OutputReport> outputs;
  std::vector<std::string> notes; ///< the scene's notes and warnings (thin bodies, filled DEM cells)
  std::vector<RankFigures> ranks;  ///< under mpirun, per rank (empty for one process)
  uint64_t wholeGathers = 0;       ///< under mpirun: the times rank 0 gathered every particle
  MemoryFigures memory;            ///< one process's (under mpirun: per rank in `ranks`)
};

/// Writes summary.json and returns its text (the report page embeds it).
std::string writeSummaryJson(const std::string& path, const Simulation& sim, const RunInfo& info);


} // namespace talus
