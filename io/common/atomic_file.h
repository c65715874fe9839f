// How every output reaches the disk: written to PATH.tmp, flushed to the device, then renamed to
// PATH (atomic on POSIX file systems). A run killed or failing mid-write leaves the previous
// version of PATH, or none, never a truncated one. Failures throw WriteError naming PATH.
#pragma once

#include "io/common/write_error.h"

#include <functional>
#include <string>

namespace talus {

/// Calls write(path + tmpSuffix) (which must truncate the file it is given, not replace it),
/// syncs it and renames it to path, the temporary held open for writing throughout. Any exception from `write`
/// (except std::bad_alloc) becomes a WriteError naming `path`; the temporary is removed. Files
/// that several processes may write at once (the terrain cache) pass a suffix with the pid.
void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write,
                     const std::string& tmpSuffix = ".tmp");

/// writeAtomically's end for a temporary that was written by other means (several processes'
/// rows in one file, io/output/particle_file_parts.h): syncs `tmp` and renames it to `path`;
/// throws WriteError(path, cause), leaving the temporary.
void commitFile(const std::string& tmp, const std::string& path);

/// Writes `size` bytes to `path` (created or truncated) with checked write(2) and close(2);
/// throws WriteError(path, cause).
void writeFileBytes(const std::string& path, const void* data, size_t size);
inline void writeFileBytes(const std::string& path, const std::string& bytes) {
  writeFileBytes(path, bytes.data(), bytes.size());
}

/// For writers that do not report write errors (OpenVDB's never checks its stream): `write`
/// writes to a scratch path in memory, and the bytes then go to `path` with checked writes.
void writeThroughMemory(const std::string& path, const std::function<void(const std::string& scratch)>& write);

} // namespace talus
