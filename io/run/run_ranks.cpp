#include "io/run/run_ranks.h"

#include <cstring>

namespace talus {

std::vector<RankFigures> rankFigures(const Simulation& sim) {
  const DomainDecomposition& dd = *sim.ranks();
  RankFigures f;
  f.particles = sim.particleCount();
  f.blocks = sim.grid().owning.size();
  f.bytesSent = dd.comm().bytesSent;
  f.rebalances = dd.rebalances;
  f.communicationSeconds = dd.comm().seconds;
  f.computeSeconds = sim.phaseTimes().total() - sim.phaseTimes().halo;
  std::vector<char> mine(sizeof f);
  std::memcpy(mine.data(), &f, sizeof f);
  std::vector<size_t> counts;
  const std::vector<char> all = dd.comm().gather(mine, counts);
  std::vector<RankFigures> out(all.size() / sizeof f);
  if (!out.empty()) std::memcpy(static_cast<void*>(out.data()), all.data(), all.size());
  return out;
}

} // namespace talus
