// HazardMaps' accumulation: splats of particle volume, mass and speed onto map cells, summed as
// fixed-point integers in bands of rows (exact: the same at any thread and rank count), merged
// over the processes' parts (io/output/step_parts.h) and folded into the maxima.
#include "io/output/hazard_maps_impl.h"

#include "io/output/animation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace talus {

HazardMaps::HazardMaps(std::string outDir, RasterGrid grid, std::shared_ptr<const DemRaster> dem, MapSettings settings)
    : impl_(std::make_unique<Impl>()), outDir_(std::move(outDir)), grid_(std::move(grid)), dem_(std::move(dem)),
      settings_(std::move(settings)) {
  if (dem_ && (dem_->grid.nx != grid_.nx || dem_->grid.ny != grid_.ny || dem_->height.size() != grid_.size()))
    throw std::invalid_argument("HazardMaps: the DEM must lie on the map grid");
}

HazardMaps::~HazardMaps() = default;

RasterGrid HazardMaps::domainGrid(const RunContext& run, double cellSize) {
  RasterGrid g;
  const Vec3d lo = run.domainMin + run.origin, hi = run.domainMax + run.origin;
  g.cellSize = cellSize;
  g.originX = lo.x();
  g.originY = hi.y();
  g.nx = std::max(1, int(std::ceil((hi.x() - lo.x()) / cellSize - 1e-9)));
  g.ny = std::max(1, int(std::ceil((hi.y() - lo.y()) / cellSize - 1e-9)));
  g.crsWkt = run.crsWkt;
  return g;
}

void HazardMaps::save(StateArchive& a, const std::string& prefix) const {
  const Impl& m = *impl_;
  for (size_t l = 0; l < m.maxima.size(); ++l) a.putVector(prefix + "maxima" + std::to_string(l), m.maxima[l]);
  for (size_t l = 0; l < m.initial.size(); ++l) a.putVector(prefix + "initial" + std::to_string(l), m.initial[l]);
  a.putVector(prefix + "cos_slope", m.cosSlope);
  a.putValue(prefix + "last_time", m.lastTime);
  a.putValue(prefix + "accumulations", uint64_t(accumulations_));
  a.putValue(prefix + "animation_next", int32_t(m.animationNext));
}

void HazardMaps::load(const StateArchive& a, const std::string& prefix) {
  Impl& m = *impl_;
  for (size_t l = 0; l < m.maxima.size(); ++l) a.getVector(prefix + "maxima" + std::to_string(l), m.maxima[l]);
  for (size_t l = 0; l < m.initial.size(); ++l) a.getVector(prefix + "initial" + std::to_string(l), m.initial[l]);
  a.getVector(prefix + "cos_slope", m.cosSlope);
  m.lastTime = a.getValue<double>(prefix + "last_time");
  accumulations_ = size_t(a.getValue<uint64_t>(prefix + "accumulations"));
  m.animationNext = a.getValue<int32_t>(prefix + "animation_next");
}

void HazardMaps::prepareParts(const Simulation& sim) {
  Impl& m = *impl_;
  const auto& st = sim.settings();
  m.origin = st.origin;
  m.dx = st.dx;
  m.zLo = st.domain.min.z(), m.zHi = st.domain.max.z();
  m.terrain = st.terrain;
  // Window: the cells of the grid the domain's xy extent touches.
  const double cs = grid_.cellSize;
  const Vec3d lo = st.domain.min + st.origin, hi = st.domain.max + st.origin;
  m.window = windowOf(grid_, lo.x(), lo.y(), hi.x(), hi.y(), m.c0, m.r0);
  if (m.window.size() == 0) throw std::runtime_error("hazard maps: the domain does not overlap the map grid");
  m.cells = m.window.size();
  m.a = 1 / cs;
  m.bx = (st.origin.x() - m.window.originX) / cs - 0.5;
  m.by = (m.window.originY - st.origin.y()) / cs - 0.5;
  m.endTime = sim.time();

  const auto& groups = sim.groups();
  m.layers = settings_.perMaterial ? int(1 + groups.size()) : 1;
  m.layerMaterial.assign(1, "");
  if (settings_.perMaterial)
    for (const auto* g : groups) m.layerMaterial.push_back(g->name());
  m.sums.assign(size_t(m.layers), std::vector<int64_t>(kSums * m.cells, 0));
  m.mark.assign(m.cells, 0);
  // Every process folds its own cells into the maxima (partsByOwner), with the slope under them.
  m.maxima.assign(size_t(m.layers), std::vector<float>(kMaxima * m.cells, 0.f));
  m.cosSlope.assign(m.cells, kNaN);

  // Cosines known everywhere before the run (a DEM's, or none without terrain) let every process
  // fold its own cells; the terrain SDF's are found on demand, where rank 0 folds every cell.
  if (dem_) m.slopeFromDem(grid_, *dem_);
  else if (!m.terrain) std::fill(m.cosSlope.begin(), m.cosSlope.end(), 1.f);
  m.slopeKnown = dem_ || !m.terrain;
}

