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

/// Collective: every rank's figures, on rank 0 (empty elsewhere).
std::vector<RankFigures> rankFigures(const Simulation& sim);

} // namespace talus
