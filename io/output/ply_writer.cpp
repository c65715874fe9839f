#include "io/output/ply_writer.h"

#include "io/common/atomic_file.h"
#include "io/output/h5_frame_writer.h"
#include "io/output/particle_file_parts.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace talus {

std::array<unsigned char, 3> materialColour(int index) {
  // Tableau 10: distinct, colour-blind tolerant.
  static const unsigned char palette[10][3] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44}, {214, 39, 40},
                                               {148, 103, 189}, {140, 86, 75}, {227, 119, 194}, {127, 127, 127},
                                               {188, 189, 34}, {23, 190, 207}};
  const auto* c = palette[((index % 10) + 10) % 10];
  return {c[0], c[1], c[2]};
}

namespace {
template <class T> void put(char*& p, T v) {
  std::memcpy(p, &v, sizeof v); // PLY is declared little-endian; so is every host Talus builds on
  p += sizeof v;
}
} // namespace

std::optional<WriteError> writeParticlesPly(Communicator& comm, const std::string& path, const Simulation& local) {
  static_assert(sizeof(double) == 8 && sizeof(float) == 4 && sizeof(int32_t) == 4);
  constexpr uint32_t kVertexBytes = 3 * 8 + 4 * 4 + 4 + 3;
  auto layout = [&](const std::string& tmp, uint64_t n) {
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment Talus particles, world coordinates (m)\n";
    char line[160];
    std::snprintf(line, sizeof line, "comment time %.17g s\n", local.time());
    header += line;
    for (const auto* g : local.groups()) header += "comment material " + std::to_string(g->index()) + " " + g->name() + "\n";
    header += "element vertex " + std::to_string(n) + "\n";
    header += "property double x\nproperty double y\nproperty double z\n"
              "property float vx\nproperty float vy\nproperty float vz\nproperty float mass\n"
              "property int material\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
              "end_header\n";
    writeFileBytes(tmp, header);
    return std::vector<FileColumn>{{header.size(), kVertexBytes}}; // the vertices follow the header
  };
  const Vec3d o = local.settings().origin;
  auto fill = [&](size_t, const MaterialGroup& g, size_t b, size_t e, char* p) {
    const auto& P = g.particles;
    const auto rgb = materialColour(g.index());
    for (size_t i = b; i < e; ++i) {
      for (int d = 0; d < 3; ++d) put(p, double(P.x[i][d]) + o[d]);
      for (int d = 0; d < 3; ++d) put(p, float(P.v[i][d]));
      put(p, float(P.mass[i]));
      put(p, int32_t(g.index()));
      for (unsigned char c : rgb) put(p, c);
    }
  };
  return writeParticleFile(comm, path, local, layout, fill);
}

void writeParticlesPly(const std::string& path, const Simulation& sim) {
  SerialCommunicator one;
  if (auto failure = writeParticlesPly(one, path, sim)) throw *failure;
}

PlyFrameWriter::PlyFrameWriter(std::string outDir) : outDir_(std::move(outDir)) {
  std::filesystem::create_directories(std::filesystem::path(outDir_) / "frames");
}

void PlyFrameWriter::onFrame(const Simulation& sim, int index) {
  SerialCommunicator one;
  if (auto failure = onFrameParts(one, sim, index)) throw *failure;
}

std::optional<WriteError> PlyFrameWriter::onFrameParts(Communicator& comm, const Simulation& local, int index) {
  const std::string rel = frameFileName("particles", index, "ply");
  auto failure = writeParticlesPly(comm, (std::filesystem::path(outDir_) / rel).string(), local);
  if (!failure) recordFile(rel);
  return failure;
}

} // namespace talus
