#include "engine/mpi_communicator.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#ifdef TALUS_HAVE_MPI
// The C API only: Open MPI's deprecated C++ bindings would need libmpi_cxx.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace talus {

bool launchedAsRanks() {
  // Open MPI's mpirun, PMIx launchers (srun --mpi=pmix, prterun) and PMI-1/2 launchers.
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  return false;
}

#ifdef TALUS_HAVE_MPI

namespace {

/// Times one collective call and counts it.
class Stopwatch {
public:
  Stopwatch(double& acc, uint64_t& calls) : acc_(acc), t0_(std::chrono::steady_clock::now()) { ++calls; }
  ~Stopwatch() { acc_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
private:
  double& acc_;
  std::chrono::steady_clock::time_point t0_;
};

int checkedCount(size_t n) {
  if (n > size_t(INT_MAX)) throw std::runtime_error("a message between ranks exceeds 2 GiB; use more ranks");
  return int(n);
}

/// MPI_User_function for minimumAndSum: inout = in (op) inout over `len` elements of a contiguous
/// type of doubles laid out as [nMin, minima..., sums...].
void minThenSum(void* in, void* inout, int* len, MPI_Datatype* type) {
  int size = 0;
  MPI_Type_size(*type, &size);
  const size_t n = size_t(size) / sizeof(double);
  const double* a = static_cast<const double*>(in);
  double* b = static_cast<double*>(inout);
  for (int e = 0; e < *len; ++e, a += n, b += n) {
    const size_t nMin = size_t(a[0]);
    for (size_t i = 1; i < 1 + nMin; ++i) b[i] = std::min(a[i], b[i]);
    for (size_t i = 1 + nMin; i < n; ++i) b[i] += a[i];
  }
}

class MpiCommunicator final : public Communicator {
public:
  MpiCommunicator() {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Op_create(&minThenSum, 1, &minThenSum_); // once: minimumAndSum runs every step
  }
  ~MpiCommunicator() override {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Op_free(&minThenSum_); // MPI_Finalize frees it otherwise
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  double maxOf(double v) override { return reduce(v, MPI_MAX); }
  double minOf(double v) override { return reduce(v, MPI_MIN); }
  double maxOfIdle(double v) override {
    Stopwatch t(seconds, collectives);
    double out = 0;
    MPI_Request request;
    MPI_Iallreduce(&v, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD, &request);
    // MPI_Test also drives the reduction's progress; half a millisecond asleep between looks.
    for (int done = 0; MPI_Test(&request, &done, MPI_STATUS_IGNORE), !done;)
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    return out;
  }
  uint64_t sumOf(uint64_t v) override {
    Stopwatch t(seconds, collectives);
    uint64_t out = 0;
    MPI_Allreduce(&v, &out, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    return out;
  }
  void minimum(double* v, size_t n) override {
    Stopwatch t(seconds, collectives);
    MPI_Allreduce(MPI_IN_PLACE, v, checkedCount(n), MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
  }
  void sum(double* v, size_t n) override {
    Stopwatch t(seconds, collectives);
    MPI_Allreduce(MPI_IN_PLACE, v, checkedCount(n), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  }
  void minimumAndSum(double* mins, size_t nMin, double* sums, size_t nSum) override {
    // One reduction of [nMin, mins..., sums...] as one element of a contiguous type, with an op
    // that takes the minimum of the first part and the sum of the rest (the split travels in
    // the buffer, the same on every rank).
    Stopwatch t(seconds, collectives);
    std::vector<double> buf(1 + nMin + nSum);
    buf[0] = double(nMin);
    std::copy(mins, mins + nMin, buf.begin() + 1);
    std::copy(sums, sums + nSum, buf.begin() + 1 + long(nMin));
    MPI_Datatype type;
    MPI_Type_contiguous(checkedCount(buf.size()), MPI_DOUBLE, &type);
    MPI_Type_commit(&type);
    MPI_Allreduce(MPI_IN_PLACE, buf.data(), 1, type, minThenSum_, MPI_COMM_WORLD);
    MPI_Type_free(&type);
    std::copy(buf.begin() + 1, buf.begin() + 1 + long(nMin), mins);
    std::copy(buf.begin() + 1 + long(nMin), buf.end(), sums);
  }
  std::vector<char> allGather(const std::vector<char>& mine, std::vector<size_t>& counts) override {
    Stopwatch t(seconds, collectives);
    const int n = checkedCount(mine.size());
    std::vector<int> c(static_cast<size_t>(size_), 0), displ(static_cast<size_t>(size_), 0);
    MPI_Allgather(&n, 1, MPI_INT, c.data(), 1, MPI_INT, MPI_COMM_WORLD);
    size_t total = 0;
    counts.assign(size_t(size_), 0);
    for (int r = 0; r < size_; ++r) {
      displ[size_t(r)] = checkedCount(total);
      counts[size_t(r)] = size_t(c[size_t(r)]);
      total += counts[size_t(r)];
    }
    std::vector<char> out(total);
    MPI_Allgatherv(mine.data(), n, MPI_BYTE, out.data(), c.data(), displ.data(), MPI_BYTE, MPI_COMM_WORLD);
    bytesSent += uint64_t(mine.size()) * uint64_t(size_ - 1);
    return out;
  }
  std::vector<char> gather(const std::vector<char>& mine, std::vector<size_t>& counts) override {
    std::vector<char> out;
    counts.assign(static_cast<size_t>(size_), 0);
    size_t at = 0;
    gatherEach(
        mine,
        [&](const std::vector<size_t>& c) {
          counts = c;
          size_t total = 0;
          for (size_t n : c) total += n;
          out.resize(total);
        },
        [&](int, std::string_view part) {
          std::copy(part.begin(), part.end(), out.begin() + long(at));
          at += part.size();
        });
    return out;
  }
  void gatherEach(const std::vector<char>& mine, const std::function<void(const std::vector<size_t>&)>& sized,
                  const std::function<void(int, std::string_view)>& take) override {
    // Point to point in pieces of at most maxMessageBytes: a rank's part may pass 2 GiB (int counts).
    double handling = 0; // rank 0's time in sized and take: not communication
    {
      Stopwatch t(seconds, collectives);
      uint64_t n = mine.size();
      std::vector<uint64_t> c(static_cast<size_t>(size_), 0);
      MPI_Gather(&n, 1, MPI_UINT64_T, c.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
      const size_t piece = std::max<size_t>(1, std::min(maxMessageBytes, size_t(INT_MAX)));
      if (rank_ != 0) {
        for (size_t at = 0; at < mine.size(); at += piece)
          MPI_Send(mine.data() + at, int(std::min(piece, mine.size() - at)), MPI_BYTE, 0, 9, MPI_COMM_WORLD);
        bytesSent += mine.size();
        return;
      }
      auto timed = [&](auto&& f) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        handling += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      };
      timed([&] { sized(std::vector<size_t>(c.begin(), c.end())); });
      timed([&] { take(0, std::string_view(mine.data(), mine.size())); });
      std::vector<char> part; // one rank's bytes at a time
      for (int r = 1; r < size_; ++r) {
        part.resize(size_t(c[size_t(r)]));
        for (size_t at = 0; at < part.size(); at += piece)
          MPI_Recv(part.data() + at, int(std::min(piece, part.size() - at)), MPI_BYTE, r, 9, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE);
        timed([&] { take(r, std::string_view(part.data(), part.size())); });
      }
    }
    seconds -= handling;
  }
  std::vector<std::vector<char>> exchange(std::vector<std::vector<char>>& send) override {
    Stopwatch t(seconds, collectives);
    std::vector<uint64_t> out(static_cast<size_t>(size_)), in(static_cast<size_t>(size_));
    for (int r = 0; r < size_; ++r) out[size_t(r)] = send[size_t(r)].size();
    MPI_Alltoall(out.data(), 1, MPI_UINT64_T, in.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD);
    std::vector<std::vector<char>> recv(static_cast<size_t>(size_));
    std::vector<MPI_Request> req;
    for (int r = 0; r < size_; ++r) {
      if (r == rank_) {
        recv[size_t(r)] = std::move(send[size_t(r)]);
        continue;
      }
      recv[size_t(r)].resize(in[size_t(r)]);
      if (in[size_t(r)]) {
        req.emplace_back();
        MPI_Irecv(recv[size_t(r)].data(), checkedCount(in[size_t(r)]), MPI_BYTE, r, 7, MPI_COMM_WORLD, &req.back());
      }
    }
    for (int r = 0; r < size_; ++r)
      if (r != rank_ && out[size_t(r)]) {
        req.emplace_back();
        MPI_Isend(send[size_t(r)].data(), checkedCount(out[size_t(r)]), MPI_BYTE, r, 7, MPI_COMM_WORLD, &req.back());
        bytesSent += out[size_t(r)];
      }
    MPI_Waitall(int(req.size()), req.data(), MPI_STATUSES_IGNORE);
    return recv;
  }

private:
  double reduce(double v, MPI_Op op) {
    Stopwatch t(seconds, collectives);
    double out = 0;
    MPI_Allreduce(&v, &out, 1, MPI_DOUBLE, op, MPI_COMM_WORLD);
    return out;
  }
  int rank_ = 0, size_ = 1;
  MPI_Op minThenSum_ = MPI_OP_NULL;
};

void finalizeAtExit() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

} // namespace

std::shared_ptr<Communicator> worldCommunicator(int* argc, char*** argv) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) {
    int provided = 0;
    // Only the main thread calls MPI; TBB's workers never do.
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
    std::atexit(finalizeAtExit);
  }
  return std::make_shared<MpiCommunicator>();
}

void abortAllRanks(int code) {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);
}

#else

std::shared_ptr<Communicator> worldCommunicator(int*, char***) {
  throw std::runtime_error("this talus was built without MPI (install libopenmpi-dev and rebuild)");
}

void abortAllRanks(int code) { std::_Exit(code); }

#endif

} // namespace talus
