#include "io/terrain/terrain_loader.h"

#include "io/terrain/vdb_level_set.h"
#include "io/terrain/dem_raster.h"
#include "io/terrain/synthetic_dem.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace talus {

namespace fs = std::filesystem;

std::string resolveScenePath(const std::string& sceneFile, const std::string& path) {
  if (path.empty() || fs::path(path).is_absolute()) return path;
  const fs::path dir = fs::path(sceneFile).parent_path();
  return (dir / path).lexically_normal().string();
}

bool isDemTerrain(const ConfigTable& t) { return t.has("dem") || t.has("synthetic"); }

std::shared_ptr<const Sdf> loadTerrain(const ConfigTable& t, const SimulationSettings& s) {
  const bool hasPlane = t.has("plane"), hasSdf = t.has("sdf"), hasDem = t.has("dem"), hasSyn = t.has("synthetic");
  if (hasPlane + hasSdf + hasDem + hasSyn != 1) t.fail("", "give exactly one of 'plane', 'sdf', 'dem' or 'synthetic'");
  if (hasDem || hasSyn) t.fail(hasDem ? "dem" : "synthetic", "a DEM terrain is built by the scene reader");
  if (hasPlane) {
    const ConfigTable* p = t.table("plane");
    const Vec3d n = p->vec3("normal");
    if (!(n.norm() > 0)) p->fail("normal", "must be a non-zero vector");
    return std::make_shared<PlaneSdf>(p->vec3("point") - s.origin, n);
  }
  const std::string file = resolveScenePath(t.file(), t.string("sdf"));
  if (!fs::exists(file)) t.fail("sdf", "file not found: " + file);
  if (!fs::is_regular_file(file)) t.fail("sdf", "not a regular file: " + file);
  try {
    return std::make_shared<VdbLevelSet>(file, t.string("grid", ""), s.origin);
  } catch (const std::exception& e) {
    t.fail("sdf", file + ": " + e.what());
  }
}

DemTerrainInput readDemTerrain(const ConfigTable& t) {
  const bool hasDem = t.has("dem"), hasSyn = t.has("synthetic");
  if (hasDem + hasSyn + t.has("plane") + t.has("sdf") != 1)
    t.fail("", "give exactly one of 'plane', 'sdf', 'dem' or 'synthetic'");
  DemTerrainInput in;
  DemReadOptions opt;
  opt.fillNodata = t.boolean("fill_nodata", false);
  opt.assignCrs = t.string("crs", "");
  if (hasDem) {
    const std::string file = resolveScenePath(t.file(), t.string("dem"));
    try {
      in.raw = std::make_shared<DemRaster>(readDem(file, opt, &in.filledCells));
    } catch (const InputError& e) {
      t.fail("dem", e.what());
    }
  } else {
    const ConfigTable* syn = t.table("synthetic");
    if (!syn) t.fail("synthetic", "expected a table: synthetic = { kind = \"slope_valley\", ... }");
    in.raw = std::make_shared<DemRaster>(makeSyntheticDem(*syn));
    if (!opt.assignCrs.empty()) t.fail("crs", "a synthetic DEM takes its CRS from synthetic.crs");
  }
  in.smoothRadius = t.positive("smooth_radius", 0, true);
  if (in.smoothRadius > 0) {
    in.smoothed = std::make_shared<DemRaster>(*in.raw);
    smoothDem(*in.smoothed, in.smoothRadius);
  } else {
    in.smoothed = in.raw;
  }
  const RasterGrid& g = in.raw->grid;
  char buf[256];
  std::snprintf(buf, sizeof buf, "%d x %d cells of %g m", g.nx, g.ny, g.cellSize);
  in.description = in.raw->sourcePath + " (" + buf + ", " + crsName(g.crsWkt) + ")";
  return in;
}

std::string terrainCacheDir() {
  std::vector<fs::path> candidates;
  if (const char* d = std::getenv("TALUS_CACHE_DIR"); d && *d) candidates.emplace_back(d);
  else if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) candidates.push_back(fs::path(x) / "talus" / "terrain");
  else if (const char* h = std::getenv("HOME"); h && *h) candidates.push_back(fs::path(h) / ".cache" / "talus" / "terrain");
  candidates.push_back(fs::temp_directory_path() / "talus-cache" / "terrain");
  for (const auto& c : candidates) {
    std::error_code ec;
    fs::create_directories(c, ec);
    if (fs::is_directory(c)) return c.string();
  }
  return fs::temp_directory_path().string();
}

namespace {
/// FNV-1a, 64 bit: the cache key of a level set (inputs are hashed byte for byte).
struct Hash {
  uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  template <class T> void value(const T& v) { bytes(&v, sizeof v); }
  void text(const std::string& s) { value(s.size()), bytes(s.data(), s.size()); }
};
// Bump when the builder's output changes, so stale cache files are not reused.
constexpr const char* kBuilderVersion = "talus-dem-level-set-4";
} // namespace

CachedLevelSet cachedDemLevelSet(const DemRaster& ground, const LevelSetBuildOptions& o) {
  using Clock = std::chrono::steady_clock;
  Hash h;
  h.text(kBuilderVersion);
  h.bytes(ground.height.data(), ground.height.size() * sizeof(float));
  const RasterGrid& g = ground.grid;
  h.value(g.nx), h.value(g.ny), h.value(g.originX), h.value(g.originY), h.value(g.cellSize);
  h.text(g.crsWkt);
  h.value(o.dx), h.value(o.origin.x()), h.value(o.origin.y()), h.value(o.origin.z()), h.value(o.band);
  h.value(o.xmin), h.value(o.ymin), h.value(o.xmax), h.value(o.ymax), h.value(o.zmin), h.value(o.closestPoint);
  h.text(o.sourcePath), h.value(o.smoothRadius);
  char name[64];
  std::snprintf(name, sizeof name, "terrain_%016llx.vdb", static_cast<unsigned long long>(h.h));
  CachedLevelSet out;
  out.path = (fs::path(terrainCacheDir()) / name).string();
  if (fs::exists(out.path)) {
    try {
      const auto t0 = Clock::now();
      out.sdf = std::make_shared<VdbLevelSet>(out.path, "terrain", o.origin, VdbLoading::OnDemand);
      out.loadSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
      out.reused = true;
      return out;
    } catch (const std::exception&) {
      // A damaged cache file: rebuild it below.
    }
  }
  out.stats = buildDemLevelSet(HeightField(ground), o, out.path);
  const auto t0 = Clock::now();
  out.sdf = std::make_shared<VdbLevelSet>(out.path, "terrain", o.origin, VdbLoading::OnDemand);
  out.loadSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

} // namespace talus
