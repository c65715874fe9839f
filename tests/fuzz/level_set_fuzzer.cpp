// libFuzzer target for .vdb level sets (terrain `sdf`, level-set structures): any bytes as a
// .vdb file, read, then sampled as the engine samples it. The reader throws std::runtime_error,
// which the scene reader reports as an InputError naming the key and the file.
#include "engine/sdf.h"
#include "fuzz_support.h"
#include "io/terrain/vdb_level_set.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  talus::fuzz::smallLimits();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = talus::fuzz::writeInput("level_set.vdb", data, size);
  try {
    const talus::VdbLevelSet ls(path, "", talus::Vec3d::Zero());
    talus::Vec3d lo, hi;
    ls.bounds(lo, hi);
    ls.distance(0.5 * (lo + hi));
    talus::SdfBlock block;
    ls.sampleBlock(talus::BlockCoord{0, 0, 0}, ls.voxelSize(), block);
  } catch (const std::runtime_error&) {
  } catch (const std::exception& e) {
    talus::fuzz::fail("level-set fuzzer", e.what());
  }
  return 0;
}
