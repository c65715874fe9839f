// Writes small seed files for the binary readers' fuzzers: rasters, polygons, level sets and
// checkpoints, generated here (never copied from real data). The scene seeds are hand-written.
#include "checkpoint_scene.h"
#include "io/common/geotiff_writer.h"
#include "io/run/checkpoint.h"
#include "io/scene/scene.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <sstream>

using namespace talus;
namespace fs = std::filesystem;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A seed is the mode byte the target reads first, then the file.
void seed(const fs::path& dir, const std::string& name, char mode, const std::string& bytes) {
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << mode << bytes;
}

void rasters(const fs::path& dir, const fs::path& tmp) {
  RasterGrid g;
  g.nx = 4, g.ny = 3, g.cellSize = 10, g.originX = 2600000, g.originY = 1200030;
  OGRSpatialReference srs;
  srs.importFromEPSG(2056);
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  g.crsWkt = wkt;
  CPLFree(wkt);
  std::vector<float> h(g.size());
  for (size_t i = 0; i < h.size(); ++i) h[i] = 1000.f + float(i);
  writeGeoTiff((tmp / "dem.tif").string(), g, h, GeoTiffBand{});
  seed(dir, "geotiff", 0, slurp((tmp / "dem.tif").string()));
  h[5] = -9999.f; // a no-data cell: refused, or filled with mode bit 1
  writeGeoTiff((tmp / "holed.tif").string(), g, h, GeoTiffBand{});
  seed(dir, "geotiff_nodata", 1, slurp((tmp / "holed.tif").string()));
  seed(dir, "ascii_grid", 4,
       "ncols 4\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 5\nNODATA_value -9999\n"
       "10 11 12 13\n9 10 11 12\n8 9 10 -9999\n");
}

void polygons(const fs::path& dir, const fs::path& tmp) {
  seed(dir, "geojson", 2,
       R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"thickness":1.5},)"
       R"("geometry":{"type":"Polygon","coordinates":[[[0,0],[10,0],[10,5],[0,5],[0,0]],[[2,2],[3,2],[3,3],[2,2]]]}}]})");
  seed(dir, "geojson_multi", 0,
       R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":{"type":)"
       R"("MultiPolygon","coordinates":[[[[0,0],[1,0],[0,1],[0,0]]],[[[5,5],[6,5],[6,6],[5,5]]]]}}]})");
  GDALAllRegister();
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("ESRI Shapefile")
                        ->Create((tmp / "area.shp").c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  OGRLayer* layer = ds->CreateLayer("area", nullptr, wkbPolygon, nullptr);
  OGRFieldDefn field("thickness", OFTReal);
  layer->CreateField(&field);
  OGRFeature* f = OGRFeature::CreateFeature(layer->GetLayerDefn());
  f->SetField("thickness", 2.0);
  OGRLinearRing ring;
  for (auto [x, y] : {std::pair{0., 0.}, {4., 0.}, {4., 3.}, {0., 3.}}) ring.addPoint(x, y);
  ring.closeRings();
  OGRPolygon poly;
  poly.addRing(&ring);
  f->SetGeometry(&poly);
  const bool written = layer->CreateFeature(f) == OGRERR_NONE;
  OGRFeature::DestroyFeature(f);
  if (!written) throw std::runtime_error("cannot write the shapefile seed");
  GDALClose(ds);
  const std::string shp = slurp((tmp / "area.shp").string()), shx = slurp((tmp / "area.shx").string());
  uint32_t n[2] = {uint32_t(shp.size()), uint32_t(shx.size())};
  std::string packed(reinterpret_cast<const char*>(n), 8);
  seed(dir, "shapefile", 3, packed + shp + shx + slurp((tmp / "area.dbf").string()));
}

void levelSets(const fs::path& dir, const fs::path& tmp) {
  openvdb::initialize();
  auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(5.f), 0.4f, 1.5f);
  sphere->setName("terrain");
  const std::pair<const char*, uint32_t> variants[] = {
      // Uncompressed files hold every internal node's tiles (over 100 KB): too big for a seed.
      {"sphere_mask", openvdb::io::COMPRESS_ACTIVE_MASK},
      {"sphere_zip", openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK},
      {"sphere_blosc", openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK}};
  for (auto [name, compression] : variants) {
    openvdb::io::File file((tmp / "ls.vdb").string());
    file.setCompression(compression);
    file.write({sphere});
    file.close();
    std::ofstream(dir / name, std::ios::binary) << slurp((tmp / "ls.vdb").string());
  }
}

void checkpoints(const fs::path& dir) {
  fs::create_directories(dir);
  SceneSetup s = loadSceneString(fuzz::kCheckpointScene, "fuzz.toml");
  Simulation sim(s.settings, std::move(s.groups));
  sim.step();
  const std::string path = (dir / "checkpoint_tmp.h5").string();
  writeCheckpoint(path, sim, CheckpointIdentity{s.hash});
  const std::string bytes = slurp(path);
  fs::remove(path);
  seed(dir, "as_written", 0, bytes);
  seed(dir, "sealed", 1, bytes);
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: talus_fuzz_seeds SEED_DIR\n");
    return 2;
  }
  const fs::path out = argv[1], tmp = fs::temp_directory_path() / "talus_fuzz_seeds";
  fs::create_directories(tmp);
  fs::create_directories(out / "level_set");
  rasters(out / "raster", tmp);
  polygons(out / "polygon", tmp);
  levelSets(out / "level_set", tmp);
  checkpoints(out / "checkpoint");
  fs::remove_all(tmp);
  return 0;
}
