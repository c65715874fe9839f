// The exception for bad user input (a scene value, a raster, a polygon, a limit): one line naming
// the file, line and key. Talus has one other, NumericalError (engine/simulation.h): a run that
// failed. Anything else (a full disk, a library failure) is a std::runtime_error.
#pragma once

#include <stdexcept>
#include <string>

namespace talus {

class InputError : public std::runtime_error {
public:
  InputError(std::string file, int line, std::string key, const std::string& message)
      : std::runtime_error(format(file, line, key, message)), file_(std::move(file)), line_(line),
        key_(std::move(key)) {}

  /// About a whole file (a raster, a polygon file), or with an empty file a plain message.
  InputError(std::string file, const std::string& message) : InputError(std::move(file), 0, "", message) {}

  const std::string& file() const { return file_; }
  /// True when the error names a place in a scene (a line or a key), not only a file.
  bool located() const { return line_ > 0 || !key_.empty(); }
  int line() const { return line_; }
  const std::string& key() const { return key_; }

private:
  static std::string format(const std::string& file, int line, const std::string& key,
                            const std::string& message) {
    if (file.empty() && line <= 0 && key.empty()) return message;
    std::string s = file.empty() ? std::string("<input>") : file;
    if (line > 0) s += ":" + std::to_string(line);
    s += ": ";
    if (!key.empty()) s += key + ": ";
    return s + message;
  }
  std::string file_;
  int line_;
  std::string key_;
};

} // namespace talus
