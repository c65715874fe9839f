// Inflow hydrographs: material entering the domain through a cross-section (a debris flow from
// a torrent, an outburst flood) at a discharge Q(t) and speed v(t) given as a table, as
// r.avaflow's input hydrographs and AvaFrame's debris hydrographs do.
//
// The section is a horizontal line across the channel (width w); material enters normal to it
// along `direction` at speed v, in a layer of thickness h = Q / (v w) on the ground. Each step
// adds the exact integral of the piecewise-linear Q over the step to a pending volume and moves
// a cursor v dt downstream; each time the cursor passes a particle spacing s (dx / cbrt(ppc)), a
// row of particles (floor(w / s) across, round(h / s) up) is placed that far downstream of the
// section with velocity v along `direction`, and takes the whole pending volume as its mass
// (rho V / particles). So the mass that entered is rho times the hydrograph's integral up to the
// last row, whatever the step size, and the layer's thickness follows h within a row.
#pragma once

#include "engine/particle_source.h"

#include <string>
#include <vector>

namespace talus {

struct InflowSpec {
  std::string name;
  int group = -1;
  double density = 0;
  Vec3d a = Vec3d::Zero(), b = Vec3d::Zero(); ///< section ends (local frame, z ignored)
  Vec3d direction = Vec3d::UnitX();          ///< horizontal unit vector of entry
  std::vector<double> time, discharge, speed; ///< the hydrograph (s, m3/s, m/s); Q = 0 outside it
  double spacing = 0;                         ///< particle spacing (m)
  std::vector<double> ground;                 ///< ground elevation (local z) at each lateral slot
};

class InflowSource final : public ParticleSource {
public:
  /// Throws std::invalid_argument: fewer than two hydrograph rows, times not increasing, negative
  /// discharge, speed not positive, a section shorter than a spacing, no slot ground.
  explicit InflowSource(InflowSpec spec);
  size_t emit(const SparseGrid& grid, double time, double dt, const std::vector<MaterialGroup*>& groups) override;
  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;

  const InflowSpec& spec() const { return spec_; }
  /// Volume placed as particles so far (m3), and the hydrograph's integral from 0 to t.
  double emittedVolume() const { return emitted_; }
  double hydrographVolume(double t) const;
  /// Q and v at t (linear between rows; Q = 0 outside the table, v held at its ends).
  double discharge(double t) const;
  double speed(double t) const;
  /// Lateral slots across the section.
  size_t slots() const { return spec_.ground.size(); }

private:
  InflowSpec spec_;
  double pending_ = 0, cursor_ = 0, emitted_ = 0;
};

} // namespace talus
