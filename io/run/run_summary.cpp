#include "io/run/run_summary.h"

#include "engine/detrainment.h"
#include "engine/inflow_source.h"
#include "engine/secondary_release.h"
#include "io/common/atomic_file.h"

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include <sys/resource.h>

namespace talus {

namespace {
std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream o;
  o << std::setprecision(10) << v;
  return o.str();
}
std::string vec(const Vec3d& v) { return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]"; }
std::string memoryJson(const MemoryFigures& m) {
  return "{\"particles\": " + std::to_string(m.particles) + ", \"grid\": " + std::to_string(m.grid) +
         ", \"terrain\": " + std::to_string(m.terrain) + ", \"peak_resident\": " + std::to_string(m.peakResident) + "}";
}
} // namespace

MemoryFigures memoryFigures(const Simulation& sim) {
  MemoryFigures m;
  m.particles = sim.particleBytes(), m.grid = sim.gridBytes(), m.terrain = sim.terrainBytes();
  rusage u{};
  if (getrusage(RUSAGE_SELF, &u) == 0) m.peakResident = uint64_t(u.ru_maxrss) * 1024; // Linux: kilobytes
  return m;
}

std::string writeSummaryJson(const std::string& path, const Simulation& sim, const RunInfo& info) {
  std::ostringstream j;
  const double pss = info.wallSeconds > 0 ? double(sim.particleSteps()) / info.wallSeconds : 0;
  j << "{\n";
  j << "  \"scene\": " << jsonString(info.scene) << ",\n";
  j << "  \"status\": " << jsonString(info.status) << ",\n";
  if (!info.signal.empty())
    j << "  \"interrupted_by\": " << jsonString(info.signal) << ",\n  \"checkpoint\": \"checkpoint.h5\",\n";
  j << "  \"steps\": " << sim.steps() << ",\n";
  j << "  \"simulated_time\": " << num(sim.time()) << ",\n";
  j << "  \"wall_seconds\": " << num(info.wallSeconds) << ",\n";
  j << "  \"threads\": " << info.threads << ",\n";
  if (!info.ranks.empty()) {
    // Per rank: its particles and owning blocks at the end, and where its time went.
    // How often rank 0 held every particle at once: the start, the end, and frames in a VDB format
    // or checkpoints where the ranks do not share the output folder (docs/scaling.md).
    j << "  \"ranks\": " << info.ranks.size() << ",\n  \"rank0_gathered_every_particle\": " << info.wholeGathers
      << ",\n  \"per_rank\": [\n";
    for (size_t r = 0; r < info.ranks.size(); ++r) {
      const RankFigures& f = info.ranks[r];
      j << "    {\"rank\": " << r << ", \"particles\": " << f.particles << ", \"blocks\": " << f.blocks
        << ", \"compute_seconds\": " << num(f.computeSeconds) << ", \"communication_seconds\": "
        << num(f.communicationSeconds) << ", \"bytes_sent\": " << f.bytesSent << ", \"collective_calls\": " << f.collectives
        << ", \"rebalances\": " << f.rebalances
        << ", \"memory_bytes\": " << memoryJson(f.memory) << "}" << (r + 1 < info.ranks.size() ? "," : "") << "\n";
    }
    j << "  ],\n";
  } else {
    j << "  \"memory_bytes\": " << memoryJson(info.memory) << ",\n";
  }
  j << "  \"particles\": " << sim.particleCount() << ",\n";
  j << "  \"particle_steps\": " << sim.particleSteps() << ",\n";
  j << "  \"particle_steps_per_second\": " << num(pss) << ",\n";
  j << "  \"particle_steps_per_second_per_thread\": " << num(pss / std::max(1, info.threads)) << ",\n";
  j << "  \"mass_initial\": " << num(sim.initialMass()) << ",\n";
  j << "  \"mass_final\": " << num(sim.totalMass()) << ",\n";
  j << "  \"mass_removed\": " << num(sim.totalMassRemoved()) << ",\n";
  if (const ErodibleBed* bed = sim.bed()) { // covers made fields: their mass is not in mass_initial
    j << "  \"erodible_fields\": [";
    for (size_t k = 0; k < bed->covers().size(); ++k)
      j << (k ? ", " : "") << "{\"name\": " << jsonString(bed->covers()[k].name) << ", \"material\": "
        << jsonString(sim.groups()[size_t(bed->covers()[k].group)]->name()) << ", \"mass_initial\": "
        << num(bed->initialMass(k)) << ", \"mass_entrained\": " << num(bed->entrainedMass(k))
        << ", \"mass_pooled\": " << num(bed->pooledMass(k)) << "}";
    j << "],\n";
  }
  std::string held, inflows, detrained; // secondary releases (released when, null: held), inflows, forests
  for (const auto& src : sim.sources()) {
    if (const auto* h = dynamic_cast<const SecondaryReleases*>(src.get()))
      for (size_t b = 0; b < h->bodies().size(); ++b) {
        const double t = h->releaseTime(b);
        held += std::string(held.empty() ? "" : ", ") + "{\"name\": " + jsonString(h->bodies()[b].name) +
                ", \"released_s\": " + (std::isnan(t) ? std::string("null") : num(t)) + "}";
      }
    if (const auto* f = dynamic_cast<const InflowSource*>(src.get()))
      inflows += std::string(inflows.empty() ? "" : ", ") + "{\"name\": " + jsonString(f->spec().name) +
                 ", \"volume_m3\": " + num(f->emittedVolume()) + ", \"hydrograph_m3\": " +
                 num(f->hydrographVolume(sim.time())) + "}";
    if (const auto* d = dynamic_cast<const Detrainment*>(src.get()))
      for (const MaterialGroup* g : sim.groups())
        detrained += std::string(detrained.empty() ? "" : ", ") + jsonString(g->name()) + ": " +
                     num(d->detrainedMass(size_t(g->index())));
  }
  if (!held.empty()) j << "  \"secondary_releases\": [" << held << "],\n";
  if (!detrained.empty()) j << "  \"detrained_kg\": {" << detrained << "},\n";
  if (!inflows.empty()) j << "  \"inflows\": [" << inflows << "],\n";
  j << "  \"max_speed\": " << num(sim.maxSpeed()) << ",\n";
  j << "  \"origin\": " << vec(sim.settings().origin) << ",\n";
  j << "  \"notes\": [";
  for (size_t i = 0; i < info.notes.size(); ++i) j << (i ? ", " : "") << jsonString(info.notes[i]);
  j << "],\n";
  const PhaseTimes& t = sim.phaseTimes();
  j << "  \"phase_seconds\": {\"bin\": " << num(t.bin) << ", \"colliders\": " << num(t.colliders) << ", \"p2g\": "
    << num(t.p2g) << ", \"grid\": " << num(t.grid) << ", \"g2p\": " << num(t.g2p) << ", \"cull\": " << num(t.cull)
    << "},\n";
  j << "  \"materials\": [";
  bool first = true;
  for (const MaterialGroup* g : sim.groups()) {
    Vec3d lo = Vec3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    double mass = 0;
    for (size_t i = 0; i < g->size(); ++i) {
      const Vec3d x = g->particles.x[i].cast<double>() + sim.settings().origin;
      lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
      mass += double(g->particles.mass[i]);
    }
    j << (first ? "\n" : ",\n") << "    {\"name\": " << jsonString(g->name()) << ", \"model\": "
      << jsonString(g->modelName()) << ", \"particles\": " << g->size() << ", \"mass\": " << num(mass)
      << ", \"mass_removed\": " << num(sim.massRemoved()[size_t(g->index())]) << ", \"bbox_min\": "
      << (g->size() ? vec(lo) : "null") << ", \"bbox_max\": " << (g->size() ? vec(hi) : "null") << "}";
    first = false;
  }
  j << "\n  ],\n";
  // What each requested output cost and wrote, so a user sees what maps or frames cost.
  j << "  \"outputs\": [";
  first = true;
  for (const OutputReport& o : info.outputs) {
    j << (first ? "\n" : ",\n") << "    {\"name\": " << jsonString(o.name) << ", \"seconds\": " << num(o.seconds)
      << ", \"files\": [";
    for (size_t i = 0; i < o.files.size(); ++i) j << (i ? ", " : "") << jsonString(o.files[i]);
    j << "]}";
    first = false;
  }
  j << "\n  ]";
  for (const OutputReport& o : info.outputs)
    for (const auto& [key, value] : o.summary) j << ",\n  " << jsonString(key) << ": " << value;
  j << "\n}\n";
  const std::string text = j.str();
  writeAtomically(path, [&](const std::string& tmp) { writeFileBytes(tmp, text); });
  return text;
}

} // namespace talus
