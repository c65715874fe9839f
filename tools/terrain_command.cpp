#include "tools/terrain_command.h"

#include "io/common/input_error.h"
#include "io/terrain/dem_level_set.h"
#include "io/terrain/dem_raster.h"
#include "io/terrain/synthetic_dem.h"
#include "io/config/toml_reader.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace talus {

CLI::App* addTerrainCommand(CLI::App& app, TerrainCommandOptions& o) {
  auto* c = app.add_subcommand("terrain", "Build a narrow-band level set (.vdb) of a DEM for [terrain] sdf = ...");
  c->add_option("dem", o.dem, "DEM: any raster GDAL reads (GeoTIFF, ASCII grid...)")->required();
  c->add_option("--out", o.out, "Output level set file (.vdb)")->required();
  c->add_option("--dx", o.dx, "Voxel size (m); default: the DEM's cell size")->check(CLI::PositiveNumber);
  c->add_option("--smooth", o.smooth, "Gaussian smoothing radius R (m): sigma = R/2, truncated at 3 sigma")
      ->check(CLI::NonNegativeNumber);
  c->add_option("--bounds", o.bounds, "Footprint to build: XMIN YMIN XMAX YMAX (world, m); default: the whole DEM")
      ->expected(4);
  c->add_option("--origin", o.origin,
                "World position X Y Z of voxel (0,0,0): give the scene's domain.origin to put voxels on its grid "
                "nodes; default 0 0 0 (voxel centres on multiples of dx)")
      ->expected(3);
  c->add_option("--band", o.band, "Half width of the narrow band (voxels)")->check(CLI::Range(1, 64));
  c->add_flag("--fill-nodata", o.fillNodata, "Fill no-data cells (inverse-distance interpolation) instead of refusing");
  c->add_option("--crs", o.crs, "CRS to assume when the DEM has none, e.g. EPSG:31287");
  c->add_flag("--vertical-distance", o.verticalDistance,
              "Store the slope-corrected vertical difference instead of the closest-point distance (for comparison)");
  return c;
}

CLI::App* addSynthDemCommand(CLI::App& app, SynthDemOptions& o) {
  auto* c = app.add_subcommand("synth-dem", "Write a synthetic alpine DEM (GeoTIFF): slope_valley, vajont, cengalo, "
                                            "fluela, whymper");
  c->add_option("kind", o.kind, "Terrain kind (see --list)");
  c->add_option("--out", o.out, "Output GeoTIFF");
  c->add_option("--cell", o.cell, "Cell size (m), default 5")->check(CLI::PositiveNumber);
  c->add_option("--set", o.sets, "A parameter: --set slope_angle=40 --set origin=[2700000,1150000]");
  c->add_flag("--list", o.list, "List the kinds and their parameters");
  return c;
}

int runTerrainCommand(const TerrainCommandOptions& o) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  DemReadOptions ro;
  ro.fillNodata = o.fillNodata;
  ro.assignCrs = o.crs;
  size_t filled = 0;
  DemRaster dem = readDem(o.dem, ro, &filled);
  smoothDem(dem, o.smooth);
  const double tRead = std::chrono::duration<double>(Clock::now() - t0).count();
  const HeightField surface(dem);
  LevelSetBuildOptions b;
  b.dx = o.dx > 0 ? o.dx : dem.grid.cellSize;
  if (!o.origin.empty()) b.origin = Vec3d(o.origin[0], o.origin[1], o.origin[2]);
  b.band = o.band;
  b.closestPoint = !o.verticalDistance;
  b.sourcePath = o.dem;
  b.smoothRadius = o.smooth;
  if (o.bounds.empty()) {
    b.xmin = surface.xmin(), b.ymin = surface.ymin(), b.xmax = surface.xmax(), b.ymax = surface.ymax();
  } else {
    b.xmin = o.bounds[0], b.ymin = o.bounds[1], b.xmax = o.bounds[2], b.ymax = o.bounds[3];
    if (!(b.xmax > b.xmin && b.ymax > b.ymin)) throw InputError("", "--bounds: expected XMIN YMIN XMAX YMAX with XMAX > XMIN, YMAX > YMIN");
    if (b.xmax < surface.xmin() || b.xmin > surface.xmax() || b.ymax < surface.ymin() || b.ymin > surface.ymax())
      throw InputError("", "--bounds: the footprint lies outside the DEM");
  }
  const LevelSetBuildStats s = buildDemLevelSet(surface, b, o.out);
  std::printf("talus terrain: %s: %d x %d cells of %g m, %s%s\n", o.dem.c_str(), dem.grid.nx, dem.grid.ny,
              dem.grid.cellSize, crsName(dem.grid.crsWkt).c_str(),
              filled ? (", " + std::to_string(filled) + " no-data cells filled").c_str() : "");
  if (o.smooth > 0) std::printf("  smoothed: Gaussian radius %g m (sigma %g m)\n", o.smooth, 0.5 * o.smooth);
  std::printf("  level set: dx %g m, band %d voxels, %zu columns, %zu active voxels in %zu leaves (%s)\n", b.dx, b.band,
              s.columns, s.activeVoxels, s.leaves,
              b.closestPoint ? "closest-point distance" : "slope-corrected vertical difference");
  std::printf("  time: read %.2f s, build %.2f s, write %.2f s -> %s (%.1f MB)\n", tRead, s.buildSeconds, s.writeSeconds,
              o.out.c_str(), double(s.fileBytes) / 1e6);
  return 0;
}

int runSynthDemCommand(const SynthDemOptions& o) {
  if (o.list) {
    std::cout << syntheticDemHelp();
    return 0;
  }
  if (o.kind.empty() || o.out.empty()) throw InputError("", "synth-dem: give a KIND and --out FILE (or --list)");
  auto spec = readTomlString("kind = \"" + o.kind + "\"\n", "synth-dem");
  if (o.cell > 0) applyOverride(*spec, "cell_size=" + std::to_string(o.cell));
  for (const auto& s : o.sets) applyOverride(*spec, s);
  DemRaster dem = makeSyntheticDem(*spec);
  spec->checkAllUsed();
  writeDemGeoTiff(dem, o.out);
  float lo = INFINITY, hi = -INFINITY;
  for (float h : dem.height) lo = std::min(lo, h), hi = std::max(hi, h);
  std::printf("talus synth-dem: %s -> %s: %d x %d cells of %g m, west %.1f, south %.1f, elevation %.1f..%.1f m, %s\n",
              o.kind.c_str(), o.out.c_str(), dem.grid.nx, dem.grid.ny, dem.grid.cellSize, dem.grid.originX,
              dem.grid.originY - dem.grid.ny * dem.grid.cellSize, lo, hi, crsName(dem.grid.crsWkt).c_str());
  return 0;
}

} // namespace talus
