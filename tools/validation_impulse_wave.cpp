// The impulse-wave validation cases: a granular slide into still water in a quasi-2-D flume, its
// largest wave against Heller & Hager (2010), and a slide narrower than a basin, its first crest
// around the impact against Evers et al. (2019). The water surface is read by the run's own wave
// gauges ([[output.gauges]], io/output/water_gauges.h).
#include "tools/validation_cases.h"
#include "tools/validation_support.h"

#include "io/output/water_gauges.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace talus::validation {

namespace {

using namespace detail;

constexpr double kDepth = 0.3, kG = 9.81;
constexpr double kSlideDensity = 1620, kWaterDensity = 1000;
/// Fritz (2002) / Fritz, Hager & Minor (2004): PP-BaSO4 granulate, phi' = 43 degrees, bed friction
/// angle delta = 24 degrees on the ramp.
constexpr double kSlideFrictionAngle = 43, kBedFriction = 0.4452; // tan 24 degrees
/// Gauges from the shoreline: every half depth from X = 1 to X = kLastGauge; the flume runs 5 h
/// beyond the last so the far wall's reflection reaches it after the leading wave has passed.
constexpr double kFirstGauge = 1, kGaugeStep = 0.5, kLastGauge = 15, kFlumeBeyond = 5;

/// The basin: x from the ramp's top to xMax, y from the slip wall at 0 to width, the still-water
/// shoreline at x = shore. The slide spans y in [0, slideWidth]: the flume's whole width, or in a
/// basin half a slide whose other half the wall at y = 0 mirrors.
struct Layout {
  double dx, width, slideWidth, shore, xMax, zMax;
};

std::string flumeScene(const ImpulseWaveCase& c, const Layout& l, double soundSpeed) {
  const double a = c.alphaDeg * M_PI / 180, ca = std::cos(a), sa = std::sin(a);
  const double h = kDepth, s = c.S * h, L = c.slideLength * h, V = c.F * std::sqrt(kG * h);
  // The slide's lower front edge on the still-water line, its body up the ramp: centre =
  // shore - L/2 along the ramp's downslope direction d = (cos a, 0, -sin a) + s/2 along its
  // normal n = (sin a, 0, cos a). A box rotated by +a about y has its x axis along d.
  const double cx = l.shore - 0.5 * L * ca + 0.5 * s * sa, cz = h + 0.5 * L * sa + 0.5 * s * ca;
  return format(R"(
[simulation]
dx = %.9g
end_time = 100
[domain]
min = [0, 0, 0]
max = [%.9g, %.9g, %.9g]
walls = "slip"
z_min = { law = "friction", friction = %.9g }
z_max = "open"
[terrain]
plane = { point = [%.9g, 0, %.9g], normal = [%.9g, 0, %.9g] }
boundary = "friction"
friction = %.9g
[[materials]]
name = "water"
model = "water"
density = %.9g
sound_speed = %.9g
basal = { law = "slip" }
[[materials]]
name = "slide"
model = "drucker_prager"
density = %.9g
youngs_modulus = 1e6
poisson_ratio = 0.3
friction_angle = %.9g
[[bodies]]
material = "water"
shape = "box"
min = [0, 0, 0]
max = [%.9g, %.9g, %.9g]
[[bodies]]
material = "slide"
shape = "box"
center = [%.9g, %.9g, %.9g]
size = [%.9g, %.9g, %.9g]
rotation = [0, %.9g, 0]
velocity = [%.9g, 0, %.9g]
)",
                l.dx, l.xMax, l.width, l.zMax, kBedFriction, l.shore, h, sa, ca, kBedFriction, kWaterDensity,
                soundSpeed, kSlideDensity, kSlideFrictionAngle, l.xMax, l.width, h, cx, 0.5 * l.slideWidth, cz, L,
                l.slideWidth, s, c.alphaDeg, V * ca, -V * sa);
}

/// The leading wave at one gauge from its surface record eta (/h) at times T: its largest crest,
/// the trough after it (down to the next up-crossing) and the zero-up-crossing period around them.
struct GaugeWave {
  double crest = 0, crestT = 0, trough = 0, period = std::numeric_limits<double>::quiet_NaN();
};
GaugeWave leadingWave(const std::vector<double>& T, const std::vector<double>& eta) {
  GaugeWave w;
  size_t ic = eta.size();
  for (size_t i = 0; i < eta.size(); ++i)
    if (std::isfinite(eta[i]) && (ic == eta.size() || eta[i] > eta[ic])) ic = i;
  if (ic == eta.size() || !(eta[ic] > 0)) return w; // never wet, or no crest
  w.crest = eta[ic], w.crestT = T[ic];
  auto crossing = [&](size_t i) { // time where eta passes 0 between samples i-1 and i
    return T[i - 1] + (T[i] - T[i - 1]) * eta[i - 1] / (eta[i - 1] - eta[i]);
  };
  double up0 = std::numeric_limits<double>::quiet_NaN();
  for (size_t i = ic; i > 0; --i)
    if (eta[i - 1] <= 0 && eta[i] > 0) {
      up0 = crossing(i);
      break;
    }
  size_t i = ic;
  while (i < eta.size() && !(eta[i] < 0)) ++i; // the down-crossing
  for (; i < eta.size(); ++i) {
    if (eta[i] > 0 && eta[i - 1] <= 0) { // the next up-crossing ends the wave
      w.period = crossing(i) - up0;
      break;
    }
    if (std::isfinite(eta[i])) w.trough = std::min(w.trough, eta[i]);
  }
  return w;
}

