#include "io/output/vdb_frame_writer.h"
#include "io/common/names.h"

#include "io/common/atomic_file.h"
#include "io/common/input_error.h"
#include "io/output/h5_frame_writer.h"
#include "io/output/node_scatter.h"

#include <cctype>
#include <filesystem>
#include <mutex>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointConversion.h>
#include <openvdb/tools/PointIndexGrid.h>

namespace talus {

namespace {

void initOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

/// dx voxels whose index (i, j, k) sits at world origin + (i, j, k) dx. The offset lives in the
/// transform (double): float voxel data never sees national grid coordinates.
openvdb::math::Transform::Ptr worldTransform(const Simulation& sim) {
  auto xf = openvdb::math::Transform::createLinearTransform(sim.settings().dx);
  const Vec3d o = sim.settings().origin;
  xf->postTranslate(openvdb::Vec3d(o.x(), o.y(), o.z()));
  return xf;
}

openvdb::MetaMap fileMetadata(const Simulation& sim, const std::string& crsWkt) {
  openvdb::MetaMap meta;
  meta.insertMeta("time", openvdb::DoubleMetadata(sim.time()));
  meta.insertMeta("time_units", openvdb::StringMetadata("s"));
  meta.insertMeta("length_units", openvdb::StringMetadata("m"));
  meta.insertMeta("creator", openvdb::StringMetadata("Talus"));
  const Vec3d o = sim.settings().origin;
  meta.insertMeta("local_origin", openvdb::Vec3DMetadata(openvdb::Vec3d(o.x(), o.y(), o.z())));
  if (!crsWkt.empty()) meta.insertMeta("crs_wkt", openvdb::StringMetadata(crsWkt));
  return meta;
}

void describe(openvdb::GridBase& g, const std::string& name, const std::string& units, double time) {
  g.setName(name);
  g.insertMeta("units", openvdb::StringMetadata(units));
  g.insertMeta("time", openvdb::DoubleMetadata(time));
}

void writeFile(const std::string& path, const openvdb::GridPtrVec& grids, const openvdb::MetaMap& meta) {
  writeAtomically(path, [&](const std::string& tmp) {
    writeThroughMemory(tmp, [&](const std::string& scratch) {
      openvdb::io::File file(scratch);
      file.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
      file.write(grids, meta);
      file.close();
    });
  });
}

/// The volume frame of node fields `f` scattered from `sim`'s particles (or every process's).
void writeVolumeVdb(const std::string& path, const NodeFields& f, const Simulation& sim, const std::string& crsWkt) {
  initOpenVdb();
  const double dx3 = f.dx * f.dx * f.dx;
  const auto xf = worldTransform(sim);
  const int nm = f.materials;

  auto density = openvdb::FloatGrid::create(0.f);
  auto velocity = openvdb::Vec3fGrid::create(openvdb::Vec3f(0.f));
  std::vector<openvdb::FloatGrid::Ptr> fraction;
  std::vector<float> fractionScale; // fraction = mass / (rho0 dx^3)
  for (int m = 0; m < nm; ++m) {
    fraction.push_back(openvdb::FloatGrid::create(0.f));
    fractionScale.push_back(float(1.0 / (sim.groups()[size_t(m)]->density() * dx3)));
  }

  // Each 8^3 block of nodes is one OpenVDB leaf at the same origin: fill leaves directly.
  using FloatLeaf = openvdb::FloatTree::LeafNodeType;
  using VecLeaf = openvdb::Vec3fTree::LeafNodeType;
  std::vector<float> total(kBlockNodes);
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    const BlockCoord& c = f.blocks[b];
    const openvdb::Coord origin(c.x * kBlockDim, c.y * kBlockDim, c.z * kBlockDim);
    std::fill(total.begin(), total.end(), 0.f);
    for (int m = 0; m < nm; ++m) {
      const float* mass = f.blockMass(b, m);
      auto* leaf = new FloatLeaf(origin, 0.f, false);
      bool any = false;
      for (int n = 0; n < kBlockNodes; ++n) {
        total[size_t(n)] += mass[n];
        if (mass[n] > 0) leaf->setValueOn(openvdb::Index(n), mass[n] * fractionScale[size_t(m)]), any = true;
      }
      if (any) fraction[size_t(m)]->tree().addLeaf(leaf);
      else delete leaf;
    }
    auto* dLeaf = new FloatLeaf(origin, 0.f, false);
    auto* vLeaf = new VecLeaf(origin, openvdb::Vec3f(0.f), false);
    const float* q = f.blockMomentum(b);
    bool any = false;
    for (int n = 0; n < kBlockNodes; ++n) {
      const float m = total[size_t(n)];
      if (!(m > 0)) continue;
      any = true;
      dLeaf->setValueOn(openvdb::Index(n), float(m / dx3));
      vLeaf->setValueOn(openvdb::Index(n), openvdb::Vec3f(q[3 * n] / m, q[3 * n + 1] / m, q[3 * n + 2] / m));
    }
    if (any) {
      density->tree().addLeaf(dLeaf);
      velocity->tree().addLeaf(vLeaf);
    } else {
      delete dLeaf;
      delete vLeaf;
    }
  }

