// The dam-break validation cases: the surge front against Martin & Moyce (1952) and Koshizuka &
// Oka (1996), and the pressure on the far wall against Buchner (2002) (data: ../shared/validation),
// with the water levels and the wall's pressure profile of Lobovsky et al. (2014) in the same
// tank (tools/validation_lobovsky_data.h).
#include "tools/validation_cases.h"
#include "tools/validation_lobovsky_data.h"
#include "tools/validation_support.h"

#include "engine/simulation.h"
#include "io/output/water_gauges.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace talus::validation {

namespace {

using namespace detail;

/// The numeric (x, y) pairs of a two-column CSV; comment lines (#) and headers are skipped.
std::vector<std::pair<double, double>> readPairs(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file + ": cannot read the digitised data");
  std::vector<std::pair<double, double>> data;
  for (std::string line; std::getline(in, line);) {
    std::stringstream ss(line);
    double x, y;
    char comma;
    if (ss >> x >> comma >> y) data.emplace_back(x, y);
  }
  if (data.size() < 3) throw std::runtime_error(file + ": fewer than three data points");
  return data;
}

/// Least-squares slope of y(x) over the pairs with lo <= y <= hi; 0 with fewer than two.
double slopeWhere(const std::vector<double>& x, const std::vector<double>& y, double lo, double hi, size_t* used) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < x.size(); ++i)
    if (y[i] >= lo && y[i] <= hi) n += 1, sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  if (used) *used = size_t(n);
  return n >= 2 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0.0;
}

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  const auto it = std::lower_bound(x.begin(), x.end(), at);
  if (it == x.begin()) return y.front();
  if (it == x.end()) return y.back();
  const size_t i = size_t(it - x.begin());
  return y[i - 1] + (y[i] - y[i - 1]) * (at - x[i - 1]) / (x[i] - x[i - 1]);
}

/// A water column [0, column] in a slip-walled box [0, domain] (m), softened to soundSpeed (m/s).
std::string waterColumnScene(double dx, const Vec3d& domain, const Vec3d& column, double soundSpeed) {
  return format(R"(
[simulation]
dx = %.9g
end_time = 100
[domain]
min = [0, 0, 0]
max = [%.9g, %.9g, %.9g]
walls = "slip"
[[materials]]
name = "water"
model = "water"
density = 1000
sound_speed = %.9g
[[bodies]]
material = "water"
shape = "box"
min = [0, 0, 0]
max = [%.9g, %.9g, %.9g]
)", dx, domain.x(), domain.y(), domain.z(), soundSpeed, column.x(), column.y(), column.z());
}

/// The far wall's node rows 0 ... top, each a panel across the whole depth (nodes outside the
/// flume included), and pressures from their loads. A sensor reads the rows within 2 dx of its
/// height, weighted by a tent of half-width 2 dx (cut at the floor): the wall's load alternates
/// between neighbouring rows (the particles' lattice against the nodes; test
/// ColliderLoads.AWallPanelOnAJetsAxis...), and a tent two rows wide cancels that alternation at
/// any offset of the sensor from the rows.
struct WallRows {
  double dx, depth, pScale;
  int top;
  std::vector<size_t> panel = {};       ///< collider index of row j
  std::vector<double> impulse = {}, window = {}; ///< per row: normal impulse since the last take, and in the window
  double windowTime = 0;

  std::string panels() const {
    std::string toml;
    for (int j = 0; j <= top; ++j)
      toml += format("[[panels]]\nname = \"row%d\"\nface = \"x_max\"\nmin = [0, -1, %.9g]\nmax = [0, %.9g, %.9g]\n", j,
                     (j - 0.25) * dx, depth + 1, (j + 0.25) * dx);
    return toml;
  }
  void find(const Simulation& sim) {
    for (int j = 0; j <= top; ++j)
      for (size_t k = 0; k < sim.colliders().size(); ++k)
        if (sim.colliders()[k]->name() == format("row%d", j)) panel.push_back(k);
    impulse.assign(panel.size(), 0.0), window.assign(panel.size(), 0.0);
  }
  void add(const Simulation& sim, double dt) {
    for (size_t j = 0; j < panel.size(); ++j) impulse[j] += dt * sim.colliderLoads()[panel[j]].force.x();
  }
  /// P = p / (rho g H) at height z from per-row impulses over `span` seconds.
  double pressure(const std::vector<double>& imp, double span, double z) const {
    double sum = 0, weights = 0;
    for (size_t j = 0; j < imp.size(); ++j) {
      const double w = 1 - std::abs(double(j) * dx - z) / (2 * dx);
      if (w > 0) sum += w * imp[j], weights += w;
    }
    return span > 0 && weights > 0 ? sum / weights / span / (dx * depth) / pScale : 0.0;
  }
  /// The pressure at z since the last take; the impulses go into the window when `inWindow`.
  double take(double span, double z, bool inWindow) {
    const double P = pressure(impulse, span, z);
    if (inWindow) {
      for (size_t j = 0; j < impulse.size(); ++j) window[j] += impulse[j];
      windowTime += span;
    }
    impulse.assign(impulse.size(), 0.0);
    return P;
  }
  double windowPressure(double z) const { return pressure(window, windowTime, z); }
};

