// `talus terrain` (DEM -> level set file) and `talus synth-dem` (synthetic DEM -> GeoTIFF).
#pragma once

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace talus {

struct TerrainCommandOptions {
  std::string dem, out;
  double dx = 0;            ///< 0: the DEM's cell size
  double smooth = 0;
  std::vector<double> bounds; ///< xmin ymin xmax ymax, empty: the whole DEM
  std::vector<double> origin; ///< x y z of voxel (0,0,0); empty: (0, 0, 0)
  int band = 3;
  bool fillNodata = false;
  bool verticalDistance = false;
  std::string crs;
};

struct SynthDemOptions {
  std::string kind, out;
  double cell = 0;
  std::vector<std::string> sets;
  bool list = false;
};

/// Registers the two subcommands on `app`; the returned pointers tell which one was chosen.
CLI::App* addTerrainCommand(CLI::App& app, TerrainCommandOptions& o);
CLI::App* addSynthDemCommand(CLI::App& app, SynthDemOptions& o);

int runTerrainCommand(const TerrainCommandOptions& o);
int runSynthDemCommand(const SynthDemOptions& o);

} // namespace talus
