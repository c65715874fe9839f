// HazardMaps' files: the final deposit and erosion, then every map as a GeoTIFF on the map grid
// and a PNG quick-look.
#include "io/output/hazard_maps_impl.h"

#include "io/common/input_error.h"
#include "io/common/json_text.h"
#include "io/output/animation.h"

#include "io/common/geotiff_writer.h"
#include "io/common/names.h"
#include "io/output/map_quicklook.h"
#include "io/output/peak_files.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace talus {

const char* HazardMaps::stem(Quantity q) {
  static const char* s[] = {"max_flow_height_vertical", "max_flow_height_slope_normal", "max_speed", "max_pressure",
                            "deposit_thickness", "erosion_depth", "initial_thickness", "ground_elevation"};
  return s[q];
}
const char* HazardMaps::band(Quantity q) {
  static const char* s[] = {"max_flow_height_vertical_m", "max_flow_height_slope_normal_m", "max_speed_m_s",
                            "max_dynamic_pressure_kPa", "final_deposit_thickness_vertical_m",
                            "erosion_depth_vertical_m", "initial_thickness_vertical_m", "ground_elevation_m"};
  return s[q];
}
const char* HazardMaps::unit(Quantity q) {
  static const char* s[] = {"m", "m", "m/s", "kPa", "m", "m", "m", "m"};
  return s[q];
}

namespace {

/// Whether group g is the material of a cover made a field (engine/erodible_bed.h).
bool coverGroup(const Simulation& sim, int g) {
  if (!sim.bed()) return false;
  for (const ErodibleCover& c : sim.bed()->covers())
    if (c.group == g) return true;
  return false;
}

} // namespace

/// Erosion of the covers made fields: each map cell reads the node column nearest its centre,
/// so a column's depth covers its dx x dx plan area (a map finer than dx is not speckled).
void HazardMaps::addBedErosion(Impl& m, const Simulation& sim) {
  const ErodibleBed& bed = *sim.bed();
  if (m.erosion.empty()) m.erosion.assign(size_t(m.layers), std::vector<float>(m.cells, 0.f));
  const double dx = sim.settings().dx;
  for (size_t c = 0; c < m.cells; ++c) {
    const int col = int(c % size_t(m.window.nx)), row = int(c / size_t(m.window.nx));
    const double x = m.window.cellCentreX(col) - sim.settings().origin.x();
    const double y = m.window.cellCentreY(row) - sim.settings().origin.y();
    const int32_t i = int32_t(std::lround(x / dx)), j = int32_t(std::lround(y / dx));
    for (size_t k = 0; k < bed.covers().size(); ++k) {
      const int g = bed.covers()[k].group;
      const float depth = float(bed.erodedMass(i, j, k) / (sim.groups()[size_t(g)]->density() * dx * dx));
      if (!(depth > 0)) continue;
      m.erosion[0][c] += depth;
      if (m.layers > 1) m.erosion[size_t(1 + g)][c] += depth;
    }
  }
}

