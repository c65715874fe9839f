// `talus run` under mpirun: the decisions every rank takes together. Rank 0 does the file I/O
// from a gathered view of the run (Simulation::gatherInto); a failure there, a signal on any rank
// or a checkpoint request becomes one decision of all ranks, so no rank waits forever in a
// collective call that another has left.
#pragma once

#include "engine/communicator.h"
#include "io/run/run_summary.h"

#include <exception>
#include <memory>
#include <string>
#include <vector>

namespace talus {

/// Thrown on ranks other than 0 when rank 0 failed (it reports the failure).
struct PeerFailed {};

class RunRanks;

/// Collective: the ranks on rank 0's machine lend it their CPUs. While the loan lives, rank 0's
/// calling thread may run on the union of their CPU sets (mpirun binds each rank to its own
/// cores); programs it starts meanwhile inherit that set. TBB's workers do not (they start on the
/// set the process began with: measured), but the calling thread, free to move to a lent core,
/// runs beside them. The lenders have nothing to do in the meantime but wait with
/// Communicator::maxOfIdle. Nothing happens without ranks.
class CoreLoan {
public:
  /// `threadsPerRank`: what each rank runs (the same command line on every rank).
  CoreLoan(const RunRanks& ranks, int threadsPerRank);
  ~CoreLoan(); ///< rank 0 gets its own CPU set back
  CoreLoan(const CoreLoan&) = delete;
  CoreLoan& operator=(const CoreLoan&) = delete;
  /// Threads rank 0 may run during the loan: the lent CPUs, at most threadsPerRank per rank on its
  /// machine; 0 when nothing was lent (one process, no other rank there, or elsewhere than rank 0).
  int cores() const { return cores_; }

private:
  std::vector<char> own_; ///< rank 0's CPU set before the loan (a cpu_set_t), when it widened it
  int cores_ = 0;
};

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
  template <class F> void onRoot(F&& f) { settle(attempt(f), false); }
  /// onRoot for rank 0's long end-of-run work (maps, film, particles): the other ranks on its
  /// machine wait asleep and lend it their cores (CoreLoan), and f(cores) is told how many
  /// threads it may run (0: its own only). Collective. Throws as onRoot.
  template <class F> void onRootWithNodeCores(int threadsPerRank, F&& f) {
    std::exception_ptr failed;
    {
      const CoreLoan loan(*this, threadsPerRank);
      failed = attempt([&] { f(loan.cores()); });
    }
    settle(failed, true);
  }
  /// The largest of every rank's v (v itself without ranks).
  int agree(int v) const { return active() ? int(comm_->maxOf(v)) : v; }
  /// Collective: whether every rank sees rank 0's folder `dir` (which must exist there) as the
  /// same folder: a file rank 0 writes into it is read back, with its content, by every rank. A
  /// cluster's shared file system passes; a node's own disk under the same path does not. True
  /// without ranks.
  bool shareFolder(const std::string& dir) const;

private:
  /// f's exception on the root (null elsewhere, or when f returned).
  template <class F> std::exception_ptr attempt(F&& f) {
    if (!root()) return nullptr;
    try {
      f();
    } catch (...) {
      return std::current_exception();
    }
    return nullptr;
  }
  void settle(const std::exception_ptr& failed, bool idle) {
    const double v = failed ? 1 : 0;
    if (active() && (idle ? comm_->maxOfIdle(v) : comm_->maxOf(v)) > 0 && !root()) throw PeerFailed{};
    if (failed) std::rethrow_exception(failed);
  }
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
