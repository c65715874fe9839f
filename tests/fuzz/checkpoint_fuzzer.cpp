// libFuzzer target for the checkpoint reader. The first input byte picks a mode, the rest is the
// file. Mode 0: the file as it is, so header parsing, length and checksum checks are exercised
// (nearly every mutation is caught by the checksum before HDF5 sees the file). Mode 1: the
// fuzzer seals the file first (a fresh header with the body's true length and CRC), as if Talus
// had written the mutated body itself, so HDF5 and the state loading behind the checksum are
// exercised too. Expected: a restored simulation or talus::InputError.
//
// With TALUS_FUZZ_SEALED=0 in the environment, mode-1 inputs are skipped: CI mutates only in
// front of the checksum and replays the committed sealed seeds once (tools/setup.sh). Behind the
// checksum the mutations reach HDF5 1.10's own metadata parser, whose faults on forged files
// (a copy from NULL, an endless allocation) are not Talus's and need a forged checksum to reach
// (docs/reliability.md); explore them by hand without the variable.
#include "checkpoint_scene.h"
#include "fuzz_support.h"
#include "io/common/input_error.h"
#include "io/run/checkpoint.h"
#include "io/scene/scene.h"

#include <cstdlib>
#include <memory>
#include <zlib.h>

namespace {

std::string hex32(uLong v) {
  char b[16];
  std::snprintf(b, sizeof b, "%08lx", v);
  return b;
}

std::string sealed(const std::string& file, const std::string& sceneHash) {
  const std::string body = file.size() > 512 ? file.substr(512) : std::string();
  std::string h = "TALUS CHECKPOINT\nformat " + std::to_string(talus::kCheckpointFormat) + "\ntalus " +
                  talus::talusVersion() + "\nscene " + sceneHash + "\nbytes " + std::to_string(body.size()) +
                  "\ncrc32 " + hex32(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))) + "\n";
  h += "header_crc32 " + hex32(crc32(0, reinterpret_cast<const Bytef*>(h.data()), uInt(h.size()))) + "\n";
  h.resize(512, '\0');
  return h + body;
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  talus::fuzz::smallLimits();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const bool sealedMutations = [] {
    const char* v = std::getenv("TALUS_FUZZ_SEALED");
    return !(v && std::string(v) == "0");
  }();
  if ((data[0] & 1) && !sealedMutations) return 0;
  talus::SceneSetup scene = talus::loadSceneString(talus::fuzz::kCheckpointScene, "fuzz.toml");
  std::string file(reinterpret_cast<const char*>(data + 1), size - 1);
  if (data[0] & 1) file = sealed(file, scene.hash);
  const std::string path =
      talus::fuzz::writeInput("checkpoint.h5", reinterpret_cast<const uint8_t*>(file.data()), file.size());
  talus::Simulation sim(scene.settings, std::move(scene.groups));
  try {
    talus::readCheckpoint(path, sim, talus::CheckpointIdentity{scene.hash});
    sim.step(); // a restored state must be steppable
  } catch (const talus::InputError&) {
  } catch (const talus::NumericalError&) {
    // a sealed body may hold non-finite values: the step's guard reports them
  } catch (const std::exception& e) {
    talus::fuzz::fail("checkpoint fuzzer", e.what());
  }
  return 0;
}
