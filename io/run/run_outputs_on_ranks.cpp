// Run's per-step outputs and their state under ranks: each rank adds up its own particles, one
// reduction and one all-to-all a step, rank 0 merges and writes (docs/scaling.md).
#include "io/run/run.h"
#include "io/run/run_state.h"

#include "engine/gathered_parts.h"

#include <chrono>
#include <string_view>

namespace talus {

Run::Agreed Run::stepOnRanks(Agreed mine) {
  State& s = *s_;
  OutputSet& out = *s.outputs;
  const bool outputs = s.output.readsEveryStep();
  // What this process adds up from its own particles every step, and its maxima (the units of
  // the parts' fixed-point sums).
  double dt = 0;
  PartBounds own;
  if (outputs) {
    dt = out.stepTime(*sim_);
    out.stepLocal(*sim_, dt);
    own = PartBounds::of(*sim_);
  }
  // One reduction for all the ranks agree on after a step: which outputs rank 0 needs, the
  // maxima, and the signal flags (a maximum over the ranks, so a signal that reached one rank
  // stops every rank at the same step).
  const bool askDue = outputs && s.ranks.root();
  double v[6] = {askDue ? -double(out.partsDue(*sim_)) : 0.0, -own.maxMass, -own.maxSpeed2, -own.maxCoord,
                 -double(mine.checkpoint), -double(mine.signal)};
  s.ranks.comm().minimum(v, 6);
  if (outputs) stepOutputsOnRanks(dt, uint32_t(-v[0]), PartBounds{-v[1], -v[2], -v[3]});
  return {int(-v[4]), int(-v[5])};
}

void Run::stepOutputsOnRanks(double dt, uint32_t due, const PartBounds& b) {
  State& s = *s_;
  OutputSet& out = *s.outputs;
  Communicator& comm = s.ranks.comm();
  const bool root = s.ranks.root();
  // One all-to-all: rank 0 gets every part; the maps' cells go to the process owning them, so
  // no process adds every cell (OutputObserver::partsByOwner).
  const int n = comm.size();
  std::vector<std::vector<char>> sent = due ? out.parts(*sim_, due, b, comm.rank(), n) : std::vector<std::vector<char>>();
  const std::vector<std::vector<char>> got = due ? comm.exchange(sent) : std::vector<std::vector<char>>();
  // Not the collectives: their time includes waiting for slower ranks.
  const auto o0 = std::chrono::steady_clock::now();
  std::vector<std::string_view> buffers;
  for (const auto& g : got) buffers.emplace_back(g.data(), g.size());
  out.mergeParts(*sim_, dt, due, b, buffers);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - o0).count();
  // Rank 0 gathers the owned cells only when it writes them (a film frame).
  GatheredParts results;
  if (out.resultsDue(n)) results = gatherParts(comm, root ? std::vector<char>() : out.results(false, n));
  s.ranks.onRoot([&] {
    const auto o1 = std::chrono::steady_clock::now();
    out.mergeResults(*sim_, false, results.parts, n);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - o1).count();
    s.balance.addOutputSeconds(seconds);
  });
}

void Run::shareOutputState() {
  State& s = *s_;
  Communicator& comm = s.ranks.comm();
  const int n = comm.size();
  if (!s.outputs->sharesState(n)) return; // the same answer on every rank: the scene's outputs
  std::vector<std::vector<char>> send(static_cast<size_t>(n));
  if (s.ranks.root()) {
    const std::vector<char> state = s.outputs->sharedState(n);
    for (int r = 1; r < n; ++r) send[size_t(r)] = state;
  }
  const std::vector<std::vector<char>> got = comm.exchange(send);
  if (!s.ranks.root()) s.outputs->takeSharedState(std::string_view(got[0].data(), got[0].size()), n);
}

void Run::gatherOutputState() {
  State& s = *s_;
  if (!s.ranks.active() || !s.outputs) return;
  Communicator& comm = s.ranks.comm();
  const GatheredParts all = gatherParts(comm, s.ranks.root() ? std::vector<char>() : s.outputs->results(true, comm.size()));
  s.ranks.onRoot([&] { s.outputs->mergeResults(*s.view, true, all.parts, comm.size()); });
}

} // namespace talus
