#include "io/output/avaframe_run_files.h"

#include "engine/detrainment.h"
#include "io/common/atomic_file.h"
#include "io/output/peak_files.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace talus {

namespace fs = std::filesystem;

AvaFrameRunFiles::AvaFrameRunFiles(std::string outDir, const OutputSettings& s, const RunContext& run)
    : outDir_(std::move(outDir)), simName_(avaFrameSimName(s.maps.peakFiles)), simType_(s.maps.peakFiles.simType),
      sceneKeys_(run.sceneKeys), erodible_(s.maps.erodible), dx_(run.dx), endTime_(run.endTime),
      entrained_(s.maps.erodible) {}

void AvaFrameRunFiles::onStart(const Simulation& sim) {
  entrained_.onStart(sim);
  rows_.clear();
  next_ = 0;
  onStep(sim, 0); // the row at t = 0: the released mass (AIMEC's relMass)
}

void AvaFrameRunFiles::onStep(const Simulation& sim, double dt) {
  if (!partDue(sim)) return;
  stepOwnPart(sim, dt);
}

bool AvaFrameRunFiles::partDue(const Simulation& sim) const { return sim.time() + 1e-9 >= double(next_) * kInterval; }

void AvaFrameRunFiles::part(const Simulation& local, const PartBounds& b, bool, std::vector<char>& out) {
  // The particles' mass but the covers' (below), in fixed point: exact in any order.
  const double perUnit = powerOfTwo(-unitExponent(b.maxMass, kTotalBits));
  __int128 units = 0;
  for (const auto& g : local.groups()) {
    if (std::find(erodible_.begin(), erodible_.end(), g->name()) != erodible_.end()) continue;
    for (Real m : g->particles.mass) units += toUnits(double(m), perUnit);
  }
  PartWriter(out).put(units);
  if (!erodible_.empty()) entrained_.part(local, b, out); // the covers' columns after it
}

void AvaFrameRunFiles::onStepParts(const Simulation& sim, double, const PartBounds& b,
                                   const std::vector<std::string_view>& parts) {
  if (parts.empty()) return;
  __int128 units = 0;
  std::vector<std::string_view> columns;
  for (const auto& p : parts) {
    units += PartReader(p).get<__int128>();
    columns.push_back(p.substr(sizeof units));
  }
  const double mass = double(units) * powerOfTwo(unitExponent(b.maxMass, kTotalBits));
  std::vector<double> covers;
  if (!erodible_.empty()) entrained_.sampleParts(sim, 0, b, columns, covers);
  // Rows on com1DFA's 0.1 s clock, each the state after the step that reaches it.
  while (partDue(sim)) sample(sim, double(next_++) * kInterval, mass, covers);
}

void AvaFrameRunFiles::sample(const Simulation& sim, double t, double particleMass, const std::vector<double>& covers) {
  double current = particleMass, entrained = 0;
  for (double m : covers) entrained += m, current += m; // what a cover lost is in the flow
  if (const ErodibleBed* bed = sim.bed())
    for (size_t k = 0; k < bed->covers().size(); ++k) {
      entrained += bed->entrainedMass(k);
      current += bed->pooledMass(k); // eroded, not yet a particle (those are counted above)
    }
  double detrained = 0;
  for (const auto& src : sim.sources())
    if (const auto* d = dynamic_cast<const Detrainment*>(src.get())) detrained += d->detrainedMass();
  rows_.insert(rows_.end(), {t, current, entrained, detrained});
}

std::string AvaFrameRunFiles::configuration() const {
  auto value = [&](const std::string& key) -> std::string {
    std::istringstream in(sceneKeys_);
    for (std::string line; std::getline(in, line);)
      if (line.rfind(key + " = ", 0) == 0) {
        std::string v = line.substr(key.size() + 3);
        if (v.size() >= 2 && v.front() == '"' && v.back() == '"') v = v.substr(1, v.size() - 2);
        return v;
      }
    return "";
  };
  auto escaped = [](std::string v) { // configparser's interpolation reads % as a reference
    for (size_t p = v.find('%'); p != std::string::npos; p = v.find('%', p + 2)) v.insert(p, "%");
    return v;
  };
  const std::string law = value("terrain.boundary");
  const std::string frict = law == "samosat" ? "samosAT" : law == "voellmy" ? "Voellmy" : law == "coulomb" ? "Coulomb" : law;
  std::ostringstream o;
  o << "# Talus run " << simName_ << ": what com1DFA names, then every scene key ([TALUS])\n[GENERAL]\n";
  o << "simTypeActual = " << simType_ << "\nmodelType = mpm\ntEnd = " << endTime_ << "\nmeshCellSize = " << dx_ << "\n";
  if (!frict.empty()) o << "frictModel = " << frict << "\n";
  // The parameters an AvaFrame user varies, under com1DFA's names where Talus has them.
  const std::pair<const char*, const char*> names[] = {{"mu", "terrain.friction"},
                                                       {"relTh", "avaframe.release_thickness"},
                                                       {"entEroEnergy", "avaframe.erosion_energy"}};
  for (const auto& [af, talus] : names)
    if (const std::string v = value(talus); !v.empty()) o << af << " = " << escaped(v) << "\n";
  o << "\n[TALUS]\n";
  std::istringstream in(sceneKeys_);
  for (std::string line; std::getline(in, line);) o << escaped(line) << "\n";
  return o.str();
}

void AvaFrameRunFiles::onFinish(const Simulation&, bool) {
  const std::string mass = "mass_" + simName_ + ".txt";
  writeAtomically((fs::path(outDir_) / mass).string(), [&](const std::string& path) {
    std::ofstream out(path);
    out << "time, current, entrained, detrained, detrainedTotal, stopped\n";
    char line[192];
    // entrained and detrained per row (AIMEC sums the entrained column), detrainedTotal so far.
    for (size_t r = 0; r + 3 < rows_.size(); r += 4) {
      const double entrained = rows_[r + 2] - (r ? rows_[r - 2] : 0.0), detrained = rows_[r + 3] - (r ? rows_[r - 1] : 0.0);
      std::snprintf(line, sizeof line, "%.2f,    %.6f,    %.6f,    %.6f,    %.6f,    %.6f\n", rows_[r], rows_[r + 1],
                    entrained, detrained, rows_[r + 3], 0.0);
      out << line;
    }
  });
  recordFile(mass);
  const std::string ini = "configurationFiles/" + simName_ + ".ini";
  fs::create_directories(fs::path(outDir_) / "configurationFiles");
  writeAtomically((fs::path(outDir_) / ini).string(), [&](const std::string& path) { std::ofstream(path) << configuration(); });
  recordFile(ini);
}

void AvaFrameRunFiles::save(StateArchive& a, const std::string& prefix) const {
  a.putVector(prefix + "rows", rows_);
  a.putValue(prefix + "next", next_);
}

void AvaFrameRunFiles::load(const StateArchive& a, const std::string& prefix) {
  a.getVector(prefix + "rows", rows_);
  next_ = a.getValue<long>(prefix + "next");
}

} // namespace talus
