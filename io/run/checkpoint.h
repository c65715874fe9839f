// HDF5 checkpoints: the full simulation state, written atomically (temporary file + rename), so a
// run killed at any moment leaves the previous checkpoint intact and readable, and sealed with a
// checksum, so a damaged one is refused instead of resumed.
#pragma once

#include "engine/simulation.h"

#include <functional>
#include <string>

namespace talus {

/// DIR/checkpoint.h5.
std::string checkpointPath(const std::string& dir);

/// What a checkpoint must match to be resumed: the scene it was written for (SceneSetup::hash:
/// its keys after --set overrides, less the end time and the frame outputs) and the Talus
/// version (checked by readCheckpoint itself). `sceneKeys` (SceneSetup::stateKeys) is stored in
/// the checkpoint, so a refusal can name the key that changed.
struct CheckpointIdentity {
  std::string sceneHash;
  std::string sceneKeys = {};
};

/// The checkpoint file format: an HDF5 file behind a 512-byte text header (an HDF5 user block)
/// holding the format, the Talus version, the scene hash, the HDF5 part's length and its CRC-32.
/// Format 3 adds the parts of a checkpoint written on ranks (kPartList), so a Talus that reads
/// format 2 only refuses one instead of resuming it without particles; format 2 (no parts) is read.
constexpr int kCheckpointFormat = 3;
constexpr int kOldestCheckpointFormat = 2;

/// The entry of a checkpoint written on ranks that lists its parts (io/run/checkpoint_parts.h).
constexpr char kPartList[] = "parts/list";

/// Writes sim's state (see Simulation::save) and whatever `extra` adds (the run driver's clock
/// and its outputs' accumulated state), atomically. Throws WriteError.
void writeCheckpoint(const std::string& path, const Simulation& sim, const CheckpointIdentity& id,
                     const std::function<void(StateArchive&)>& extra = {});

/// Restores a checkpoint into a simulation built from the same scene, then calls `extra`. A
/// checkpoint written on ranks (its `extra` put kPartList) gets its particles from its parts. The
/// header is checked before HDF5 sees the file, so a damaged file never reaches its parser.
/// Throws InputError naming the file and the reason: missing, truncated, damaged (checksum), not
/// a checkpoint, another format, another Talus version, another scene, or contents that do not
/// fit the scene.
void readCheckpoint(const std::string& path, Simulation& sim, const CheckpointIdentity& id,
                    const std::function<void(const StateArchive&)>& extra = {});

/// A checkpoint's header, after its checksum was verified.
struct CheckpointHeader {
  int format = 0;
  std::string talusVersion, sceneHash;
};

/// Checks that `path` is a whole, undamaged checkpoint of this format and Talus version (header,
/// length, checksum) without reading its contents; throws InputError with the reason.
CheckpointHeader inspectCheckpoint(const std::string& path);

/// The Talus version written into checkpoints (the project version).
const char* talusVersion();

} // namespace talus
