#include "io/run/checkpoint.h"

#include "io/common/atomic_file.h"
#include "io/common/h5_file.h"

#include <filesystem>
#include <stdexcept>

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

} // namespace

std::string checkpointPath(const std::string& dir) { return (std::filesystem::path(dir) / "checkpoint.h5").string(); }

void writeCheckpoint(const std::string& path, const Simulation& sim, const std::function<void(StateArchive&)>& extra) {
  writeAtomically(path, [&](const std::string& tmp) {
    h5::Handle f = h5::createFile(tmp);
    {
      H5Archive a(f, true);
      sim.save(a);
      if (extra) extra(a);
    }
    h5::writeAttribute(f, "time", sim.time());
    h5::closeFile(f);
  });
}

void readCheckpoint(const std::string& path, Simulation& sim, const std::function<void(const StateArchive&)>& extra) {
  if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no checkpoint to resume from");
  try {
    h5::Handle f = h5::openFile(path);
    H5Archive a(f, false);
    sim.load(a);
    if (extra) extra(a);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

} // namespace talus