void HazardMaps::Impl::slopeFromDem(const RasterGrid& grid, const DemRaster& dem) {
  // Central differences, one-sided next to missing cells.
  const auto& z = dem.height;
  const double cs = grid.cellSize;
  for (int r = 0; r < window.ny; ++r)
    for (int c = 0; c < window.nx; ++c) {
      const int gc = c0 + c, gr = r0 + r;
      auto at = [&](int cc, int rr) -> double {
        if (cc < 0 || rr < 0 || cc >= grid.nx || rr >= grid.ny) return NAN;
        return z[grid.index(cc, rr)];
      };
      const double h = at(gc, gr);
      double e = at(gc + 1, gr), w = at(gc - 1, gr), n = at(gc, gr - 1), s = at(gc, gr + 1);
      double sx = 2 * cs, sy = 2 * cs;
      if (!std::isfinite(e)) e = h, sx -= cs;
      if (!std::isfinite(w)) w = h, sx -= cs;
      if (!std::isfinite(n)) n = h, sy -= cs;
      if (!std::isfinite(s)) s = h, sy -= cs;
      const double zx = sx > 0 && std::isfinite(h) ? (e - w) / sx : 0;
      const double zy = sy > 0 && std::isfinite(h) ? (n - s) / sy : 0;
      cosSlope[size_t(r) * window.nx + c] = float(1 / std::sqrt(1 + zx * zx + zy * zy));
    }
}

void HazardMaps::onStart(const Simulation& sim) {
  prepareParts(sim);
  Impl& m = *impl_;
  const auto& groups = sim.groups();
  m.erodibleGroup.assign(groups.size(), 0);
  for (size_t g = 0; g < groups.size(); ++g)
    for (const auto& n : settings_.erodible)
      if (groups[g]->name() == n) m.erodibleGroup[g] = 1;
  if (!settings_.erodible.empty()) m.thickness(sim, m.erodibleGroup, m.initial);
  m.thickness(sim, std::vector<uint8_t>(groups.size(), 1), m.start);
  stepOwnPart(sim, 0); // the first accumulation: the start
}

void HazardMaps::onStep(const Simulation& sim, double dt) {
  if (partDue(sim)) stepOwnPart(sim, dt);
}

bool HazardMaps::partDue(const Simulation& sim) const {
  // Rank 0 tells the others in its parts whether this accumulation makes a film frame.
  impl_->frameDue = animationFrameDue(sim.time());
  return sim.time() - impl_->lastTime + 1e-12 >= settings_.interval || impl_->frameDue;
}

bool HazardMaps::animationFrameDue(double time) const {
  const AnimationSettings& a = settings_.animation;
  return a.enabled && time + 1e-9 * a.interval >= impl_->animationNext * a.interval;
}

void HazardMaps::Impl::setUnits(const Simulation& sim, const PartBounds& b) {
  const double bound[kSums] = {volumeBound(sim, b), b.maxMass, b.maxMass * std::sqrt(b.maxSpeed2), b.maxMass * b.maxSpeed2};
  for (int k = 0; k < kSums; ++k) unit[k] = unitExponent(bound[k], kCellBits);
}

