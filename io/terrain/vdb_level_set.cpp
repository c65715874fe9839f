#include "io/terrain/vdb_level_set.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <stdexcept>

namespace talus {

struct VdbLevelSet::Impl {
  openvdb::FloatGrid::Ptr grid;
};

VdbLevelSet::VdbLevelSet(const std::string& path, const std::string& gridName, const Vec3d& origin)
    : impl_(std::make_unique<Impl>()), origin_(origin), path_(path) {
  openvdb::initialize();
  try {
    openvdb::io::File file(path);
    file.open();
    openvdb::GridBase::Ptr base;
    if (!gridName.empty()) {
      if (!file.hasGrid(gridName)) throw std::runtime_error("no grid named '" + gridName + "'");
      base = file.readGrid(gridName);
    } else {
      for (auto it = file.beginName(); it != file.endName(); ++it) {
        auto g = file.readGrid(it.gridName());
        if (openvdb::gridPtrCast<openvdb::FloatGrid>(g)) {
          base = g;
          break;
        }
      }
    }
    file.close();
    impl_->grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
    if (!impl_->grid) throw std::runtime_error("no float level-set grid found");
  } catch (const openvdb::Exception& e) {
    throw std::runtime_error(e.what());
  }
}

VdbLevelSet::~VdbLevelSet() = default;

double VdbLevelSet::voxelSize() const { return impl_->grid->voxelSize()[0]; }

bool VdbLevelSet::sampleBlock(const BlockCoord& c, double dx, SdfBlock& out) const {
  using Sampler = openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>;
  const auto acc = impl_->grid->getConstAccessor();
  Sampler sampler(acc, impl_->grid->transform());
  // Sample a lattice one node wider than the block so normals are central differences.
  constexpr int W = kBlockDim + 2;
  float phi[W][W][W];
  for (int i = 0; i < W; ++i)
    for (int j = 0; j < W; ++j)
      for (int k = 0; k < W; ++k) {
        const Vec3d local((c.x * kBlockDim + i - 1) * dx, (c.y * kBlockDim + j - 1) * dx,
                          (c.z * kBlockDim + k - 1) * dx);
        const Vec3d w = origin_ + local;
        phi[i][j][k] = sampler.wsSample(openvdb::Vec3d(w.x(), w.y(), w.z()));
      }
  bool any = false;
  for (int i = 0; i < kBlockDim; ++i)
    for (int j = 0; j < kBlockDim; ++j)
      for (int k = 0; k < kBlockDim; ++k) {
        const int n = blockNodeIndex(i, j, k);
        const float p = phi[i + 1][j + 1][k + 1];
        Vec3d g(phi[i + 2][j + 1][k + 1] - phi[i][j + 1][k + 1], phi[i + 1][j + 2][k + 1] - phi[i + 1][j][k + 1],
                phi[i + 1][j + 1][k + 2] - phi[i + 1][j + 1][k]);
        const double len = g.norm();
        g = len > 1e-12 ? Vec3d(g / len) : Vec3d::Zero();
        out.phi[n] = p;
        for (int d = 0; d < 3; ++d) out.normal[n][d] = float(g[d]);
        any |= p <= 0.f;
      }
  return any;
}

double VdbLevelSet::distance(const Vec3d& x) const {
  const Vec3d w = origin_ + x;
  return openvdb::tools::BoxSampler::sample(impl_->grid->tree(),
                                            impl_->grid->transform().worldToIndex(openvdb::Vec3d(w.x(), w.y(), w.z())));
}

void VdbLevelSet::worldBounds(Vec3d& lo, Vec3d& hi) const {
  const openvdb::CoordBBox bb = impl_->grid->evalActiveVoxelBoundingBox();
  const auto a = impl_->grid->indexToWorld(bb.min()), b = impl_->grid->indexToWorld(bb.max());
  lo = Vec3d(a.x(), a.y(), a.z());
  hi = Vec3d(b.x(), b.y(), b.z());
}

void VdbLevelSet::bounds(Vec3d& lo, Vec3d& hi) const {
  worldBounds(lo, hi);
  lo -= origin_, hi -= origin_;
}

std::string VdbLevelSet::metadata(const std::string& key) const {
  auto m = (*impl_->grid)[key];
  return m ? m->str() : std::string();
}

std::string VdbLevelSet::describe() const {
  return "level set '" + impl_->grid->getName() + "' from " + path_ + " (voxel " + std::to_string(voxelSize()) + " m)";
}

} // namespace talus
