#include "io/run/run_ranks.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sched.h>
#include <unistd.h>

namespace talus {

void RootLoadBalance::afterStep(const RunRanks& ranks, Simulation& sim) {
  const double compute = sim.phaseTimes().total() - sim.phaseTimes().halo;
  if (compute0_ < 0) compute0_ = compute; // the first step: start the window here
  work_ += double(sim.particleCount());
  const int n = ranks.comm().size();
  if (++steps_ < window_ || n < 2) return;
  // Seconds per particle-step over all ranks (rank 0 may own none), rank 0's output seconds.
  double sums[3] = {compute - compute0_, work_, ranks.root() ? output_ : 0.0};
  ranks.comm().sum(sums, 3);
  steps_ = 0, output_ = 0, work_ = 0, compute0_ = compute;
  if (sums[0] <= 0 || sums[1] <= 0) return;
  const double equivalent = sums[2] / (sums[0] / sums[1]) / window_; // particles per step
  const double total = double(sim.globalParticleCount());
  const double target = std::max(0.0, 1.0 / n - equivalent * (n - 1) / (n * total));
  // Halfway there each window, so one slow step (a page fault, a plot) does not empty rank 0.
  // Every rank takes rank 0's figure: ranges computed from different shares would lose particles.
  const double previous = share_ < 0 ? 1.0 / n : share_;
  share_ = ranks.comm().maxOf(ranks.root() ? 0.5 * (previous + target) : -1.0);
  std::vector<double> shares(size_t(n), (1 - share_) / (n - 1));
  shares[0] = share_;
  sim.setRankShares(std::move(shares));
}

bool RunRanks::shareFolder(const std::string& dir) const {
  if (!active()) return true;
  // A token no other run writes: rank 0's host, process and clock.
  const std::filesystem::path probe = std::filesystem::path(dir) / ".talus_ranks_probe";
  std::string token;
  if (root()) {
    char host[64] = {};
    gethostname(host, sizeof host - 1);
    token = std::string(host) + " " + std::to_string(getpid()) + " " +
            std::to_string(std::chrono::steady_clock::now().time_since_epoch().count());
    std::ofstream(probe) << token; // closed here, before the others look (NFS: close-to-open)
  }
  std::vector<size_t> counts;
  const std::vector<char> all = comm_->allGather(std::vector<char>(token.begin(), token.end()), counts);
  std::ifstream in(probe);
  const std::string seen((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const bool same = !counts.empty() && counts[0] > 0 && seen == std::string(all.data(), counts[0]);
  const bool everyone = comm_->minOf(same ? 1.0 : 0.0) > 0;
  std::error_code ec;
  if (root()) std::filesystem::remove(probe, ec); // after every rank has looked
  return everyone;
}

namespace {
/// What a rank tells rank 0 when it lends its CPUs.
struct Lender {
  char host[64];
  cpu_set_t cpus;
};
} // namespace

CoreLoan::CoreLoan(const RunRanks& ranks, int threadsPerRank) {
  if (!ranks.active()) return;
  Lender mine{};
  gethostname(mine.host, sizeof mine.host - 1);
  if (sched_getaffinity(0, sizeof mine.cpus, &mine.cpus) != 0) CPU_ZERO(&mine.cpus); // lends nothing
  std::vector<char> bytes(sizeof mine);
  std::memcpy(bytes.data(), &mine, sizeof mine);
  std::vector<size_t> counts;
  const std::vector<char> all = ranks.comm().gather(bytes, counts);
  if (!ranks.root() || CPU_COUNT(&mine.cpus) == 0) return;
  cpu_set_t wide = mine.cpus;
  int here = 1; // ranks on rank 0's machine
  for (size_t at = sizeof mine; at + sizeof mine <= all.size(); at += sizeof mine) {
    Lender other;
    std::memcpy(&other, all.data() + at, sizeof other);
    if (std::strncmp(other.host, mine.host, sizeof mine.host) != 0) continue;
    CPU_OR(&wide, &wide, &other.cpus);
    ++here;
  }
  if (here == 1 || sched_setaffinity(0, sizeof wide, &wide) != 0) return;
  own_.resize(sizeof mine.cpus);
  std::memcpy(own_.data(), &mine.cpus, sizeof mine.cpus);
  cores_ = std::min(CPU_COUNT(&wide), std::max(threadsPerRank, 1) * here);
}

CoreLoan::~CoreLoan() {
  if (own_.empty()) return;
  cpu_set_t own;
  std::memcpy(&own, own_.data(), sizeof own);
  sched_setaffinity(0, sizeof own, &own); // back on its own cores; nothing to do if refused
}

std::vector<RankFigures> rankFigures(const Simulation& sim) {
  const DomainDecomposition& dd = *sim.ranks();
  RankFigures f;
  f.particles = sim.particleCount();
  f.blocks = sim.grid().owning.size();
  f.bytesSent = dd.comm().bytesSent;
  f.collectives = dd.comm().collectives;
  f.rebalances = dd.rebalances;
  f.communicationSeconds = dd.comm().seconds;
  f.computeSeconds = sim.phaseTimes().total() - sim.phaseTimes().halo;
  f.memory = memoryFigures(sim);
  std::vector<char> mine(sizeof f);
  std::memcpy(mine.data(), &f, sizeof f);
  std::vector<size_t> counts;
  const std::vector<char> all = dd.comm().gather(mine, counts);
  std::vector<RankFigures> out(all.size() / sizeof f);
  if (!out.empty()) std::memcpy(static_cast<void*>(out.data()), all.data(), all.size());
  return out;
}

} // namespace talus