void HazardMaps::Impl::binSplats(const Simulation& sim, const std::vector<uint8_t>& use, float minSpeed) {
  Impl& m = *this;
  const auto& groups = sim.groups();
  const int w = m.window.nx, h = m.window.ny;
  const float a = float(m.a), bx = float(m.bx), by = float(m.by); // local metres are float anyway
  m.rowStart.resize(groups.size());
  m.splats.resize(groups.size());
  auto& row = m.rowOf;
  float perUnit[kSums];
  for (int k = 0; k < kSums; ++k) perUnit[k] = float(powerOfTwo(-m.unit[k]));
  for (size_t g = 0; g < groups.size(); ++g) {
    if (!use[g]) continue;
    const ParticleSet& P = groups[g]->particles;
    const float invRho = float(1.0 / groups[g]->density());
    row.resize(P.size());
    // Fixed chunks (not thread-dependent): each counts its particles per row; a stable counting
    // sort then places the splats by row, chunk by chunk, in the order a serial pass would.
    constexpr size_t kChunk = 16384;
    const size_t chunks = (P.size() + kChunk - 1) / kChunk, rows = size_t(h) + 1;
    std::vector<uint32_t> count(chunks * rows, 0);
    auto cellOf = [&](size_t p) { return std::pair{a * P.x[p][0] + bx, -a * P.x[p][1] + by}; };
    tbb::parallel_for(size_t(0), chunks, [&](size_t ch) {
      uint32_t* cnt = count.data() + ch * rows;
      for (size_t p = ch * kChunk; p < std::min(P.size(), (ch + 1) * kChunk); ++p) {
        const auto [fx, fy] = cellOf(p);
        // First of the two rows the splat covers, plus one (0 .. h); floor via int as fy >= -1.
        const bool moving = !(minSpeed > 0) || P.v[p].squaredNorm() >= minSpeed * minSpeed;
        row[p] = moving && fx >= -1 && fx < w && fy >= -1 && fy < h ? int32_t(fy + 1) : -1;
        if (row[p] >= 0) ++cnt[size_t(row[p])];
      }
    });
    auto& start = m.rowStart[g];
    start.assign(rows + 1, 0);
    uint32_t total = 0; // count[] becomes each (chunk, row)'s first slot in the sorted splats
    for (size_t r = 0; r < rows; ++r) {
      start[r] = total;
      for (size_t ch = 0; ch < chunks; ++ch) {
        const uint32_t c = count[ch * rows + r];
        count[ch * rows + r] = total;
        total += c;
      }
    }
    start[rows] = total;
    auto& splat = m.splats[g];
    splat.resize(total);
    tbb::parallel_for(size_t(0), chunks, [&](size_t ch) {
      uint32_t* next = count.data() + ch * rows;
      for (size_t p = ch * kChunk; p < std::min(P.size(), (ch + 1) * kChunk); ++p) {
        if (row[p] < 0) continue;
        const auto [fx, fy] = cellOf(p);
        Splat& sp = splat[next[size_t(row[p])]++];
        sp.col = int32_t(fx + 1) - 1;
        sp.tx = fx - float(sp.col);
        sp.ty = fy - float(row[p] - 1);
        const float mass = P.mass[p], v2 = P.v[p].squaredNorm();
        const float q[kSums] = {mass * invRho, mass, mass * std::sqrt(v2), mass * v2};
        for (int k = 0; k < kSums; ++k) sp.q[k] = q[k] * perUnit[k]; // a power of two: exact
      }
    });
  }
}

void HazardMaps::Impl::sumBands(const Simulation& sim, const std::vector<uint8_t>& use) {
  Impl& m = *this;
  const auto& groups = sim.groups();
  const int w = m.window.nx, h = m.window.ny;
  constexpr int kBand = 8;
  const int bands = (h + kBand - 1) / kBand;
  m.bandTouched.resize(size_t(bands));
  tbb::parallel_for(0, bands, [&](int band) {
    const int r0 = band * kBand, r1 = std::min(h, r0 + kBand);
    std::vector<uint32_t>& touched = m.bandTouched[size_t(band)];
    touched.clear();
    uint8_t* mark = m.mark.data();
    for (size_t g = 0; g < groups.size(); ++g) {
      if (!use[g]) continue;
      // Per material when there are materials' layers (the total is their sum, at the fold).
      int64_t* __restrict s0 = m.sums[m.layers > 1 ? 1 + g : 0].data();
      const Splat* splats = m.splats[g].data();
      const uint32_t* start = m.rowStart[g].data();
      // Splats starting in row r0 - 1 reach row r0; those starting in row r1 - 1 end in r1.
      for (int j = r0; j <= r1; ++j) {
        const int r = j - 1;
        const bool upper = r >= r0, lower = r + 1 < r1; // which of the splat's rows are ours
        for (uint32_t k = start[j]; k < start[j + 1]; ++k) {
          const Splat sp = splats[k];
          const float wx[2] = {1 - sp.tx, sp.tx}, wy[2] = {1 - sp.ty, sp.ty};
          for (int dr = upper ? 0 : 1; dr < (lower ? 2 : 1); ++dr)
            for (int dc = 0; dc < 2; ++dc) {
              const int cc = sp.col + dc;
              const float wt = wy[dr] * wx[dc];
              if (cc < 0 || cc >= w || !(wt > 0)) continue;
              const uint32_t cell = uint32_t(size_t(r + dr) * w + cc);
              // A float times a float is exact in double: only the fraction of a unit is lost.
              int64_t* s = s0 + kSums * cell;
              for (int q = 0; q < kSums; ++q) s[q] += toUnits(double(wt), double(sp.q[q]));
              if (!mark[cell]) mark[cell] = 1, touched.push_back(cell);
            }
        }
      }
    }
  });
  for (const auto& t : m.bandTouched) m.touched.insert(m.touched.end(), t.begin(), t.end());
}

