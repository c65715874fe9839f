// libFuzzer target for the checkpoint reader. The first input byte picks a mode, the rest is the
// file. Mode 0: the file as it is, so header parsing, length and checksum checks are exercised
// (nearly every mutation is caught by the checksum before HDF5 sees the file). Mode 1: the
// fuzzer seals the file first (a fresh header with the body's true length and CRC), as if Talus
// had written the mutated body itself, so HDF5 and the state loading behind the checksum are
// exercised too. Expected: a restored simulation or talus::InputError.
#include "checkpoint_scene.h"
#include "fuzz_support.h"
#include "io/common/input_error.h"
#include "io/run/checkpoint.h"
#include "io/scene/scene.h"

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