void HazardMaps::onFinish(const Simulation& sim, bool completed) {
  Impl& m = *impl_;
  m.endTime = sim.time();
  std::vector<std::vector<float>> finalErodible;
  if (completed) {
    m.thickness(sim, std::vector<uint8_t>(sim.groups().size(), 1), m.deposit);
    if (!settings_.erodible.empty()) {
      m.thickness(sim, m.erodibleGroup, finalErodible);
      m.erosion.assign(size_t(m.layers), std::vector<float>(m.cells, 0.f));
      const float least = float(settings_.minErosionFraction);
      for (int l = 0; l < m.layers; ++l)
        for (size_t c = 0; c < m.cells; ++c) {
          const float before = m.initial[size_t(l)][c], lost = before - finalErodible[size_t(l)][c];
          m.erosion[size_t(l)][c] = lost > least * before ? lost : 0.f; // creep is not erosion
        }
    }
    if (sim.bed()) addBedErosion(m, sim);
  }

  namespace fs = std::filesystem;
  std::vector<float> windowHeights;
  if (dem_) {
    windowHeights.resize(m.cells);
    for (int r = 0; r < m.window.ny; ++r)
      for (int c = 0; c < m.window.nx; ++c)
        windowHeights[size_t(r) * m.window.nx + c] = dem_->height[grid_.index(m.c0 + c, m.r0 + r)];
  }
  static const char* titles[] = {"Maximum flow height (vertical)", "Maximum flow height (slope-normal)",
                                 "Maximum speed", "Maximum dynamic pressure", "Final deposit thickness (vertical)",
                                 "Erosion depth (vertical)", "Initial thickness (vertical)", "Ground elevation"};
  static const chart::Ramp ramps[] = {chart::Ramp::Viridis, chart::Ramp::Viridis, chart::Ramp::Plasma,
                                      chart::Ramp::Magma, chart::Ramp::Browns, chart::Ramp::Blues,
                                      chart::Ramp::Browns, chart::Ramp::Viridis};
  char span[64];
  std::snprintf(span, sizeof span, "t = 0 - %.4g s", m.endTime);
  for (int l = 0; l < m.layers; ++l) {
    const bool anyErodible = l == 0 ? !settings_.erodible.empty() || sim.bed()
                                    : m.erodibleGroup[size_t(l - 1)] != 0 || coverGroup(sim, l - 1);
    const std::string dir = l == 0 ? "maps" : "maps/" + safeName(m.layerMaterial[size_t(l)]);
    fs::create_directories(fs::path(outDir_) / dir);
    for (int qi = 0; qi < kQuantities; ++qi) {
      const auto q = Quantity(qi);
      if ((q == Deposit || q == Erosion) && !completed) continue;
      if (q == Erosion && !anyErodible) continue;
      if (q == Ground && (l > 0 || !dem_)) continue;
      const std::string rel = dir + "/" + stem(q);
      GeoTiffBand b;
      b.description = band(q);
      b.unit = unit(q);
      b.nodata = kNoData;
      b.metadata = {{"TALUS_QUANTITY", band(q)},
                    {"TALUS_MATERIAL", l == 0 ? std::string("all") : m.layerMaterial[size_t(l)]},
                    {"TALUS_TIME_END_S", std::to_string(m.endTime)}};
      writeGeoTiff((fs::path(outDir_) / (rel + ".tif")).string(), grid_, raster(q, l), b);
      recordFile(rel + ".tif");
      if (settings_.quicklook && q != Ground) {
        std::vector<float> win(m.cells);
        const std::vector<float> full = raster(q, l);
        for (int r = 0; r < m.window.ny; ++r)
          for (int c = 0; c < m.window.nx; ++c)
            win[size_t(r) * m.window.nx + c] = full[grid_.index(m.c0 + c, m.r0 + r)];
        QuicklookStyle style;
        style.title = titles[qi];
        style.subtitle = (l == 0 ? std::string("all materials") : "material '" + m.layerMaterial[size_t(l)] + "'") +
                         ", " + span;
        style.unit = unit(q);
        style.ramp = ramps[qi];
        writeMapQuicklook((fs::path(outDir_) / (rel + ".png")).string(), m.window, win, windowHeights, style, kNoData);
        recordFile(rel + ".png");
      }
    }
  }
  if (settings_.peakFiles.enabled) {
    // The DEM's format, as AvaFrame writes its peak files.
    const std::string src = dem_ ? fs::path(dem_->sourcePath).extension().string() : "";
    const std::string format = !settings_.peakFiles.format.empty() ? settings_.peakFiles.format
                               : src == ".asc" || src == ".ASC" ? "asc" : "tif";
    std::vector<std::vector<float>> peaks = {raster(MaxHeightNormal), raster(MaxSpeed), raster(MaxPressure),
                                             raster(MaxHeightVertical)};
    RasterGrid grid = grid_;
    float nodata = kNoData;
    if (settings_.peakFiles.grid == "com1dfa") { // com1DFA's own mesh, no data NaN as com1DFA writes
      grid = com1dfaGrid(grid_, settings_.peakFiles.meshCellSize);
      for (auto& p : peaks) p = resampleCentres(grid_, p, kNoData, grid);
      nodata = NAN;
    }
    for (const auto& f : writePeakFiles(outDir_, settings_.peakFiles, format, grid, peaks, nodata)) recordFile(f);
  }
  if (settings_.animation.enabled) makeFilm();
}

void HazardMaps::makeFilm() {
  // The film is a view of the run: without ffmpeg the run still completes, and says so.
  AnimationStyle style;
  style.quantity = settings_.animation.quantity;
  style.fps = settings_.animation.fps;
  style.scaleMax = settings_.animation.scaleMax;
  const Impl& m = *impl_;
  if (m.filmKnown) style.known = AnimationStyle::Known{size_t(m.filmFrames), m.filmLargest};
  try {
    const AnimationResult r = makeAnimation(outDir_, style);
    for (const auto& f : r.files) recordFile(f);
    animationOutcome_ = r.problem.empty() ? r.files.front() : r.problem;
    if (!r.retried.empty()) animationOutcome_ += " (encoded again after a failed try: " + r.retried + ")";
  } catch (const InputError& e) {
    animationOutcome_ = e.what();
  }
}

