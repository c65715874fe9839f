#include "io/common/h5_file.h"

#include "io/common/write_error.h"

#include <cstdint>

namespace talus::h5 {

namespace {
// HDF5 1.10 keeps a file whose close failed (its last flush hit a full disk) in its table of
// open objects, and its exit handler then crashes closing it again: the segmentation fault
// after "cannot write HDF5 dataset". Every file here is closed explicitly, so the handler is
// not needed; this runs before main, before HDF5 initialises itself.
const bool kNoExitHandler = (H5dont_atexit(), true);

// Silence HDF5's own error stack printing; failures surface as exceptions with our message.
struct QuietErrors {
  QuietErrors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }
};
void quiet() { static QuietErrors q; }

herr_t collect(unsigned, const H5E_error2_t* e, void* out) {
  if (e->desc) static_cast<std::vector<std::string>*>(out)->emplace_back(e->desc);
  return 0;
}

std::string fileName(hid_t obj) {
  char name[4096] = "";
  return H5Fget_name(obj, name, sizeof name) > 0 ? std::string(name) : std::string("HDF5 file");
}
} // namespace

std::string lastError() {
  std::vector<std::string> descs;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect, &descs);
  // The system's reason (ENOSPC, EFBIG, EROFS...) is quoted in the file driver's message.
  const std::string key = "error message = '";
  for (const auto& d : descs)
    if (const auto at = d.find(key); at != std::string::npos) {
      const auto end = d.find('\'', at + key.size());
      return d.substr(at + key.size(), end == std::string::npos ? std::string::npos : end - at - key.size());
    }
  return descs.empty() ? "HDF5 call failed" : descs.back();
}

Handle createFile(const std::string& path, size_t userBlock) {
  quiet();
  Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
  if (userBlock) H5Pset_userblock(fcpl, hsize_t(userBlock));
  hid_t f = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
  if (f < 0) throw WriteError(path, lastError());
  return Handle(f, H5Fclose);
}

void closeFile(Handle& file) {
  const std::string name = fileName(file);
  if (file.close() < 0) throw WriteError(name, lastError());
}

Handle openFile(const std::string& path) {
  quiet();
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (f < 0) throw std::runtime_error("cannot open HDF5 file " + path + " (" + lastError() + ")");
  return Handle(f, H5Fclose);
}

// No modification times in objects: identical runs then write identical files.
Handle untimedObjects(hid_t cls) {
  Handle p(H5Pcreate(cls), H5Pclose);
  H5Pset_obj_track_times(p, false);
  return p;
}

Handle createGroup(hid_t parent, const std::string& name) {
  Handle gcpl = untimedObjects(H5P_GROUP_CREATE);
  const hid_t id = H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT);
  if (id < 0) throw WriteError(fileName(parent), lastError());
  return Handle(id, H5Gclose);
}

template <> hid_t nativeType<double>() { return H5T_NATIVE_DOUBLE; }
template <> hid_t nativeType<float>() { return H5T_NATIVE_FLOAT; }
template <> hid_t nativeType<int32_t>() { return H5T_NATIVE_INT32; }
template <> hid_t nativeType<uint32_t>() { return H5T_NATIVE_UINT32; }
template <> hid_t nativeType<uint64_t>() { return H5T_NATIVE_UINT64; }
template <> hid_t nativeType<uint8_t>() { return H5T_NATIVE_UINT8; }

