// `talus run` under mpirun: the decisions every rank takes together. Rank 0 does the file I/O
// from a gathered view of the run (Simulation::gatherInto); a failure there, a signal on any rank
// or a checkpoint request becomes one decision of all ranks, so no rank waits forever in a
// collective call that another has left.
#pragma once

#include "engine/communicator.h"
#include "io/run/run_summary.h"

#include <exception>
#include <memory>

namespace talus {

/// Thrown on ranks other than 0 when rank 0 failed (it reports the failure).
struct PeerFailed {};

class RunRanks {
public:
  explicit RunRanks(std::shared_ptr<Communicator> comm) : comm_(std::move(comm)) {}
  /// More than one rank.
  bool active() const { return comm_ && comm_->size() > 1; }
  /// The rank that writes files and prints (the only one without ranks).
  bool root() const { return !active() || comm_->rank() == 0; }
  Communicator& comm() const { return *comm_; }

  /// Runs f on the root; then every rank learns whether it threw: the root rethrows, the others
  /// throw PeerFailed.
  template <class F> void onRoot(F&& f) {
    std::exception_ptr failed;
    if (root()) {
      try {
        f();
      } catch (...) {
        failed = std::current_exception();
      }
    }
    if (active() && comm_->maxOf(failed ? 1 : 0) > 0 && !root()) throw PeerFailed{};
    if (failed) std::rethrow_exception(failed);
  }
  /// The largest of every rank's v (v itself without ranks).
  int agree(int v) const { return active() ? int(comm_->maxOf(v)) : v; }

private:
  std::shared_ptr<Communicator> comm_;
};

/// Rank 0 gathers the particles and runs the per-step outputs while the other ranks wait for it in
/// the next step's reductions, so it should own fewer particles. Every `window` steps it compares
/// its output seconds with its compute seconds per particle-step: the outputs are worth E
/// particles, and with N particles on R ranks rank 0 gets N/R - E (R-1)/R of them (none if that
/// is negative) and every other rank N/R + E/R, which evens their step times. The ranges move,
/// the results do not (they are the same at any ranges).
class RootLoadBalance {
public:
  explicit RootLoadBalance(int window = 100) : window_(window) {}
  /// Rank 0's seconds on outputs since the last step (ignored on the other ranks).
  void addOutputSeconds(double s) { output_ += s; }
  /// Collective, after every step on every rank.
  void afterStep(const RunRanks& ranks, Simulation& sim);
  /// The share rank 0 was last given (1/R until the first window).
  double rootShare() const { return share_; }

private:
  int window_, steps_ = 0;
  double output_ = 0, compute0_ = -1, work_ = 0, share_ = -1;
};

/// Collective: every rank's figures, on rank 0 (empty elsewhere).
std::vector<RankFigures> rankFigures(const Simulation& sim);

} // namespace talus
