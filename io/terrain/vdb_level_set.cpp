#include "io/terrain/vdb_level_set.h"

#include "io/terrain/vdb_file_check.h"

#include <openvdb/openvdb.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/Interpolation.h>
#include <cmath>
#include <fstream>
#include <ios>
#include <limits>
#include <stdexcept>

namespace talus {

extern const bool kVdbBloscGuard; // vdb_blosc_guard.cpp: OpenVDB's blosc reader, with length checks

namespace {
/// Removes the tree's nodes of type NodeT lying wholly outside `keep` (a tile of the background,
/// outside, takes each one's place: never read, see VdbLevelSet::focus).
template <class NodeT> void dropOutside(openvdb::FloatTree& tree, const openvdb::CoordBBox& keep) {
  std::vector<NodeT*> nodes;
  tree.getNodes(nodes);
  std::vector<openvdb::Coord> outside;
  for (const NodeT* n : nodes)
    if (!keep.hasOverlap(n->getNodeBoundingBox())) outside.push_back(n->origin());
  for (const openvdb::Coord& o : outside) delete tree.template stealNode<NodeT>(o, tree.background(), false);
}

/// The float grid `gridName` (the first float grid when empty) of `path`, its layout read and
/// its values left in the file: the leaves keep the memory-mapped file open after close(), and
/// each loads its values under its own lock the first time it is read, from any thread.
/// Throws openvdb::Exception for a file OpenVDB cannot read, std::runtime_error for no such grid.
openvdb::FloatGrid::Ptr readOnDemand(const std::string& path, const std::string& gridName) {
  openvdb::io::File file(path);
  file.open(/*delayLoad=*/true);
  openvdb::FloatGrid::Ptr grid;
  if (!gridName.empty()) {
    if (!file.hasGrid(gridName)) throw std::runtime_error("no grid named '" + printable(gridName) + "'");
    grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(gridName));
  } else {
    for (auto it = file.beginName(); it != file.endName() && !grid; ++it)
      grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(*it));
  }
  file.close();
  if (!grid)
    throw std::runtime_error(gridName.empty() ? "no float grid found" : "grid '" + gridName + "' is not a float grid");
  return grid;
}
} // namespace

struct VdbLevelSet::Impl {
  openvdb::FloatGrid::Ptr grid;
  std::string name;          ///< the grid's, to read it again (focus)
  Vec3d heldLo = Vec3d::Constant(-std::numeric_limits<double>::infinity()); ///< local frame:
  Vec3d heldHi = Vec3d::Constant(std::numeric_limits<double>::infinity());  ///< what the tree holds
};

VdbLevelSet::VdbLevelSet(const std::string& path, const std::string& gridName, const Vec3d& origin,
                         VdbLoading loading)
    : impl_(std::make_unique<Impl>()), origin_(origin), path_(path), loading_(loading) {
  openvdb::initialize();
  if (!kVdbBloscGuard) throw std::logic_error("the blosc guard is not linked");
  checkVdbFile(path);
  try {
    if (loading == VdbLoading::Whole) readWhole(gridName);
    else impl_->grid = readOnDemand(path_, gridName);
  } catch (const openvdb::Exception& e) {
    throw std::runtime_error("OpenVDB cannot read it: " + printable(e.what(), 200));
  } catch (const std::ios_base::failure&) {
    throw std::runtime_error("truncated or damaged: OpenVDB read past the end of a grid");
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("damaged: a size in the file asks for more memory than there is");
  }
  check(loading == VdbLoading::Whole);
  impl_->name = impl_->grid->getName();
  const openvdb::CoordBBox bb = impl_->grid->evalActiveVoxelBoundingBox(); // the layout only
  const auto a = impl_->grid->indexToWorld(bb.min()), b = impl_->grid->indexToWorld(bb.max());
  boundsLo_ = Vec3d(a.x(), a.y(), a.z()), boundsHi_ = Vec3d(b.x(), b.y(), b.z());
}

