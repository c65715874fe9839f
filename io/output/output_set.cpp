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
#include <cstring>

namespace talus {

OutputSet::OutputSet(const OutputSettings& o, const RunContext& run, const std::string& outDir) {
  addFrameOutputs(o, run, outDir, false);
  addStepOutputs(o, run, outDir);
  seconds_.assign(outputs_.size(), 0.0);
}

void OutputSet::addFrameOutputs(const OutputSettings& o, const RunContext& run, const std::string& outDir, bool inPartsOnly) {
  if (o.frameInterval <= 0) return;
  const std::string& crs = run.crsWkt;
  if (o.h5Frames) outputs_.push_back(std::make_unique<H5FrameWriter>(outDir, run.materialNames));
  if (o.vdb) outputs_.push_back(std::make_unique<VdbVolumeWriter>(outDir, crs));
  if (o.vdbPoints && !inPartsOnly) outputs_.push_back(std::make_unique<VdbPointsWriter>(outDir, crs));
  if (o.ply) outputs_.push_back(std::make_unique<PlyFrameWriter>(outDir));
}

void OutputSet::addStepOutputs(const OutputSettings& o, const RunContext& run, const std::string& outDir) {
  // Their constructors touch no file (the frame formats' make folders): PartsOnly makes them too.
  if (o.series) outputs_.push_back(std::make_unique<TimeSeries>(outDir, o, run.endTime, run.particleSpacing));
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
}

OutputSet::OutputSet(PartsOnly, const OutputSettings& o, const RunContext& run, const Simulation& sim,
                     const std::string& framesDir) {
  // The frames written in parts, then the per-step outputs, each in rank 0's order.
  if (!framesDir.empty()) addFrameOutputs(o, run, framesDir, true);
  addStepOutputs(o, run, "");
  outputs_.erase(std::remove_if(outputs_.begin(), outputs_.end(),
                                [](const auto& out) { return !out->readsEveryStep() && !out->framesInParts(); }),
                 outputs_.end());
  for (auto& out : outputs_) out->prepareParts(sim);
  seconds_.assign(outputs_.size(), 0.0);
  lastTime_ = sim.time();
  root_ = false;
}

OutputSet::~OutputSet() = default;

template <class F> void OutputSet::eachInParts(F&& f) {
  for (size_t i = 0, k = 0; i < outputs_.size(); ++i) {
    if (!outputs_[i]->readsEveryStep()) continue;
    const auto t0 = std::chrono::steady_clock::now();
    f(*outputs_[i], k++);
    seconds_[i] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
}

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
  // The same calls as under ranks, with this process's buffer the only one: the same bytes.
  const double dt = stepTime(sim);
  stepLocal(sim, dt);
  const uint32_t due = partsDue(sim);
  const PartBounds b = due ? PartBounds::of(sim) : PartBounds{};
  const std::vector<std::vector<char>> mine = parts(sim, due, b, 0, 1);
  std::vector<std::string_view> buffers;
  if (due) buffers.emplace_back(mine[0].data(), mine[0].size());
  mergeParts(sim, dt, due, b, buffers);
  mergeResults(sim, false, {}, 1);
}

double OutputSet::stepTime(const Simulation& sim) {
  const double dt = sim.time() - lastTime_;
  lastTime_ = sim.time();
  return dt;
}

void OutputSet::stepLocal(const Simulation& local, double dt) {
  eachInParts([&](OutputObserver& o, size_t) { o.stepLocal(local, dt); });
}

uint32_t OutputSet::partsDue(const Simulation& sim) const {
  uint32_t due = 0, bit = 1;
  for (const auto& out : outputs_)
    if (out->readsEveryStep()) due |= out->partDue(sim) ? bit : 0, bit <<= 1;
  return due;
}

namespace {
/// Parts after their lengths: open(r) appends a length to buffer r, close(r) writes it in place
/// once the part is appended.
struct SizedParts {
  std::vector<std::vector<char>>& to;
  std::vector<size_t> at;
  explicit SizedParts(std::vector<std::vector<char>>& buffers) : to(buffers), at(buffers.size()) {}
  void open(size_t r) {
    at[r] = to[r].size();
    PartWriter(to[r]).put(uint64_t(0));
  }
  void close(size_t r) {
    const uint64_t n = to[r].size() - at[r] - sizeof n;
    std::memcpy(to[r].data() + at[r], &n, sizeof n);
  }
};
} // namespace

std::vector<std::vector<char>> OutputSet::parts(const Simulation& local, uint32_t due, const PartBounds& b, int self,
                                                int ranks) {
  std::vector<std::vector<char>> buffers(static_cast<size_t>(ranks));
  SizedParts sized(buffers);
  eachInParts([&](OutputObserver& o, size_t k) {
    if (!(due >> k & 1)) return;
    if (byOwner(o, ranks)) { // a part for every process (its own kept in place)
      for (size_t r = 0; r < buffers.size(); ++r) sized.open(r);
      o.partByOwner(local, b, self, buffers);
      for (size_t r = 0; r < buffers.size(); ++r) sized.close(r);
    } else { // rank 0's
      sized.open(0);
      o.part(local, b, self == 0, buffers[0]);
      sized.close(0);
    }
  });
  return buffers;
}

void OutputSet::mergeParts(const Simulation& sim, double dt, uint32_t due, const PartBounds& b,
                           const std::vector<std::string_view>& buffers) {
  std::vector<std::string_view> rest = buffers;
  const int ranks = int(buffers.size());
  eachInParts([&](OutputObserver& o, size_t k) {
    const bool owned = byOwner(o, ranks);
    if (!root_ && !owned) return; // made on rank 0 alone
    std::vector<std::string_view> mine;
    if (due >> k & 1)
      for (auto& r : rest) mine.push_back(takeSized(r));
    o.onStepParts(sim, dt, b, mine);
  });
}

bool OutputSet::byOwner(const OutputObserver& o, int ranks) const { return ranks > 1 && o.partsByOwner(); }

bool OutputSet::resultsDue(int ranks) const {
  bool due = false;
  for (const auto& out : outputs_) due |= out->readsEveryStep() && byOwner(*out, ranks) && out->resultDue();
  return due;
}

bool OutputSet::gathersState(const OutputObserver& o, int ranks) const {
  return byOwner(o, ranks) || (ranks > 1 && o.accumulatesOnRanks());
}

std::vector<char> OutputSet::results(bool state, int ranks) {
  std::vector<std::vector<char>> buffer(1);
  SizedParts sized(buffer);
  eachInParts([&](OutputObserver& o, size_t) {
    if (state ? !gathersState(o, ranks) : !(byOwner(o, ranks) && o.resultDue())) return;
    sized.open(0);
    o.ownedResult(state, buffer[0]);
    sized.close(0);
  });
  return std::move(buffer[0]);
}

void OutputSet::mergeResults(const Simulation& sim, bool state, const std::vector<std::string_view>& buffers, int ranks) {
  // Rank 0's own buffer (the first) is empty: its cells and totals are in place.
  std::vector<std::string_view> rest(buffers.begin() + std::min<size_t>(1, buffers.size()), buffers.end());
  eachInParts([&](OutputObserver& o, size_t) {
    const bool sent = state ? gathersState(o, ranks) : byOwner(o, ranks) && o.resultDue();
    if (state ? !sent : !o.resultDue()) return;
    std::vector<std::string_view> others;
    if (sent)
      for (auto& r : rest) others.push_back(takeSized(r));
    o.mergeResults(sim, state, others);
  });
}

bool OutputSet::sharesState(int ranks) const {
  bool any = false;
  for (const auto& out : outputs_) any |= out->readsEveryStep() && byOwner(*out, ranks) && out->sharesState();
  return any;
}

std::vector<char> OutputSet::sharedState(int ranks) {
  std::vector<std::vector<char>> buffer(1);
  SizedParts sized(buffer);
  eachInParts([&](OutputObserver& o, size_t) {
    if (!byOwner(o, ranks) || !o.sharesState()) return;
    sized.open(0);
    o.shareState(buffer[0]);
    sized.close(0);
  });
  return std::move(buffer[0]);
}

void OutputSet::takeSharedState(std::string_view rest, int ranks) {
  eachInParts([&](OutputObserver& o, size_t) {
    if (byOwner(o, ranks) && o.sharesState()) o.takeState(takeSized(rest));
  });
}

void OutputSet::save(StateArchive& a) const {
  a.putValue("outputs/last_time", lastTime_);
  for (size_t i = 0; i < outputs_.size(); ++i) {
    const std::string prefix = "outputs/" + std::to_string(i) + "_" + outputs_[i]->name() + "/";
    outputs_[i]->save(a, prefix);
    outputs_[i]->saveFiles(a, prefix + "files");
  }
}

void OutputSet::loadClock(const StateArchive& a) { lastTime_ = a.getValue<double>("outputs/last_time"); }

void OutputSet::load(const StateArchive& a) {
  loadClock(a);
  for (size_t i = 0; i < outputs_.size(); ++i) {
    const std::string prefix = "outputs/" + std::to_string(i) + "_" + outputs_[i]->name() + "/";
    outputs_[i]->load(a, prefix);
    outputs_[i]->loadFiles(a, prefix + "files");
  }
}

void OutputSet::frame(const Simulation& sim, int index, bool partsWritten) {
  each([&](OutputObserver& o) {
    if (!(partsWritten && o.framesInParts())) o.onFrame(sim, index);
  });
}

std::optional<WriteError> OutputSet::frameParts(Communicator& comm, const Simulation& local, int index) {
  std::optional<WriteError> first;
  each([&](OutputObserver& o) {
    if (!o.framesInParts()) return;
    auto failure = o.onFrameParts(comm, local, index);
    if (failure && !first) first = std::move(failure);
  });
  return first;
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
