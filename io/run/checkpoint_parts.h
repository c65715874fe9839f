// A checkpoint written on MPI ranks: every rank writes its own particles into a part file beside
// the checkpoint, at once and without sending them anywhere, and rank 0 writes the checkpoint
// itself (io/run/checkpoint.h: the clock, ledgers, outputs' state) with the list of the parts,
// their lengths and checksums. Rank 0 never holds every particle for it. A resumed run reads
// the parts back in one process's order, so it resumes at any rank count.
//
// The parts of a checkpoint are named by its step (checkpoint_parts/step<S>_rank<R>.h5), so a
// new checkpoint's parts never replace the ones the checkpoint on disk lists: a run killed at any
// moment leaves that checkpoint and its parts whole. The older parts go once the new checkpoint
// is in place.
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

/// One rank's part as the checkpoint lists it: the file's name relative to the checkpoint's
/// folder, its length and its CRC-32.
struct CheckpointPart {
  std::string file;
  uint64_t bytes = 0;
  uint32_t crc = 0;
};

/// Collective: every rank writes its own particles (Simulation::particleRecords of every group)
/// to checkpoint_parts/step<S>_rank<R>.h5 beside `checkpointPath`, atomically, at once. On rank 0, every
/// rank's part in rank order, or the first failure as a WriteError to throw (the others get
/// nothing: rank 0 reports, as it does every write failure of a run on ranks).
struct WrittenParts {
  std::vector<CheckpointPart> parts;
  std::optional<WriteError> failure;
};
WrittenParts writeCheckpointParts(Communicator& comm, const std::string& checkpointPath, const Simulation& sim);

/// The parts as text, a line "file bytes crc32" each (what the checkpoint stores), and back.
/// parsePartList throws std::runtime_error on a line it cannot read.
std::string partListText(const std::vector<CheckpointPart>& parts);
std::vector<CheckpointPart> parsePartList(const std::string& text);

/// Appends the parts' particles to `sim` (its groups as the checkpoint left them) in one
/// process's order: every part's settled particles in rank order, then every part's fresh ones
/// (Simulation::particleRecords). Each part's length and CRC-32 are checked first. Throws
/// InputError naming the part: missing, truncated, damaged, or not fitting the scene.
void readCheckpointParts(const std::string& checkpointPath, const std::vector<CheckpointPart>& parts, Simulation& sim);

/// After a checkpoint listing `keep` is in place: removes the other files of its parts folder
/// (an older checkpoint's), and the folder when nothing is kept. A file that cannot be removed
/// is left (it costs disk, never a resume).
void removeStaleParts(const std::string& checkpointPath, const std::vector<CheckpointPart>& keep);

/// CRC-32 (zlib's) of bytes [from, end) of an open file. `fail` gets the cause of a read error
/// and must throw.
uint32_t crc32OfFile(int fd, uint64_t from, uint64_t end, const std::function<void(const std::string&)>& fail);

} // namespace talus
