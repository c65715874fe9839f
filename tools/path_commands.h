// `talus map-stats --aimec` and `talus compare --aimec`: AvaFrame's AIMEC path analysis
// (hazard/aimec.h) of one run, or of a run against another or a reference.
#pragma once

#include "tools/analysis_commands.h"

namespace talus {

void addAimecOptions(CLI::App* mapStats, CLI::App* compare, AnalysisOptions& o);
int runAimecMapStats(const AnalysisOptions& o);
int runAimecCompare(const AnalysisOptions& o);

} // namespace talus
