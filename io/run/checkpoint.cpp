#include "io/run/checkpoint.h"

#include "io/run/checkpoint_parts.h"

#include "io/common/atomic_file.h"
#include "io/common/h5_file.h"
#include "io/common/input_error.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <map>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

namespace talus {

namespace {

/// Blobs as 1-D uint8 datasets under /state; '/' in a name makes HDF5 groups.
class H5Archive final : public StateArchive {
public:
  H5Archive(hid_t file, bool writing) : file_(file) {
    if (writing) root_ = h5::createGroup(file_, "state");
  }
  void put(const std::string& name, const void* data, size_t bytes) override {
    const std::string path = "/state/" + name;
    const auto slash = path.rfind('/');
    const std::string parent = path.substr(0, slash);
    if (!h5::exists(file_, parent)) h5::createGroup(file_, parent);
    h5::writeDataset(file_, path, static_cast<const uint8_t*>(data), bytes, 1);
  }
  size_t size(const std::string& name) const override {
    load(name);
    return cache_.size();
  }
  void get(const std::string& name, void* data, size_t bytes) const override {
    load(name);
    if (cache_.size() != bytes) throw std::runtime_error("checkpoint entry '" + name + "' has the wrong size");
    std::copy(cache_.begin(), cache_.end(), static_cast<uint8_t*>(data));
  }

private:
  void load(const std::string& name) const {
    if (cachedName_ == name) return;
    const std::string path = "/state/" + name;
    if (!h5::exists(file_, path)) throw std::runtime_error("checkpoint has no entry '" + name + "'");
    size_t rows = 0, cols = 0;
    cache_ = h5::readDataset<uint8_t>(file_, path, rows, cols);
    cachedName_ = name;
  }
  hid_t file_;
  h5::Handle root_;
  mutable std::string cachedName_;
  mutable std::vector<uint8_t> cache_;
};

constexpr size_t kHeaderBytes = 512; // an HDF5 user block: HDF5 skips it
constexpr char kMagic[] = "TALUS CHECKPOINT\n";

struct Header {
  int format = 0;
  std::string version, scene;
  uint64_t bytes = 0;
  uint32_t crc = 0;
};

uint32_t crc32Of(const std::string& s) {
  return uint32_t(::crc32(0, reinterpret_cast<const Bytef*>(s.data()), uInt(s.size())));
}

std::string hex32(uint32_t v) {
  char b[16];
  std::snprintf(b, sizeof b, "%08x", v);
  return b;
}

std::string headerBody(const Header& h) {
  return std::string(kMagic) + "format " + std::to_string(h.format) + "\ntalus " + h.version + "\nscene " +
         h.scene + "\nbytes " + std::to_string(h.bytes) + "\ncrc32 " + hex32(h.crc) + "\n";
}

/// The HDF5 part is written and closed; now its length and checksum go into the user block.
void seal(const std::string& tmp, const CheckpointIdentity& id) {
  const int fd = ::open(tmp.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) throw WriteError(tmp, errnoText(errno));
  auto fail = [&](const std::string& cause) {
    ::close(fd);
    throw WriteError(tmp, cause);
  };
  struct stat st{};
  if (::fstat(fd, &st) != 0) fail(errnoText(errno));
  Header h;
  h.format = kCheckpointFormat;
  h.version = talusVersion();
  h.scene = id.sceneHash;
  h.bytes = uint64_t(st.st_size) - kHeaderBytes;
  h.crc = crc32OfFile(fd, kHeaderBytes, uint64_t(st.st_size), fail);
  std::string text = headerBody(h);
  text += "header_crc32 " + hex32(crc32Of(text)) + "\n";
  if (text.size() > kHeaderBytes) fail("checkpoint header too long");
  text.resize(kHeaderBytes, '\0');
  if (::pwrite(fd, text.data(), text.size(), 0) != ssize_t(text.size())) fail(errnoText(errno));
  if (::close(fd) != 0) throw WriteError(tmp, errnoText(errno));
}

} // namespace

CheckpointHeader inspectCheckpoint(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, "no checkpoint to resume from");
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "not a regular file");
  auto refuse = [&](const std::string& why) { throw InputError(path, why); };
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) refuse("cannot open (" + errnoText(errno) + ")");
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st{};
  if (::fstat(fd, &st) != 0) refuse("cannot read (" + errnoText(errno) + ")");
  const uint64_t size = uint64_t(st.st_size);
  std::string block(kHeaderBytes, '\0');
  const ssize_t got = ::pread(fd, block.data(), block.size(), 0);
  if (got < 0) refuse("cannot read (" + errnoText(errno) + ")");
  block.resize(size_t(got));
  if (size == 0) refuse("empty file");
  if (block.compare(0, 8, "\x89HDF\r\n\x1a\n") == 0)
    refuse("an HDF5 file without a checkpoint header: checkpoint format 1 (an older Talus, without checksum) or "
           "not a checkpoint; this Talus reads format " + std::to_string(kCheckpointFormat) + ": start the run again");
  if (block.compare(0, sizeof kMagic - 1, kMagic) != 0) refuse("not a Talus checkpoint");
  if (size < kHeaderBytes) refuse("truncated (" + std::to_string(size) + " bytes)");
  block.resize(std::min(block.find('\0'), block.size()));
  const auto crcLine = block.rfind("header_crc32 ");
  if (crcLine == std::string::npos || hex32(crc32Of(block.substr(0, crcLine))) + "\n" != block.substr(crcLine + 13))
    refuse("damaged header (checksum mismatch)");
  std::istringstream in(block.substr(sizeof kMagic - 1, crcLine - (sizeof kMagic - 1)));
  Header h;
  std::string key[5], crc;
  in >> key[0] >> h.format >> key[1] >> h.version >> key[2] >> h.scene >> key[3] >> h.bytes >> key[4] >> crc;
  if (!in || key[0] != "format" || key[1] != "talus" || key[2] != "scene" || key[3] != "bytes" || key[4] != "crc32")
    refuse("damaged header");
  if (h.format < kOldestCheckpointFormat || h.format > kCheckpointFormat)
    refuse("checkpoint format " + std::to_string(h.format) + "; this Talus reads formats " +
           std::to_string(kOldestCheckpointFormat) + " to " + std::to_string(kCheckpointFormat));
  if (h.version != talusVersion())
    refuse("written by Talus " + h.version + "; this is Talus " + talusVersion() +
           ", which resumes only its own checkpoints (finish the run with Talus " + h.version + " or start again)");
  if (h.bytes != size - kHeaderBytes)
    refuse("truncated or extended: " + std::to_string(size - kHeaderBytes) + " bytes after the header, " +
           std::to_string(h.bytes) + " written");
  if (hex32(crc32OfFile(fd, kHeaderBytes, size, refuse)) != crc) refuse("damaged (checksum mismatch)");
  return {h.format, h.version, h.scene};
}

