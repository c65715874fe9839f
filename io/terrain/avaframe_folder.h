// An AvaFrame avalanche folder, read as AvaFrame's com1DFA lays it out (docs/moduleCom1DFA.rst,
// "Input", from version 1.11 to the 2025-11-06 snapshot; docs/hazard.md):
//
//   NAME/Inputs/       one DEM, *.asc (ESRI ASCII) or *.tif (GeoTIFF)
//   Inputs/REL/        release scenarios: each shapefile is one scenario whose features are
//                      released together; per feature `thickness` (legacy `d0`) and `ci95`
//   Inputs/ENT/        at most one shapefile of entrainment areas, attribute `thickness`
//   Inputs/RES/        at most one shapefile of resistance areas (forest)
//   Inputs/SECREL/, DAM/, RASTERS/, POLYGONS/, REFDATA/   recognised and reported, not applied
//   Inputs/LINES/path_aimec.shp   the AIMEC thalweg;   Inputs/POINTS/splitPoint.shp
//
// Only reads and validates: what the folder means for a scene is io/scene/avaframe_scene.
// Every problem is an InputError naming the file.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

namespace talus {

/// One polygon feature's AvaFrame attributes (NaN when absent or null).
struct AvaFrameFeature {
  std::string name;   ///< `name`/`Name` attribute, else "feature <fid>"
  double thickness;   ///< `thickness`, else the legacy `d0` (m, slope-normal)
  double ci95;        ///< 95 % confidence half-width of the thickness (m)
};

/// A shapefile of areas (release scenario, entrainment, resistance, secondary release).
struct AvaFrameAreas {
  std::string path;          ///< the .shp
  std::string name;          ///< its stem, e.g. "relWog"
  std::string thicknessField; ///< "thickness" or "d0" when every feature has one, else ""
  std::vector<AvaFrameFeature> features;
  std::string crsWkt;
};

struct AvaFrameFolder {
  std::string dir;        ///< the avalanche folder (holds Inputs/)
  std::string name;       ///< its name, e.g. "avaWog"
  std::string dem;        ///< Inputs/<dem>.asc or .tif
  std::string demCrsWkt;  ///< the DEM's own CRS ("" when it has none, as a .asc without .prj)
  std::vector<AvaFrameAreas> releases;
  std::optional<AvaFrameAreas> entrainment, resistance, secondaryRelease;
  std::string damFile; ///< DAM/<file>.shp: dam lines (vertex z = crest, `slope` attribute), or ""
  std::string thalwegFile;                  ///< Inputs/LINES/path_aimec.shp, or ""
  std::vector<Eigen::Vector2d> thalweg;     ///< its vertices (world, m)
  std::optional<Eigen::Vector2d> splitPoint; ///< Inputs/POINTS/splitPoint.shp
  /// What was found but is not used by a Talus run (one line each).
  std::vector<std::string> notes;

  /// The release scenario named `name` ("" = the only one); InputError listing them otherwise.
  const AvaFrameAreas& release(const std::string& name) const;
};

/// Reads and checks the folder: the layout, one DEM, shapefiles complete (.shp, .shx, .dbf),
/// polygon (or line, point) geometry, thickness attributes (all features or none; none >= 0),
/// and one CRS for all of them.
AvaFrameFolder readAvaFrameFolder(const std::string& dir);

/// A resistance (RES/) area as a basal-law region, with the parameters AvaFrame attaches to it.
/// AvaFrame's resistance (1.13 and the 2025-11 snapshot; com1DFACfg.ini defaults) is a drag
/// F = -cResH rho A |u| u, with detrainment dM/dt = -detK A / |u| below the forest thresholds.
/// Not applied by Talus yet: this is where per-region basal laws will connect.
struct ResistanceRegion {
  std::string polygonFile; ///< RES/<file>.shp
  int feature = 0;         ///< feature index in that file
  double cResH = 0.01;     ///< drag coefficient (1/m)
  bool detrainment = true;
  double detK = 5;         ///< detrainment: dM/dt = -detK A / |u| (AvaFrame's units)
  double forestVMin = 6, forestThMin = 0.6;  ///< below both (m/s, m): detrainment only
  double forestVMax = 40, forestThMax = 10;  ///< above either: no resistance
};
std::vector<ResistanceRegion> resistanceRegions(const AvaFrameFolder& folder);

} // namespace talus