  openvdb::GridPtrVec grids;
  density->setTransform(xf);
  density->setGridClass(openvdb::GRID_FOG_VOLUME);
  describe(*density, "density", "kg/m3", sim.time());
  grids.push_back(density);
  for (int m = 0; m < nm; ++m) {
    auto& g = fraction[size_t(m)];
    g->setTransform(xf->copy());
    g->setGridClass(openvdb::GRID_FOG_VOLUME);
    describe(*g, "fraction_" + safeName(sim.groups()[size_t(m)]->name()), "1", sim.time());
    g->insertMeta("material", openvdb::StringMetadata(sim.groups()[size_t(m)]->name()));
    g->insertMeta("reference_density", openvdb::DoubleMetadata(sim.groups()[size_t(m)]->density()));
    grids.push_back(g);
  }
  velocity->setTransform(xf->copy());
  velocity->setVectorType(openvdb::VEC_CONTRAVARIANT_RELATIVE);
  describe(*velocity, "velocity", "m/s", sim.time());
  grids.push_back(velocity);
  writeFile(path, grids, fileMetadata(sim, crsWkt));
}

} // namespace

void writeVolumeVdb(const std::string& path, const Simulation& sim, const std::string& crsWkt) {
  writeVolumeVdb(path, scatterNodeFields(sim), sim, crsWkt);
}

VolumeFrameInfo readVolumeFrameInfo(const std::string& path) {
  initOpenVdb();
  VolumeFrameInfo info;
  try {
    openvdb::io::File file(path);
    file.open(false);
    const openvdb::MetaMap::Ptr meta = file.getMetadata();
    const auto origin = meta->getMetadata<openvdb::Vec3DMetadata>("local_origin");
    if (!origin || !file.hasGrid("density")) throw InputError(path, "not a Talus volume frame (no local_origin or density grid)");
    info.localOrigin = Vec3d(origin->value().x(), origin->value().y(), origin->value().z());
    if (const auto t = meta->getMetadata<openvdb::DoubleMetadata>("time")) info.time = t->value();
    const openvdb::GridPtrVecPtr described = file.readAllGridMetadata(); // kept: the loop reads into it
    for (const openvdb::GridBase::Ptr& g : *described) {
      const std::string name = g->getName();
      if (name.rfind("fraction_", 0) != 0) continue;
      const auto rho = g->getMetadata<openvdb::DoubleMetadata>("reference_density");
      info.materials.push_back({name.substr(9), rho ? rho->value() : 1000.0});
    }
    const openvdb::GridBase::Ptr density = file.readGrid("density");
    file.close();
    const openvdb::CoordBBox box = density->evalActiveVoxelBoundingBox();
    if (!box.empty()) {
      const openvdb::Vec3d a = density->indexToWorld(box.min()), b = density->indexToWorld(box.max());
      info.empty = false;
      info.lo = Vec3d(std::min(a.x(), b.x()), std::min(a.y(), b.y()), std::min(a.z(), b.z()));
      info.hi = Vec3d(std::max(a.x(), b.x()), std::max(a.y(), b.y()), std::max(a.z(), b.z()));
    }
  } catch (const openvdb::Exception& e) {
    throw InputError(path, std::string("cannot read this volume frame: ") + e.what());
  }
  return info;
}

