#include "io/run/checkpoint_parts.h"

#include "io/common/atomic_file.h"
#include "io/common/h5_file.h"
#include "io/common/input_error.h"

#include <algorithm>
#include <cerrno>
#include <fcntl.h>
#include <filesystem>
#include <set>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

namespace talus {

namespace fs = std::filesystem;

namespace {

fs::path partsFolder(const std::string& checkpointPath) {
  const fs::path p(checkpointPath);
  return p.parent_path() / (p.stem().string() + "_parts");
}

/// The part's name relative to the checkpoint's folder.
std::string partName(const std::string& checkpointPath, uint64_t step, int rank) {
  return (partsFolder(checkpointPath).filename() / ("step" + std::to_string(step) + "_rank" + std::to_string(rank) + ".h5"))
      .string();
}

std::string groupPath(size_t g, const char* what) { return "group" + std::to_string(g) + "/" + what; }

/// Length and CRC-32 of a closed file; throws via `fail`.
CheckpointPart measure(const std::string& path, const std::function<void(const std::string&)>& fail) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(errnoText(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st{};
  if (::fstat(fd, &st) != 0) fail(errnoText(errno));
  CheckpointPart m;
  m.bytes = uint64_t(st.st_size);
  m.crc = crc32OfFile(fd, 0, m.bytes, fail);
  return m;
}

/// Writes this process's particles (Simulation::particleRecords of every group) to
/// checkpoint_parts/step<S>_rank<rank>.h5 beside `checkpointPath`, atomically; returns the part
/// as the checkpoint lists it. Throws WriteError naming the file.
CheckpointPart writeCheckpointPart(const std::string& checkpointPath, const Simulation& sim, int rank) {
  CheckpointPart part;
  part.file = partName(checkpointPath, sim.steps(), rank);
  const std::string path = (fs::path(checkpointPath).parent_path() / part.file).string();
  std::error_code ec;
  fs::create_directories(partsFolder(checkpointPath), ec);
  if (ec) throw WriteError(partsFolder(checkpointPath).string(), ec.message());
  writeAtomically(path, [&](const std::string& tmp) {
    {
      h5::Handle f = h5::createFile(tmp);
      std::vector<char> settled, fresh;
      for (size_t g = 0; g < sim.groups().size(); ++g) {
        sim.particleRecords(g, settled, fresh);
        h5::createGroup(f, "group" + std::to_string(g));
        h5::writeDataset(f, groupPath(g, "settled"), reinterpret_cast<const uint8_t*>(settled.data()), settled.size(), 1);
        h5::writeDataset(f, groupPath(g, "fresh"), reinterpret_cast<const uint8_t*>(fresh.data()), fresh.size(), 1);
      }
      h5::writeAttribute(f, "groups", double(sim.groups().size()));
      h5::closeFile(f);
    }
    const CheckpointPart m = measure(tmp, [&](const std::string& cause) -> void { throw WriteError(tmp, cause); });
    part.bytes = m.bytes, part.crc = m.crc;
  });
  return part;
}

} // namespace

uint32_t crc32OfFile(int fd, uint64_t from, uint64_t end, const std::function<void(const std::string&)>& fail) {
  std::vector<unsigned char> buf(size_t(1) << 20);
  uLong crc = ::crc32(0, nullptr, 0);
  for (uint64_t at = from; at < end;) {
    const ssize_t r = ::pread(fd, buf.data(), size_t(std::min<uint64_t>(buf.size(), end - at)), off_t(at));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) fail(r < 0 ? errnoText(errno) : "file shrank while being read");
    crc = ::crc32(crc, buf.data(), uInt(r));
    at += uint64_t(r);
  }
  return uint32_t(crc);
}

WrittenParts writeCheckpointParts(Communicator& comm, const std::string& checkpointPath, const Simulation& sim) {
  // Each rank's outcome as lines: "ok" and its part's line, or "failed", the file and the cause.
  std::string mine;
  try {
    mine = "ok\n" + partListText({writeCheckpointPart(checkpointPath, sim, comm.rank())});
  } catch (const WriteError& e) {
    mine = "failed\n" + e.file() + "\n" + e.cause() + "\n";
  }
  std::vector<size_t> counts;
  const std::vector<char> all = comm.gather(std::vector<char>(mine.begin(), mine.end()), counts);
  WrittenParts out;
  size_t at = 0;
  for (size_t c : counts) {
    std::istringstream in(std::string(all.data() + at, c));
    at += c;
    std::string status, a, b;
    std::getline(in, status), std::getline(in, a), std::getline(in, b);
    if (status == "ok") out.parts.push_back(parsePartList(a).at(0));
    else if (!out.failure) out.failure.emplace(a, b);
  }
  return out;
}

std::string partListText(const std::vector<CheckpointPart>& parts) {
  std::ostringstream out;
  for (const CheckpointPart& p : parts) out << p.file << ' ' << p.bytes << ' ' << p.crc << '\n';
  return out.str();
}

std::vector<CheckpointPart> parsePartList(const std::string& text) {
  std::vector<CheckpointPart> parts;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::istringstream l(line);
    CheckpointPart p;
    if (!(l >> p.file >> p.bytes >> p.crc)) throw std::runtime_error("unreadable list of parts: '" + line + "'");
    parts.push_back(p);
  }
  return parts;
}

