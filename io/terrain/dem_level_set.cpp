#include "io/terrain/dem_level_set.h"

#include "io/common/atomic_file.h"
#include "io/common/resource_limits.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

namespace talus {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Min and max of the cell-centre heights within `w` cells of each cell (a square window):
/// the bilinear surface within w-1 cells of a point lies between them.
void windowMinMax(const DemRaster& dem, int w, std::vector<float>& lo, std::vector<float>& hi) {
  const RasterGrid& g = dem.grid;
  std::vector<float> tlo(g.size()), thi(g.size());
  tbb::parallel_for(0, g.ny, [&](int r) {
    for (int c = 0; c < g.nx; ++c) {
      float a = dem.height[g.index(c, r)], b = a;
      for (int k = std::max(0, c - w); k <= std::min(g.nx - 1, c + w); ++k) {
        const float h = dem.height[g.index(k, r)];
        a = std::min(a, h), b = std::max(b, h);
      }
      tlo[g.index(c, r)] = a, thi[g.index(c, r)] = b;
    }
  });
  lo.resize(g.size());
  hi.resize(g.size());
  tbb::parallel_for(0, g.ny, [&](int r) {
    for (int c = 0; c < g.nx; ++c) {
      float a = tlo[g.index(c, r)], b = thi[g.index(c, r)];
      for (int k = std::max(0, r - w); k <= std::min(g.ny - 1, r + w); ++k)
        a = std::min(a, tlo[g.index(c, k)]), b = std::max(b, thi[g.index(c, k)]);
      lo[g.index(c, r)] = a, hi[g.index(c, r)] = b;
    }
  });
}

/// HeightField::heightAndGradient, inlined here: it is the build's inner loop.
struct Surface {
  const float* h;
  int nx, ny;
  double west, north, cell, inv;
  explicit Surface(const HeightField& f)
      : h(f.dem().height.data()), nx(f.grid().nx), ny(f.grid().ny), west(f.grid().originX), north(f.grid().originY),
        cell(f.grid().cellSize), inv(1 / f.grid().cellSize) {}
  double eval(double x, double y, double& gx, double& gy) const {
    double u = (x - west) * inv - 0.5, v = (north - y) * inv - 0.5;
    const bool cu = u < 0 || u > nx - 1, cv = v < 0 || v > ny - 1;
    u = std::clamp(u, 0.0, double(nx - 1));
    v = std::clamp(v, 0.0, double(ny - 1));
    const int i = std::min(int(u), nx - 2), j = std::min(int(v), ny - 2);
    const double fu = u - i, fv = v - j;
    const float* p = h + size_t(j) * size_t(nx) + size_t(i);
    const double h00 = p[0], h10 = p[1], h01 = p[nx], h11 = p[nx + 1];
    gx = cu ? 0.0 : ((1 - fv) * (h10 - h00) + fv * (h11 - h01)) * inv;
    gy = cv ? 0.0 : -((1 - fu) * (h01 - h00) + fu * (h11 - h10)) * inv;
    return (1 - fv) * ((1 - fu) * h00 + fu * h10) + fv * ((1 - fu) * h01 + fu * h11);
  }
};

/// Signed distance from (x, y, z) to the bilinear surface.
///  - The two voxels of a column that bracket the surface (|z - h| < dx) hold the slope-corrected
///    vertical difference (z - h) / sqrt(1 + |grad h|^2) with the smooth (central-difference)
///    gradient: the true distance to second order, and it puts the zero crossing of every voxel
///    column exactly at the surface height. True distances cannot: across a crease of the
///    bilinear surface the distance has a kink, and interpolating it linearly between the two
///    voxels moves the zero by up to ~0.2 dx on a rough 5 m DEM.
///  - Farther voxels hold the closest-point distance: from the point straight below/above, the
///    foot point on the local tangent plane is iterated (a plane's is exact in one step). Every
///    iterate is a true surface point, so the result is the distance to the nearest surface
///    point visited: never below the true distance, and equal to it when the projection
///    converges (smooth terrain, |phi| below the curvature radius). Points whose tangent-plane
///    distance exceeds `far` are only estimated (they are outside the band anyway).
inline double surfaceDistance(const Surface& s, const HeightField& f, double x, double y, double z, double dx,
                              double far, bool closestPoint) {
  double gx, gy;
  const double h = s.eval(x, y, gx, gy);
  if (!closestPoint) return (z - h) / std::sqrt(1 + gx * gx + gy * gy);
  if (std::fabs(z - h) < dx) {
    double sx, sy;
    f.slopeGradient(x, y, sx, sy);
    return (z - h) / std::sqrt(1 + sx * sx + sy * sy);
  }
  const double plane = (z - h) / std::sqrt(1 + gx * gx + gy * gy);
  if (std::fabs(plane) > far) return plane;
  const double sign = z >= h ? 1.0 : -1.0, tol = 1e-2 * dx;
  double best2 = (z - h) * (z - h);
  double qx = x, qy = y, hq = h;
  for (int it = 0; it < 8; ++it) {
    const double sq = (z - hq - gx * (x - qx) - gy * (y - qy)) / (1 + gx * gx + gy * gy);
    const double nx = x + sq * gx, ny = y + sq * gy;
    if ((nx - qx) * (nx - qx) + (ny - qy) * (ny - qy) < tol * tol) { // converged: q is the foot
      best2 = std::min(best2, sq * sq * (1 + gx * gx + gy * gy));      // distance to its tangent plane
      break;
    }
    qx = nx, qy = ny;
    hq = s.eval(qx, qy, gx, gy);
    best2 = std::min(best2, (x - qx) * (x - qx) + (y - qy) * (y - qy) + (z - hq) * (z - hq));
  }
  return sign * std::sqrt(best2);
}

inline int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

} // namespace

