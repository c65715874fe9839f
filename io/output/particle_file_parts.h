// Particle files written by every process at once. Rank 0 lays the file out (everything but the
// particles' rows: a header, attributes, where each column's rows go) and every process writes
// its own particles' rows in place, where one process would have put them. The file is byte for
// byte one process's at any rank count, and no process holds, sends or receives every particle
// for it. One process writes the same way (a SerialCommunicator), so its files are the same too.
#pragma once

#include "engine/communicator.h"
#include "engine/simulation.h"
#include "io/common/write_error.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace talus {

/// Where a column's rows lie in a file: row r's `width` bytes at offset + r * width.
struct FileColumn {
  uint64_t offset = 0;
  uint32_t width = 0;
};

/// The rows of a particle file in one process's order: group by group (Simulation::groups()),
/// in each every rank's settled particles in rank order, then every rank's fresh ones
/// (Simulation::particleRecords' split, the order gatherInto keeps), and this process's runs.
class ParticleRows {
public:
  /// Collective: one allGather of every process's counts.
  ParticleRows(Communicator& comm, const Simulation& local);
  uint64_t total() const { return total_; }
  /// Particles [begin, end) of group `group` of this process go to rows row, row + 1, ...
  struct Run {
    size_t group, begin, end;
    uint64_t row;
  };
  const std::vector<Run>& mine() const { return mine_; }

private:
  uint64_t total_ = 0;
  std::vector<Run> mine_;
};

/// On rank 0: writes everything of the file but the rows to `tmp` (created or truncated) for
/// `rows` particles and returns its columns. May throw (WriteError, std::exception).
using FileLayout = std::function<std::vector<FileColumn>(const std::string& tmp, uint64_t rows)>;
/// Column `column`'s bytes of particles [begin, end) of `g`, `width` bytes each, one after another.
using RowFiller = std::function<void(size_t column, const MaterialGroup& g, size_t begin, size_t end, char* out)>;

/// Collective: writes `path` as rank 0's layout and every process's rows (at the rows
/// ParticleRows gives them), through path.tmp, which rank 0 syncs and renames once every process
/// has written and synced its rows: a reader never sees a half-written file, and a failure keeps
/// the file that was there. Every process must see rank 0's folder (RunRanks::shareFolder).
/// Returns, on rank 0, the first failure (any process's) as a WriteError naming `path`; nothing
/// on the others (rank 0 reports).
std::optional<WriteError> writeParticleFile(Communicator& comm, const std::string& path, const Simulation& local,
                                            const FileLayout& layout, const RowFiller& fill);

} // namespace talus
