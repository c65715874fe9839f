// `talus profile`, `talus map-stats`, `talus compare`, `talus series-stats`: post-processing of
// a run's maps and series (tools/analysis.h does the work).
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace talus {

struct AnalysisOptions {
  // profile
  std::vector<std::string> rasters, labels;
  std::string line, ground, csv, plot, title;
  double step = 0; ///< 0: the first raster's cell size
  // map-stats / compare
  std::vector<double> thresholds;
  std::string path, simulation, reference, dem, png;
  double halfWidth = std::numeric_limits<double>::infinity();
  // AIMEC path analysis (map-stats / compare --aimec): tools/path_commands.cpp
  bool aimec = false;
  double domainWidth = 600; ///< AIMEC's domainWidth (m)
  double cellSL = 0;        ///< (s, l) cell; 0 = the (reference) raster's
  double runoutAreaAngle = 0; ///< > 0: compare areas only from where the thalweg flattens below this (deg)
  std::string splitPoint;   ///< "x,y": the run-out area starts after it
  double scale = 1;         ///< multiplies the section integrals (a density: an erosion depth's kg/m)
  std::string integralPlot; ///< the section integral per metre along s
  std::string integralLabel; ///< its axis label (e.g. "entrained snow (kg/m)")
  // series-stats
  std::string series;
  double restFraction = 0.01;
  double frontStep = 5, frontWindow = 25;
  std::string frontPlot, frontCsv;
};

struct AnalysisCommands {
  CLI::App* profile = nullptr;
  CLI::App* mapStats = nullptr;
  CLI::App* compare = nullptr;
  CLI::App* seriesStats = nullptr;
};

AnalysisCommands addAnalysisCommands(CLI::App& app, AnalysisOptions& o);
/// Runs whichever of the commands was chosen; -1 when none was.
int runAnalysisCommand(const AnalysisCommands& c, const AnalysisOptions& o);

} // namespace talus
