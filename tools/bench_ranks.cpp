// `talus bench --ranks` under mpirun: throughput of one scene distributed over the ranks, with
// what the distribution costs (time in communication, bytes exchanged per step and particle).
#include "tools/benchmark.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <tbb/global_control.h>

namespace talus {

int runRankBenchmarks(const BenchOptions& opt, const std::shared_ptr<Communicator>& ranks) {
  Communicator& comm = *ranks;
  const int threads = opt.threads.empty() ? 1 : opt.threads.front();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const bool root = comm.rank() == 0;
  if (root)
    std::printf("%-10s %5s %7s %9s %12s %12s %8s %8s %12s %10s %9s %8s\n", "case", "ranks", "threads", "particles",
                "p-steps/s", "per core", "mpi%", "halo%", "bytes/step", "B/part/st", "imbalance", "coll/st");
  if (root)
    std::printf("(mpi%%: time in MPI calls, waiting included, on the slowest rank; halo%%: the phase only ranks\n"
                " run: migration, the P2G scatter of boundary blocks ahead of the exchange, the exchange)\n");
  for (const std::string& name : opt.cases) {
    SceneSetup s = benchmarkScene(name, opt);
    Simulation sim(s.settings, std::move(s.groups));
    sim.distribute(ranks);
    for (int i = 0, n = benchmarkWarmup(name, opt); i < n; ++i) sim.step();
    comm.maxOf(0); // start together
    const double halo0 = sim.phaseTimes().halo;
    const uint64_t bytes0 = comm.bytesSent, ps0 = sim.particleSteps(), calls0 = comm.collectives;
    const double comm0 = comm.seconds;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < opt.steps; ++i) sim.step();
    const double wall = comm.maxOf(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    // Communication: time inside the communicator's calls (waiting included); the halo phase
    // also holds the packing of particles and rows around them.
    const double commShare = comm.maxOf((comm.seconds - comm0) / wall);
    const double haloShare = comm.maxOf((sim.phaseTimes().halo - halo0) / wall);
    const double calls = double(comm.collectives - calls0) / opt.steps; // MPI calls per step, this rank's
    const double bytes = double(comm.sumOf(comm.bytesSent - bytes0)) / opt.steps;
    const size_t particles = sim.globalParticleCount();
    const double imbalance = sim.ranks()->imbalance(sim.particleCount());
    const double pss = double(sim.particleSteps() - ps0) / wall;
    const PhaseTimes& pt = sim.phaseTimes();
    std::fprintf(stderr, "rank %d: %zu particles, %zu blocks (%zu on the boundary, halo %zu B/step), compute %.3f s (bin %.3f p2g %.3f grid %.3f g2p %.3f), halo %.3f s, mpi %.3f s, rebalances %llu\n",
                 comm.rank(), sim.particleCount(), sim.grid().owning.size(), sim.halo().boundaryBlocks(), sim.halo().lastBytes(), pt.total() - pt.halo, pt.bin, pt.p2g, pt.grid, pt.g2p, pt.halo,
                 comm.seconds, (unsigned long long)sim.ranks()->rebalances);
    if (root)
      std::printf("%-10s %5d %7d %9zu %12.3e %12.3e %8.1f %8.1f %12.4g %10.2f %8.1f%% %8.1f\n", name.c_str(), comm.size(),
                  threads, particles, pss, pss / (comm.size() * threads), 100 * commShare, 100 * haloShare, bytes,
                  bytes / double(particles), 100 * imbalance, calls);
  }
  return 0;
}

} // namespace talus
