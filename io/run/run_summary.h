// DIR/summary.json: what a run did, for humans and scripts.
#pragma once

#include "engine/simulation.h"
#include "io/common/json_text.h"
#include "io/output/output_set.h"

#include <string>
#include <vector>

namespace talus {

/// One MPI rank's share of a run (summary.json "ranks").
struct RankFigures {
  uint64_t particles = 0, blocks = 0, bytesSent = 0, rebalances = 0;
  double computeSeconds = 0;       ///< the step's phases other than communication
  double communicationSeconds = 0; ///< migration, halo, reductions and gathers (waiting included)
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
};

/// Writes summary.json and returns its text (the report page embeds it).
std::string writeSummaryJson(const std::string& path, const Simulation& sim, const RunInfo& info);


} // namespace talus