LevelSetBuildStats buildDemLevelSet(const HeightField& surface, const LevelSetBuildOptions& o,
                                    const std::string& path) {
  using namespace openvdb;
  initialize();
  using LeafT = FloatTree::LeafNodeType;
  const auto t0 = Clock::now();
  LevelSetBuildStats stats;
  const double dx = o.dx;
  const RasterGrid& g = surface.grid();
  const float bg = float(o.band * dx);
  const int i0 = int(std::ceil((o.xmin - o.origin.x()) / dx - 1e-9)), i1 = int(std::floor((o.xmax - o.origin.x()) / dx + 1e-9));
  const int j0 = int(std::ceil((o.ymin - o.origin.y()) / dx - 1e-9)), j1 = int(std::floor((o.ymax - o.origin.y()) / dx + 1e-9));
  if (double(i1 - i0 + 1) * double(j1 - j0 + 1) * (2 * o.band + 3) > resourceLimits().maxVoxels)
    throw InputError("", "the terrain level set would need more than " + std::to_string(resourceLimits().maxVoxels) +
                             " voxels: use a larger dx or a smaller domain");
  if (i1 < i0 || j1 < j0) throw std::runtime_error("level set footprint is empty");
  stats.columns = size_t(i1 - i0 + 1) * size_t(j1 - j0 + 1);

  // A voxel within band dx of the surface has a surface point within band dx horizontally, so
  // its z lies within band dx of the surface's range over that neighbourhood.
  const int w = int(std::ceil(o.band * dx / g.cellSize)) + 1;
  std::vector<float> nbLo, nbHi;
  windowMinMax(surface.dem(), w, nbLo, nbHi);
  auto nearestCell = [&](double x, double y) {
    const int c = std::clamp(int(std::floor((x - g.originX) / g.cellSize)), 0, g.nx - 1);
    const int r = std::clamp(int(std::floor((g.originY - y) / g.cellSize)), 0, g.ny - 1);
    return g.index(c, r);
  };

  const Surface fast(surface);
  std::mutex mutex;
  std::vector<LeafT*> leaves;
  struct Floor {
    int L, M, k; ///< leaf column and the first voxel z index of its lowest leaf with active voxels
  };
  std::vector<Floor> floors;
  const int L0 = i0 >> 3, L1 = i1 >> 3, M0 = j0 >> 3, M1 = j1 >> 3; // leaf columns (floor division)
  tbb::parallel_for(tbb::blocked_range2d<int>(L0, L1 + 1, M0, M1 + 1), [&](const tbb::blocked_range2d<int>& r) {
    std::vector<LeafT*> local;
    std::vector<Floor> localFloors;
    int klo[64], khi[64];
    double hc[64];
    for (int L = r.rows().begin(); L != r.rows().end(); ++L)
      for (int M = r.cols().begin(); M != r.cols().end(); ++M) {
        int kmin = INT32_MAX, kmax = INT32_MIN;
        for (int a = 0; a < 8; ++a)
          for (int b = 0; b < 8; ++b) {
            const int i = L * 8 + a, j = M * 8 + b, n = a * 8 + b;
            klo[n] = 1, khi[n] = 0;
            if (i < i0 || i > i1 || j < j0 || j > j1) continue;
            const double x = o.origin.x() + i * dx, y = o.origin.y() + j * dx;
            const size_t cell = nearestCell(x, y);
            hc[n] = surface.height(x, y);
            klo[n] = int(std::floor((nbLo[cell] - o.origin.z()) / dx - o.band)) - 1;
            khi[n] = int(std::ceil((nbHi[cell] - o.origin.z()) / dx + o.band)) + 1;
            kmin = std::min(kmin, klo[n]), kmax = std::max(kmax, khi[n]);
          }
        if (kmin > kmax) continue;
        for (int K = kmin >> 3; K <= (kmax >> 3); ++K) {
          auto leaf = std::make_unique<LeafT>(Coord(L * 8, M * 8, K * 8), bg, false);
          bool any = false;
          for (int a = 0; a < 8; ++a)
            for (int b = 0; b < 8; ++b) {
              const int n = a * 8 + b;
              const int i = L * 8 + a, j = M * 8 + b;
              const double x = o.origin.x() + i * dx, y = o.origin.y() + j * dx;
              for (int c = 0; c < 8; ++c) {
                const int k = K * 8 + c;
                const double z = o.origin.z() + k * dx;
                const Index off = LeafT::coordToOffset(Coord(i, j, k));
                if (k < klo[n] || k > khi[n]) {
                  if (klo[n] <= khi[n] && z < hc[n]) leaf->setValueOff(off, -bg);
                  continue;
                }
                const double phi = surfaceDistance(fast, surface, x, y, z, dx, 1.25 * bg, o.closestPoint);
                if (std::fabs(phi) < bg) {
                  leaf->setValueOn(off, float(phi));
                  any = true;
                } else {
                  leaf->setValueOff(off, phi < 0 ? -bg : bg);
                }
              }
            }
          // A leaf without active voxels lies wholly below the leaf column's band (the tiles
          // filled below are right for it) or above it (the background is): neighbouring voxel
          // columns' surfaces differ by |grad h| dx, less than the band's vertical thickness
          // 2 band dx sqrt(1 + |grad h|^2), so the bands of a leaf column leave no gap.
          if (any) {
            if (localFloors.empty() || localFloors.back().L != L || localFloors.back().M != M)
              localFloors.push_back({L, M, K * 8});
            local.push_back(leaf.release());
          }
        }
      }
    std::lock_guard<std::mutex> lock(mutex);
    leaves.insert(leaves.end(), local.begin(), local.end());
    floors.insert(floors.end(), localFloors.begin(), localFloors.end());
  });

  FloatGrid::Ptr grid = FloatGrid::create(bg);
  FloatTree& tree = grid->tree();
  for (LeafT* leaf : leaves) tree.addLeaf(leaf); // the tree takes ownership
  // Below the band is ground: inactive tiles of -bg (OpenVDB's signedFloodFill guesses inside
  // from scan order, which fails where a height field leaves whole columns of nodes empty).
  // Each leaf column gets 8^3 tiles down to its node's floor, each 128^2 footprint whole
  // 128^3 tiles below that, down to zmin. Above the band the background (+bg) is outside.
  {
    float hlo, hhi;
    surface.range(hlo, hhi);
    const double zmin = std::isfinite(o.zmin) ? std::min(o.zmin, double(hlo)) : hlo - 128 * dx;
    const int kFloor = floorDiv(int(std::floor((zmin - o.origin.z()) / dx)), 128) * 128;
    std::map<std::pair<int, int>, int> nodeFloor; // 128^2 footprint -> its lowest leaf, rounded down
    for (const Floor& f : floors) {
      auto key = std::make_pair(floorDiv(f.L, 16), floorDiv(f.M, 16));
      const int z1 = floorDiv(f.k, 128) * 128;
      auto it = nodeFloor.find(key);
      if (it == nodeFloor.end()) nodeFloor.emplace(key, z1);
      else it->second = std::min(it->second, z1);
    }
    for (const Floor& f : floors) {
      const int z1 = nodeFloor[std::make_pair(floorDiv(f.L, 16), floorDiv(f.M, 16))];
      if (f.k > z1) tree.fill(CoordBBox(Coord(f.L * 8, f.M * 8, z1), Coord(f.L * 8 + 7, f.M * 8 + 7, f.k - 1)), -bg, false);
    }
    for (const auto& [key, z1] : nodeFloor)
      if (z1 > kFloor)
        tree.fill(CoordBBox(Coord(key.first * 128, key.second * 128, kFloor),
                            Coord(key.first * 128 + 127, key.second * 128 + 127, z1 - 1)),
                  -bg, false);
  }
  stats.leaves = leaves.size();
  stats.activeVoxels = grid->activeVoxelCount();
  math::Transform::Ptr xf = math::Transform::createLinearTransform(dx);
  xf->postTranslate(math::Vec3d(o.origin.x(), o.origin.y(), o.origin.z()));
  grid->setTransform(xf);
  grid->setGridClass(GRID_LEVEL_SET);
  grid->setName("terrain");
  grid->insertMeta("crs_wkt", StringMetadata(g.crsWkt));
  grid->insertMeta("origin", Vec3DMetadata(math::Vec3d(o.origin.x(), o.origin.y(), o.origin.z())));
  grid->insertMeta("dx", DoubleMetadata(dx));
  grid->insertMeta("band_voxels", Int32Metadata(o.band));
  grid->insertMeta("source", StringMetadata(o.sourcePath));
  grid->insertMeta("smooth_radius", DoubleMetadata(o.smoothRadius));
  grid->insertMeta("distance_method",
                   StringMetadata(o.closestPoint ? "closest point on the bilinear DEM surface (vertical next to it)"
                                                 : "slope-corrected vertical difference"));
  grid->insertMeta("dem_grid", StringMetadata(std::to_string(g.nx) + " x " + std::to_string(g.ny) + " cells of " +
                                              std::to_string(g.cellSize) + " m, west " + std::to_string(g.originX) +
                                              ", north " + std::to_string(g.originY)));
  stats.buildSeconds = since(t0);

  const auto t1 = Clock::now();
  writeAtomically(path, [&](const std::string& tmp) {
    writeThroughMemory(tmp, [&](const std::string& scratch) {
      io::File file(scratch);
      file.write(GridPtrVec{grid});
      file.close();
    });
  }, ".tmp." + std::to_string(::getpid())); // two runs may build the same cache file at once
  stats.writeSeconds = since(t1);
  stats.fileBytes = size_t(std::filesystem::file_size(path));
  return stats;
}

} // namespace talus