void readCheckpointParts(const std::string& checkpointPath, const std::vector<CheckpointPart>& parts, Simulation& sim) {
  const size_t groups = sim.groups().size();
  std::vector<std::string> paths;
  auto refuser = [&](size_t i) {
    return [&, i](const std::string& why) -> void {
      throw InputError(paths[i], "a part of checkpoint " + checkpointPath + ": " + why);
    };
  };
  for (const CheckpointPart& part : parts) {
    paths.push_back((fs::path(checkpointPath).parent_path() / part.file).string());
    const auto refuse = refuser(paths.size() - 1);
    if (!fs::exists(paths.back())) refuse("missing");
    const CheckpointPart m = measure(paths.back(), refuse);
    if (m.bytes != part.bytes) refuse("truncated or extended: " + std::to_string(m.bytes) + " bytes, " + std::to_string(part.bytes) + " written");
    if (m.crc != part.crc) refuse("damaged (checksum mismatch)");
    try {
      if (h5::readDoubleAttribute(h5::openFile(paths.back()), "groups") != double(groups))
        refuse("written for another number of materials");
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      refuse(std::string("unreadable: ") + e.what());
    }
  }
  // One part's records in memory at a time, appended where one process has them. A part is
  // opened for each read, not held open: at a thousand ranks they would pass the open-file limit.
  for (size_t g = 0; g < groups; ++g)
    for (const char* kind : {"settled", "fresh"})
      for (size_t i = 0; i < paths.size(); ++i) {
        std::vector<uint8_t> r;
        try {
          size_t rows = 0, cols = 0;
          r = h5::readDataset<uint8_t>(h5::openFile(paths[i]), groupPath(g, kind), rows, cols);
          sim.appendParticleRecords(g, std::string_view(reinterpret_cast<const char*>(r.data()), r.size()));
        } catch (const std::exception& e) {
          refuser(i)(std::string("does not fit this scene: ") + e.what());
        }
      }
  try {
    sim.checkParticles();
  } catch (const std::exception& e) {
    throw InputError(checkpointPath, std::string("its parts do not fit this scene: ") + e.what());
  }
}

void removeStaleParts(const std::string& checkpointPath, const std::vector<CheckpointPart>& keep) {
  const fs::path folder = partsFolder(checkpointPath);
  std::set<std::string> kept;
  for (const CheckpointPart& p : keep) kept.insert(fs::path(p.file).filename().string());
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (!kept.count(it->path().filename().string())) fs::remove(it->path(), ec), ec.clear();
  if (keep.empty()) fs::remove(folder, ec); // only when empty
}

} // namespace talus