std::vector<std::pair<std::string, std::string>> HazardMaps::summary() const {
  if (animationOutcome_.empty()) return {};
  return {{"animation", jsonString(animationOutcome_)}};
}

std::vector<float> HazardMaps::raster(Quantity q, int layer) const {
  const Impl& m = *impl_;
  std::vector<float> out(grid_.size(), kNoData);
  if (layer < 0 || layer >= m.layers) throw std::out_of_range("HazardMaps::raster: no such layer");
  const float* src = nullptr;
  if (q < kMaxima) src = m.maxima[size_t(layer)].data() + size_t(q) * m.cells;
  else if (q == Deposit && !m.deposit.empty()) src = m.deposit[size_t(layer)].data();
  else if (q == Erosion && !m.erosion.empty()) src = m.erosion[size_t(layer)].data();
  else if (q == Initial && !m.start.empty()) src = m.start[size_t(layer)].data();
  if (q == Ground) {
    if (dem_)
      for (size_t g = 0; g < out.size(); ++g)
        if (std::isfinite(dem_->height[g])) out[g] = dem_->height[g];
    return out;
  }
  for (int r = 0; r < m.window.ny; ++r)
    for (int c = 0; c < m.window.nx; ++c) {
      const size_t g = grid_.index(m.c0 + c, m.r0 + r);
      if (dem_ && !std::isfinite(dem_->height[g])) continue; // no ground there: no data
      out[g] = src ? src[size_t(r) * m.window.nx + c] : 0.f;
    }
  return out;
}

// What rank 0 gathers of the cells every process folds (partsByOwner): a film frame's rasters
// and, before a checkpoint or the end's files, the maxima.

bool HazardMaps::resultDue() const { return impl_->framePending; }

// A result: per cell its index, then its floats (the frame's thickness and speed, or every
// layer's maxima), only for cells with a non-zero value (rank 0's are zero or a lower maximum).
void HazardMaps::ownedResult(bool state, std::vector<char>& out) {
  Impl& m = *impl_;
  const size_t n = m.cells, floats = state ? size_t(m.layers) * kMaxima : 2;
  std::vector<float> v(floats);
  for (uint32_t cell = 0; cell < n; ++cell) {
    bool any = false;
    for (size_t i = 0; i < floats; ++i) {
      const size_t l = i / kMaxima, q = i % kMaxima;
      v[i] = !state ? (i ? m.frameSpeed[cell] : m.frameThickness[cell]) : m.maxima[l][q * n + cell];
      any |= v[i] != 0;
    }
    if (!any) continue;
    PartWriter w(out);
    w.put(cell);
    for (float f : v) w.put(f);
  }
  if (!state) m.framePending = false;
}

void HazardMaps::mergeResults(const Simulation& sim, bool state, const std::vector<std::string_view>& others) {
  Impl& m = *impl_;
  const size_t n = m.cells, floats = state ? size_t(m.layers) * kMaxima : 2;
  for (std::string_view part : others) {
    if (part.size() % (sizeof(uint32_t) + floats * sizeof(float)))
      throw std::runtime_error("hazard maps: a result does not hold whole cells");
    PartReader r(part);
    while (!r.done()) {
      const auto cell = r.get<uint32_t>();
      if (cell >= n) throw std::runtime_error("hazard maps: a result names a cell outside the map");
      for (size_t i = 0; i < floats; ++i) {
        const float f = r.get<float>();
        const size_t l = i / kMaxima, q = i % kMaxima;
        if (state) m.maxima[l][q * n + cell] = std::max(m.maxima[l][q * n + cell], f);
        else (i ? m.frameSpeed : m.frameThickness)[cell] = f;
      }
    }
  }
  if (!state && m.framePending) writeFrame(sim.time());
}

void HazardMaps::writeFrame(double time) {
  Impl& m = *impl_;
  for (const auto& f : writeAnimationFrame(outDir_, m.animationNext, time, m.window, m.frameThickness, m.frameSpeed))
    recordFile(f);
  m.filmKnown = m.filmKnown && m.animationNext == m.filmFrames;
  ++m.filmFrames;
  const std::vector<float>* frame[2] = {&m.frameThickness, &m.frameSpeed}; // animationQuantities' order
  for (int q = 0; q < 2; ++q)
    for (float v : *frame[q])
      if (std::isfinite(v)) m.filmLargest[size_t(q)] = std::max(m.filmLargest[size_t(q)], v);
  // Steps longer than the interval skip frames rather than repeat one.
  m.animationNext = int(std::floor(time / settings_.animation.interval + 1e-9)) + 1;
  m.framePending = false;
}

} // namespace talus
