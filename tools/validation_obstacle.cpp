// The dam break onto a box (Kleefsman et al. 2005, MARIN; SPHERIC Test 2): the water depth at
// four gauges and the horizontal load on the box against the experiment's records
// (tools/validation_kleefsman_data.h). The depth is the water column the run's own wave gauges
// find in their footprints ([[output.gauges]]; a jet thrown over a gauge adds its thickness, not
// its elevation); the load is the box's own ([[structures]]).
#include "tools/validation_cases.h"
#include "tools/validation_kleefsman_data.h"
#include "tools/validation_support.h"

#include "io/output/water_gauges.h"

#include <algorithm>
#include <cmath>

namespace talus::validation {

namespace {

using namespace detail;

/// MARIN's tank 3.22 x 1 x 1 m; the water x in [1.992, 3.22], 0.55 m deep; the box x in
/// [0.6635, 0.8245], 0.161 m high, 0.403 m wide. The box stands 3 mm off the tank's centre line
/// (y 0.2955-0.6985); here it is centred, so half the tank (y in [0, 0.5]) with a slip wall on the
/// centre line stands for the whole: 3 mm is a tenth of the finest cell run here.
constexpr double kTank = 3.22, kHalfWidth = 0.5, kWaterX0 = 1.992, kDepth = 0.55;
constexpr double kBoxX0 = 0.6635, kBoxX1 = 0.8245, kBoxHeight = 0.161, kBoxHalfWidth = 0.2015;

/// The tank's length at dx: the far wall on the node row nearest 3.22 m (a closed face holds the
/// row at or beyond it, so a face between rows would give the water up to a cell more room).
double tankLength(double dx) { return std::round(kTank / dx) * dx; }

std::string obstacleScene(double dx, double soundSpeed) {
  // The box reaches below the floor and past the centre line so no node row of water lies
  // between it and either wall. The walls lie on node rows: the centre line as dx is a whole
  // part of the half width, the far wall within dx/2 of MARIN's (tankLength), the water to it.
  return format(R"(
[simulation]
dx = %.9g
end_time = 100
[domain]
min = [0, 0, 0]
max = [%.9g, %.9g, 1]
walls = "slip"
z_max = "open"
[[materials]]
name = "water"
model = "water"
density = 1000
sound_speed = %.9g
[[bodies]]
material = "water"
shape = "box"
min = [%.9g, 0, 0]
max = [%.9g, %.9g, %.9g]
[[structures]]
name = "box"
shape = "box"
min = [%.9g, %.9g, -0.2]
max = [%.9g, 1, %.9g]
law = "slip"
)",
                dx, tankLength(dx), kHalfWidth, soundSpeed, kWaterX0, tankLength(dx), kHalfWidth, kDepth, kBoxX0,
                kHalfWidth - kBoxHalfWidth, kBoxX1, kBoxHeight);
}

/// Relative L1 distance sum |a - b| / sum |b| over the samples where both are finite.
double relativeL1(const std::vector<double>& a, const std::vector<double>& b) {
  double num = 0, den = 0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    if (std::isfinite(a[i]) && std::isfinite(b[i])) num += std::abs(a[i] - b[i]), den += std::abs(b[i]);
  return den > 0 ? num / den : 0.0;
}

/// About r.cells across the depth, and a whole number across the half width (on node rows).
double obstacleDx(const Resolution& r) { return kHalfWidth / std::max(1.0, std::round(kHalfWidth * r.cells / kDepth)); }

/// c = 50 m/s unless r sets it: ten times the front's 2 sqrt(g d) = 4.6 m/s, a density error
/// under 1 % (the depths). The box's load depends on the time step c sets, through the box's
/// edges (docs/convergence.md, "Dam break onto a box").
double obstacleSoundSpeed(const Resolution& r) { return r.soundSpeed > 0 ? r.soundSpeed : 50; }

} // namespace

const std::vector<double>& ObstacleImpactResult::gaugeX() {
  static const std::vector<double> x(std::begin(kleefsman::kGaugeX), std::end(kleefsman::kGaugeX));
  return x;
}

std::string obstacleSceneText(const Resolution& r) { return obstacleScene(obstacleDx(r), obstacleSoundSpeed(r)); }

