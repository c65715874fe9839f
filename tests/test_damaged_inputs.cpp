// Every file a user gives Talus, damaged: truncated, corrupted, or of the wrong kind. Each is
// refused with one line naming the file and the reason (scene: also the line or key), never a
// crash or a silently wrong value. Checkpoints: test_checkpoint_file.cpp.
#include "io/terrain/polygon_set.h"
#include "io/terrain/vdb_level_set.h"
#include "process_support.h"
#include "terrain_test_support.h"

#include <cstring>
#include <gtest/gtest.h>
#include <unistd.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

using namespace talus;

namespace {

const std::string& dir() {
  // Per process: ctest runs this file's tests in parallel processes.
  static const std::string d = test::tempDir("damaged_inputs_" + std::to_string(::getpid()));
  return d;
}

std::string write(const std::string& name, const std::string& bytes) {
  std::ofstream(dir() + "/" + name, std::ios::binary) << bytes;
  return dir() + "/" + name;
}

/// `f` throws E with a one-line message naming `file` and containing `why`.
template <class E, class F> void expectRefused(F&& f, const std::string& file, const std::string& why) {
  try {
    f();
    FAIL() << file << " was accepted (expected: " << why << ")";
  } catch (const E& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(file), std::string::npos) << m;
    EXPECT_NE(m.find(why), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line: " << m;
  }
}

std::string goodDem() {
  static const std::string p = [] {
    const std::string path = dir() + "/good.tif";
    writeDemGeoTiff(test::makeDem(40, 30, 5, 2600000, 1200000, [](double x, double y) { return 900 + 0.01 * (x + y - 3800000); }), path);
    return path;
  }();
  return p;
}

std::string goodLevelSet() {
  static const std::string p = [] {
    openvdb::initialize();
    auto g = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(2.f, openvdb::Vec3f(0.f), 0.25f);
    g->setName("sphere");
    openvdb::io::File f(dir() + "/sphere.vdb");
    f.write({g});
    f.close();
    return dir() + "/sphere.vdb";
  }();
  return p;
}

void expectDemRefused(const std::string& path, const std::string& why) {
  expectRefused<InputError>([&] { readDem(path); }, path, why);
}
void expectPolygonsRefused(const std::string& path, const std::string& why, const std::string& attribute = "") {
  expectRefused<InputError>([&] { PolygonSet::read(path, attribute); }, path, why);
}
void expectLevelSetRefused(const std::string& path, const std::string& why, const std::string& grid = "") {
  expectRefused<std::runtime_error>([&] { VdbLevelSet(path, grid, Vec3d::Zero()); }, "", why);
}

} // namespace

TEST(DamagedInputs, SceneFilesTruncatedBinaryEmptyOrNotFiles) {
  const std::string scene = "[simulation]\ndx = 0.1\nend_time = 1\n[domain]\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n"
                            "[[materials]]\nname = \"rock\"\npreset = \"rock\"\n";
  auto refused = [](const std::string& path, const std::string& why) {
    expectRefused<InputError>([&] { loadSceneFile(path); }, path, why);
  };
  refused(write("cut.toml", scene.substr(0, scene.find("rock\"") + 2)), "cut.toml:8"); // inside a string
  refused(write("binary.toml", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)), "binary.toml");
  refused(write("latin1.toml", "[simulation]\nname = \"Gl\xe4rnisch\"\n"), "latin1.toml:2");
  refused(write("empty.toml", ""), "empty.toml");
  std::filesystem::create_directories(dir() + "/folder.toml");
  refused(dir() + "/folder.toml", "not a regular file");
  // Through the program: exit status 2 and one line.
  const test::Exit e = test::runTalusProcess({"run", dir() + "/binary.toml", "--quiet"}, dir() + "/scene.log");
  EXPECT_EQ(e.code, 2);
  EXPECT_EQ(e.lines().size(), 1u) << e.log;
}

