// Frame files read back with their own readers: VDB volumes and points through OpenVDB, PLY
// through its header and binary layout. Values are checked against sums computed here from the
// particles with the quadratic B-spline, not against the writer's own scatter.
#include "io/output/ply_writer.h"
#include "io/run/run_driver.h"
#include "io/output/vdb_frame_writer.h"
#include "test_support.h"

#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>

using namespace talus;

namespace {
// Two adjacent boxes of different materials at national grid coordinates, in uniform motion.
const char* kScene = R"([simulation]
dx = 0.1
particles_per_cell = 8
end_time = 1
gravity = [0, 0, 0]
[domain]
min = [2600000.0, 1200000.0, 1500.0]
max = [2600003.0, 1200002.0, 1502.0]
[[materials]]
name = "rock"
model = "elastic"
density = 2500
youngs_modulus = 1e7
[[materials]]
name = "ice"
model = "elastic"
density = 900
youngs_modulus = 1e7
[[bodies]]
material = "rock"
shape = "box"
min = [2600000.5, 1200000.5, 1500.5]
max = [2600001.5, 1200001.5, 1501.0]
velocity = [1.5, -0.5, 0.25]
[[bodies]]
material = "ice"
shape = "box"
min = [2600001.5, 1200000.5, 1500.5]
max = [2600002.5, 1200001.5, 1501.0]
velocity = [1.5, -0.5, 0.25]
)";
const Vec3d kVelocity(1.5, -0.5, 0.25);

double bspline(double r) {
  r = std::abs(r);
  return r < 0.5 ? 0.75 - r * r : r < 1.5 ? 0.5 * (1.5 - r) * (1.5 - r) : 0.0;
}

/// Sum over the particles of group g (all when g < 0) of m_p N((x_p - X) / dx), X a local node.
double nodeMass(const Simulation& sim, const Vec3d& X, int g) {
  const double dx = sim.settings().dx;
  double m = 0;
  for (size_t k = 0; k < sim.groups().size(); ++k) {
    if (g >= 0 && int(k) != g) continue;
    const auto& P = sim.groups()[k]->particles;
    for (size_t p = 0; p < P.size(); ++p) {
      const Vec3d r = (P.x[p].cast<double>() - X) / dx;
      if (r.cwiseAbs().maxCoeff() >= 1.5) continue;
      m += double(P.mass[p]) * bspline(r.x()) * bspline(r.y()) * bspline(r.z());
    }
  }
  return m;
}

std::unique_ptr<Simulation> movedSimulation() {
  auto sim = test::makeSimulation(kScene);
  for (int i = 0; i < 3; ++i) sim->step(); // time > 0, still a uniform translation
  return sim;
}
} // namespace

