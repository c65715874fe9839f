#include "io/terrain/terrain_bodies.h"

#include "engine/sdf_solids.h"
#include "io/terrain/terrain_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tbb/parallel_for.h>

namespace talus {

namespace {

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}
std::string range(double a, double b) { return "[" + fmt(a) + ", " + fmt(b) + "]"; }

} // namespace

TerrainBody::TerrainBody(const ConfigTable& t, const std::string& kind, const DemTerrainInput& dem, const Vec3d& origin,
                         const Vec3d& domainMin, const Vec3d& domainMax)
    : t_(&t), kindName_(kind) {
  kind_ = kind == "release" ? Kind::Release : kind == "layer" ? Kind::Layer : kind == "water" ? Kind::Water : Kind::Fixed;
  const DemRaster& raw = *dem.raw;
  grid_ = &dem.smoothed->grid;
  const HeightField demField(raw);
  const std::string demCrs = raw.grid.crsWkt;
  velocity_ = t.vec3("velocity", Vec3d::Zero());
  if (kind_ == Kind::Fixed && t.has("velocity")) t.fail("velocity", "a fixed region does not move");

  // The region: a polygon file, a box, or (layers and fixed layers) the domain's footprint.
  if (t.has("polygon") && t.has("bounds")) t.fail("bounds", "give either 'polygon' or 'bounds', not both");
  const bool attr = t.has("thickness_attribute");
  if (t.has("polygon")) {
    const std::string file = resolveScenePath(t.file(), t.string("polygon"));
    try {
      region_ = PolygonSet::read(file, attr ? t.string("thickness_attribute") : "", t.string("polygon_layer", ""));
    } catch (const InputError& e) {
      t.fail(attr && std::string(e.what()).find("attribute") != std::string::npos ? "thickness_attribute" : "polygon",
             e.what());
    }
    if (!sameCrs(region_->crsWkt(), demCrs))
      t.fail("polygon", file + ": its CRS, " + crsName(region_->crsWkt()) + ", differs from the DEM's, " +
                            crsName(demCrs) + "; reproject it (ogr2ogr -t_srs)" +
                            (file.find("json") != std::string::npos ? " or, if its coordinates are in the DEM's CRS, "
                                                                      "give it a \"crs\" member (GeoJSON without "
                                                                      "one is WGS 84)"
                                                                    : ""));
  } else if (t.has("bounds")) {
    const auto b = t.numbers("bounds");
    if (b.size() != 4 || !(b[2] > b[0]) || !(b[3] > b[1]))
      t.fail("bounds", "expected [xmin, ymin, xmax, ymax] with xmax > xmin and ymax > ymin (m)");
    region_ = PolygonSet::rectangle(b[0], b[1], b[2], b[3]);
  }
  if (region_) {
    double x0, y0, x1, y1;
    region_->bounds(x0, y0, x1, y1);
    const std::string key = t.has("polygon") ? "polygon" : "bounds";
    const std::string where = "x " + range(x0, x1) + ", y " + range(y0, y1);
    const std::string demExt = "x " + range(demField.xmin(), demField.xmax()) + ", y " +
                               range(demField.ymin(), demField.ymax());
    if (x1 < demField.xmin() || x0 > demField.xmax() || y1 < demField.ymin() || y0 > demField.ymax())
      t.fail(key, "lies outside the DEM (" + where + "; DEM " + demExt + ")");
    if (x0 < demField.xmin() || x1 > demField.xmax() || y0 < demField.ymin() || y1 > demField.ymax())
      t.fail(key, "extends beyond the DEM (" + where + "; DEM " + demExt + ")");
  }

  auto readThickness = [&](bool allowAttribute) {
    if (attr && !allowAttribute) t.fail("thickness_attribute", "only a release or layer polygon takes its thickness from an attribute");
    if (attr && !t.has("polygon")) t.fail("thickness_attribute", "needs a 'polygon' whose features carry the attribute");
    if (attr && t.has("thickness")) t.fail("thickness", "give either 'thickness' or 'thickness_attribute', not both");
    if (attr) {
      fromAttribute_ = true;
      for (size_t f = 0; f < region_->features(); ++f) {
        const double v = region_->value(int(f));
        if (!(v >= 0) || !std::isfinite(v))
          t.fail("thickness_attribute", region_->path() + ": feature " + std::to_string(f) + " has thickness " + fmt(v) +
                                            " (must be a non-negative number of metres)");
        maxThickness_ = std::max(maxThickness_, v);
      }
    } else {
      thickness_ = maxThickness_ = t.positive("thickness");
    }
    slopeNormal_ = t.choice("thickness_direction", "slope_normal", {"vertical", "slope_normal"}) == "slope_normal";
  };
  auto wholeDomain = [&]() {
    const double x0 = std::max(domainMin.x(), demField.xmin()), x1 = std::min(domainMax.x(), demField.xmax());
    const double y0 = std::max(domainMin.y(), demField.ymin()), y1 = std::min(domainMax.y(), demField.ymax());
    region_ = PolygonSet::rectangle(x0, y0, x1, y1);
  };

  switch (kind_) {
  case Kind::Release:
    if (t.has("dem_after")) {
      if (attr || t.has("thickness")) t.fail("dem_after", "give either 'dem_after' or a thickness, not both");
      const std::string file = resolveScenePath(t.file(), t.string("dem_after"));
      DemReadOptions opt;
      opt.keepNodata = true;
      DemRaster post;
      try {
        post = readDem(file, opt);
      } catch (const InputError& e) {
        t.fail("dem_after", e.what());
      }
      if (!sameCrs(post.grid.crsWkt, demCrs))
        t.fail("dem_after", file + ": its CRS, " + crsName(post.grid.crsWkt) + ", differs from the DEM's, " +
                                crsName(demCrs));
      const double minT = t.positive("min_thickness", 0, true);
      const HeightField postField(post);
      const RasterGrid& g = raw.grid;
      carve_.assign(g.size(), 0.f);
      double total = 0;
      for (int r = 0; r < g.ny; ++r)
        for (int c = 0; c < g.nx; ++c) {
          const double x = g.cellCentreX(c), y = g.cellCentreY(r);
          if (!postField.covers(x, y) || (region_ && !region_->contains(x, y))) continue;
          const double d = raw.height[g.index(c, r)] - postField.height(x, y);
          if (d > minT) carve_[g.index(c, r)] = float(d), total += d, maxThickness_ = std::max(maxThickness_, d);
        }
      if (!(total > 0))
        t.fail("dem_after", file + ": the post-event DEM is nowhere below the DEM" +
                                (minT > 0 ? " by more than min_thickness" : std::string()) + ": nothing to release");
      carveNbMax_.assign(g.size(), 0.f);
      for (int r = 0; r < g.ny; ++r)
        for (int c = 0; c < g.nx; ++c) {
          float m = 0;
          for (int j = std::max(0, r - 1); j <= std::min(g.ny - 1, r + 1); ++j)
            for (int i = std::max(0, c - 1); i <= std::min(g.nx - 1, c + 1); ++i) m = std::max(m, carve_[g.index(i, j)]);
          carveNbMax_[g.index(c, r)] = m;
        }
      if (!t.has("polygon") && !t.has("bounds")) // where both DEMs exist
        region_ = PolygonSet::rectangle(std::max(postField.xmin(), demField.xmin()), std::max(postField.ymin(), demField.ymin()),
                                        std::min(postField.xmax(), demField.xmax()), std::min(postField.ymax(), demField.ymax()));
    } else {
      if (!region_) t.fail("", "a release needs 'dem_after', or a 'polygon' (or 'bounds') with a thickness");
      readThickness(true);
    }
    break;
  case Kind::Layer:
    readThickness(true); // per-feature covers: AvaFrame's ENT/ thickness attribute
    if (!region_) wholeDomain();
    maxSlope_ = t.inRange("max_slope", 90, 0, 90);
    minElevation_ = t.number("min_elevation", -INFINITY);
    maxElevation_ = t.number("max_elevation", INFINITY);
    if (!(maxElevation_ > minElevation_)) t.fail("max_elevation", "must exceed min_elevation");
    break;
  case Kind::Water:
    if (!region_) t.fail("", "a water body needs a 'polygon' or 'bounds' to hold it");
    level_ = t.number("level");
    break;
  case Kind::Fixed:
    if (t.has("material")) t.fail("material", "a fixed region is static terrain and holds no material");
    if (t.has("solid")) {
      if (region_) t.fail("solid", "give either a 'solid' or a region ('polygon'/'bounds') with a thickness");
      solid_ = readBodyShape(t, origin, "solid");
    } else {
      readThickness(false);
      if (!region_) wholeDomain();
    }
    break;
  }
}

