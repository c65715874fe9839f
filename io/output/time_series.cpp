#include "io/output/time_series.h"

#include "io/common/atomic_file.h"
#include "io/output/collider_loads.h"
#include "io/output/entrained_mass.h"
#include "io/output/front_tracker.h"
#include "io/output/probe_tracker.h"
#include "io/output/section_discharge.h"
#include "io/output/series_plots.h"
#include "io/output/water_gauges.h"

#include <cmath>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace talus {

int SeriesTable::column(const std::string& name) const {
  for (size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return int(i);
  return -1;
}

namespace {

/// Energies, masses and the maximum speed. Potential energy is -m g.x relative to the initial
/// state, so kinetic + potential shows what friction and plasticity dissipated.
class StateColumns final : public PartsColumns {
public:
  void onStart(const Simulation& sim) override {
    names_.clear();
    for (const auto* g : sim.groups()) names_.push_back(safeName(g->name()));
    covers_.clear();
    if (sim.bed())
      for (const auto& c : sim.bed()->covers()) covers_.push_back(safeName(c.name));
    first_ = true;
  }
  std::vector<std::string> header() const override {
    std::vector<std::string> h;
    for (const auto& n : names_) h.push_back("kinetic_energy_J_" + n);
    if (names_.size() > 1) h.push_back("kinetic_energy_J_total");
    h.push_back("potential_energy_J");
    for (const auto& n : names_) h.push_back("mass_kg_" + n);
    h.push_back("mass_removed_kg");
    h.push_back("max_speed_m_s");
    // Covers made fields (engine/erodible_bed.h): the mass the flow has taken from each.
    for (const auto& n : covers_) h.push_back("entrained_mass_kg_field_" + n);
    return h;
  }
  // Per material: mass, kinetic and potential energy as fixed-point sums (each particle's value
  // in 64-bit units below 2^-62 of the largest, summed in 128 bits: exact in any order), and the
  // mass culled here.
  void part(const Simulation& local, const PartBounds& b, std::vector<char>& out) const override {
    PartWriter put(out);
    const Vec3d g = local.settings().gravity;
    const Units u = unitsOf(local, b);
    const double per[3] = {powerOfTwo(-u.e[0]), powerOfTwo(-u.e[1]), powerOfTwo(-u.e[2])};
    for (size_t gi = 0; gi < local.groups().size(); ++gi) {
      const ParticleSet& P = local.groups()[gi]->particles;
      const Sums s = tbb::parallel_reduce(
          tbb::blocked_range<size_t>(0, P.size(), 8192), Sums{},
          [&](const tbb::blocked_range<size_t>& r, Sums acc) {
            for (size_t i = r.begin(); i != r.end(); ++i) {
              const double m = double(P.mass[i]);
              acc.v[0] += toUnits(m, per[0]);
              acc.v[1] += toUnits(0.5 * m * double(P.v[i].squaredNorm()), per[1]);
              acc.v[2] += toUnits(-m * g.dot(P.x[i].cast<double>()), per[2]);
            }
            return acc;
          },
          [](Sums a, const Sums& c) {
            for (int k = 0; k < 3; ++k) a.v[k] += c.v[k];
            return a;
          });
      for (int k = 0; k < 3; ++k) put.put(s.v[k]);
      put.put(gi < local.massRemoved().size() ? local.massRemoved()[gi] : 0.0);
    }
  }
  void sampleParts(const Simulation& sim, double, const PartBounds& b, const std::vector<std::string_view>& parts,
                   std::vector<double>& row) override {
    const size_t n = sim.groups().size();
    std::vector<Sums> sums(n);
    std::vector<double> removed(n, 0.0);
    for (const auto& p : parts) {
      PartReader get(p);
      for (size_t gi = 0; gi < n; ++gi) {
        for (int k = 0; k < 3; ++k) sums[gi].v[k] += get.get<__int128>();
        removed[gi] += get.get<double>(); // in rank order, as the ranks' ledgers are summed
      }
    }
    const Units u = unitsOf(sim, b);
    auto value = [&](__int128 n, int k) { return double(n) * powerOfTwo(u.e[k]); };
    double kinetic = 0, potential = 0, massRemoved = 0;
    for (const Sums& s : sums) {
      const double k = value(s.v[1], 1);
      row.push_back(k), kinetic += k, potential += value(s.v[2], 2);
    }
    if (names_.size() > 1) row.push_back(kinetic);
    if (first_) potential0_ = potential, first_ = false;
    row.push_back(potential - potential0_);
    for (const Sums& s : sums) row.push_back(value(s.v[0], 0));
    for (double r : removed) massRemoved += r;
    row.push_back(massRemoved);
    row.push_back(sim.maxSpeed());
    for (size_t k = 0; k < covers_.size(); ++k) row.push_back(sim.bed()->entrainedMass(k));
  }

private:
  void save(StateArchive& a, const std::string& prefix) const override { a.putValue(prefix + "potential0", potential0_); }
  void load(const StateArchive& a, const std::string& prefix) override { potential0_ = a.getValue<double>(prefix + "potential0"); }

  struct Sums {
    __int128 v[3] = {0, 0, 0}; ///< mass, kinetic, potential
  };
  struct Units {
    int e[3];
  };
  static Units unitsOf(const Simulation& sim, const PartBounds& b) {
    const Vec3d g = sim.settings().gravity;
    const double gSum = std::abs(g.x()) + std::abs(g.y()) + std::abs(g.z());
    return {{unitExponent(b.maxMass, kTotalBits), unitExponent(0.5 * b.maxMass * b.maxSpeed2, kTotalBits),
             unitExponent(b.maxMass * gSum * b.maxCoord, kTotalBits)}};
  }

  std::vector<std::string> names_, covers_;
  double potential0_ = 0; ///< potential energy at the first row (-m g.x, local frame)
  bool first_ = true;
};

/// Highest water particle (world z, m): the materials listed in water_materials, or else every
/// material whose model is "water". No column when there is none.
class WaterSurfaceColumns final : public PartsColumns {
public:
  explicit WaterSurfaceColumns(std::vector<std::string> names) : names_(std::move(names)) {}
  void onStart(const Simulation& sim) override {
    // By index: rank 0 starts on its gathered copy and takes parts from its own groups.
    water_ = waterGroupIndices(sim, names_);
  }
  bool any() const { return !water_.empty(); }
  std::vector<std::string> header() const override { return {"max_water_surface_m"}; }
  void part(const Simulation& local, const PartBounds&, std::vector<char>& out) const override {
    double z = -std::numeric_limits<double>::infinity(); // a maximum: exact in any order
    for (size_t g : water_)
      for (const Vec3& x : local.groups()[g]->particles.x) z = std::max(z, double(x[2]));
    PartWriter(out).put(z);
  }
  void sampleParts(const Simulation& sim, double, const PartBounds&, const std::vector<std::string_view>& parts,
                   std::vector<double>& row) override {
    double z = -std::numeric_limits<double>::infinity();
    for (const auto& p : parts) z = std::max(z, PartReader(p).get<double>());
    row.push_back(std::isfinite(z) ? z + sim.settings().origin.z() : std::numeric_limits<double>::quiet_NaN());
  }

private:
  std::vector<std::string> names_;
  std::vector<size_t> water_; ///< indices into the groups
};

} // namespace

TimeSeries::TimeSeries(std::string outDir, const OutputSettings& s, double endTime, double particleSpacing)
    : outDir_(std::move(outDir)), plots_(s.plots), interval_(s.seriesInterval > 0 ? s.seriesInterval : endTime / 1000) {
  columns_.push_back(std::make_unique<StateColumns>());
  if (!s.maps.erodible.empty()) columns_.push_back(std::make_unique<EntrainedMassColumns>(s.maps.erodible));
  for (const auto& sec : s.sections) columns_.push_back(std::make_unique<SectionDischarge>(sec));
  for (const auto& p : s.paths) columns_.push_back(std::make_unique<FrontTracker>(p, particleSpacing));
  for (const auto& p : s.probes) columns_.push_back(std::make_unique<ProbeTracker>(p));
  if (!s.gauges.empty()) columns_.push_back(std::make_unique<WaterGauges>(s.gauges, s.waterMaterials, particleSpacing));
  if (s.loads) {
    auto loads = std::make_unique<ColliderLoadColumns>();
    loads_ = loads.get();
    columns_.push_back(std::move(loads));
  }
  columns_.push_back(std::make_unique<WaterSurfaceColumns>(s.waterMaterials));
}

TimeSeries::~TimeSeries() = default;

void TimeSeries::prepare(const Simulation& sim, bool whole) {
  for (auto& c : columns_) whole ? c->onStart(sim) : c->prepareParts(sim);
  // The water column only exists when the scene has water.
  if (auto* w = dynamic_cast<WaterSurfaceColumns*>(columns_.back().get()); w && !w->any()) columns_.pop_back();
  table_.header = {"time_s", "dt_s"};
  for (const auto& c : columns_)
    for (const auto& h : c->header()) table_.header.push_back(h);
  shared_ = false;
  for (const auto& c : columns_) shared_ |= c->reads() == SeriesColumns::Reads::Shared;
}

void TimeSeries::prepareParts(const Simulation& sim) { prepare(sim, false); }

void TimeSeries::onStart(const Simulation& sim) {
  prepare(sim, true);
  root_ = true;
  lastSample_ = sim.time();
  sample(sim);
}

void TimeSeries::stepLocal(const Simulation& local, double dt) {
  for (auto& c : columns_) c->stepLocal(local, dt);
}

bool TimeSeries::accumulatesOnRanks() const {
  for (const auto& c : columns_)
    if (c->accumulates()) return true;
  return false;
}

void TimeSeries::ownedResult(bool state, std::vector<char>& out) {
  if (!state) return; // nothing by owner
  for (auto& c : columns_) {
    if (!c->accumulates()) continue;
    std::vector<char> p;
    c->handOver(p);
    putSized(out, p);
  }
}

void TimeSeries::mergeResults(const Simulation&, bool state, const std::vector<std::string_view>& others) {
  if (!state) return;
  for (std::string_view rest : others)
    for (auto& c : columns_)
      if (c->accumulates()) c->takeOver(takeSized(rest));
}

bool TimeSeries::sampleDue(const Simulation& sim) const { return sim.time() >= nextSample_ - 1e-9 * interval_; }

bool TimeSeries::partDue(const Simulation& sim) const { return shared_ || sampleDue(sim); }

void TimeSeries::putParts(const Simulation& local, const PartBounds& b, bool samples, std::vector<char>& out) const {
  for (const auto& c : columns_) {
    if (c->reads() != SeriesColumns::Reads::Shared) continue;
    std::vector<char> p;
    c->sharedPart(local, b, p);
    putSized(out, p);
  }
  if (!samples) return;
  for (const auto& c : columns_) {
    if (c->reads() != SeriesColumns::Reads::Parts) continue;
    std::vector<char> p;
    c->part(local, b, p);
    putSized(out, p);
  }
}

void TimeSeries::part(const Simulation& local, const PartBounds& b, bool, std::vector<char>& out) {
  // Due without probes means a row (rank 0 decides; another process keeps no clock then).
  putParts(local, b, !shared_ || sampleDue(local), out);
}

void TimeSeries::partByOwner(const Simulation& local, const PartBounds& b, int, std::vector<std::vector<char>>& outs) {
  // The probes' sums to every process; a row's parts to rank 0 alone. Every process keeps the
  // series' clock (its state comes from rank 0), so each knows when a row is due.
  const bool samples = sampleDue(local);
  for (size_t r = 0; r < outs.size(); ++r) putParts(local, b, samples && r == 0, outs[r]);
}

void TimeSeries::onStepParts(const Simulation& sim, double dt, const PartBounds& b,
                             const std::vector<std::string_view>& parts) {
  lastDt_ = dt;
  for (auto& c : columns_) c->onStep(sim, dt); // none reads particles (SeriesColumns::reads)
  if (parts.empty()) return;
  // Each process's part is its columns' parts in turn, each after its length: the Shared
  // columns' first, then, at a row, the Parts columns'.
  std::vector<std::string_view> rest = parts;
  auto take = [&] {
    std::vector<std::string_view> mine;
    for (auto& r : rest) mine.push_back(takeSized(r));
    return mine;
  };
  for (auto& c : columns_)
    if (c->reads() == SeriesColumns::Reads::Shared) c->sharedStep(sim, dt, b, take());
  if (!sampleDue(sim)) return;
  if (!root_) return advanceClock(sim); // only rank 0 makes the row
  const double elapsed = sim.time() - lastSample_;
  std::vector<double> row{sim.time(), lastDt_};
  for (auto& c : columns_)
    c->sampleParts(sim, elapsed, b, c->reads() == SeriesColumns::Reads::Parts ? take() : std::vector<std::string_view>(), row);
  endSample(sim, std::move(row));
}

void TimeSeries::shareState(std::vector<char>& out) const {
  PartWriter(out).put(nextSample_);
  for (const auto& c : columns_) {
    if (c->reads() != SeriesColumns::Reads::Shared) continue;
    std::vector<char> p;
    c->shareState(p);
    putSized(out, p);
  }
}

void TimeSeries::takeState(std::string_view in) {
  nextSample_ = PartReader(in).get<double>();
  in.remove_prefix(sizeof nextSample_);
  for (auto& c : columns_)
    if (c->reads() == SeriesColumns::Reads::Shared) c->takeState(takeSized(in));
}

void TimeSeries::save(StateArchive& a, const std::string& prefix) const {
  std::vector<double> flat;
  for (const auto& r : table_.rows) flat.insert(flat.end(), r.begin(), r.end());
  a.putVector(prefix + "rows", flat);
  a.putValue(prefix + "row_width", uint64_t(table_.header.size()));
  const double clock[3] = {lastSample_, nextSample_, lastDt_};
  a.put(prefix + "clock", clock, sizeof clock);
  for (size_t i = 0; i < columns_.size(); ++i) columns_[i]->save(a, prefix + "columns" + std::to_string(i) + "/");
}

void TimeSeries::load(const StateArchive& a, const std::string& prefix) {
  std::vector<double> flat;
  a.getVector(prefix + "rows", flat);
  const size_t width = size_t(a.getValue<uint64_t>(prefix + "row_width"));
  if (width != table_.header.size()) throw std::runtime_error("checkpoint series has different columns than the scene");
  table_.rows.clear();
  for (size_t i = 0; i + width <= flat.size(); i += width)
    table_.rows.emplace_back(flat.begin() + long(i), flat.begin() + long(i + width));
  double clock[3];
  a.get(prefix + "clock", clock, sizeof clock);
  lastSample_ = clock[0], nextSample_ = clock[1], lastDt_ = clock[2];
  for (size_t i = 0; i < columns_.size(); ++i) columns_[i]->load(a, prefix + "columns" + std::to_string(i) + "/");
}

void TimeSeries::onStep(const Simulation& sim, double dt) {
  // One process with every particle: the calls of a run in parts, with its own part alone.
  stepLocal(sim, dt);
  stepOwnPart(sim, dt);
}

void TimeSeries::sample(const Simulation& sim) {
  const double elapsed = sim.time() - lastSample_;
  std::vector<double> row{sim.time(), lastDt_};
  for (auto& c : columns_) c->sample(sim, elapsed, row);
  endSample(sim, std::move(row));
}

void TimeSeries::endSample(const Simulation& sim, std::vector<double>&& row) {
  table_.rows.push_back(std::move(row));
  advanceClock(sim);
}

void TimeSeries::advanceClock(const Simulation& sim) {
  lastSample_ = sim.time();
  nextSample_ = (std::floor(sim.time() / interval_ + 1e-9) + 1) * interval_;
}

void TimeSeries::writeCsv() {
  const std::string path = (std::filesystem::path(outDir_) / "series.csv").string();
  writeAtomically(path, [&](const std::string& tmp) {
    std::string f;
    for (size_t i = 0; i < table_.header.size(); ++i) f += (i ? "," : "") + table_.header[i];
    f += '\n';
    char buf[32];
    for (const auto& row : table_.rows) {
      for (size_t i = 0; i < row.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%.10g", row[i]);
        if (i) f += ',';
        f += buf;
      }
      f += '\n';
    }
    writeFileBytes(tmp, f);
  });
  recordFile("series.csv");
}

void TimeSeries::onFrame(const Simulation&, int) { writeCsv(); }

std::vector<std::pair<std::string, std::string>> TimeSeries::summary() const {
  if (!loads_) return {};
  return {{"loads", loads_->summaryJson()}};
}

void TimeSeries::onFinish(const Simulation& sim, bool completed) {
  if (completed && (table_.rows.empty() || table_.rows.back()[0] < sim.time())) sample(sim);
  writeCsv();
  if (plots_)
    for (const auto& f : writeSeriesPlots(outDir_, table_)) recordFile(f);
}

} // namespace talus