// A part: the touched cells' indices, then each cell's kSums * layers sums, cell by cell.
void HazardMaps::Impl::writeTouched(std::vector<char>* outs, int ranks, int self) {
  const size_t row = sizeof(int64_t) * kSums, record = row * size_t(layers - firstLayer());
  auto ownerOf = [&](uint32_t cell) { return OutputObserver::ownerOfRow(int(cell / uint32_t(window.nx)), ranks); };
  const size_t n = size_t(ranks);
  std::vector<size_t> count(n, 0), index(n, 0), data(n, 0);
  for (uint32_t cell : touched) ++count[size_t(ownerOf(cell))];
  for (int r = 0; r < ranks; ++r) {
    if (r == self) continue;
    std::vector<char>& out = outs[r];
    index[size_t(r)] = out.size();
    data[size_t(r)] = out.size() + count[size_t(r)] * sizeof(uint32_t);
    out.resize(data[size_t(r)] + count[size_t(r)] * record);
  }
  size_t kept = 0;
  for (uint32_t cell : touched) {
    const int r = ownerOf(cell);
    if (r == self) {
      touched[kept++] = cell;
      continue;
    }
    char* out = outs[r].data();
    std::memcpy(out + index[size_t(r)], &cell, sizeof cell);
    index[size_t(r)] += sizeof cell;
    for (int l = firstLayer(); l < layers; ++l, data[size_t(r)] += row) {
      int64_t* s = sums[size_t(l)].data() + kSums * cell;
      std::memcpy(out + data[size_t(r)], s, row);
      std::fill_n(s, kSums, 0);
    }
    mark[cell] = 0;
  }
  touched.resize(kept);
}

void HazardMaps::Impl::addPart(std::string_view part) {
  const size_t row = sizeof(int64_t) * kSums, record = sizeof(uint32_t) + row * size_t(layers - firstLayer());
  if (part.size() % record) throw std::runtime_error("hazard maps: a part does not hold whole cells");
  const size_t n = part.size() / record;
  const char* at = part.data() + n * sizeof(uint32_t);
  for (size_t i = 0; i < n; ++i) {
    uint32_t cell;
    std::memcpy(&cell, part.data() + i * sizeof(uint32_t), sizeof cell);
    if (cell >= cells) throw std::runtime_error("hazard maps: a part names a cell outside the map");
    for (int l = firstLayer(); l < layers; ++l, at += row) {
      int64_t v[kSums], *s = sums[size_t(l)].data() + kSums * cell;
      std::memcpy(v, at, row);
      for (int k = 0; k < kSums; ++k) s[k] += v[k];
    }
    if (!mark[cell]) mark[cell] = 1, touched.push_back(cell);
  }
}

template <class Fold> void HazardMaps::Impl::foldTouched(Fold&& fold) {
  double scale[kSums];
  for (int k = 0; k < kSums; ++k) scale[k] = powerOfTwo(unit[k]);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, touched.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<float> s(size_t(kSums * layers));
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const uint32_t cell = touched[i];
      int64_t* total = sums[0].data() + kSums * cell;
      for (int l = 1; l < layers; ++l) // the materials' integer sums add up to the total exactly
        for (int k = 0; k < kSums; ++k) total[k] += sums[size_t(l)][kSums * cell + k];
      for (int l = 0; l < layers; ++l) {
        int64_t* n = sums[size_t(l)].data() + kSums * cell;
        for (int k = 0; k < kSums; ++k) s[size_t(l * kSums + k)] = float(double(n[k]) * scale[k]), n[k] = 0;
      }
      mark[cell] = 0;
      fold(cell, s.data());
    }
  });
  touched.clear();
}