ObstacleImpactResult obstacleImpact(const Resolution& r, double endTime) {
  const double dx = obstacleDx(r);
  ObstacleImpactResult res;
  res.soundSpeed = obstacleSoundSpeed(r);
  auto sim = build(obstacleScene(dx, res.soundSpeed), r, res);
  size_t box = 0;
  while (sim->colliders()[box]->name() != "box") ++box;
  // The gauges on the centre line: their footprints (half-width dx) lie against the mirror wall.
  std::vector<GaugeSpec> gauges;
  for (double x : ObstacleImpactResult::gaugeX())
    gauges.push_back({format("x%g", x), Eigen::Vector2d(x, kHalfWidth - dx), dx});
  WaterGauges reader(gauges, {"water"}, dx / std::cbrt(double(r.particlesPerCell)));
  reader.onStart(*sim);
  res.depth.resize(gauges.size());
  const auto t0 = Clock::now();
  double impulse = 0, tLast = 0; // the box's x impulse since the last sample (N s), whole tank
  double collidersImpulse = 0, largest = 0; // every collider's x impulse; the largest x momentum
  const double momentum0 = sim->linearMomentum().x();
  auto onStep = [&] {
    const double dt = sim->time() - tLast;
    impulse += 2 * dt * sim->colliderLoads()[box].force.x();
    for (const ColliderLoad& l : sim->colliderLoads()) collidersImpulse += dt * l.force.x();
    largest = std::max(largest, std::abs(sim->linearMomentum().x()));
    tLast = sim->time();
  };
  const double water0 = sim->groupSums()[0].mass;
  for (int i = 0; ObstacleImpactResult::kSample * i <= endTime + 1e-9; ++i) {
    const double t = ObstacleImpactResult::kSample * i, tStart = sim->time();
    sim->advanceTo(t, onStep);
    res.t.push_back(t);
    // The water pushes the box towards -x: the load counts positive that way.
    res.force.push_back(sim->time() > tStart ? -impulse / (sim->time() - tStart) : 0.0);
    impulse = 0;
    const std::vector<double> d = reader.depths(*sim);
    for (size_t k = 0; k < d.size(); ++k) res.depth[k].push_back(d[k]);
  }
  finish(*sim, t0, res);
  res.lostWater = 1 - sim->groupSums()[0].mass / water0;
  // The loads are what the colliders took from the water: the x momentum it lost.
  res.momentumImbalance =
      std::abs(collidersImpulse - (momentum0 - sim->linearMomentum().x())) / std::max(largest, 1e-30);
  compareWithExperiment(res);
  return res;
}

void compareWithExperiment(ObstacleImpactResult& res) {
  using R = ObstacleImpactResult;
  const size_t gauges = R::gaugeX().size(), nDepth = std::size(kleefsman::kDepths);
  res.depthExp.assign(gauges, {});
  res.depthError.clear(), res.arrival.clear(), res.arrivalExp.clear();
  for (size_t k = 0; k < gauges; ++k) {
    std::vector<double> sim;
    for (size_t i = 0, j = 0; i < res.t.size(); i += R::kDepthEvery, ++j) {
      sim.push_back(res.depth[k][i]);
      res.depthExp[k].push_back(j < nDepth ? kleefsman::kDepths[j][k] : std::nan(""));
    }
    res.depthError.push_back(relativeL1(sim, res.depthExp[k]));
    res.arrival.push_back(firstAbove(res.t, res.depth[k], R::kArrivalDepth));
    res.arrivalExp.push_back(kleefsman::kArrival[k]);
  }
  // The experiment's load on the run's instants: each sample the mean over the interval before it.
  res.forceExp.clear();
  for (double t : res.t) {
    const long j = std::lround((t - kleefsman::kForceT0) / R::kSample);
    res.forceExp.push_back(j >= 0 && j < long(std::size(kleefsman::kForce)) ? kleefsman::kForce[j] : 0.0);
  }
  struct Load {
    const std::vector<double>& raw;
    std::vector<double>& filtered;
    double &peak, &peakT, &plateau;
  };
  for (Load l : {Load{res.force, res.forceFiltered, res.peak, res.peakT, res.plateau},
                 Load{res.forceExp, res.forceExpFiltered, res.peakExp, res.peakTExp, res.plateauExp}}) {
    l.filtered = movingAverage(l.raw, R::kFilterHalf);
    l.peak = l.peakT = l.plateau = 0;
    double n = 0;
    for (size_t i = 0; i < res.t.size(); ++i) {
      const double t = res.t[i], f = l.filtered[i];
      if (t <= R::kImpactEnd + 1e-9 && f > l.peak) l.peak = f, l.peakT = t;
      if (t >= R::kPlateau[0] - 1e-9 && t <= R::kPlateau[1] + 1e-9) l.plateau += f, n += 1;
    }
    l.plateau /= std::max(n, 1.0);
  }
}

} // namespace talus::validation
