#include "io/output/particle_writer.h"

#include "io/common/atomic_file.h"
#include "io/common/h5_file.h"

namespace talus {

void writeParticlesH5(const std::string& path, const Simulation& sim, const std::vector<std::string>& names) {
  const size_t n = sim.particleCount();
  std::vector<double> pos;
  std::vector<float> vel, mass;
  std::vector<int32_t> mat;
  pos.reserve(3 * n), vel.reserve(3 * n), mass.reserve(n), mat.reserve(n);
  const Vec3d o = sim.settings().origin;
  for (const MaterialGroup* g : sim.groups()) {
    const auto& P = g->particles;
    for (size_t i = 0; i < P.size(); ++i) {
      for (int d = 0; d < 3; ++d) {
        pos.push_back(double(P.x[i][d]) + o[d]);
        vel.push_back(float(P.v[i][d]));
      }
      mass.push_back(float(P.mass[i]));
      mat.push_back(g->index());
    }
  }
  writeAtomically(path, [&](const std::string& tmp) {
    h5::Handle f = h5::createFile(tmp);
    {
      h5::Handle grp = h5::createGroup(f, "particles");
      h5::writeDataset(grp, "position", pos.data(), n, 3);
      h5::writeDataset(grp, "velocity", vel.data(), n, 3);
      h5::writeDataset(grp, "material", mat.data(), n, 1);
      h5::writeDataset(grp, "mass", mass.data(), n, 1);
    }
    h5::writeAttribute(f, "time", sim.time());
    h5::writeAttribute(f, "material_names", names);
    h5::closeFile(f);
  });
}

} // namespace talus
