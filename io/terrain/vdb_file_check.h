// A structural check of a .vdb file before OpenVDB reads it. OpenVDB's reader trusts the lengths
// a file states (a damaged string length makes it fill gigabytes with spaces) and never checks
// that a grid lies inside the file; this walks the header, the metadata, the grid descriptors,
// each grid's metadata and transform name, and every stated offset, against the file's size.
#pragma once

#include <string>

namespace talus {

/// Throws std::runtime_error with the reason when `path` is not a whole .vdb file.
void checkVdbFile(const std::string& path);

/// `s` made fit for a one-line message: printable ASCII only, at most `max` characters.
std::string printable(const std::string& s, size_t max = 80);

} // namespace talus
