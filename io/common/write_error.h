// The exception for an output that could not be written: a full disk, a quota, a read-only or
// vanished folder, a file-size limit. It names the file the user asked for (never a temporary)
// and the cause as the system reports it, e.g. "No space left on device".
#pragma once

#include <stdexcept>
#include <string>

namespace talus {

class WriteError : public std::runtime_error {
public:
  WriteError(std::string file, std::string cause)
      : std::runtime_error("cannot write " + file + ": " + cause), file_(std::move(file)), cause_(std::move(cause)) {}
  const std::string& file() const { return file_; }
  const std::string& cause() const { return cause_; }

private:
  std::string file_, cause_;
};

/// strerror(err) as a string (thread-safe).
std::string errnoText(int err);

} // namespace talus