const char* talusVersion() { return TALUS_VERSION; }

std::string checkpointPath(const std::string& dir) { return (std::filesystem::path(dir) / "checkpoint.h5").string(); }

void writeCheckpoint(const std::string& path, const Simulation& sim, const CheckpointIdentity& id,
                     const std::function<void(StateArchive&)>& extra) {
  writeAtomically(path, [&](const std::string& tmp) {
    h5::Handle f = h5::createFile(tmp, kHeaderBytes);
    {
      H5Archive a(f, true);
      sim.save(a);
      if (!id.sceneKeys.empty()) a.put("scene/keys", id.sceneKeys.data(), id.sceneKeys.size());
      if (extra) extra(a);
    }
    h5::writeAttribute(f, "time", sim.time());
    h5::closeFile(f);
    seal(tmp, id);
  });
}

namespace {
/// The first key whose line differs between two SceneSetup::stateKeys listings, as "key (a
/// there, b here)"; empty when none can be named.
std::string changedKey(const std::string& there, const std::string& here) {
  auto parse = [](const std::string& text) {
    std::map<std::string, std::string> keys;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
      if (const size_t eq = line.find(" = "); eq != std::string::npos) keys[line.substr(0, eq)] = line.substr(eq + 3);
    return keys;
  };
  const auto a = parse(there), b = parse(here);
  if (a.empty() || b.empty()) return "";
  auto ia = a.begin();
  auto ib = b.begin();
  while (ia != a.end() || ib != b.end()) {
    if (ib == b.end() || (ia != a.end() && ia->first < ib->first)) return ia->first + " (" + ia->second + " there, absent here)";
    if (ia == a.end() || ib->first < ia->first) return ib->first + " (absent there, " + ib->second + " here)";
    if (ia->second != ib->second) return ia->first + " (" + ia->second + " there, " + ib->second + " here)";
    ++ia, ++ib;
  }
  return "";
}

/// The scene keys a checkpoint recorded (empty when it has none: written before they were kept).
std::string recordedKeys(const std::string& path) {
  try {
    h5::Handle f = h5::openFile(path);
    H5Archive a(f, false);
    std::string keys(a.size("scene/keys"), '\0');
    a.get("scene/keys", keys.data(), keys.size());
    return keys;
  } catch (const std::exception&) {
    return "";
  }
}
} // namespace

void readCheckpoint(const std::string& path, Simulation& sim, const CheckpointIdentity& id,
                    const std::function<void(const StateArchive&)>& extra) {
  const CheckpointHeader h = inspectCheckpoint(path);
  if (h.sceneHash != id.sceneHash) {
    const std::string key = changedKey(recordedKeys(path), id.sceneKeys);
    throw InputError(path, "written for another scene (scene hash " + h.sceneHash + ", this scene " + id.sceneHash +
                               (key.empty() ? std::string("): the scene file or its --set overrides changed since")
                                            : "): " + key + " changed since") +
                               "; a resumed run may change only simulation.end_time and the frame outputs");
  }
  try {
    h5::Handle f = h5::openFile(path);
    H5Archive a(f, false);
    sim.load(a);
    // Written on ranks: the particles are in the parts the checkpoint lists.
    if (h5::exists(f, "/state/" + std::string(kPartList))) {
      std::string list(a.size(kPartList), '\0');
      a.get(kPartList, list.data(), list.size());
      readCheckpointParts(path, parsePartList(list), sim);
    }
    if (extra) extra(a);
  } catch (const InputError&) {
    throw; // a part, named
  } catch (const std::exception& e) {
    throw InputError(path, std::string("does not fit this scene: ") + e.what());
  }
}

} // namespace talus