TEST(OutputVdb, VolumeRoundTripsThroughOpenVdbWithDensityFractionsVelocityAndWorldPlacement) {
  const auto sim = movedSimulation();
  const std::string path = test::tempDir("vdb_volume") + "/volume.vdb";
  writeVolumeVdb(path, *sim, "test-crs");

  openvdb::initialize();
  openvdb::io::File file(path);
  file.open();
  EXPECT_TRUE(file.compression() & openvdb::io::COMPRESS_BLOSC);
  const auto meta = file.getMetadata();
  EXPECT_DOUBLE_EQ(meta->metaValue<double>("time"), sim->time());
  EXPECT_EQ(meta->metaValue<std::string>("crs_wkt"), "test-crs");
  auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
  auto rock = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("fraction_rock"));
  auto ice = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("fraction_ice"));
  auto velocity = openvdb::gridPtrCast<openvdb::Vec3fGrid>(file.readGrid("velocity"));
  file.close();
  ASSERT_TRUE(density && rock && ice && velocity);
  EXPECT_EQ(density->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(density->metaValue<std::string>("units"), "kg/m3");
  EXPECT_EQ(velocity->metaValue<std::string>("units"), "m/s");
  EXPECT_DOUBLE_EQ(density->metaValue<double>("time"), sim->time());

  // Voxel (i, j, k) sits at origin + (i, j, k) dx in world coordinates: to 1e-6 m at x ~ 2.6e6.
  const double dx = sim->settings().dx;
  const Vec3d origin = sim->settings().origin;
  for (const openvdb::Coord c : {openvdb::Coord(0, 0, 0), openvdb::Coord(7, -3, 12), openvdb::Coord(25, 15, 9)}) {
    const openvdb::Vec3d w = density->transform().indexToWorld(c);
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(w[d], origin[d] + c[d] * dx, 1e-6);
  }

  // Every active voxel against the B-spline sums over the particles. Tolerance: float storage
  // and summation of up to 27 x 8 contributions per node, 1e-5 of the largest density.
  const double dx3 = dx * dx * dx, rhoRock = 2500, rhoIce = 900;
  double massSum = 0, rockVolume = 0, iceVolume = 0;
  size_t active = 0;
  auto racc = rock->getConstAccessor();
  auto iacc = ice->getConstAccessor();
  auto vacc = velocity->getConstAccessor();
  for (auto it = density->cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    const Vec3d X = Vec3d(c.x(), c.y(), c.z()) * dx;
    ASSERT_NEAR(*it, nodeMass(*sim, X, -1) / dx3, 1e-5 * rhoRock) << c;
    ASSERT_NEAR(racc.getValue(c), nodeMass(*sim, X, 0) / (rhoRock * dx3), 1e-5) << c;
    ASSERT_NEAR(iacc.getValue(c), nodeMass(*sim, X, 1) / (rhoIce * dx3), 1e-5) << c;
    const openvdb::Vec3f v = vacc.getValue(c);
    for (int d = 0; d < 3; ++d) ASSERT_NEAR(v[d], kVelocity[d], 1e-5) << c;
    massSum += *it * dx3;
    rockVolume += racc.getValue(c) * dx3;
    iceVolume += iacc.getValue(c) * dx3;
    ++active;
  }
  EXPECT_GT(active, 2000u);
  // B-spline weights are a partition of unity: the grids hold every kilogram and cubic metre.
  EXPECT_NEAR(massSum, sim->totalMass(), 1e-5 * sim->totalMass());
  EXPECT_NEAR(rockVolume, 0.5, 1e-5);
  EXPECT_NEAR(iceVolume, 0.5, 1e-5);
  // Inside a body (two cells from every face) the lattice of 8 particles per cell gives exactly
  // the reference density and a fraction of one.
  const Vec3d inside = sim->groups()[0]->particles.x[0].cast<double>();
  const openvdb::Coord deep(int(std::round(inside.x() / dx)) + 3, int(std::round(inside.y() / dx)) + 3,
                            int(std::round(inside.z() / dx)) + 2);
  EXPECT_NEAR(density->tree().getValue(deep), rhoRock, 1e-5 * rhoRock);
  EXPECT_NEAR(racc.getValue(deep), 1.0, 1e-5);
  EXPECT_EQ(iacc.getValue(deep), 0.f);
}

