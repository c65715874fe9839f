// The Tait water's update (TaitWaterModel::update, materials/tait_water.h) for several particles
// side by side in SIMD lanes, as materials/solid_lanes.h does for the solids: the same bits on
// every Highway target; within float rounding of the scalar update (the invariants of dt C are
// summed in another order). libm's log1p and expm1 run per lane.
#pragma once

#include "materials/tait_water.h"

namespace talus {

/// Particles per call of updateWaterLanes (a multiple of every target's lane count).
constexpr int kWaterLanes = 16;

/// Structure-of-arrays input and output of kWaterLanes particles; C row by row (index 3 i + j).
struct alignas(64) WaterLanes {
  double C[9][kWaterLanes];   ///< in: APIC velocity gradient
  double dJ[kWaterLanes];     ///< in: J - 1 of the last step; out: the new one (to be stored as a float)
  double tau[6][kWaterLanes]; ///< out: Kirchhoff stress xx, yy, zz, xy, xz, yz
};

/// Updates lanes [0, n) of `io` (n <= kWaterLanes) over the step dt; lanes up to the next multiple
/// of the target's width are computed too and must hold finite values (e.g. zeros).
void updateWaterLanes(const TaitWaterModel& model, double dt, int n, WaterLanes& io);

} // namespace talus