double TerrainBody::thicknessAt(const HeightField& bed, int feature, double x, double y) const {
  const double d = fromAttribute_ ? region_->value(feature) : thickness_;
  if (!slopeNormal_) return d;
  double gx, gy;
  bed.slopeGradient(x, y, gx, gy);
  return d * std::sqrt(1 + gx * gx + gy * gy); // d / cos(slope)
}

bool TerrainBody::interval(const HeightField& bed, double x, double y, double& zb, double& zt) const {
  zb = zt = 0;
  if (!region_) return false; // a fixed solid: not a column of the terrain
  const int f = region_->locate(x, y);
  if (f < 0) return false;
  zb = zt = bed.height(x, y);
  switch (kind_) {
  case Kind::Release:
    if (!carve_.empty()) {
      // Bilinear, like the heights: the carved bed and the body's top stay consistent.
      zt = zb + sampleBilinear(*grid_, carve_, x, y);
    } else {
      zt = zb + thicknessAt(bed, f, x, y);
    }
    break;
  case Kind::Layer: {
    if (zb < minElevation_ || zb > maxElevation_) return false;
    if (maxSlope_ < 90 && bed.slope(x, y) * (180 / M_PI) > maxSlope_) return false;
    zt = zb + thicknessAt(bed, f, x, y);
    break;
  }
  case Kind::Water:
    zt = level_;
    break;
  case Kind::Fixed:
    if (solid_) return false;
    zt = zb + thicknessAt(bed, f, x, y);
    break;
  }
  return zt > zb;
}