TEST(DamagedInputs, DemRastersTruncatedCorruptedOrOfTheWrongKind) {
  const std::string good = test::slurp(goodDem());
  ASSERT_NO_THROW(readDem(goodDem()));
  expectDemRefused(write("cut_header.tif", good.substr(0, 64)), "not a raster");
  expectDemRefused(write("cut_data.tif", good.substr(0, good.size() - 200)), "cut_data.tif");
  std::string flipped = good; // the DEFLATE stream of the heights, damaged
  for (size_t i = good.size() - 400; i < good.size() - 300; ++i) flipped[i] = char(~flipped[i]);
  expectDemRefused(write("corrupt.tif", flipped), "corrupt.tif");
  expectDemRefused(write("empty.tif", ""), "not a raster");
  expectDemRefused(write("text.tif", "this is not a raster\n"), "not a raster");
  test::writePolygons(dir() + "/area.geojson", {{test::rectangleRing(0, 0, 1, 1), 1}}, "", "GeoJSON");
  expectDemRefused(dir() + "/area.geojson", "not a raster");
  // A damaged header claiming a huge raster is refused before it is allocated.
  expectDemRefused(write("huge.asc", "ncols 200000\nnrows 200000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n"),
                   "more than the limit");
  expectDemRefused(write("infinite.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1e400\n1 2\n3 4\n"),
                   "infinite.asc");
  expectDemRefused(write("nan.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 nan\n3 4\n"),
                   "line 6: 'nan' is not a number"); // GDAL alone reads it as 0
  expectDemRefused(write("typo.asc", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4,5\n"),
                   "line 7: '4,5' is not a number");
}

TEST(DamagedInputs, PolygonFilesTruncatedCorruptedOrOfTheWrongKind) {
  const std::string poly = R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"thickness":2,)"
                           R"("name":"slab"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[10,0],[10,5],[0,0]]]}}]})";
  ASSERT_NO_THROW(PolygonSet::read(write("good.geojson", poly), "thickness"));
  expectPolygonsRefused(write("cut.geojson", poly.substr(0, poly.size() / 2)), "not a vector file");
  expectPolygonsRefused(write("empty.geojson", ""), "not a vector file");
  expectPolygonsRefused(write("points.geojson", R"({"type":"FeatureCollection","features":[{"type":"Feature",)"
                                                R"("properties":{},"geometry":{"type":"Point","coordinates":[1,2]}}]})"),
                        "no polygon features");
  std::string inf = poly;
  inf.replace(inf.find("[10,5]"), 6, "[1e400,5]");
  expectPolygonsRefused(write("infinite.geojson", inf), "not a finite coordinate");
  expectPolygonsRefused(dir() + "/good.geojson", "'name' is a String field, not a number", "name");
  expectPolygonsRefused(goodDem(), "not a vector file");
  // A shapefile missing its index, and one whose geometry file is cut short.
  test::writePolygons(dir() + "/area.shp", {{test::rectangleRing(0, 0, 10, 10), 1}}, "EPSG:2056");
  const std::string shp = test::slurp(dir() + "/area.shp");
  std::filesystem::remove(dir() + "/area.shx");
  expectPolygonsRefused(dir() + "/area.shp", "area.shp");
  test::writePolygons(dir() + "/cut.shp", {{test::rectangleRing(0, 0, 10, 10), 1}}, "EPSG:2056");
  write("cut.shp", shp.substr(0, shp.size() - 40));
  expectPolygonsRefused(dir() + "/cut.shp", "cut.shp");
}

