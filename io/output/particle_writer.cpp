#include "io/output/particle_writer.h"

#include "io/common/h5_file.h"
#include "io/output/particle_file_parts.h"

#include <cstring>

namespace talus {

std::optional<WriteError> writeParticlesH5(Communicator& comm, const std::string& path, const Simulation& local,
                                           const std::vector<std::string>& names) {
  auto layout = [&](const std::string& tmp, uint64_t n) {
    std::vector<FileColumn> columns;
    h5::Handle f = h5::createFile(tmp);
    {
      h5::Handle grp = h5::createGroup(f, "particles");
      columns.push_back({h5::createDatasetForRawWrites<double>(grp, "position", n, 3), uint32_t(3 * sizeof(double))});
      columns.push_back({h5::createDatasetForRawWrites<float>(grp, "velocity", n, 3), uint32_t(3 * sizeof(float))});
      columns.push_back({h5::createDatasetForRawWrites<int32_t>(grp, "material", n, 1), uint32_t(sizeof(int32_t))});
      columns.push_back({h5::createDatasetForRawWrites<float>(grp, "mass", n, 1), uint32_t(sizeof(float))});
    }
    h5::writeAttribute(f, "time", local.time());
    h5::writeAttribute(f, "material_names", names);
    h5::closeFile(f);
    return columns;
  };
  const Vec3d o = local.settings().origin;
  auto fill = [&](size_t column, const MaterialGroup& g, size_t b, size_t e, char* out) {
    const ParticleSet& P = g.particles;
    auto put = [&out](auto v) {
      std::memcpy(out, &v, sizeof v);
      out += sizeof v;
    };
    for (size_t i = b; i < e; ++i) switch (column) {
      case 0:
        for (int d = 0; d < 3; ++d) put(double(P.x[i][d]) + o[d]);
        break;
      case 1:
        for (int d = 0; d < 3; ++d) put(float(P.v[i][d]));
        break;
      case 2:
        put(int32_t(g.index()));
        break;
      default:
        put(float(P.mass[i]));
      }
  };
  return writeParticleFile(comm, path, local, layout, fill);
}

void writeParticlesH5(const std::string& path, const Simulation& sim, const std::vector<std::string>& names) {
  SerialCommunicator one;
  if (auto failure = writeParticlesH5(one, path, sim, names)) throw *failure;
}

} // namespace talus
