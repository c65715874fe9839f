// Thin RAII helpers over the HDF5 C API (datasets of numbers and string attributes).
#pragma once

#include <hdf5.h>
#include <stdexcept>
#include <string>
#include <vector>

namespace talus::h5 {

/// The cause of the last failed HDF5 call on this thread: the system's message when a file
/// operation failed ("No space left on device"), else HDF5's innermost description.
std::string lastError();

/// Owns an hid_t and closes it with the matching H5*close.
class Handle {
public:
  Handle() = default;
  Handle(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error("HDF5 call failed: " + lastError());
  }
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Handle& operator=(Handle&& o) noexcept {
    reset();
    id_ = o.id_, close_ = o.close_, o.id_ = -1;
    return *this;
  }
  ~Handle() { reset(); }
  operator hid_t() const { return id_; }
  void reset() { close(); }
  /// Closes now and returns the close function's status (a file's close flushes it: it fails
  /// when the disk is full).
  herr_t close() {
    const herr_t r = id_ >= 0 && close_ ? close_(id_) : 0;
    id_ = -1;
    return r;
  }
private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

/// Creates (truncates) a file for writing; throws WriteError naming it and the cause.
/// `userBlock` bytes (0 or a power of two >= 512) are left at the start for the caller.
Handle createFile(const std::string& path, size_t userBlock = 0);
/// Closes a file created for writing, reporting a failed final flush as a WriteError. A writer
/// must call it: the handle's destructor ignores errors.
void closeFile(Handle& file);

Handle openFile(const std::string& path);
Handle createGroup(hid_t parent, const std::string& name);

template <class T> hid_t nativeType();

/// Writes a rows x cols dataset (cols = 1 writes a 1-D dataset).
template <class T>
void writeDataset(hid_t parent, const std::string& name, const T* data, size_t rows, size_t cols);
/// Creates a rows x cols dataset of T whose storage is allocated now, contiguous and unfilled,
/// and returns the file offset where its row-major bytes start (0 when rows == 0). They are written
/// afterwards, by any process, in place (io/output/particle_file_parts.h): HDF5 never writes
/// them. The file's type is T's native (little-endian) type. Throws WriteError naming the file.
template <class T>
uint64_t createDatasetForRawWrites(hid_t parent, const std::string& name, size_t rows, size_t cols);
template <class T>
std::vector<T> readDataset(hid_t file, const std::string& name, size_t& rows, size_t& cols);
bool exists(hid_t file, const std::string& path);

void writeAttribute(hid_t obj, const std::string& name, double value);
void writeAttribute(hid_t obj, const std::string& name, const std::string& value);
void writeAttribute(hid_t obj, const std::string& name, const std::vector<std::string>& values);
double readDoubleAttribute(hid_t obj, const std::string& name);
std::vector<std::string> readStringsAttribute(hid_t obj, const std::string& name);

} // namespace talus::h5