/// Mean pressure (Pa) of the particles beyond x0 within dx/2 of height z (world frame): the cell
/// sensor.
double wallCellPressure(const Simulation& sim, double x0, double z, double dx) {
  const double ox = sim.settings().origin.x(), oz = sim.settings().origin.z();
  std::vector<float> pressure;
  double sum = 0;
  size_t n = 0;
  for (const auto* grp : sim.groups()) {
    grp->scalar("pressure", pressure);
    for (size_t p = 0; p < grp->size(); ++p) {
      const Vec3 x = grp->particles.x[p];
      if (double(x.x()) + ox >= x0 && std::abs(double(x.z()) + oz - z) <= 0.5 * dx) sum += pressure[p], ++n;
    }
  }
  return n ? sum / double(n) : 0.0;
}

/// WallImpactResult's level comparison from its levels, sampled every 0.01 in T from 0.
void compareLevels(WallImpactResult& res) {
  using namespace lobovsky;
  const int every = int(std::lround(kStepT / 0.01));
  for (size_t k = 0; k < res.level.size(); ++k) {
    double num = 0, den = 0, spread = 0, mean = 0, meanExp = 0, n = 0;
    std::vector<double> lateT, late, lateExp; // from kReturnFrom: the wave the wall throws back
    for (int i = 0; i < kSamples && size_t(i * every) < res.level[k].size(); ++i) {
      const double h = res.level[k][size_t(i * every)], hExp = kLevel[k][i], T = i * kStepT;
      if (T <= kSheetUntilT + 1e-9) num += std::abs(h - hExp), den += hExp, spread += kSpread[k][i];
      if (WallImpactResult::inPlateau(T)) mean += h, meanExp += hExp, n += 1;
      if (T >= WallImpactResult::kReturnFrom - 1e-9) lateT.push_back(T), late.push_back(h), lateExp.push_back(hExp);
    }
    res.levelError.push_back(den > 0 ? num / den : 0.0);
    res.levelErrorExp.push_back(den > 0 ? spread / den : 0.0);
    res.levelMean.push_back(n > 0 ? mean / n : 0.0), res.levelMeanExp.push_back(n > 0 ? meanExp / n : 0.0);
    auto wave = [&](const std::vector<double>& v) {
      return WallImpactResult::Return{firstAbove(lateT, v, WallImpactResult::kReturnLevel),
                                      v.empty() ? 0.0 : *std::max_element(v.begin(), v.end())};
    };
    res.back.push_back(wave(late)), res.backExp.push_back(wave(lateExp));
  }
}

} // namespace

DamBreakResult damBreak(const Resolution& r) {
  // a = 0.1 m (Froude scaling), two cells across the flume, water softened to c = 30 m/s
  // (ten times the peak speed 2 sqrt(2 g a)); the flume is long enough for Z = 9.
  const double a = 0.1, dx = a / r.cells, depth = 2 * dx, zMax = FrontComparison::kSpeedZ[1];
  const std::string toml = waterColumnScene(dx, Vec3d((zMax + 1) * a, depth, 0.25), Vec3d(a, depth, 2 * a),
                                            r.soundSpeed > 0 ? r.soundSpeed : 30);
  DamBreakResult res;
  auto sim = build(toml, r, res);
  const auto t0 = Clock::now();
  const double tScale = std::sqrt(2 * 9.81 / a);
  // Front: water at least 0.025 a thick (one particle spacing at a/dx = 20, 1.4 mm at the
  // experiment's scale), in bins of one particle spacing, across gaps of up to a cell (water a
  // cell apart still shares grid nodes; late in the run the thin sheet has such holes).
  const double spacing = dx / std::cbrt(double(r.particlesPerCell));
  for (int i = 0;; ++i) {
    const double T = 0.05 * i;
    sim->advanceTo(T / tScale);
    res.T.push_back(T);
    res.Z.push_back(contiguousFront(*sim, spacing, depth, 0.025 * a, dx) / a);
    if ((T >= 3.2 && res.Z.back() > zMax + 0.2) || T >= 12) break;
  }
  finish(*sim, t0, res);
  return res;
}

FrontComparison compareFront(const DamBreakResult& run, const std::string& dataFile) {
  FrontComparison c;
  std::vector<double> Te, Ze;
  for (const auto& [T, Zexp] : readPairs(dataFile)) {
    Te.push_back(T), Ze.push_back(Zexp);
    if (T > 3.0) continue;
    c.T.push_back(T), c.Z.push_back(interpolate(run.T, run.Z, T)), c.Zexp.push_back(Zexp);
  }
  for (size_t i = 0; i < c.T.size(); ++i) {
    const double e = std::abs(c.Z[i] / c.Zexp[i] - 1);
    c.meanRelError += e / double(c.T.size());
    c.maxRelError = std::max(c.maxRelError, e);
  }
  const auto [lo, hi] = FrontComparison::kSpeedZ;
  c.frontSpeed = slopeWhere(run.T, run.Z, lo, hi, nullptr);
  c.frontSpeedExp = slopeWhere(Te, Ze, lo, hi, &c.speedPointsExp);
  return c;
}

