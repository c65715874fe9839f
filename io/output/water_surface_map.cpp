#include "io/output/water_surface_map.h"

#include "io/common/geotiff_writer.h"
#include "io/output/map_quicklook.h"
#include "io/output/water_gauges.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <limits>

namespace talus {

namespace {
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kNoData = -9999.f;
} // namespace

WaterSurfaceMap::WaterSurfaceMap(std::string outDir, RasterGrid grid, std::shared_ptr<const DemRaster> dem,
                                 std::vector<std::string> waterMaterials, double particleSpacing, bool quicklook)
    : outDir_(std::move(outDir)), grid_(std::move(grid)), dem_(std::move(dem)),
      waterMaterials_(std::move(waterMaterials)), spacing_(particleSpacing), quicklook_(quicklook) {}

void WaterSurfaceMap::prepareParts(const Simulation& sim) {
  // By index: rank 0 starts on its gathered copy and takes parts from its own groups.
  water_ = waterGroupIndices(sim, waterMaterials_);
  if (water_.empty()) return;
  // The window: the cells of the grid the domain's xy extent touches (as the hazard maps').
  const auto& st = sim.settings();
  const Vec3d lo = st.domain.min + st.origin, hi = st.domain.max + st.origin;
  window_ = windowOf(grid_, lo.x(), lo.y(), hi.x(), hi.y(), c0_, r0_);
  originZ_ = st.origin.z();
  volume_.assign(window_.size(), 0);
  bottom_.assign(window_.size(), std::numeric_limits<float>::infinity());
  max_.assign(window_.size(), kNaN); // each process's own rows (partsByOwner); rank 0's from the start
}

void WaterSurfaceMap::onStart(const Simulation& sim) {
  prepareParts(sim);
  if (water_.empty()) return;
  surfaces(sim, initial_);
  max_ = initial_;
}

int WaterSurfaceMap::volumeUnit(const Simulation& sim, const PartBounds& b) const {
  double invRho = 0;
  for (size_t g : water_) invRho = std::max(invRho, 1.0 / sim.groups()[g]->density());
  return unitExponent(b.maxMass * invRho, kCellBits); // the water alone
}

void WaterSurfaceMap::sumOwn(const Simulation& local, const PartBounds& b) {
  const Vec3d& o = local.settings().origin;
  const double inv = 1 / window_.cellSize, perUnit = powerOfTwo(-volumeUnit(local, b));
  // Fixed-point volumes and the lowest particle per cell: exact in any order and any split.
  for (size_t g : water_) {
    const ParticleSet& P = local.groups()[g]->particles;
    const double rho = local.groups()[g]->density();
    for (size_t p = 0; p < P.size(); ++p) {
      const double c = (double(P.x[p].x()) + o.x() - window_.originX) * inv;
      const double r = (window_.originY - double(P.x[p].y()) - o.y()) * inv;
      if (!(c >= 0 && r >= 0 && c < window_.nx && r < window_.ny)) continue;
      const uint32_t cell = uint32_t(window_.index(int(c), int(r)));
      if (std::isinf(bottom_[cell])) touched_.push_back(cell);
      volume_[cell] += toUnits(double(P.mass[p]) / rho, perUnit);
      bottom_[cell] = std::min(bottom_[cell], float(double(P.x[p].z()) - 0.5 * spacing_));
    }
  }
}

void WaterSurfaceMap::part(const Simulation& local, const PartBounds& b, bool keep, std::vector<char>& out) {
  sumOwn(local, b);
  if (!keep) writeTouched(&out, 1, -1); // else onStepParts adds the others' cells to these
}

void WaterSurfaceMap::partByOwner(const Simulation& local, const PartBounds& b, int self,
                                  std::vector<std::vector<char>>& outs) {
  if (water_.empty()) return;
  sumOwn(local, b);
  writeTouched(outs.data(), int(outs.size()), self);
}

void WaterSurfaceMap::writeTouched(std::vector<char>* outs, int ranks, int self) {
  size_t kept = 0;
  for (uint32_t cell : touched_) {
    const int r = ownerOfRow(int(cell / uint32_t(window_.nx)), ranks);
    if (r == self) {
      touched_[kept++] = cell;
      continue;
    }
    PartWriter put(outs[r]);
    put.put(cell), put.put(volume_[cell]), put.put(bottom_[cell]);
    volume_[cell] = 0, bottom_[cell] = std::numeric_limits<float>::infinity();
  }
  touched_.resize(kept);
}

void WaterSurfaceMap::ownedResult(bool state, std::vector<char>& out) {
  if (!state) return; // nothing is written during the run
  PartWriter put(out);
  for (uint32_t cell = 0; cell < uint32_t(max_.size()); ++cell)
    if (!std::isnan(max_[cell])) put.put(cell), put.put(max_[cell]);
}

void WaterSurfaceMap::mergeResults(const Simulation&, bool state, const std::vector<std::string_view>& others) {
  if (!state) return;
  for (const auto& p : others) {
    PartReader get(p);
    while (!get.done()) {
      const uint32_t cell = get.get<uint32_t>();
      if (cell >= max_.size()) throw std::runtime_error("run-up map: a result names a cell outside the map");
      const float z = get.get<float>();
      if (!(max_[cell] >= z)) max_[cell] = z; // the highest over every process's steps
    }
  }
}

std::vector<uint32_t> WaterSurfaceMap::mergeParts(const Simulation& sim, const PartBounds& b,
                                                  const std::vector<std::string_view>& parts, std::vector<float>& out) {
  for (const auto& p : parts) {
    PartReader get(p);
    while (!get.done()) {
      const uint32_t cell = get.get<uint32_t>();
      if (cell >= volume_.size()) throw std::runtime_error("run-up map: a part names a cell outside the map");
      if (std::isinf(bottom_[cell])) touched_.push_back(cell);
      volume_[cell] += get.get<int64_t>();
      bottom_[cell] = std::min(bottom_[cell], get.get<float>());
    }
  }
  out.assign(window_.size(), kNaN);
  const double perArea = powerOfTwo(volumeUnit(sim, b)) / (window_.cellSize * window_.cellSize);
  for (uint32_t cell : touched_) {
    out[cell] = float(originZ_ + bottom_[cell] + double(volume_[cell]) * perArea);
    volume_[cell] = 0;
    bottom_[cell] = std::numeric_limits<float>::infinity();
  }
  std::vector<uint32_t> cells;
  cells.swap(touched_); // the scratch is empty for the next part
  return cells;
}

void WaterSurfaceMap::surfaces(const Simulation& sim, std::vector<float>& out) {
  std::vector<char> own;
  const PartBounds b = PartBounds::of(sim);
  part(sim, b, true, own);
  mergeParts(sim, b, {}, out);
}

void WaterSurfaceMap::onStep(const Simulation& sim, double dt) {
  if (!water_.empty()) stepOwnPart(sim, dt);
}

void WaterSurfaceMap::onStepParts(const Simulation& sim, double, const PartBounds& b,
                                  const std::vector<std::string_view>& parts) {
  if (water_.empty()) return;
  std::vector<float> now;
  for (uint32_t cell : mergeParts(sim, b, parts, now))
    if (!(max_[cell] >= now[cell])) max_[cell] = now[cell]; // NaN (never wet) is replaced
}

std::vector<float> WaterSurfaceMap::onGrid(const std::vector<float>& window) const {
  std::vector<float> full(grid_.size(), kNaN);
  for (int r = 0; r < window_.ny; ++r)
    for (int c = 0; c < window_.nx; ++c) full[grid_.index(c0_ + c, r0_ + r)] = window[window_.index(c, r)];
  return full;
}

std::vector<float> WaterSurfaceMap::maxSurface() const { return onGrid(max_); }

std::vector<float> WaterSurfaceMap::rise() const {
  // The initial level of every cell: its own where wet at the start, else the nearest wet
  // cell's, reached in 4-neighbour steps from all wet cells at once (in cell order: ties go to
  // the first, the same every run).
  std::vector<float> level = initial_;
  std::deque<uint32_t> queue;
  for (uint32_t c = 0; c < level.size(); ++c)
    if (!std::isnan(level[c])) queue.push_back(c);
  while (!queue.empty()) {
    const uint32_t c = queue.front();
    queue.pop_front();
    const int x = int(c % uint32_t(window_.nx)), y = int(c / uint32_t(window_.nx));
    const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
    for (int k = 0; k < 4; ++k) {
      if (nx[k] < 0 || ny[k] < 0 || nx[k] >= window_.nx || ny[k] >= window_.ny) continue;
      const uint32_t n = uint32_t(window_.index(nx[k], ny[k]));
      if (std::isnan(level[n])) level[n] = level[c], queue.push_back(n);
    }
  }
  std::vector<float> out(max_.size(), kNaN);
  for (size_t c = 0; c < out.size(); ++c)
    if (!std::isnan(max_[c])) out[c] = max_[c] - level[c];
  return onGrid(out);
}

void WaterSurfaceMap::onFinish(const Simulation&, bool) {
  if (water_.empty()) return;
  namespace fs = std::filesystem;
  fs::create_directories(fs::path(outDir_) / "maps");
  auto write = [&](const char* stem, const char* description, std::vector<float> values) {
    for (float& v : values)
      if (std::isnan(v)) v = kNoData;
    GeoTiffBand b;
    b.description = description;
    b.unit = "m";
    b.nodata = kNoData;
    b.metadata = {{"TALUS_QUANTITY", description}};
    writeGeoTiff((fs::path(outDir_) / "maps" / (std::string(stem) + ".tif")).string(), grid_, values, b);
    recordFile(std::string("maps/") + stem + ".tif");
    return values;
  };
  write("max_water_surface", "highest water surface elevation", maxSurface());
  const std::vector<float> r = write("water_surface_rise", "water surface rise above its initial level", rise());
  if (!quicklook_) return;
  std::vector<float> heights;
  if (dem_) heights = dem_->height;
  QuicklookStyle style;
  style.title = "Water surface rise (run-up and flooding)";
  style.subtitle = "highest surface above the initial level";
  style.unit = "m";
  style.ramp = chart::Ramp::Blues;
  writeMapQuicklook((fs::path(outDir_) / "maps" / "water_surface_rise.png").string(), grid_, r, heights, style, kNoData);
  recordFile("maps/water_surface_rise.png");
}

std::vector<std::pair<std::string, std::string>> WaterSurfaceMap::summary() const {
  if (water_.empty()) return {};
  // The largest rise anywhere, the run-up (largest rise where the ground was dry at the start)
  // and the area flooded that was dry.
  const std::vector<float> r = rise();
  const std::vector<float> init = onGrid(initial_);
  double maxRise = 0, runup = 0, flooded = 0;
  for (size_t c = 0; c < r.size(); ++c) {
    if (std::isnan(r[c])) continue;
    maxRise = std::max(maxRise, double(r[c]));
    if (std::isnan(init[c])) runup = std::max(runup, double(r[c])), flooded += grid_.cellSize * grid_.cellSize;
  }
  char buf[64];
  auto num = [&](double v) { return std::snprintf(buf, sizeof buf, "%.6g", v), std::string(buf); };
  return {{"water_surface_rise_max_m", num(maxRise)}, {"water_runup_max_m", num(runup)}, {"water_flooded_area_m2", num(flooded)}};
}

void WaterSurfaceMap::save(StateArchive& a, const std::string& prefix) const {
  a.putVector(prefix + "initial", initial_);
  a.putVector(prefix + "max", max_);
}

void WaterSurfaceMap::load(const StateArchive& a, const std::string& prefix) {
  a.getVector(prefix + "initial", initial_);
  a.getVector(prefix + "max", max_);
}

} // namespace talus