void HazardMaps::Impl::thickness(const Simulation& sim, const std::vector<uint8_t>& use,
                                 std::vector<std::vector<float>>& out) {
  out.assign(size_t(layers), std::vector<float>(cells, 0.f));
  const float invArea = float(1.0 / (window.cellSize * window.cellSize));
  setUnits(sim, PartBounds::of(sim)); // one process: it holds every particle here (the start)
  binSplats(sim, use);
  sumBands(sim, use);
  foldTouched([&](uint32_t cell, const float* s) {
    for (int l = 0; l < layers; ++l) out[size_t(l)][cell] = s[l * kSums] * invArea;
  });
}

bool HazardMaps::partsByOwner() const { return impl_->slopeKnown; }

// Every part starts with one byte: whether rank 0 records a film frame from this accumulation
// (only rank 0 knows the film's clock; the others learn it from its part).
void HazardMaps::part(const Simulation& local, const PartBounds& b, bool keep, std::vector<char>& out) {
  Impl& m = *impl_;
  m.sumOwn(local, b, float(settings_.minSpeed));
  if (keep) return; // the sums stay, and onStepParts adds the others to them
  out.push_back(char(m.frameDue)); // read by no one: rank 0 merges these parts
  m.writeTouched(&out, 1, -1);
}

void HazardMaps::partByOwner(const Simulation& local, const PartBounds& b, int self, std::vector<std::vector<char>>& outs) {
  Impl& m = *impl_;
  m.self = self;
  m.sumOwn(local, b, float(settings_.minSpeed));
  const char frame = char(self == 0 && m.frameDue);
  for (int r = 0; r < int(outs.size()); ++r)
    if (r != self) outs[size_t(r)].push_back(frame);
  m.writeTouched(outs.data(), int(outs.size()), self);
}

void HazardMaps::Impl::sumOwn(const Simulation& local, const PartBounds& b, float minSpeed) {
  const std::vector<uint8_t> all(local.groups().size(), 1);
  setUnits(local, b);
  binSplats(local, all, minSpeed); // moving material only, when min_speed is set
  sumBands(local, all);
}

void HazardMaps::onStepParts(const Simulation& sim, double, const PartBounds& b,
                             const std::vector<std::string_view>& parts) {
  // Every part's cells are summed as integers, so each cell's sum is the same whatever the split
  // of the particles into parts (ranks) and bands (threads): maps are bit-identical at any
  // number of either. Each cell is then folded into the maxima on its own, in parallel; by
  // owner, each process folds its own cells (a maximum is the same over any split of the steps).
  if (parts.empty()) return;
  Impl& m = *impl_;
  m.setUnits(sim, b);
  const bool fromRoot = m.self != 0 && !parts[0].empty();
  m.framePending = m.self == 0 ? animationFrameDue(sim.time()) : fromRoot && parts[0][0];
  for (const auto& p : parts)
    if (!p.empty()) m.addPart(p.substr(1));
  m.lastTime = sim.time();
  m.endTime = sim.time();
  ++accumulations_;
  const float invArea = float(1.0 / (m.window.cellSize * m.window.cellSize));
  const float minH = float(settings_.minHeight);
  const size_t n = m.cells;
  // An animation frame records this accumulation's thickness and speed of all material.
  const bool frame = m.framePending;
  if (frame) m.frameThickness.assign(n, 0.f), m.frameSpeed.assign(n, 0.f);
  m.foldTouched([&](uint32_t cell, const float* all) {
    if (frame) {
      m.frameThickness[cell] = all[0] * invArea;
      if (all[0] * invArea >= minH && all[1] > 0) m.frameSpeed[cell] = all[2] / all[1];
    }
    const float cosS = m.cosAt(cell);
    for (int l = 0; l < m.layers; ++l) {
      const float* s = all + l * kSums;
      if (!(s[0] > 0)) continue;
      float* mx = m.maxima[size_t(l)].data();
      const float hv = s[0] * invArea;
      mx[MaxHeightVertical * n + cell] = std::max(mx[MaxHeightVertical * n + cell], hv);
      mx[MaxHeightNormal * n + cell] = std::max(mx[MaxHeightNormal * n + cell], hv * cosS);
      if (hv >= minH) {
        mx[MaxSpeed * n + cell] = std::max(mx[MaxSpeed * n + cell], s[2] / s[1]);
        mx[MaxPressure * n + cell] = std::max(mx[MaxPressure * n + cell], 1e-3f * s[3] / s[0]);
      }
    }
  });
}

} // namespace talus
