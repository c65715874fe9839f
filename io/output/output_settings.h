// What a run writes: the [output] section of a scene (docs/outputs.md lists every key).
//
// Defaults: the time series (with its plots and collider loads) is on; frames are written only
// when frame_interval > 0, and then as HDF5 particles and VDB volumes unless switched off; VDB
// points, PLY and hazard maps are off unless requested, so a scene without maps never
// accumulates them.
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace talus {

/// A vertical section through which discharge is measured: a polyline in world xy, extended
/// vertically over [zMin, zMax] (world z).
struct SectionSpec {
  std::string name;
  std::vector<Eigen::Vector2d> points;
  double zMin = -std::numeric_limits<double>::infinity();
  double zMax = std::numeric_limits<double>::infinity();
};

/// A path in world xy along which the flow front is tracked.
struct PathSpec {
  std::string name;
  std::vector<Eigen::Vector2d> points;
  double threshold = 0; ///< flow thickness (m) that counts as "reached"; 0 = one particle spacing
  double halfWidth = 0; ///< corridor half-width (m) searched either side of the path
  double minSpeed = 0;  ///< particles slower than this (m/s) are ignored: a resting cover is no front
  std::vector<std::string> materials; ///< only these count; empty = all
};

/// A point advected with the flow ([[output.probes]]), whose speed is recorded.
struct ProbeSpec {
  std::string name;
  Eigen::Vector3d point = Eigen::Vector3d::Zero(); ///< world (m); z unused unless hasZ
  bool hasZ = false;    ///< [x, y] given: start at the mass-weighted mean height of that column
  double radius = 0;    ///< m; 0 = two grid cells
  std::vector<std::string> materials; ///< empty = all
};

/// A wave gauge ([[output.gauges]]): the water's surface elevation at a point of world xy
/// (io/output/water_gauges.h).
struct GaugeSpec {
  std::string name;
  Eigen::Vector2d point = Eigen::Vector2d::Zero(); ///< world xy (m)
  double radius = 0; ///< half-width of the square footprint (m); 0 = one grid cell
};

/// AvaFrame peak files (peakFiles/<simName>_pft.asc ...) written from the hazard maps; the name
/// parts follow AvaFrame's simName (io/output/peak_files.h, docs/hazard.md).
struct PeakFileSettings {
  bool enabled = false;
  std::string format;                  ///< "asc", "tif" or "both"; "" = the DEM's format
  std::string releaseName = "release"; ///< the release scenario (first release body)
  std::string simType = "null";        ///< "null" (releases only) or "ent" (with covers)
  std::string simHash = "0000000000";  ///< 10 hex digits naming the scene's configuration
  std::string grid = "dem";            ///< "dem" (the maps' grid) or "com1dfa" (com1DFA's mesh)
  double meshCellSize = 5;             ///< com1DFA's meshCellSize (m), for grid = "com1dfa"
};

/// The film of a run (io/output/animation.h): frames recorded with the hazard maps.
struct AnimationSettings {
  bool enabled = false;
  std::optional<bool> requested; ///< as the scene says; unset: on for scenes on terrain with maps
  double interval = 0;          ///< s between frames; 0 = end_time / 100
  std::string quantity = "thickness";
  int fps = 10;
  double scaleMax = 0;          ///< top of the colour scale; 0 = the film's largest value
};

struct MapSettings {
  bool enabled = false;
  double cellSize = 0;       ///< m, when the scene has no DEM; 0 = two grid cells
  bool perMaterial = false;  ///< also one set of maps per material
  bool quicklook = true;     ///< PNG next to every GeoTIFF
  double minHeight = 0;      ///< speed and pressure count only where flow height >= this (m)
  /// Flow height, speed, pressure and the film count only particles at least this fast (m/s):
  /// a resting snowpack or cover is then not reported as flow. 0 (AvaFrame's way): every particle.
  double minSpeed = 0;
  double interval = 0;       ///< s between accumulations; 0 = every step
  std::vector<std::string> erodible; ///< materials whose lost thickness is erosion depth
  /// Erosion depth counts where an erodible cover of particles lost more than this fraction of
  /// its initial thickness: a cover that only crept or settled (moved unevenly by fractions of a
  /// particle spacing) changes its mass per map cell by a per cent or so, which is not erosion.
  double minErosionFraction = 0.02;
  PeakFileSettings peakFiles;
  AnimationSettings animation;
};

struct OutputSettings {
  std::string directory = "talus_out";
  double frameInterval = 0; ///< seconds between frames; 0 writes only the final state
  /// Seconds of simulated time between checkpoints (DIR/checkpoint.h5); 0 = none; negative =
  /// the default, a tenth of the end time.
  double checkpointInterval = -1;
  /// CRS of the scene's world coordinates as WKT, from `crs` ("EPSG:2056", ...); used by maps and
  /// VDB metadata when the scene has no DEM (a DEM brings its own).
  std::string crsWkt;
  // Formats written at every frame.
  bool h5Frames = true;     ///< frames/particles_NNNNN.h5
  bool vdb = true;          ///< frames/volume_NNNNN.vdb (density, fractions, velocity)
  bool vdbPoints = false;   ///< frames/points_NNNNN.vdb (OpenVDB points, for Houdini)
  bool ply = false;         ///< frames/particles_NNNNN.ply (Blender, ParaView)
  // Time series.
  bool series = true;       ///< series.csv
  double seriesInterval = 0; ///< s between rows; 0 = end_time / 1000
  bool plots = true;        ///< plots/*.png from the series
  bool report = true;       ///< report.html: the run on one page (io/run/run_report.h)
  bool loads = true;        ///< force and moment on every collider in the series
  std::vector<std::string> waterMaterials; ///< explicit; otherwise models named "water"
  std::vector<SectionSpec> sections;
  std::vector<PathSpec> paths;
  std::vector<ProbeSpec> probes;
  std::vector<GaugeSpec> gauges;
  MapSettings maps;

  /// Whether an output reads the particles after every step (the series and the maps; frame
  /// formats read them at frames only). Under MPI ranks this decides the per-step gather.
  bool readsEveryStep() const { return series || maps.enabled; }
  /// Whether a frame needs every particle in one process: VDB points (a point grid is built
  /// from all of them). HDF5, PLY and VDB volume frames are written in parts (framesInParts).
  bool framesNeedEveryParticle() const { return frameInterval > 0 && vdbPoints; }
};

} // namespace talus