/// The first crest of a surface record (/h): from the first reading above `rise` to the next
/// down-crossing, its largest value and time; zero when the water never rose that far.
GaugeWave firstCrest(const std::vector<double>& T, const std::vector<double>& eta, double rise) {
  GaugeWave w;
  size_t i = 0;
  while (i < eta.size() && !(eta[i] > rise)) ++i;
  for (; i < eta.size() && !(eta[i] <= 0); ++i)
    if (eta[i] > w.crest) w.crest = eta[i], w.crestT = T[i];
  return w;
}

/// Every gauge's record, eta / h every 0.05 in T = t sqrt(g/h).
struct GaugeRecords {
  std::vector<double> T;
  std::vector<std::vector<double>> eta;
};

/// Steps sim to endT, reading the water surface at every gauge (still water: z = h). NaN where
/// slide material lies under the gauge (it reads the slide's bulge with the water on it, not a
/// wave: the experiments' gauges stood beyond the slide's reach) and once `reflected(k, T)` says a
/// wall's reflection may have come back to gauge k. `onStep` runs after every step.
GaugeRecords recordGauges(Simulation& sim, const std::vector<GaugeSpec>& gauges, double spacing, double endT,
                          const std::function<bool(size_t, double)>& reflected, const std::function<void()>& onStep) {
  WaterGauges reader(gauges, {"water"}, spacing), slideReader(gauges, {"slide"}, spacing);
  reader.onStart(sim);
  slideReader.onStart(sim);
  GaugeRecords rec;
  rec.eta.resize(gauges.size());
  const double tScale = std::sqrt(kG / kDepth);
  for (int i = 0; 0.05 * i <= endT; ++i) {
    sim.advanceTo(0.05 * i / tScale, onStep);
    rec.T.push_back(0.05 * i);
    const std::vector<double> z = reader.surfaces(sim), slide = slideReader.surfaces(sim);
    for (size_t k = 0; k < z.size(); ++k) {
      const bool cut = reflected(k, rec.T.back()) || std::isfinite(slide[k]);
      rec.eta[k].push_back(cut ? std::numeric_limits<double>::quiet_NaN() : (z[k] - kDepth) / kDepth);
    }
  }
  return rec;
}

/// The softened water's c. The wave depends on it far beyond the 10 times the flow's speed that
/// serves a dam break: in p09_a45 at h/dx 8 the far-field heights' error against Heller & Hager
/// falls 43 / 30 / 17 / 3.5 % at c = 20 / 40 / 80 / 160 sqrt(gh) (13 to 106 V_s;
/// docs/impulse_waves.md). 160 sqrt(gh) is the default (272 m/s here).
double soundSpeedOf(const Resolution& r, double slideSpeed) {
  return r.soundSpeed > 0 ? r.soundSpeed : std::max(160 * std::sqrt(kG * kDepth), 8 * slideSpeed);
}

} // namespace

double ImpulseWaveCase::M() const { return kSlideDensity * S * slideLength / kWaterDensity; }

double ImpulseWaveCase::P() const {
  return F * std::sqrt(S) * std::pow(M(), 0.25) * std::sqrt(std::cos(6.0 / 7.0 * alphaDeg * M_PI / 180));
}

const std::vector<ImpulseWaveCase>& impulseWaveCases() {
  static const std::vector<ImpulseWaveCase> cases = {
      {"p04_a60", 60, 1.0, 1.0 / 3, 1.5}, // P 0.43
      {"p09_a45", 45, 1.5, 0.4, 2.0},     // P 0.90
      {"p15_a90", 90, 4.0, 0.5, 2.0},     // P 1.50
      {"p29_a30", 30, 3.0, 0.6, 3.0},     // P 2.88
      {"p50_a45", 45, 4.5, 0.8, 3.0},     // P 5.0
  };
  return cases;
}