WallImpactResult wallImpact(const std::string& pressureFile, const Resolution& r) {
  const auto data = readPairs(pressureFile);
  // H = 0.6 m as in Marrone et al. The tank is 3 H tall so the run-up jet stays inside.
  const double H = 0.6, dx = H / r.cells, depth = 2 * dx, length = 5.366 * H, g = 9.81;
  const double tScale = std::sqrt(g / H), zSensor = 0.2592 * H;
  WallRows rows{dx, depth, 1000 * g * H, int(std::ceil(std::max(zSensor + 2 * dx, 0.3 * H) / dx))};
  const std::string toml = waterColumnScene(dx, Vec3d(length, depth, 3 * H), Vec3d(2 * H, depth, H),
                                            r.soundSpeed > 0 ? r.soundSpeed : 200) + rows.panels();
  WallImpactResult res;
  auto sim = build(toml, r, res);
  rows.find(*sim);
  // Lobovsky et al.'s gauges: the water column in a footprint a cell wide across the flume.
  std::vector<GaugeSpec> gauges;
  for (double x : lobovsky::kGaugeX) gauges.push_back({format("H%g", x), Eigen::Vector2d(x * H, 0.5 * depth), dx});
  WaterGauges levels(gauges, {"water"}, dx / std::cbrt(double(r.particlesPerCell)));
  levels.onStart(*sim);
  res.level.resize(gauges.size());
  const auto t0 = Clock::now();
  double tLast = 0, wallsImpulse = 0, largest = 0; // every collider's x impulse; the largest x momentum
  const double momentum0 = sim->linearMomentum().x();
  auto onStep = [&] {
    const double dt = sim->time() - tLast;
    tLast = sim->time();
    rows.add(*sim, dt);
    for (const ColliderLoad& l : sim->colliderLoads()) wallsImpulse += dt * l.force.x();
    largest = std::max(largest, std::abs(sim->linearMomentum().x()));
  };
  for (int i = 0; 0.01 * i <= 7.5 + 1e-9; ++i) { // the plateau window ends at 5, the levels' record at 7.5
    const double T = 0.01 * i, tStart = sim->time();
    sim->advanceTo(T / tScale, onStep);
    res.wall.P.push_back(rows.take(sim->time() - tStart, zSensor, WallImpactResult::inPlateau(T) && T > 3.5 + 1e-9));
    res.T.push_back(T), res.cell.P.push_back(wallCellPressure(*sim, length - dx, zSensor, dx) / rows.pScale);
    const std::vector<double> d = levels.depths(*sim);
    for (size_t k = 0; k < d.size(); ++k) res.level[k].push_back(d[k] / H);
  }
  for (size_t k = 0; k < std::size(lobovsky::kSensorZ); ++k)
    res.profile.push_back(rows.windowPressure(lobovsky::kSensorZ[k] * H));
  finish(*sim, t0, res);
  // The loads are what the colliders took from the water: the x momentum it lost.
  const double lost = momentum0 - sim->linearMomentum().x();
  res.momentumImbalance = std::abs(wallsImpulse - lost) / std::max(largest, 1e-30);
  for (double m : sim->massRemoved()) res.massRemoved += m;
  const int half = int(std::lround(0.5 * WallImpactResult::kFilterT / 0.01));
  for (PressureSignal* s : {&res.wall, &res.cell}) {
    const int count = int(s->P.size());
    s->PFiltered = movingAverage(s->P, half);
    double plateauN = 0;
    for (int i = 0; i < count; ++i) {
      const double T = res.T[size_t(i)], P = s->PFiltered[size_t(i)];
      if (T <= 3.3 && P > s->peak) s->peak = P, s->peakT = T;
      if (s->onsetT == 0 && P >= 0.1) s->onsetT = T;
      if (WallImpactResult::inPlateau(T)) s->plateau += P, plateauN += 1;
    }
    s->plateau /= std::max(1.0, plateauN);
  }
  double plateauExpN = 0;
  for (const auto& [T, P] : data) {
    if (T <= 3.3 && P > res.exp.peak) res.exp.peak = P, res.exp.peakT = T;
    if (res.exp.onsetT == 0 && P >= 0.1) res.exp.onsetT = T;
    if (WallImpactResult::inPlateau(T)) res.exp.plateau += P, plateauExpN += 1;
  }
  res.exp.plateau /= std::max(1.0, plateauExpN);
  compareLevels(res);
  return res;
}

} // namespace talus::validation
