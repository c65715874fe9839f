#include "io/scene/erodible_cover_reader.h"

#include <cmath>
#include <cstdio>

namespace talus {

std::optional<ErodibleCover> readErodibleCover(const TerrainBody& body, const HeightField& bed, const Vec3d& origin,
                                               double dx, int particlesPerCell, const MaterialGroup& group,
                                               int groupPosition, const std::vector<const TerrainBody*>& earlier,
                                               BodyReport& rep) {
  const ConfigTable& t = body.table();
  const bool layer = body.kind() == TerrainBody::Kind::Layer;
  for (const char* k : {"field_below", "erosion_energy"})
    if (!layer && t.has(k)) t.fail(k, "only a layer (kind = \"layer\") can be an erodible field");
  if (!layer) return std::nullopt;
  const double below = t.number("field_below", dx);
  if (!(below >= 0)) t.fail("field_below", "must be a thickness (m), 0 for particles always");
  const double energy = t.positive("erosion_energy", 5000.0);
  Vec3d lo, hi;
  double area = 0;
  const double volume = body.measure(bed, 0.5 * std::min(dx, body.grid().cellSize), lo, hi, &area);
  const double mean = area > 0 ? volume / area : 0;
  if (!(mean > 0) || !(mean < below)) return std::nullopt;

  ErodibleCover c;
  c.name = t.string("name", "layer");
  c.group = groupPosition;
  c.erosionEnergy = energy;
  const double rho = group.density();
  double total = 0;
  const int i0 = int(std::floor((lo.x() - origin.x()) / dx)), i1 = int(std::ceil((hi.x() - origin.x()) / dx));
  const int j0 = int(std::floor((lo.y() - origin.y()) / dx)), j1 = int(std::ceil((hi.y() - origin.y()) / dx));
  for (int i = i0; i <= i1; ++i)
    for (int j = j0; j <= j1; ++j) {
      const double x = origin.x() + i * dx, y = origin.y() + j * dx;
      double zb, zt;
      if (!body.interval(bed, x, y, zb, zt) || !(zt > zb)) continue;
      bool covered = false; // a release (or any earlier body) on the ground here takes the place
      for (const TerrainBody* e : earlier)
        covered |= e->kind() != TerrainBody::Kind::Fixed && e->contains(bed, x, y, zb + 1e-3 * (zt - zb));
      if (covered) continue;
      c.columns.push_back({int32_t(i), int32_t(j), rho * (zt - zb) * dx * dx});
      total += c.columns.back().mass;
    }
  if (c.columns.empty())
    t.fail(body.regionKey(), "the erodible cover holds no grid node column (thinner than field_below, under a release "
                             "everywhere, or smaller than a cell)");
  // A particle of the seeding's size, or a mean column's mass when that is less: a column eroded
  // to the ground then gives about one particle.
  c.particleMass = std::min(rho * dx * dx * dx / particlesPerCell, total / double(c.columns.size()));
  rep.kind = "layer";
  rep.material = group.name();
  rep.geometricVolume = volume;
  rep.meanThickness = mean;
  rep.particlesPerCell = particlesPerCell;
  rep.fieldMass = total;
  return c;
}

std::string erodibleCoverNote(const ErodibleCover& cover, const BodyReport& rep, double dx) {
  char s[400];
  std::snprintf(s, sizeof s,
                "%s: %.3g m thick on average (vertical), %.2g cells at dx %g m: an erodible field of %zu node columns, "
                "%.4g kg of %s (AvaFrame's erosion, erosion_energy %g J/kg), not particles",
                rep.label.c_str(), rep.meanThickness, rep.meanThickness / dx, dx, cover.columns.size(), rep.fieldMass,
                rep.material.c_str(), cover.erosionEnergy);
  return s;
}

} // namespace talus
