// Named binary blobs: how simulation state is written to and read from checkpoints without the
// engine knowing the file format (io/checkpoint.cpp stores them in HDF5).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace talus {

class StateArchive {
public:
  virtual ~StateArchive() = default;
  virtual void put(const std::string& name, const void* data, size_t bytes) = 0;
  /// Size of a stored blob; throws std::runtime_error when it is missing.
  virtual size_t size(const std::string& name) const = 0;
  virtual void get(const std::string& name, void* data, size_t bytes) const = 0;

  template <class T> void putVector(const std::string& name, const std::vector<T>& v) {
    put(name, v.data(), v.size() * sizeof(T));
  }
  template <class T> void getVector(const std::string& name, std::vector<T>& v) const {
    const size_t bytes = size(name);
    if (bytes % sizeof(T) != 0) throw std::runtime_error("entry '" + name + "' is not a whole number of elements");
    v.resize(bytes / sizeof(T));
    get(name, v.data(), v.size() * sizeof(T));
  }
  template <class T> void putValue(const std::string& name, const T& v) { put(name, &v, sizeof(T)); }
  template <class T> T getValue(const std::string& name) const {
    T v{};
    get(name, &v, sizeof(T));
    return v;
  }
};

} // namespace talus
