// OpenVDB 10's reader of blosc chunks (io::bloscFromStream) trusts the chunk's stated length: a
// negative one (a stored, uncompressed chunk) is read into the caller's buffer before its length
// is compared with the buffer's, overflowing the heap, and a positive one is allocated as stated
// (a damaged .vdb asked for 4.5e18 bytes). Both were found by fuzzing the level-set reader.
// This definition takes the library's place (ELF symbol interposition: calls from libopenvdb.so
// resolve to the executable's definition first) and checks every length before it reads. Its
// contract is the library's: fill `data` with `numBytes` bytes, or skip the chunk when `data` is
// null, or throw openvdb::RuntimeError. vdb_level_set.cpp turns that into a one-line refusal.
#include <blosc.h>
#include <openvdb/Exceptions.h>
#include <openvdb/io/Compression.h>

#include <istream>
#include <memory>
#include <string>

namespace openvdb {
OPENVDB_USE_VERSION_NAMESPACE
namespace OPENVDB_VERSION_NAME {
namespace io {

void bloscFromStream(std::istream& is, char* data, size_t numBytes) {
  Int64 stated = 0;
  is.read(reinterpret_cast<char*>(&stated), 8);
  if (!is.good()) OPENVDB_THROW(RuntimeError, "truncated: the file ends inside a blosc chunk's length");
  if (stated <= 0) { // stored as is: exactly numBytes follow
    if (stated == INT64_MIN || size_t(-stated) != numBytes)
      OPENVDB_THROW(RuntimeError, "a stored chunk of " + std::to_string(numBytes) + " bytes states another length");
    if (data == nullptr) is.seekg(-stated, std::ios_base::cur);
    else is.read(data, -stated);
    return;
  }
  // blosc never stores more than the data and its 16-byte header.
  if (size_t(stated) > numBytes + BLOSC_MAX_OVERHEAD)
    OPENVDB_THROW(RuntimeError, "a blosc chunk of " + std::to_string(numBytes) + " bytes states " +
                                    std::to_string(stated) + " compressed bytes");
  if (data == nullptr) {
    is.seekg(stated, std::ios_base::cur);
    return;
  }
  std::unique_ptr<char[]> packed(new char[size_t(stated)]);
  is.read(packed.get(), stated);
  if (!is.good()) OPENVDB_THROW(RuntimeError, "truncated: the file ends inside a blosc chunk");
  size_t unpacked = 0;
  if (blosc_cbuffer_validate(packed.get(), size_t(stated), &unpacked) != 0 || unpacked != numBytes ||
      blosc_decompress_ctx(packed.get(), data, numBytes, 1) != int(numBytes))
    OPENVDB_THROW(RuntimeError, "a damaged blosc chunk (expected " + std::to_string(numBytes) + " bytes)");
}

} // namespace io
} // namespace OPENVDB_VERSION_NAME
} // namespace openvdb

// Referenced by the level-set reader so that the linker always takes this file from the archive.
namespace talus {
extern const bool kVdbBloscGuard = true;
}
