// frames/particles_NNNNN.h5: the particle state at every frame, in the particles.h5 layout.
#pragma once

#include "io/output/output_observer.h"

namespace talus {

class H5FrameWriter final : public OutputObserver {
public:
  H5FrameWriter(std::string outDir, std::vector<std::string> materialNames);
  std::string name() const override { return "h5_frames"; }
  void onFrame(const Simulation& sim, int index) override;
  bool framesInParts() const override { return true; }
  std::optional<WriteError> onFrameParts(Communicator& comm, const Simulation& local, int index) override;

private:
  std::string outDir_;
  std::vector<std::string> materialNames_;
};

/// "frames/<stem>_NNNNN.<ext>": every frame writer numbers its files the same way.
std::string frameFileName(const std::string& stem, int index, const std::string& ext);

} // namespace talus