void writePointsVdb(const std::string& path, const Simulation& sim, const std::string& crsWkt) {
  initOpenVdb();
  namespace pts = openvdb::points;
  const size_t n = sim.particleCount();
  std::vector<openvdb::Vec3d> pos;
  std::vector<openvdb::Vec3f> vel;
  std::vector<float> mass;
  std::vector<int32_t> mat;
  pos.reserve(n), vel.reserve(n), mass.reserve(n), mat.reserve(n);
  const Vec3d o = sim.settings().origin;
  for (const MaterialGroup* g : sim.groups()) {
    const auto& P = g->particles;
    for (size_t i = 0; i < P.size(); ++i) {
      pos.emplace_back(double(P.x[i][0]) + o.x(), double(P.x[i][1]) + o.y(), double(P.x[i][2]) + o.z());
      vel.emplace_back(float(P.v[i][0]), float(P.v[i][1]), float(P.v[i][2]));
      mass.push_back(float(P.mass[i]));
      mat.push_back(g->index());
    }
  }
  const auto xf = worldTransform(sim);
  // Positions are stored per voxel relative to its centre, so world coordinates keep full precision.
  pts::PointAttributeVector<openvdb::Vec3d> wrapper(pos);
  auto index = openvdb::tools::createPointIndexGrid<openvdb::tools::PointIndexGrid>(wrapper, *xf);
  auto grid = pts::createPointDataGrid<pts::NullCodec, pts::PointDataGrid>(*index, wrapper, *xf);
  pts::appendAttribute<openvdb::Vec3f>(grid->tree(), "v");
  pts::populateAttribute(grid->tree(), index->tree(), "v", pts::PointAttributeVector<openvdb::Vec3f>(vel));
  pts::appendAttribute<float>(grid->tree(), "mass");
  pts::populateAttribute(grid->tree(), index->tree(), "mass", pts::PointAttributeVector<float>(mass));
  pts::appendAttribute<int32_t>(grid->tree(), "material");
  pts::populateAttribute(grid->tree(), index->tree(), "material", pts::PointAttributeVector<int32_t>(mat));
  describe(*grid, "points", "m", sim.time());
  std::string names;
  for (const MaterialGroup* g : sim.groups()) names += (names.empty() ? "" : ",") + g->name();
  grid->insertMeta("material_names", openvdb::StringMetadata(names));
  writeFile(path, {grid}, fileMetadata(sim, crsWkt));
}

VdbVolumeWriter::VdbVolumeWriter(std::string outDir, std::string crsWkt)
    : outDir_(std::move(outDir)), crsWkt_(std::move(crsWkt)) {
  std::filesystem::create_directories(std::filesystem::path(outDir_) / "frames");
}

void VdbVolumeWriter::onFrame(const Simulation& sim, int index) {
  SerialCommunicator one;
  if (auto failure = onFrameParts(one, sim, index)) throw *failure;
}

std::optional<WriteError> VdbVolumeWriter::onFrameParts(Communicator& comm, const Simulation& local, int index) {
  // Every process scatters its own particles; rank 0 adds their blocks (exact integer sums) and
  // writes the file. No process holds every particle.
  NodeSums sums = scatterNodeSums(comm, local);
  gatherNodeSums(comm, sums);
  if (comm.rank() != 0) return std::nullopt;
  const std::string rel = frameFileName("volume", index, "vdb");
  try {
    writeVolumeVdb((std::filesystem::path(outDir_) / rel).string(), nodeFields(sums), local, crsWkt_);
  } catch (const WriteError& e) {
    return e;
  }
  recordFile(rel);
  return std::nullopt;
}

VdbPointsWriter::VdbPointsWriter(std::string outDir, std::string crsWkt)
    : outDir_(std::move(outDir)), crsWkt_(std::move(crsWkt)) {
  std::filesystem::create_directories(std::filesystem::path(outDir_) / "frames");
}

void VdbPointsWriter::onFrame(const Simulation& sim, int index) {
  const std::string rel = frameFileName("points", index, "vdb");
  writePointsVdb((std::filesystem::path(outDir_) / rel).string(), sim, crsWkt_);
  recordFile(rel);
}

} // namespace talus
