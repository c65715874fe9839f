#include "io/output/output_set.h"

#include "io/output/avaframe_run_files.h"
#include "io/output/h5_frame_writer.h"
#include "io/output/hazard_maps.h"
#include "io/output/ply_writer.h"
#include "io/output/time_series.h"
#include "io/output/vdb_frame_writer.h"
#include "io/output/water_surface_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace talus {

OutputSet::OutputSet(const OutputSettings& o, const RunContext& run, const std::string& outDir) {
  const std::string& crs = run.crsWkt;
  if (o.frameInterval > 0) {
    if (o.h5Frames) outputs_.push_back(std::make_unique<H5FrameWriter>(outDir, run.materialNames));
    if (o.vdb) outputs_.push_back(std::make_unique<VdbVolumeWriter>(outDir, crs));
    if (o.vdbPoints) outputs_.push_back(std::make_unique<VdbPointsWriter>(outDir, crs));
    if (o.ply) outputs_.push_back(std::make_unique<PlyFrameWriter>(outDir));
  }
  if (o.series) {
    outputs_.push_back(std::make_unique<TimeSeries>(outDir, o, run.endTime, run.particleSpacing));
  }
  if (o.maps.enabled) {
    // On the DEM's grid when there is one; else over the domain, two grid cells per map cell
    // unless cell_size says otherwise (fewer particles per cell make noisier maps).
    const double cell = o.maps.cellSize > 0 ? o.maps.cellSize : 2 * run.dx;
    RasterGrid grid = run.dem ? run.dem->grid : HazardMaps::domainGrid(run, cell);
    outputs_.push_back(std::make_unique<HazardMaps>(outDir, grid, run.dem, o.maps));
    if (o.maps.peakFiles.enabled) outputs_.push_back(std::make_unique<AvaFrameRunFiles>(outDir, o, run));
    // The run-up and flooding map, on the same grid, where there is water.
    const auto& models = run.materialModels;
    if (!o.waterMaterials.empty() || std::find(models.begin(), models.end(), "water") != models.end())
      outputs_.push_back(std::make_unique<WaterSurfaceMap>(outDir, grid, run.dem, o.waterMaterials,
                                                           run.particleSpacing, o.maps.quicklook));
  }
  seconds_.assign(outputs_.size(), 0.0);
}

OutputSet::~OutputSet() = default;

template <class F> void OutputSet::each(F&& f) {
  for (size_t i = 0; i < outputs_.size(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f(*outputs_[i]);
    seconds_[i] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
}

void OutputSet::start(const Simulation& sim) {
  lastTime_ = sim.time();
  each([&](OutputObserver& o) { o.onStart(sim); });
}

void OutputSet::step(const Simulation& sim) {
  const double dt = sim.time() - lastTime_;
  lastTime_ = sim.time();
  each([&](OutputObserver& o) { o.onStep(sim, dt); });
}

void OutputSet::save(StateArchive& a) const {
  a.putValue("outputs/last_time", lastTime_);
  for (size_t i = 0; i < outputs_.size(); ++i) {
    const std::string prefix = "outputs/" + std::to_string(i) + "_" + outputs_[i]->name() + "/";
    outputs_[i]->save(a, prefix);
    outputs_[i]->saveFiles(a, prefix + "files");
  }
}

void OutputSet::load(const StateArchive& a) {
  lastTime_ = a.getValue<double>("outputs/last_time");
  for (size_t i = 0; i < outputs_.size(); ++i) {
    const std::string prefix = "outputs/" + std::to_string(i) + "_" + outputs_[i]->name() + "/";
    outputs_[i]->load(a, prefix);
    outputs_[i]->loadFiles(a, prefix + "files");
  }
}

void OutputSet::frame(const Simulation& sim, int index) {
  each([&](OutputObserver& o) { o.onFrame(sim, index); });
}

void OutputSet::finish(const Simulation& sim, bool completed) {
  each([&](OutputObserver& o) { o.onFinish(sim, completed); });
}

std::vector<std::string> OutputSet::names() const {
  std::vector<std::string> n;
  for (const auto& o : outputs_) n.push_back(o->name());
  return n;
}

std::vector<OutputReport> OutputSet::reports() const {
  std::vector<OutputReport> r;
  for (size_t i = 0; i < outputs_.size(); ++i) r.push_back({outputs_[i]->name(), seconds_[i], outputs_[i]->files(), outputs_[i]->summary()});
  return r;
}

} // namespace talus
