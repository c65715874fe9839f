#include "io/output/h5_frame_writer.h"

#include "io/output/particle_writer.h"

#include <cstdio>
#include <filesystem>

namespace talus {

std::string frameFileName(const std::string& stem, int index, const std::string& ext) {
  char name[96];
  std::snprintf(name, sizeof name, "frames/%s_%05d.%s", stem.c_str(), index, ext.c_str());
  return name;
}

H5FrameWriter::H5FrameWriter(std::string outDir, std::vector<std::string> materialNames)
    : outDir_(std::move(outDir)), materialNames_(std::move(materialNames)) {
  std::filesystem::create_directories(std::filesystem::path(outDir_) / "frames");
}

void H5FrameWriter::onFrame(const Simulation& sim, int index) {
  SerialCommunicator one;
  if (auto failure = onFrameParts(one, sim, index)) throw *failure;
}

std::optional<WriteError> H5FrameWriter::onFrameParts(Communicator& comm, const Simulation& local, int index) {
  const std::string rel = frameFileName("particles", index, "h5");
  auto failure = writeParticlesH5(comm, (std::filesystem::path(outDir_) / rel).string(), local, materialNames_);
  if (!failure) recordFile(rel);
  return failure;
}

} // namespace talus