ImpulseWaveResult impulseWave(const ImpulseWaveCase& c, const Resolution& r) {
  const double h = kDepth, dx = h / r.cells, V = c.F * std::sqrt(kG * h);
  const double a = c.alphaDeg * M_PI / 180, s = c.S * h, L = c.slideLength * h;
  Layout l;
  l.dx = dx, l.width = l.slideWidth = 2 * dx;
  l.shore = L * std::cos(a) + 3 * dx;
  l.xMax = l.shore + (kLastGauge + kFlumeBeyond) * h;
  l.zMax = std::max(h + L * std::sin(a) + s * std::cos(a) + 3 * dx, 4 * h);
  ImpulseWaveResult res;
  res.P = c.P();
  res.soundSpeed = soundSpeedOf(r, V);
  auto sim = build(flumeScene(c, l, res.soundSpeed), r, res);

  std::vector<GaugeSpec> gauges;
  for (double X = kFirstGauge; X <= kLastGauge + 1e-9; X += kGaugeStep) {
    res.X.push_back(X);
    gauges.push_back({format("x%g", X), Eigen::Vector2d(l.shore + X * h, 0.5 * l.width), dx});
  }
  const double water0 = sim->groupSums()[0].mass;

  // Long enough for the leading wave's trough to pass the last gauge (crest near T = X, the
  // trough half a period T_M later).
  const double endT = kLastGauge + 2 + 6 * std::sqrt(res.P);
  const auto t0 = Clock::now();
  // The slide's centroid along the ramp's downslope direction, from its start (-L/2 from the
  // shoreline), and its mean velocity there, every step until it passes the shoreline.
  const Vec3d down(std::cos(a), 0, -std::sin(a));
  double start = std::numeric_limits<double>::quiet_NaN();
  auto onStep = [&] {
    if (res.centroidSpeedRatio > 0) return;
    const ParticleSet& P = sim->groups()[1]->particles;
    double m = 0, along = 0;
    Vec3d mv = Vec3d::Zero();
    for (size_t p = 0; p < P.size(); ++p) {
      m += double(P.mass[p]), mv += double(P.mass[p]) * P.v[p].cast<double>();
      along += double(P.mass[p]) * P.x[p].cast<double>().dot(down);
    }
    if (std::isnan(start)) start = along / m;
    if (along / m - start >= 0.5 * L) res.centroidSpeedRatio = mv.dot(down) / m / V;
  };
  // The far wall's reflection (at X = kLastGauge + kFlumeBeyond) returns to gauge X no sooner than
  // (2 X_wall - X) / 1.3 in T (1.3: a solitary wave of a / h = 0.7 moves at 1.3 sqrt(gh)).
  auto reflected = [&](size_t k, double T) { return T > (2 * (kLastGauge + kFlumeBeyond) - res.X[k]) / 1.3; };
  const GaugeRecords rec =
      recordGauges(*sim, gauges, dx / std::cbrt(double(r.particlesPerCell)), endT, reflected, onStep);
  finish(*sim, t0, res);
  res.lostWater = 1 - sim->groupSums()[0].mass / water0;

  size_t kM = 0;
  for (size_t k = 0; k < gauges.size(); ++k) {
    const GaugeWave w = leadingWave(rec.T, rec.eta[k]);
    res.crest.push_back(w.crest), res.height.push_back(w.crest - w.trough), res.crestT.push_back(w.crestT);
    res.aM = std::max(res.aM, w.crest);
    if (res.height[k] > res.height[kM]) kM = k;
    if (k == kM) res.TM = w.period;
  }
  res.HM = res.height[kM], res.xM = res.X[kM];
  res.aMRef = 4.0 / 9 * std::pow(res.P, 0.8), res.HMRef = 5.0 / 9 * std::pow(res.P, 0.8);
  res.xMRef = 5.5 * std::sqrt(res.P), res.TMRef = 9 * std::sqrt(res.P);
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t k = kM + 1; k < gauges.size(); ++k) {
    const double ref = 0.75 * std::pow(res.P * std::pow(res.X[k], -1.0 / 3), 0.8);
    res.decayError += std::abs(res.height[k] / ref - 1), n += 1;
    const double lx = std::log(res.X[k]), ly = std::log(res.height[k]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  res.decayError = n > 0 ? res.decayError / n : 0.0;
  res.decayExponent = n > 1 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : 0.0;
  return res;
}

ImpulseWave3dResult impulseWave3d(const Resolution& r) {
  // Evers, Heller, Fuchs, Hager & Boes (2019), VAW-Mitteilung 254, Eqs. 3.22-3.31 (spatial case),
  // with alpha_eff = 6 alpha / 7. The configuration lies inside their Table 3-3 ranges: F 2.5
  // (0.4-3.4), S 0.4 (0.15-0.6), M 0.97 (0.25-1.0), V = s L / h^2 0.6 (0.187-0.75), D 1.62
  // (0.59-1.72), B 2 (0.83-5), P 1.39 (0.13-2.08), alpha 45 (30-90), r/h 3-7.5 (1-16).
  const ImpulseWaveCase c{"3d_p14_a45_b2", 45, 2.5, 0.4, 1.5};
  const double B = 2, h = kDepth, dx = h / r.cells, V = c.F * std::sqrt(kG * h);
  const double a = c.alphaDeg * M_PI / 180, cosEff = std::cos(6.0 / 7.0 * a);
  ImpulseWave3dResult res;
  res.P = c.P(), res.B = B;
  res.a0 = 0.20 * std::sqrt(res.P) * std::pow(B, 0.75) * std::pow(cosEff, 0.25);
  res.impactRadius0 = 2.5 * std::pow(res.P * B * cosEff, 0.25);
  res.impactRadius90 = B / 2 + 1.5 * std::pow(res.P * cosEff, 0.25);
  auto impactRadius = [&](double g) {
    const double r0 = res.impactRadius0, r9 = res.impactRadius90;
    return std::sqrt(r0 * r0 * r9 * r9 / (r0 * r0 * std::pow(std::sin(g), 2) + r9 * r9 * std::pow(std::cos(g), 2)));
  };
  // Half the basin: the slip wall at y = 0 mirrors the slide's other half. Gauges at r/h 3-7.5
  // from the impact point (the shoreline on the slide's axis), the walls 1.5 h beyond the last.
  constexpr double kReach = 9;
  Layout l;
  l.dx = dx, l.width = kReach * h, l.slideWidth = 0.5 * B * h;
  l.shore = c.slideLength * h * std::cos(a) + 3 * dx;
  l.xMax = l.shore + kReach * h;
  l.zMax = 4 * h;
  res.soundSpeed = soundSpeedOf(r, V);
  auto sim = build(flumeScene(c, l, res.soundSpeed), r, res);
  std::vector<GaugeSpec> gauges;
  for (double rh : {3.0, 4.5, 6.0, 7.5})
    for (double deg : {0.0, 30.0, 60.0}) {
      const double g = deg * M_PI / 180;
      // On the axis the gauge's footprint (half-width dx) lies against the mirror wall.
      const Eigen::Vector2d at(l.shore + rh * h * std::cos(g), std::max(rh * h * std::sin(g), dx));
      gauges.push_back({format("r%g_g%g", rh, deg), at, dx});
      res.gauges.push_back({rh, deg});
    }
  const double water0 = sim->groupSums()[0].mass;
  const auto t0 = Clock::now();
  // A wall's reflection reaches gauge k no sooner than the path from the impact point to the
  // gauge's mirror image across it, at 1.3 sqrt(gh).
  auto reflected = [&](size_t k, double T) {
    const Eigen::Vector2d p = (gauges[k].point - Eigen::Vector2d(l.shore, 0)) / h;
    const double far = std::hypot(2 * (l.xMax - l.shore) / h - p.x(), p.y());
    const double side = std::hypot(p.x(), 2 * l.width / h - p.y());
    return T > std::min(far, side) / 1.3;
  };
  const GaugeRecords rec =
      recordGauges(*sim, gauges, dx / std::cbrt(double(r.particlesPerCell)), 12, reflected, [] {});
  finish(*sim, t0, res);
  res.lostWater = 1 - sim->groupSums()[0].mass / water0;
  double n[2] = {0, 0};
  for (size_t k = 0; k < gauges.size(); ++k) {
    ImpulseWave3dGauge& gk = res.gauges[k];
    const GaugeWave w = firstCrest(rec.T, rec.eta[k], 0.02);
    gk.crest = w.crest, gk.crestT = w.crestT;
    const double g = gk.gammaDeg * M_PI / 180, rs = gk.r - impactRadius(g); // r* / h
    if (rs <= 0) continue; // inside the impact zone the relations say nothing
    gk.ref = res.a0 * std::exp(-0.4 * std::pow(res.a0, -0.3) * std::sqrt(rs)) *
             std::pow(1 / std::cosh(3.2 * gk.gammaDeg / 90), cosEff * std::exp(-0.15 * std::sqrt(rs)));
    const int i = gk.gammaDeg == 0 ? 0 : 1;
    const double e = std::abs(gk.crest / gk.ref - 1);
    (i == 0 ? res.axisError : res.offAxisError) += e, res.error += e, n[i] += 1;
  }
  res.error /= std::max(n[0] + n[1], 1.0);
  res.axisError /= std::max(n[0], 1.0), res.offAxisError /= std::max(n[1], 1.0);
  return res;
}

} // namespace talus::validation
