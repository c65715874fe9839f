#include "io/terrain/vdb_level_set.h"

#include "io/terrain/vdb_file_check.h"

#include <openvdb/openvdb.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/Interpolation.h>
#include <cmath>
#include <fstream>
#include <ios>
#include <stdexcept>

namespace talus {

extern const bool kVdbBloscGuard; // vdb_blosc_guard.cpp: OpenVDB's blosc reader, with length checks

struct VdbLevelSet::Impl {
  openvdb::FloatGrid::Ptr grid;
};

VdbLevelSet::VdbLevelSet(const std::string& path, const std::string& gridName, const Vec3d& origin)
    : impl_(std::make_unique<Impl>()), origin_(origin), path_(path) {
  openvdb::initialize();
  if (!kVdbBloscGuard) throw std::logic_error("the blosc guard is not linked");
  checkVdbFile(path);
  try {
    // Read as a stream that throws at the first read past the end, so a damaged count inside a
    // tree stops at the file's end instead of looping over garbage.
    std::ifstream in(path, std::ios::binary);
    in.exceptions(std::ios::failbit | std::ios::badbit);
    openvdb::io::Stream stream(in, /*delayLoad=*/false);
    bool named = false;
    for (const auto& g : *stream.getGrids()) {
      if (!gridName.empty() && g->getName() != gridName) continue;
      named = true;
      impl_->grid = openvdb::gridPtrCast<openvdb::FloatGrid>(g);
      if (impl_->grid || !gridName.empty()) break;
    }
    if (!gridName.empty() && !named) throw std::runtime_error("no grid named '" + printable(gridName) + "'");
    if (!impl_->grid)
      throw std::runtime_error(gridName.empty() ? "no float grid found" : "grid '" + gridName + "' is not a float grid");
  } catch (const openvdb::Exception& e) {
    throw std::runtime_error("OpenVDB cannot read it: " + printable(e.what(), 200));
  } catch (const std::ios_base::failure&) {
    throw std::runtime_error("truncated or damaged: OpenVDB read past the end of a grid");
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("damaged: a size in the file asks for more memory than there is");
  }
  check();
}

void VdbLevelSet::check() const {
  // What every signed distance below relies on: a linear, uniform transform, a positive
  // background (outside), finite values and something inside.
  const openvdb::FloatGrid& g = *impl_->grid;
  const std::string name = "grid '" + printable(g.getName()) + "'";
  if (g.getGridClass() == openvdb::GRID_FOG_VOLUME) throw std::runtime_error(name + " is a fog volume, not a level set");
  const openvdb::math::Transform& xf = g.transform();
  const openvdb::Vec3d v = g.voxelSize();
  if (!xf.isLinear() || !xf.hasUniformScale() || !(v[0] > 0) || !std::isfinite(v[0]))
    throw std::runtime_error(name + " has no uniform voxel size (a linear transform with equal, positive scales)");
  if (!(g.background() > 0) || !std::isfinite(g.background()))
    throw std::runtime_error(name + " is not a level set: its background (the distance outside) must be positive");
  if (g.activeVoxelCount() == 0) throw std::runtime_error(name + " holds no active voxels");
  for (auto it = g.cbeginValueAll(); it; ++it)
    if (!std::isfinite(*it)) throw std::runtime_error(name + " holds a value that is not finite");
  bool inside = false;
  for (auto it = g.cbeginValueOn(); it && !inside; ++it) inside = *it <= 0;
  if (!inside) throw std::runtime_error(name + " has no voxel at or below zero: nothing is inside it");
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