template <class T>
void writeDataset(hid_t parent, const std::string& name, const T* data, size_t rows, size_t cols) {
  hsize_t dims[2] = {hsize_t(rows), hsize_t(cols)};
  Handle space(H5Screate_simple(cols == 1 ? 1 : 2, dims, nullptr), H5Sclose);
  Handle dcpl = untimedObjects(H5P_DATASET_CREATE);
  const hid_t id = H5Dcreate2(parent, name.c_str(), nativeType<T>(), space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (id < 0) throw WriteError(fileName(parent), lastError());
  Handle set(id, H5Dclose);
  if (rows && H5Dwrite(set, nativeType<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw WriteError(fileName(parent), lastError());
}

template <class T>
uint64_t createDatasetForRawWrites(hid_t parent, const std::string& name, size_t rows, size_t cols) {
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "raw rows are written in the host's byte order");
  hsize_t dims[2] = {hsize_t(rows), hsize_t(cols)};
  Handle space(H5Screate_simple(cols == 1 ? 1 : 2, dims, nullptr), H5Sclose);
  Handle dcpl = untimedObjects(H5P_DATASET_CREATE);
  H5Pset_layout(dcpl, H5D_CONTIGUOUS);
  H5Pset_alloc_time(dcpl, H5D_ALLOC_TIME_EARLY); // the offset exists before any write
  H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER);   // every byte is the writers'
  const hid_t id = H5Dcreate2(parent, name.c_str(), nativeType<T>(), space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (id < 0) throw WriteError(fileName(parent), lastError());
  Handle set(id, H5Dclose);
  if (!rows || !cols) return 0;
  const haddr_t at = H5Dget_offset(set);
  if (at == HADDR_UNDEF) throw WriteError(fileName(parent), "no storage allocated for dataset " + name);
  return uint64_t(at);
}

template <class T>
std::vector<T> readDataset(hid_t file, const std::string& name, size_t& rows, size_t& cols) {
  Handle set(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
  Handle space(H5Dget_space(set), H5Sclose);
  hsize_t dims[2] = {0, 1};
  const int nd = H5Sget_simple_extent_ndims(space);
  H5Sget_simple_extent_dims(space, dims, nullptr);
  rows = dims[0];
  cols = nd == 2 ? dims[1] : 1;
  std::vector<T> out(rows * cols);
  if (!out.empty() && H5Dread(set, nativeType<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    throw std::runtime_error("cannot read HDF5 dataset " + name);
  return out;
}

#define TALUS_H5_INSTANTIATE(T)                                                                     \
  template void writeDataset<T>(hid_t, const std::string&, const T*, size_t, size_t);             \
  template std::vector<T> readDataset<T>(hid_t, const std::string&, size_t&, size_t&);             \
  template uint64_t createDatasetForRawWrites<T>(hid_t, const std::string&, size_t, size_t);
TALUS_H5_INSTANTIATE(double)
TALUS_H5_INSTANTIATE(float)
TALUS_H5_INSTANTIATE(int32_t)
TALUS_H5_INSTANTIATE(uint32_t)
TALUS_H5_INSTANTIATE(uint64_t)
TALUS_H5_INSTANTIATE(uint8_t)
#undef TALUS_H5_INSTANTIATE

bool exists(hid_t file, const std::string& path) { return H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0; }

void writeAttribute(hid_t obj, const std::string& name, double value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  const hid_t id = H5Acreate2(obj, name.c_str(), H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) throw WriteError(fileName(obj), lastError());
  Handle attr(id, H5Aclose);
  if (H5Awrite(attr, H5T_NATIVE_DOUBLE, &value) < 0) throw WriteError(fileName(obj), lastError());
}

namespace {
Handle stringType() {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  return type;
}

void writeStrings(hid_t obj, const std::string& name, const std::vector<std::string>& values, bool scalar) {
  Handle type = stringType();
  hsize_t n = values.size();
  Handle space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &n, nullptr), H5Sclose);
  const hid_t id = H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) throw WriteError(fileName(obj), lastError());
  Handle attr(id, H5Aclose);
  std::vector<const char*> ptrs;
  for (const auto& v : values) ptrs.push_back(v.c_str());
  if (H5Awrite(attr, type, ptrs.data()) < 0) throw WriteError(fileName(obj), lastError());
}
} // namespace

void writeAttribute(hid_t obj, const std::string& name, const std::string& value) {
  writeStrings(obj, name, {value}, true);
}

void writeAttribute(hid_t obj, const std::string& name, const std::vector<std::string>& values) {
  writeStrings(obj, name, values, false);
}

double readDoubleAttribute(hid_t obj, const std::string& name) {
  Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose);
  double v = 0;
  H5Aread(attr, H5T_NATIVE_DOUBLE, &v);
  return v;
}

std::vector<std::string> readStringsAttribute(hid_t obj, const std::string& name) {
  Handle attr(H5Aopen(obj, name.c_str(), H5P_DEFAULT), H5Aclose);
  Handle space(H5Aget_space(attr), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  Handle type = stringType();
  std::vector<char*> ptrs(size_t(n), nullptr);
  if (H5Aread(attr, type, ptrs.data()) < 0) throw std::runtime_error("cannot read HDF5 attribute " + name);
  std::vector<std::string> out;
  for (char* p : ptrs) out.emplace_back(p ? p : "");
  H5Dvlen_reclaim(type, space, H5P_DEFAULT, ptrs.data());
  return out;
}

} // namespace talus::h5