TEST(DamagedInputs, LevelSetsTruncatedCorruptedOrNotLevelSets) {
  const std::string good = test::slurp(goodLevelSet());
  ASSERT_NO_THROW(VdbLevelSet(goodLevelSet(), "", Vec3d::Zero()));
  expectLevelSetRefused(write("cut_header.vdb", good.substr(0, 20)), "truncated");
  expectLevelSetRefused(write("cut.vdb", good.substr(0, good.size() / 2)), "truncated or damaged: grid 'sphere'");
  expectLevelSetRefused(write("cut_end.vdb", good.substr(0, good.size() - 1)), "truncated");
  std::string length = good; // the first metadata name's length, damaged: 4 GB of name
  length.replace(good.find("class") - 4, 4, "\xff\xff\xff\xff");
  expectLevelSetRefused(write("length.vdb", length), "truncated or damaged");
  expectLevelSetRefused(write("empty.vdb", ""), "not a .vdb file");
  expectLevelSetRefused(write("text.vdb", "not a level set\n"), "not a .vdb file");
  expectLevelSetRefused(goodDem(), "not a .vdb file");
  expectLevelSetRefused(goodLevelSet(), "no grid named 'terrain'", "terrain");
  auto save = [&](const std::string& name, openvdb::GridBase::Ptr g) {
    openvdb::io::File f(dir() + "/" + name);
    f.write({g});
    f.close();
    return dir() + "/" + name;
  };
  auto velocity = openvdb::Vec3fGrid::create();
  velocity->tree().setValue(openvdb::Coord(0, 0, 0), openvdb::Vec3f(1.f));
  expectLevelSetRefused(save("vectors.vdb", velocity), "no float grid found");
  auto fog = openvdb::FloatGrid::create(0.f);
  fog->setGridClass(openvdb::GRID_FOG_VOLUME);
  fog->tree().setValue(openvdb::Coord(0, 0, 0), 1.f);
  expectLevelSetRefused(save("fog.vdb", fog), "is a fog volume");
  expectLevelSetRefused(save("empty_grid.vdb", openvdb::FloatGrid::create(1.f)), "holds no active voxels");
  auto outside = openvdb::FloatGrid::create(1.f);
  outside->tree().setValue(openvdb::Coord(0, 0, 0), 0.5f);
  expectLevelSetRefused(save("outside.vdb", outside), "nothing is inside it");
  auto notFinite = openvdb::FloatGrid::create(1.f);
  notFinite->tree().setValue(openvdb::Coord(0, 0, 0), std::numeric_limits<float>::quiet_NaN());
  expectLevelSetRefused(save("nan.vdb", notFinite), "not finite");
  // A blosc chunk's stated length, damaged (found by the level-set fuzzer): OpenVDB 10 read a
  // stored chunk of any length into its buffer and allocated any compressed length.
  auto blosc = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(2.f, openvdb::Vec3f(0.f), 0.25f);
  openvdb::io::File bf(dir() + "/blosc.vdb");
  bf.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
  bf.write({blosc});
  bf.close();
  const std::string packed = test::slurp(dir() + "/blosc.vdb");
  ASSERT_NO_THROW(VdbLevelSet(dir() + "/blosc.vdb", "", Vec3d::Zero()));
  size_t at = 0; // the first chunk: its int64 length, then a blosc header (version 2) repeating it
  for (; at + 24 < packed.size(); ++at) {
    int64_t n;
    uint32_t cbytes;
    std::memcpy(&n, packed.data() + at, 8);
    std::memcpy(&cbytes, packed.data() + at + 20, 4);
    if (n > 16 && n < 1 << 20 && packed[at + 8] == 2 && cbytes == uint64_t(n)) break;
  }
  ASSERT_LT(at + 24, packed.size()) << "no blosc chunk found";
  for (const int64_t stated : {int64_t(-100000), int64_t(0x3f0946503f094650)}) {
    std::string bad = packed;
    std::memcpy(bad.data() + at, &stated, 8);
    expectLevelSetRefused(write("blosc_length.vdb", bad), stated < 0 ? "states another length" : "compressed bytes");
  }
  // Through the scene reader: the key and the file on one line.
  const std::string scene = "[simulation]\ndx = 0.1\nend_time = 1\n[domain]\nmin = [-3, -3, -3]\nmax = [3, 3, 3]\n"
                            "[terrain]\nsdf = \"" + dir() + "/cut.vdb\"\nboundary = \"slip\"\n"
                            "[[materials]]\nname = \"rock\"\npreset = \"rock\"\n"
                            "[[bodies]]\nmaterial = \"rock\"\nshape = \"sphere\"\ncenter = [0, 0, 2.5]\nradius = 0.3\n";
  expectRefused<InputError>([&] { loadSceneString(scene, "s.toml"); }, "s.toml:8: terrain.sdf: " + dir() + "/cut.vdb", "");
}
