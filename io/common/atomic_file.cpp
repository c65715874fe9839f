#include "io/common/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <new>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace talus {

std::string errnoText(int err) {
  char buf[256];
  // GNU strerror_r returns the message (which may not be buf).
  return strerror_r(err, buf, sizeof buf);
}

namespace {

/// Closes on scope exit unless released; close errors matter only on the success path.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
  int release() {
    const int f = fd;
    fd = -1;
    return f;
  }
};

void writeAll(int fd, const char* p, size_t n, const std::string& path) {
  while (n > 0) {
    const ssize_t w = ::write(fd, p, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      throw WriteError(path, errnoText(errno));
    }
    p += w, n -= size_t(w);
  }
}

void closeChecked(Fd& f, const std::string& path) {
  if (::close(f.release()) != 0) throw WriteError(path, errnoText(errno));
}

/// The bytes reach the device before the rename makes them the file: a machine that loses
/// power right after never shows a renamed but empty file.
void syncFile(const std::string& path) {
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (f.fd < 0) throw WriteError(path, errnoText(errno));
  if (::fsync(f.fd) != 0 && errno != EINVAL && errno != EROFS) throw WriteError(path, errnoText(errno));
}

} // namespace

void writeFileBytes(const std::string& path, const void* data, size_t size) {
  Fd f{::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666)};
  if (f.fd < 0) throw WriteError(path, errnoText(errno));
  writeAll(f.fd, static_cast<const char*>(data), size, path);
  closeChecked(f, path);
}

void writeThroughMemory(const std::string& path, const std::function<void(const std::string&)>& write) {
  Fd mem{::memfd_create("talus-output", MFD_CLOEXEC)};
  if (mem.fd < 0) throw WriteError(path, "no memory for the file's bytes (" + errnoText(errno) + ")");
  write("/proc/self/fd/" + std::to_string(mem.fd));
  struct stat st{};
  if (::fstat(mem.fd, &st) != 0) throw WriteError(path, errnoText(errno));
  const size_t size = size_t(st.st_size);
  void* bytes = size ? ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, mem.fd, 0) : nullptr;
  if (bytes == MAP_FAILED) throw WriteError(path, errnoText(errno));
  try {
    writeFileBytes(path, bytes, size);
  } catch (...) {
    ::munmap(bytes, size);
    throw;
  }
  if (size) ::munmap(bytes, size);
}

void commitFile(const std::string& tmp, const std::string& path) {
  try {
    syncFile(tmp);
  } catch (const WriteError& e) {
    throw WriteError(path, e.cause());
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) throw WriteError(path, errnoText(errno));
}

void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write,
                     const std::string& tmpSuffix) {
  const std::string tmp = path + tmpSuffix;
  auto discard = [&] {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
  };
  try {
    // Held open for writing until after the rename: a file system cannot be remounted read-only
    // while a file on it is open for writing (EBUSY), so it cannot turn read-only between the
    // writer's close and the rename, which would strand the temporary where it cannot be removed.
    // Every writer truncates the path it is given, so the guard and the writer share the file.
    Fd guard{::open(tmp.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0666)};
    if (guard.fd < 0) throw WriteError(path, errnoText(errno));
    write(tmp);
    syncFile(tmp);
    if (::rename(tmp.c_str(), path.c_str()) != 0) throw WriteError(path, errnoText(errno));
  } catch (const std::bad_alloc&) {
    discard();
    throw;
  } catch (const WriteError& e) {
    discard();
    throw WriteError(path, e.cause());
  } catch (const std::exception& e) {
    discard();
    throw WriteError(path, e.what());
  }
}

} // namespace talus
