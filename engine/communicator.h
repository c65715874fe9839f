// What the engine needs from the processes running one scene together: reductions, an all-gather
// and an all-to-all of bytes. One process is SerialCommunicator; MPI ranks are
// engine/mpi_communicator.h. The engine never includes MPI itself.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

namespace talus {

class Communicator {
public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Collective: the largest / smallest value over all ranks (exact: no rounding).
  virtual double maxOf(double v) = 0;
  virtual double minOf(double v) = 0;
  /// Collective: maxOf, but a rank that arrives early sleeps between looks instead of spinning,
  /// which leaves its core to a rank still working on the same machine (rank 0's end-of-run
  /// files, RunRanks::onRootWithNodeCores). A millisecond later at most. This default is maxOf.
  virtual double maxOfIdle(double v) { return maxOf(v); }
  virtual uint64_t sumOf(uint64_t v) = 0;
  /// Collective: element-wise sums of n doubles over all ranks, into v on every rank.
  virtual void sum(double* v, size_t n) = 0;
  /// Collective: element-wise minima of n doubles over all ranks (exact), into v on every rank.
  /// A step merges what it needs into one call of each kind (a maximum as the minimum of -x).
  virtual void minimum(double* v, size_t n) = 0;
  /// Collective: minimum() of mins[0, nMin) and sum() of sums[0, nSum) in one call, so a step's
  /// figures (its largest speed, the groups' minima, the counts and every rank's count) take one
  /// latency. MPI overrides it with one reduction; this default makes the two calls.
  virtual void minimumAndSum(double* mins, size_t nMin, double* sums, size_t nSum) {
    minimum(mins, nMin);
    sum(sums, nSum);
  }
  /// Collective: every rank's bytes, concatenated in rank order; `counts` gets each rank's size.
  virtual std::vector<char> allGather(const std::vector<char>& mine, std::vector<size_t>& counts) = 0;
  /// Collective: every rank's bytes, concatenated in rank order, on rank 0 only (empty elsewhere).
  virtual std::vector<char> gather(const std::vector<char>& mine, std::vector<size_t>& counts) = 0;
  /// Collective: every rank's bytes to rank 0 one rank at a time, so it never holds them all at
  /// once. On rank 0 only: `sized` gets every rank's count first, then `take` each rank's bytes in
  /// rank order (its own first); the bytes live until `take` returns. Its time is not counted as
  /// communication. This default gathers them whole.
  virtual void gatherEach(const std::vector<char>& mine, const std::function<void(const std::vector<size_t>&)>& sized,
                          const std::function<void(int, std::string_view)>& take) {
    std::vector<size_t> counts;
    const std::vector<char> all = gather(mine, counts);
    if (rank() != 0) return;
    sized(counts);
    size_t at = 0;
    for (int r = 0; r < size(); at += counts[size_t(r)], ++r) take(r, std::string_view(all.data() + at, counts[size_t(r)]));
  }
  /// Collective: send[r] goes to rank r; returns what each rank sent here (index = source rank).
  virtual std::vector<std::vector<char>> exchange(std::vector<std::vector<char>>& send) = 0;
  /// Bytes this rank has sent to other ranks so far (the halo, migration, gathers).
  uint64_t bytesSent = 0;
  /// Wall seconds this rank has spent inside the calls above (waiting included), and how many
  /// calls it made.
  double seconds = 0;
  uint64_t collectives = 0;
  /// Largest single MPI message: gathers beyond it (rank 0's view of 17.5 M particles is
  /// 2.4 GB, past MPI's int counts) travel in pieces. Smaller in tests.
  size_t maxMessageBytes = size_t(1) << 30;
};

/// One process: reductions are identities, gathers return the caller's own bytes.
class SerialCommunicator final : public Communicator {
public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  double maxOf(double v) override { return v; }
  double minOf(double v) override { return v; }
  uint64_t sumOf(uint64_t v) override { return v; }
  void sum(double*, size_t) override {}
  void minimum(double*, size_t) override {}
  std::vector<char> allGather(const std::vector<char>& mine, std::vector<size_t>& counts) override {
    counts.assign(1, mine.size());
    return mine;
  }
  std::vector<char> gather(const std::vector<char>& mine, std::vector<size_t>& counts) override {
    return allGather(mine, counts);
  }
  std::vector<std::vector<char>> exchange(std::vector<std::vector<char>>& send) override { return send; }
};

} // namespace talus
