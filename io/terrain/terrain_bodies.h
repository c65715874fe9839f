// [[bodies]] that lie on a DEM, selected by `kind`:
//   release  the volume between the DEM and a second surface: a post-event DEM (dem_after), or
//            the DEM raised by a thickness over a polygon (thickness or thickness_attribute)
//   layer    a cover of given thickness over a polygon, a box or the whole domain, optionally
//            only where the slope is below max_slope and the elevation in a range
//   water    the terrain filled up to a water level inside a polygon or box (a reservoir)
//   fixed    a region held still, built into the terrain itself (no particles): a layer of
//            given thickness raises the height field before the level set is built, and a
//            solid (box, sphere, cylinder) is united with the level set analytically
// Coordinates are world coordinates in the DEM's CRS.
#pragma once

#include "io/config/config_table.h"
#include "engine/sdf.h"
#include "io/terrain/shape_reader.h"
#include "io/terrain/dem_raster.h"
#include "io/terrain/polygon_set.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace talus {

struct DemTerrainInput;

class TerrainBody {
public:
  enum class Kind { Release, Layer, Water, Fixed };

  /// Reads and validates the table (polygons and post-event DEMs against the DEM's extent and
  /// CRS). `domainMin/Max` (world) bound a layer without a region. Throws InputError.
  TerrainBody(const ConfigTable& t, const std::string& kind, const DemTerrainInput& dem, const Vec3d& origin,
              const Vec3d& domainMin, const Vec3d& domainMax);

  Kind kind() const { return kind_; }
  const ConfigTable& table() const { return *t_; }
  const std::string& kindName() const { return kindName_; }

  /// Release from a post-event DEM: depth to carve out of the DEM per cell (pre - post, 0
  /// where none). Empty otherwise.
  const std::vector<float>& carveDepth() const { return carve_; }
  /// Fixed layer: adds its thickness to `ground` at the cell centres inside the region.
  void raise(const HeightField& bed, DemRaster& ground) const;
  /// Fixed solid in the local frame, or nullptr.
  std::shared_ptr<const Sdf> fixedSolid() const;

  /// The body's vertical extent [zb, zt] at world (x, y) on `bed`; false when (x, y) is not part
  /// of it (outside the region or a mask, or zero thickness).
  bool interval(const HeightField& bed, double x, double y, double& zb, double& zt) const;

  /// Volume by quadrature (spacing q) and the body's world bounds; `area` (optional) receives
  /// its plan area.
  double measure(const HeightField& bed, double q, Vec3d& lo, Vec3d& hi, double* area = nullptr) const;
  /// An upper bound of the body's top at world (x, y) whose bed height is zb (it bounds the cells
  /// seeding visits in a column; `contains` decides each sample).
  double columnTopBound(const HeightField& bed, double x, double y, double zb) const;
  /// The key that names the body's region in messages: polygon, bounds, dem_after or kind.
  std::string regionKey() const;
  const Vec3d& velocity() const { return velocity_; }
  /// The DEM grid the body's region lies on.
  const RasterGrid& grid() const { return *grid_; }
  /// A fixed solid (box, sphere, cylinder) rather than a region of the DEM.
  const Shape* solid() const { return solid_.get(); }
  /// Whether world point (x, y, z) lies in the body (on `bed`).
  bool contains(const HeightField& bed, double x, double y, double z) const {
    double zb, zt;
    return interval(bed, x, y, zb, zt) && z > zb && z <= zt;
  }

private:
  double thicknessAt(const HeightField& bed, int feature, double x, double y) const;

  const ConfigTable* t_;
  Kind kind_;
  std::string kindName_;
  std::optional<PolygonSet> region_; ///< the polygon, a rectangle, or the domain footprint
  std::vector<float> carve_;         ///< release from dem_after
  std::vector<float> carveNbMax_;    ///< max of carve_ over each cell's 3 x 3 neighbourhood
  const RasterGrid* grid_ = nullptr;
  bool fromAttribute_ = false;
  double thickness_ = 0, maxThickness_ = 0;
  bool slopeNormal_ = true;
  double maxSlope_ = 90, minElevation_ = -INFINITY, maxElevation_ = INFINITY;
  double level_ = 0;
  std::shared_ptr<const Shape> solid_; ///< shared with the terrain, which outlives the body
  Vec3d velocity_ = Vec3d::Zero();
};

} // namespace talus