void TerrainBody::raise(const HeightField& bed, DemRaster& ground) const {
  if (kind_ != Kind::Fixed || solid_) return;
  const RasterGrid& g = ground.grid;
  for (int r = 0; r < g.ny; ++r)
    for (int c = 0; c < g.nx; ++c) {
      double zb, zt;
      if (interval(bed, g.cellCentreX(c), g.cellCentreY(r), zb, zt)) ground.height[g.index(c, r)] += float(zt - zb);
    }
}

std::shared_ptr<const Sdf> TerrainBody::fixedSolid() const {
  if (!solid_) return nullptr;
  return std::make_shared<ShapeSdf>(solid_, "fixed " + t_->string("solid") + " of " + t_->keyPath(""));
}

double TerrainBody::measure(const HeightField& bed, double q, Vec3d& lo, Vec3d& hi, double* area) const {
  double x0, y0, x1, y1;
  region_->bounds(x0, y0, x1, y1);
  const long nx = std::max(1L, long(std::ceil((x1 - x0) / q))), ny = std::max(1L, long(std::ceil((y1 - y0) / q)));
  const double qx = (x1 - x0) / double(nx), qy = (y1 - y0) / double(ny);
  std::vector<double> vol(size_t(ny), 0.0), plan(size_t(ny), 0.0), zlo(size_t(ny), INFINITY), zhi(size_t(ny), -INFINITY);
  tbb::parallel_for(0L, ny, [&](long j) {
    const double y = y0 + (double(j) + 0.5) * qy;
    for (long i = 0; i < nx; ++i) {
      double zb, zt;
      if (!interval(bed, x0 + (double(i) + 0.5) * qx, y, zb, zt)) continue;
      vol[size_t(j)] += (zt - zb) * qx * qy;
      plan[size_t(j)] += qx * qy;
      zlo[size_t(j)] = std::min(zlo[size_t(j)], zb), zhi[size_t(j)] = std::max(zhi[size_t(j)], zt);
    }
  });
  double v = 0, a = 0;
  lo = Vec3d(x0, y0, INFINITY), hi = Vec3d(x1, y1, -INFINITY);
  for (long j = 0; j < ny; ++j) {
    v += vol[size_t(j)], a += plan[size_t(j)];
    lo.z() = std::min(lo.z(), zlo[size_t(j)]), hi.z() = std::max(hi.z(), zhi[size_t(j)]);
  }
  if (area) *area = a;
  return v;
}

std::string TerrainBody::regionKey() const {
  const ConfigTable& t = *t_;
  return t.has("polygon") ? "polygon" : t.has("bounds") ? "bounds" : t.has("dem_after") ? "dem_after" : "kind";
}

double TerrainBody::columnTopBound(const HeightField& bed, double x, double y, double zb) const {
  if (kind_ == Kind::Water) return level_;
  if (!carve_.empty()) {
    int c, r;
    return zb + (grid_->locate(x, y, c, r) ? carveNbMax_[grid_->index(c, r)] : 0.f);
  }
  double sx, sy;
  bed.slopeGradient(x, y, sx, sy);
  return zb + 1.2 * maxThickness_ * (slopeNormal_ ? std::sqrt(1 + sx * sx + sy * sy) : 1.0);
}

} // namespace talus
