#include "io/output/particle_file_parts.h"

#include "io/common/atomic_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sstream>
#include <unistd.h>

namespace talus {

namespace {

template <class T> std::vector<char> bytesOf(const std::vector<T>& v) {
  std::vector<char> b(v.size() * sizeof(T));
  if (!v.empty()) std::memcpy(b.data(), v.data(), b.size());
  return b;
}

/// Rank 0's bytes on every process.
std::vector<char> fromRoot(Communicator& comm, const std::string& text) {
  std::vector<size_t> counts;
  return comm.allGather(comm.rank() == 0 ? std::vector<char>(text.begin(), text.end()) : std::vector<char>(), counts);
}

/// Writes this process's rows of every column into `tmp` and syncs them; the cause of a failure,
/// or empty.
std::string writeRows(const std::string& tmp, const std::vector<FileColumn>& columns, const ParticleRows& rows,
                      const Simulation& local, const RowFiller& fill) {
  if (rows.mine().empty()) return {};
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return errnoText(errno);
  struct Closer {
    int fd;
    ~Closer() {
      if (fd >= 0) ::close(fd);
    }
  } closer{fd};
  constexpr size_t kChunkBytes = size_t(1) << 20; // rows go out in pieces of about a megabyte
  std::vector<char> buf;
  for (size_t c = 0; c < columns.size(); ++c) {
    const size_t width = columns[c].width;
    const size_t perChunk = std::max<size_t>(1, kChunkBytes / width);
    for (const ParticleRows::Run& r : rows.mine())
      for (size_t b = r.begin; b < r.end; b += perChunk) {
        const size_t e = std::min(r.end, b + perChunk);
        buf.resize((e - b) * width);
        fill(c, *local.groups()[r.group], b, e, buf.data());
        uint64_t at = columns[c].offset + (r.row + (b - r.begin)) * width;
        for (const char* p = buf.data(); p != buf.data() + buf.size();) {
          const ssize_t w = ::pwrite(fd, p, size_t(buf.data() + buf.size() - p), off_t(at));
          if (w < 0 && errno == EINTR) continue;
          if (w < 0) return errnoText(errno);
          p += w, at += uint64_t(w);
        }
      }
  }
  if (::fdatasync(fd) != 0 && errno != EINVAL && errno != EROFS) return errnoText(errno);
  const int f = closer.fd;
  closer.fd = -1;
  return ::close(f) == 0 ? std::string() : errnoText(errno);
}

} // namespace

ParticleRows::ParticleRows(Communicator& comm, const Simulation& local) {
  const size_t groups = local.groups().size();
  std::vector<uint64_t> mine(2 * groups); // settled, fresh per group
  for (size_t g = 0; g < groups; ++g) {
    const size_t fresh = local.freshParticles(g);
    mine[2 * g] = local.groups()[g]->size() - fresh, mine[2 * g + 1] = fresh;
  }
  std::vector<size_t> counts;
  const std::vector<char> all = comm.allGather(bytesOf(mine), counts);
  const size_t ranks = counts.size();
  if (all.size() != ranks * mine.size() * sizeof(uint64_t)) throw std::logic_error("ParticleRows: uneven counts");
  auto count = [&](size_t r, size_t g, int fresh) {
    uint64_t v;
    std::memcpy(&v, all.data() + ((r * groups + g) * 2 + size_t(fresh)) * sizeof v, sizeof v);
    return v;
  };
  const size_t self = size_t(comm.rank());
  for (size_t g = 0; g < groups; ++g)
    for (int fresh = 0; fresh < 2; ++fresh)
      for (size_t r = 0; r < ranks; ++r) {
        const uint64_t n = count(r, g, fresh);
        if (r == self && n) {
          const size_t settled = size_t(mine[2 * g]);
          mine_.push_back({g, fresh ? settled : 0, fresh ? settled + size_t(n) : size_t(n), total_});
        }
        total_ += n;
      }
}

std::optional<WriteError> writeParticleFile(Communicator& comm, const std::string& path, const Simulation& local,
                                            const FileLayout& layout, const RowFiller& fill) {
  const ParticleRows rows(comm, local);
  const bool root = comm.rank() == 0;
  const std::string tmp = path + ".tmp";
  // 1. Rank 0 lays the file out and tells every process its columns ("ok", then "offset width"
  //    lines) or why it could not ("failed", then the cause).
  std::string plan;
  std::vector<FileColumn> columns;
  if (root) {
    try {
      columns = layout(tmp, rows.total());
      std::ostringstream out;
      out << "ok\n";
      for (const FileColumn& c : columns) out << c.offset << ' ' << c.width << '\n';
      plan = out.str();
    } catch (const WriteError& e) {
      plan = "failed\n" + e.cause();
    } catch (const std::exception& e) {
      plan = std::string("failed\n") + e.what();
    }
  }
  const std::vector<char> got = fromRoot(comm, plan);
  std::istringstream in(std::string(got.begin(), got.end()));
  std::string status;
  std::getline(in, status);
  std::string cause;
  if (status == "ok") {
    if (!root)
      for (FileColumn c; in >> c.offset >> c.width;) columns.push_back(c);
    // 2. Every process its rows.
    cause = writeRows(tmp, columns, rows, local, fill);
  } else {
    std::getline(in, cause);
  }
  // 3. Rank 0 learns every outcome and commits the file or removes it.
  std::vector<size_t> counts;
  const std::vector<char> causes = comm.gather(std::vector<char>(cause.begin(), cause.end()), counts);
  if (!root) return std::nullopt;
  size_t at = 0;
  for (size_t c : counts) {
    if (c && cause.empty()) cause.assign(causes.data() + at, c);
    at += c;
  }
  try {
    if (cause.empty()) commitFile(tmp, path);
  } catch (const WriteError& e) {
    cause = e.cause();
  }
  if (cause.empty()) return std::nullopt;
  std::error_code ec;
  std::filesystem::remove(tmp, ec);
  return WriteError(path, cause);
}

} // namespace talus
