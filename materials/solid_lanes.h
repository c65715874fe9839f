// The solid update of updateSolid (materials/hencky.h) for several particles side by side in SIMD
// lanes: the deformation increment, the Hencky strain by its series, the return mapping, the
// plastic correction and the Kirchhoff stress. Google Highway picks the machine's widest target at
// run time (SSE4, AVX2, AVX-512, or portable scalar code without them).
//
// Every lane runs the same IEEE operations in the same order, and the kernel is compiled without
// contraction into fused multiply-adds, so a particle's result is bit for bit the same on every
// target and at any lane grouping (tests/test_solid_lanes.cpp checks each target the machine has).
// It is not bit for bit the scalar updateSolid's (Eigen sums some products in another order): the
// two agree to the float the results are stored in, within a few units in its last place.
//
// Covered: the elastic model, Drucker–Prager (the lab box, rock and debris, with or without
// softening), μ(I) and Cam Clay (snow), on the usual path (|b - I| <= 0.25, J > 0). A lane outside
// it, or whose Cam Clay hardening Newton fails, is flagged and its particle takes the scalar
// updateSolid.
#pragma once

#include "materials/cam_clay.h"
#include "materials/drucker_prager.h"
#include "materials/elastic.h"
#include "materials/mu_i.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace talus {

/// Particles per call of updateSolidLanes: a multiple of every target's lane count (2 to 8 doubles).
constexpr int kSolidLanes = 16;

/// What the kernel needs of the model: the Hencky moduli and, for Drucker–Prager at constant
/// strength, the cone (q = gamma (p + c)).
struct SolidLaneParams {
  enum class Kind { Elastic, DruckerPrager, SofteningDruckerPrager, CamClay, MuI };
  Kind kind = Kind::Elastic;
  double mu = 0, lambda = 0;
  double bulk = 0;      ///< lambda + 2 mu / 3
  double qScale = 0;    ///< q = qScale |dev eps| = sqrt(3/2) 2 mu |dev eps|
  double gamma = 0;     ///< cone slope
  double cohesion = 0;  ///< c (Pa): tension tip at p = -c
  double M = 0, Ms = 0, beta = 0, xi = 0; ///< Cam Clay: slopes before and after yield, tension ratio, hardening
  double sqrtBulk = 0, sqrt3mu = 0, sqrtTension = 0; ///< Cam Clay: CamClayModel::Scales, once per group
  /// Softening Drucker–Prager: initial and residual friction angles (rad), chi, the cone's fit
  /// (`cohesion` is then the initial one).
  double frictionAngle = 0, residualFrictionAngle = 0, softening = 0;
  DruckerPragerCone cone = DruckerPragerCone::Compression;
  /// μ(I): static and limiting friction coefficients, I0, grain diameter (m) and density (kg/m3).
  double muS = 0, mu2 = 0, i0 = 0, grainDiameter = 0, grainDensity = 0;
};

/// Structure-of-arrays input and output of kSolidLanes particles; matrices row by row (index 3 i + j).
struct alignas(64) SolidLanes {
  double C[9][kSolidLanes];      ///< in: APIC velocity gradient
  double fbar[kSolidLanes];      ///< in: F-bar's scale of the increment (1 when off)
  double F[9][kSolidLanes];      ///< in: elastic F of the last step; out: the new one
  double strain[kSolidLanes];    ///< in/out: plastic strain (Drucker–Prager's e, Cam Clay's eps_v)
  double extra[kSolidLanes];     ///< in/out: a second state variable: Cam Clay's yielded flag (0 or 1)
  double tau[6][kSolidLanes];    ///< out: Kirchhoff stress xx, yy, zz, xy, xz, yz
  double Ftrial[9][kSolidLanes]; ///< out: (fbar (I + dt C)) F, for the lanes left to the scalar path
  double scalar[kSolidLanes];    ///< out: 1 where the lane is off the usual path, else 0
};