TEST(OutputVdb, PointsRoundTripWithPositionsVelocityMassAndMaterial) {
  const auto sim = movedSimulation();
  const std::string path = test::tempDir("vdb_points") + "/points.vdb";
  writePointsVdb(path, *sim);
  openvdb::initialize();
  openvdb::io::File file(path);
  file.open();
  auto grid = openvdb::gridPtrCast<openvdb::points::PointDataGrid>(file.readGrid("points"));
  file.close();
  ASSERT_TRUE(grid);
  EXPECT_EQ(openvdb::points::pointCount(grid->tree()), sim->particleCount());

  // World positions come back to float precision of voxel-relative offsets (1e-6 m here), even
  // at national coordinates; the bounding box and mass-weighted centre must match.
  Vec3d lo = Vec3d::Constant(1e300), hi = -lo, centre = Vec3d::Zero();
  double mass = 0;
  size_t rockCount = 0;
  for (auto leaf = grid->tree().cbeginLeaf(); leaf; ++leaf) {
    openvdb::points::AttributeHandle<openvdb::Vec3f> P(leaf->constAttributeArray("P"));
    openvdb::points::AttributeHandle<openvdb::Vec3f> V(leaf->constAttributeArray("v"));
    openvdb::points::AttributeHandle<float> M(leaf->constAttributeArray("mass"));
    openvdb::points::AttributeHandle<int32_t> K(leaf->constAttributeArray("material"));
    for (auto idx = leaf->beginIndexOn(); idx; ++idx) {
      const openvdb::Vec3d w = grid->transform().indexToWorld(idx.getCoord().asVec3d() + P.get(*idx));
      const Vec3d x(w.x(), w.y(), w.z());
      lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
      centre += M.get(*idx) * x;
      mass += M.get(*idx);
      for (int d = 0; d < 3; ++d) ASSERT_NEAR(V.get(*idx)[d], kVelocity[d], 1e-5);
      rockCount += K.get(*idx) == 0;
    }
  }
  Vec3d elo = Vec3d::Constant(1e300), ehi = -elo, ecentre = Vec3d::Zero();
  for (const auto* g : sim->groups())
    for (size_t p = 0; p < g->size(); ++p) {
      const Vec3d x = g->particles.x[p].cast<double>() + sim->settings().origin;
      elo = elo.cwiseMin(x), ehi = ehi.cwiseMax(x), ecentre += double(g->particles.mass[p]) * x;
    }
  EXPECT_NEAR(mass, sim->totalMass(), 1e-5 * sim->totalMass());
  EXPECT_LT((lo - elo).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_LT((hi - ehi).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_LT((centre / mass - ecentre / sim->totalMass()).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_EQ(rockCount, sim->groups()[0]->size());
}

TEST(OutputPly, BinaryPointCloudHoldsEveryParticleInWorldCoordinates) {
  const auto sim = movedSimulation();
  const std::string path = test::tempDir("ply") + "/particles.ply";
  writeParticlesPly(path, *sim);
  std::ifstream in(path, std::ios::binary);
  std::string line, header;
  size_t vertices = 0;
  while (std::getline(in, line) && line != "end_header") {
    header += line + "\n";
    if (line.rfind("element vertex ", 0) == 0) vertices = std::stoul(line.substr(15));
  }
  EXPECT_EQ(header.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  EXPECT_NE(header.find("property double x\nproperty double y\nproperty double z\n"), std::string::npos);
  ASSERT_EQ(vertices, sim->particleCount());
  const size_t stride = 3 * 8 + 4 * 4 + 4 + 3;
  std::vector<char> body(vertices * stride);
  in.read(body.data(), std::streamsize(body.size()));
  ASSERT_EQ(size_t(in.gcount()), body.size());
  EXPECT_EQ(in.peek(), EOF);
  // The last particle of the last material, byte for byte.
  const MaterialGroup* g = sim->groups().back();
  const size_t p = g->size() - 1;
  const char* v = body.data() + (vertices - 1) * stride;
  double x[3];
  float vel[3];
  int32_t mat;
  std::memcpy(x, v, 24);
  std::memcpy(vel, v + 24, 12);
  std::memcpy(&mat, v + 40, 4);
  for (int d = 0; d < 3; ++d) {
    EXPECT_EQ(x[d], double(g->particles.x[p][d]) + sim->settings().origin[d]);
    EXPECT_EQ(vel[d], float(g->particles.v[p][d]));
  }
  EXPECT_EQ(mat, g->index());
}

TEST(OutputFrames, EveryFrameIsWrittenIncludingOneAtTheEndTime) {
  // end_time = 0.3 and frame_interval = 0.1: 3 * 0.1 is 0.30000000000000004 in floating point,
  // and frame 3 must still be written.
  const std::string dir = test::tempDir("frames_end");
  SceneSetup s = loadSceneString(kScene, "test.toml",
                                 {"simulation.end_time=0.3", "output.frame_interval=0.1", "output.ply=true",
                                  "materials.rock.youngs_modulus=1e5", "materials.ice.youngs_modulus=1e5"});
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(std::move(s), opt).ok);
  for (int f = 0; f <= 3; ++f)
    for (const char* stem : {"volume", "particles"}) {
      char name[64];
      std::snprintf(name, sizeof name, "/frames/%s_%05d.%s", stem, f, std::string(stem) == "volume" ? "vdb" : "ply");
      EXPECT_TRUE(std::filesystem::exists(dir + name)) << name;
    }
  EXPECT_FALSE(std::filesystem::exists(dir + "/frames/volume_00004.vdb"));
}
