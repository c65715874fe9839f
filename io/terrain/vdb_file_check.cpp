#include "io/terrain/vdb_file_check.h"

#include <cstdint>
#include <fstream>
#include <stdexcept>

namespace talus {

namespace {

// The OpenVDB file format (io/Archive.cc, io/GridDescriptor.cc, MetaMap::readMeta).
constexpr int64_t kMagic = 0x56444220;
constexpr uint32_t kOldestVersion = 220, kNewestVersion = 224;
constexpr uint32_t kInstancing = 216, kPerGridCompression = 222;

class Reader {
public:
  explicit Reader(const std::string& path) : in_(path, std::ios::binary) {
    if (!in_) throw std::runtime_error("cannot open the file");
    in_.seekg(0, std::ios::end);
    size_ = uint64_t(in_.tellg());
    in_.seekg(0);
  }
  uint64_t size() const { return size_; }
  uint64_t pos() { return uint64_t(in_.tellg()); }
  void seek(uint64_t at) { in_.seekg(std::streamoff(at)); }

  template <class T> T value(const char* what) {
    need(sizeof(T), what);
    T v{};
    in_.read(reinterpret_cast<char*>(&v), sizeof v);
    return v;
  }
  void skip(uint64_t n, const char* what) {
    need(n, what);
    seek(pos() + n);
  }
  std::string string(const char* what) {
    const uint32_t n = value<uint32_t>(what);
    need(n, what);
    std::string s(n, '\0');
    in_.read(s.data(), std::streamsize(n));
    return s;
  }

private:
  void need(uint64_t n, const char* what) {
    const uint64_t at = pos();
    if (at > size_ || n > size_ - at)
      throw std::runtime_error(std::string("truncated or damaged: ") + what + " at byte " + std::to_string(at) +
                               " needs " + std::to_string(n) + " bytes, the file has " + std::to_string(size_));
  }
  std::ifstream in_;
  uint64_t size_ = 0;
};

void metadata(Reader& r) {
  const uint32_t count = r.value<uint32_t>("the metadata count");
  if (count > r.size()) throw std::runtime_error("damaged: " + std::to_string(count) + " metadata entries");
  for (uint32_t i = 0; i < count; ++i) {
    r.string("a metadata name");
    r.string("a metadata type");
    r.skip(r.value<uint32_t>("a metadata value"), "a metadata value");
  }
}

} // namespace

std::string printable(const std::string& s, size_t max) {
  std::string out;
  for (char c : s.substr(0, max)) out += c >= 0x20 && c < 0x7f ? c : '?';
  return s.size() > max ? out + "..." : out;
}

void checkVdbFile(const std::string& path) {
  Reader r(path);
  if (r.size() < 8 || r.value<int64_t>("the magic number") != kMagic) throw std::runtime_error("not a .vdb file");
  const uint32_t version = r.value<uint32_t>("the file version");
  if (version < kOldestVersion || version > kNewestVersion)
    throw std::runtime_error("VDB file format version " + std::to_string(version) + "; Talus reads " +
                             std::to_string(kOldestVersion) + " to " + std::to_string(kNewestVersion));
  r.skip(8, "the library version");
  const bool offsets = r.value<char>("the grid-offsets flag") != 0;
  if (version < kPerGridCompression) r.skip(1, "the compression flag");
  r.skip(36, "the file's UUID");
  if (!offsets) throw std::runtime_error("written as a stream without grid offsets; save it as a .vdb file");
  metadata(r);
  const int32_t grids = r.value<int32_t>("the grid count");
  if (grids < 0 || uint64_t(grids) > r.size()) throw std::runtime_error("damaged: " + std::to_string(grids) + " grids");
  for (int32_t g = 0; g < grids; ++g) {
    const std::string name = printable(r.string("a grid name"));
    r.string("a grid type");
    const bool instance = version >= kInstancing && !r.string("an instance parent").empty();
    const auto gridPos = r.value<int64_t>("a grid offset"), blockPos = r.value<int64_t>("a grid offset"),
               endPos = r.value<int64_t>("a grid offset");
    if (gridPos != int64_t(r.pos()) || endPos < gridPos || uint64_t(endPos) > r.size() ||
        (!instance && (blockPos < gridPos || blockPos > endPos)))
      throw std::runtime_error("truncated or damaged: grid '" + name + "' is stated to lie at bytes " +
                               std::to_string(gridPos) + " to " + std::to_string(endPos) + " of " +
                               std::to_string(r.size()));
    if (version >= kPerGridCompression) r.skip(4, "a grid's compression");
    metadata(r);
    r.string("a grid's transform type");
    if (r.pos() > uint64_t(endPos)) throw std::runtime_error("damaged: grid '" + name + "' overruns its end");
    r.seek(uint64_t(endPos));
  }
}

} // namespace talus