void VdbLevelSet::focus(const BlockCoord& lo, const BlockCoord& hi, double dx) const {
  if (loading_ != VdbLoading::OnDemand) return;
  const double b = kBlockDim * dx;
  // Block c covers [c b, (c + 1) b); the queries reach one block around the active ones.
  const Vec3d needLo = Vec3d(lo.x - 1, lo.y - 1, lo.z - 1) * b, needHi = Vec3d(hi.x + 2, hi.y + 2, hi.z + 2) * b;
  const Vec3d keepLo = needLo - Vec3d::Constant(kFocusMargin * b), keepHi = needHi + Vec3d::Constant(kFocusMargin * b);
  auto area = [](const Vec3d& l, const Vec3d& h) { return (h.x() - l.x()) * (h.y() - l.y()); };
  Impl& m = *impl_;
  const bool holds = (m.heldLo.array() <= needLo.array()).all() && (m.heldHi.array() >= needHi.array()).all();
  // Also re-read when the blocks hold under a quarter of what is kept (the flow moved on, or
  // the whole file from start-up): memory follows the blocks both ways.
  if (holds && area(m.heldLo, m.heldHi) <= 4 * area(keepLo, keepHi)) return;
  // The layout again (values stay on disk), then every node wholly outside dropped. Not
  // OpenVDB's clip(): where its box cuts the solid interior's tiles it fills them into dense
  // leaves, more than it frees.
  openvdb::FloatGrid::Ptr g;
  try {
    g = readOnDemand(path_, m.name);
  } catch (const std::exception& e) {
    throw std::runtime_error(path_ + ": the level set cannot be read again (the cache removed during the run?): " +
                             printable(e.what(), 200));
  }
  const Vec3d wl = origin_ + keepLo, wh = origin_ + keepHi;
  const openvdb::CoordBBox keep(openvdb::Coord::floor(g->worldToIndex(openvdb::Vec3d(wl.x(), wl.y(), wl.z()))),
                                openvdb::Coord::ceil(g->worldToIndex(openvdb::Vec3d(wh.x(), wh.y(), wh.z()))));
  using Leaf = openvdb::FloatTree::LeafNodeType;
  using Lower = openvdb::FloatTree::RootNodeType::ChildNodeType::ChildNodeType;
  using Upper = openvdb::FloatTree::RootNodeType::ChildNodeType;
  dropOutside<Upper>(g->tree(), keep);
  dropOutside<Lower>(g->tree(), keep);
  dropOutside<Leaf>(g->tree(), keep);
  m.grid = std::move(g);
  m.heldLo = keepLo, m.heldHi = keepHi;
}

void VdbLevelSet::requireHeld(const Vec3d& lo, const Vec3d& hi) const {
  if ((impl_->heldLo.array() <= lo.array()).all() && (impl_->heldHi.array() >= hi.array()).all()) return;
  throw std::logic_error(path_ + ": asked outside the part of the level set focus() kept");
}

void VdbLevelSet::readWhole(const std::string& gridName) {
  // Read as a stream that throws at the first read past the end, so a damaged count inside a
  // tree stops at the file's end instead of looping over garbage.
  std::ifstream in(path_, std::ios::binary);
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
}

size_t VdbLevelSet::residentBytes() const {
  return size_t(impl_->grid->memUsage()); // a leaf's values count only once loaded
}

void VdbLevelSet::check(bool values) const {
  // What every signed distance below relies on: a linear, uniform transform, a positive
  // background (outside), finite values and something inside. The values only when asked:
  // reading them all would load every leaf of an on-demand level set.
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
  if (!values) return;
  for (auto it = g.cbeginValueAll(); it; ++it)
    if (!std::isfinite(*it)) throw std::runtime_error(name + " holds a value that is not finite");
  bool inside = false;
  for (auto it = g.cbeginValueOn(); it && !inside; ++it) inside = *it <= 0;
  if (!inside) throw std::runtime_error(name + " has no voxel at or below zero: nothing is inside it");
}

VdbLevelSet::~VdbLevelSet() = default;

double VdbLevelSet::voxelSize() const { return impl_->grid->voxelSize()[0]; }

bool VdbLevelSet::sampleBlock(const BlockCoord& c, double dx, SdfBlock& out) const {
  const double b = kBlockDim * dx, reach = dx + 2 * voxelSize(); // the lattice and its interpolation
  requireHeld(Vec3d(c.x, c.y, c.z) * b - Vec3d::Constant(reach), Vec3d(c.x + 1, c.y + 1, c.z + 1) * b + Vec3d::Constant(reach));
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
  bool any = false, finite = true;
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
        finite &= std::isfinite(p);
      }
  if (!finite) // only an on-demand level set gets here: a whole one had every value checked
    throw std::runtime_error(path_ + ": the level set holds a value that is not finite");
  return any;
}

double VdbLevelSet::distance(const Vec3d& x) const {
  const double reach = 2 * voxelSize();
  requireHeld(x - Vec3d::Constant(reach), x + Vec3d::Constant(reach));
  const Vec3d w = origin_ + x;
  return openvdb::tools::BoxSampler::sample(impl_->grid->tree(),
                                            impl_->grid->transform().worldToIndex(openvdb::Vec3d(w.x(), w.y(), w.z())));
}

void VdbLevelSet::worldBounds(Vec3d& lo, Vec3d& hi) const { lo = boundsLo_, hi = boundsHi_; }

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