/// Updates lanes [0, n) of `io` (n <= kSolidLanes) over the step dt. Lanes from n up to the next
/// multiple of the target's width are computed too and must hold finite values (e.g. identity F).
/// Where io.scalar is 1, F, tau and strain are not written: the caller runs updateSolid on Ftrial.
void updateSolidLanes(const SolidLaneParams& params, double dt, int n, SolidLanes& io);

// The target it runs on, and for tests the choice of another: engine/stencil_lanes.h (simdTargets).

/// Whether Model's update runs in lanes, and with what; false leaves it to the scalar updateSolid.
/// The fields every kind shares: the Hencky moduli.
inline SolidLaneParams henckyLaneParams(SolidLaneParams::Kind kind, const HenckyElasticity& e) {
  SolidLaneParams out;
  out.kind = kind;
  out.mu = e.mu, out.lambda = e.lambda, out.bulk = e.bulk();
  out.qScale = std::sqrt(1.5) * 2 * e.mu;
  return out;
}
inline bool solidLaneParams(const ElasticModel& m, SolidLaneParams& out) {
  out = henckyLaneParams(SolidLaneParams::Kind::Elastic, m.elastic);
  return true;
}
inline bool solidLaneParams(const DruckerPragerModel& m, SolidLaneParams& out) {
  const DruckerPragerParams& p = m.params();
  out = henckyLaneParams(m.softens() ? SolidLaneParams::Kind::SofteningDruckerPrager : SolidLaneParams::Kind::DruckerPrager,
                         m.elastic);
  out.gamma = DruckerPragerModel::gammaOf(p.residualFrictionAngle, p.cone), out.cohesion = p.cohesion;
  out.frictionAngle = p.frictionAngle, out.residualFrictionAngle = p.residualFrictionAngle;
  out.softening = p.softening, out.cone = p.cone;
  return true;
}
inline bool solidLaneParams(const CamClayModel& m, SolidLaneParams& out) {
  const CamClayParams& c = m.params;
  const CamClayModel::Scales scales(m);
  out = henckyLaneParams(SolidLaneParams::Kind::CamClay, m.elastic);
  out.M = c.M, out.Ms = c.Ms, out.beta = c.beta, out.xi = c.xi;
  out.sqrtBulk = scales.sK, out.sqrt3mu = scales.s3mu, out.sqrtTension = scales.sqrtTension;
  return true;
}
inline bool solidLaneParams(const MuIModel& m, SolidLaneParams& out) {
  out = henckyLaneParams(SolidLaneParams::Kind::MuI, m.elastic);
  out.muS = m.params.muS, out.mu2 = m.params.mu2, out.i0 = m.params.i0;
  out.grainDiameter = m.params.grainDiameter, out.grainDensity = m.params.grainDensity;
  return true;
}
/// A model without a lane kernel stays scalar.
template <class Model>
bool solidLaneParams(const Model&, SolidLaneParams&) { return false; }

/// The plastic strain and flag a lane carries, read from and written back to a model's state.
inline void laneState(const DruckerPragerModel::State& s, double& strain, double& flag) { strain = s.plasticStrain, flag = 0; }
inline void setLaneState(DruckerPragerModel::State& s, double strain, double) { s.plasticStrain = float(strain); }
inline void laneState(const MuIModel::State& s, double& strain, double& flag) { strain = s.plasticStrain, flag = 0; }
inline void setLaneState(MuIModel::State& s, double strain, double) { s.plasticStrain = float(strain); }
inline void laneState(const CamClayModel::State& s, double& strain, double& yielded) {
  strain = s.volumetricPlasticStrain(), yielded = s.yielded();
}
inline void setLaneState(CamClayModel::State& s, double strain, double yielded) {
  s.set(strain, yielded != 0);
}
template <class State>
void laneState(const State&, double& strain, double& yielded) {
  strain = 0, yielded = 0;
}
template <class State>
void setLaneState(State&, double, double) {}

} // namespace talus
