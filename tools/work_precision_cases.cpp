#include "tools/work_precision_cases.h"
#include "tools/validation_lobovsky_data.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <tuple>

namespace talus::work_precision {

using namespace validation;

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

namespace {

Point fromCost(double cells, double error, const RunCost& c) {
  return {cells, error, c.wallSeconds, c.particles, c.steps, {}};
}

/// The wall impact's figures against Lobovsky et al. (2014): the levels, the wave thrown back,
/// the wall's pressure profile.
std::string lobovskyDetail(const WallImpactResult& r) {
  std::string d = "; Lobovsky's levels (gauge x/H: error (the records' own), mean h/H at 3.5-5 (exp))";
  for (size_t k = 0; k < r.levelError.size(); ++k)
    d += fmt(" %.2f:", lobovsky::kGaugeX[k]) + fmt(" %.3f", r.levelError[k]) + fmt(" (%.3f)", r.levelErrorExp[k]) +
         fmt(", %.3f", r.levelMean[k]) + fmt(" (%.3f)", r.levelMeanExp[k]);
  d += "; the wave thrown back (gauge: T at h/H 0.4, highest h/H (exp))";
  for (size_t k = 1; k < r.back.size(); ++k)
    d += fmt(" %.2f:", lobovsky::kGaugeX[k]) + fmt(" %.2f", r.back[k].T) + fmt(" (%.2f)", r.backExp[k].T) +
         fmt(", %.3f", r.back[k].peak) + fmt(" (%.3f)", r.backExp[k].peak);
  d += "; wall pressure at 3.5-5 (Lobovsky) by z/H:";
  for (size_t k = 0; k < r.profile.size(); ++k)
    d += fmt(" %.3g", lobovsky::kSensorZ[k]) + fmt(": %.3f", r.profile[k]) + fmt(" (%.3f)", lobovsky::kSensorPlateau[k]);
  return d;
}

/// Analytic mechanics: a sliding block and an elastic bar.
void mechanicsCases(std::vector<Case>& c) {
  c.push_back({"sliding_block", "block on a 30° plane turned 20° off the axes, Coulomb μ = 0.3, gravity ramped over 0.2 s",
               "max |s/s_exact − 1| once s > 0.1 m (half the block height)", "cells across the 0.2 m block height",
               [](const Resolution& res) {
                 const auto r = slidingBlock(0.3, res, 0.9, 0.2);
                 return fromCost(res.cells, r.maxRelErrorBeyond(0.1), r);
               },
               {2, 4, 8, 16},
               {2, 4}});
  c.push_back({"elastic_bar", "fixed–free elastic bar, first mode", "|T/(4L/c) − 1|", "cells along the bar",
               [](const Resolution& res) {
                 const auto r = elasticBar(res);
                 return fromCost(res.cells, std::abs(r.relError), r);
               },
               {8, 16, 32, 64},
               {8, 16}});
}

/// Dam breaks against Koshizuka & Oka, Martin & Moyce and Buchner (data in ../shared).
void damBreakCases(std::vector<Case>& c, const std::string& shared) {
  const std::string dir = shared + "/validation/dam_break/";
  // One run per resolution serves both comparisons (its wall time is reported with each).
  auto runs = std::make_shared<std::map<std::tuple<double, int, double, double, bool>, DamBreakResult>>();
  auto damBreakRun = [runs](const Resolution& res) -> const DamBreakResult& {
    const auto key = std::make_tuple(res.cells, res.particlesPerCell, res.cfl, res.flip, res.fbar);
    auto it = runs->find(key);
    if (it == runs->end()) it = runs->emplace(key, damBreak(res)).first;
    return it->second;
  };
  c.push_back({"dam_break", "dam break against Koshizuka & Oka (1996), T ≤ 3",
               "mean |Z/Z_exp − 1| (includes the experiment's late start)", "cells across the column width",
               [dir, damBreakRun](const Resolution& res) {
                 const auto& run = damBreakRun(res);
                 const auto k = compareFront(run, dir + "koshizuka_oka_1996_pysph.csv");
                 Point p = fromCost(res.cells, k.meanRelError, run);
                 p.detail = fmt("max %.3f", k.maxRelError);
                 return p;
               },
               {10, 20, 40},
               {10}});
  c.push_back({"dam_break_speed", "dam-break front speed dZ/dT (2 ≤ Z ≤ 8) against Martin & Moyce (1952)",
               "|dZ/dT / (dZ/dT)_exp − 1|", "cells across the column width",
               [dir, damBreakRun](const Resolution& res) {
                 const auto& run = damBreakRun(res);
                 const auto m = compareFront(run, dir + "martin_moyce_1952_n2eq2_a2.25in_pysph.csv");
                 Point p = fromCost(res.cells, std::abs(m.frontSpeed / m.frontSpeedExp - 1), run);
                 p.detail = fmt("dZ/dT %.3f", m.frontSpeed) + fmt(" (%.3f)", m.frontSpeedExp);
                 return p;
               },
               {10, 20, 40},
               {10}});
  c.push_back({"wall_impact", "dam break onto a wall, sensor P1 against Buchner (2002), c = 200 m/s",
               "|P_peak/P_peak,exp − 1| of the impact (T ≤ 3.3) from the wall's load at P1's height ([[panels]]), 0.2 moving average", "cells across the column height H",
               [dir](const Resolution& res) {
                 const auto r = wallImpact(dir + "buchner2002_pressure_P1_trixiparticles.csv", res);
                 Point p = fromCost(res.cells, std::abs(r.wall.peak / r.exp.peak - 1), r);
                 for (const auto& [name, s] : {std::pair{"wall", &r.wall}, std::pair{"; cell", &r.cell}})
                   p.detail += name + fmt(": onset T %.2f", s->onsetT) + fmt(", peak %.3f", s->peak) +
                               fmt(" at %.2f", s->peakT) + fmt(", plateau %.3f", s->plateau);
                 p.detail += fmt(" (Buchner onset %.2f", r.exp.onsetT) + fmt(", peak %.3f", r.exp.peak) +
                             fmt(" at %.2f", r.exp.peakT) + fmt(", plateau %.3f)", r.exp.plateau);
                 p.detail += lobovskyDetail(r);
                 return p;
               },
               {10, 20, 30},
               {10}});
}

/// Slides into still water against Heller & Hager (2010) and Evers et al. (2019).
void waveCases(std::vector<Case>& c) {
  // At two resolutions 1.5 apart.
  for (const ImpulseWaveCase& w : impulseWaveCases())
    c.push_back({std::string("impulse_wave_") + w.name,
                 fmt("granular slide into water (P = %.2f", w.P()) + fmt(", α = %g°) against Heller & Hager (2010)", w.alphaDeg),
                 "|a_M / (4/9 P^0.8) − 1|, the largest crest over the gauges at x/h = 1–15", "cells across the water depth h",
                 [w](const Resolution& res) {
                   const auto r = impulseWave(w, res);
                   Point p = fromCost(res.cells, std::abs(r.aM / r.aMRef - 1), r);
                   p.detail = fmt("P %.3f", r.P) + fmt(", c %.0f m/s", r.soundSpeed) + fmt(": a_M/h %.3f", r.aM) + fmt(" (%.3f)", r.aMRef) +
                              fmt(", H_M/h %.3f", r.HM) + fmt(" (%.3f)", r.HMRef) + fmt(", x_M/h %.1f", r.xM) +
                              fmt(" (%.1f)", r.xMRef) + fmt(", T_M %.1f", r.TM) + fmt(" (%.1f)", r.TMRef) +
                              fmt(", decay beyond x_M %.3f", r.decayError) + fmt(" (exponent %.3f, H&H -0.267)", r.decayExponent) +
                              fmt(", V at centroid impact / V_s %.3f", r.centroidSpeedRatio) + fmt(", water lost %.4f", r.lostWater) +
                              "; crest a/h at X = 3, 5, 8, 12:";
                   for (size_t k = 0; k < r.X.size(); ++k)
                     if (r.X[k] == 3 || r.X[k] == 5 || r.X[k] == 8 || r.X[k] == 12) p.detail += fmt(" %.3f", r.crest[k]);
                   return p;
                 },
                 {8, 12},
                 {8}});
  // The spatial case: a slide narrower than the basin against Evers et al. (2019).
  c.push_back({"impulse_wave_3d", "granular slide two depths wide into a basin (P = 1.39, α = 45°) against Evers et al. (2019)",
               "mean |a_c1 / a_c1,ref − 1| over the gauges at r/h = 3–7.5, γ = 0, 30, 60° beyond the impact zone",
               "cells across the water depth h",
               [](const Resolution& res) {
                 const auto r = impulseWave3d(res);
                 Point p = fromCost(res.cells, r.error, r);
                 p.detail = fmt("P %.3f", r.P) + fmt(", c %.0f m/s", r.soundSpeed) + fmt(", a_0,c1/h %.3f", r.a0) +
                            fmt(", r_0/h %.2f", r.impactRadius0) + fmt(" (γ 0), %.2f (90)", r.impactRadius90) +
                            fmt("; error on the axis %.3f", r.axisError) + fmt(", off it %.3f", r.offAxisError) +
                            fmt(", water lost %.4f", r.lostWater) + "; a_c1/h (ref) at r/h, γ:";
                 for (const auto& g : r.gauges)
                   p.detail += fmt(" %g", g.r) + fmt("/%g°", g.gammaDeg) + fmt(" %.3f", g.crest) + fmt(" (%.3f)", g.ref);
                 return p;
               },
               {4, 6},
               {4}});
}

/// A dam break onto a box against MARIN's depths and load (Kleefsman et al. 2005).
void obstacleCase(std::vector<Case>& c) {
  c.push_back({"obstacle_impact", "dam break onto a box: water depths at four gauges, 0–6 s, against Kleefsman et al. (2005)",
               "mean over the gauges of Σ|d − d_exp| / Σ d_exp (every 0.05 s)", "cells across the water depth 0.55 m",
               [](const Resolution& res) {
                 const auto r = obstacleImpact(res);
                 double mean = 0;
                 for (double e : r.depthError) mean += e / double(r.depthError.size());
                 Point p = fromCost(res.cells, mean, r);
                 p.detail = fmt("c %.0f m/s; per gauge (x m: error, arrival s (exp))", r.soundSpeed);
                 for (size_t k = 0; k < r.depthError.size(); ++k)
                   p.detail += fmt(" %g:", ObstacleImpactResult::gaugeX()[k]) + fmt(" %.3f", r.depthError[k]) +
                               fmt(", %.2f", r.arrival[k]) + fmt(" (%.2f)", r.arrivalExp[k]);
                 p.detail += fmt("; box load: peak %.0f N", r.peak) + fmt(" at %.2f s", r.peakT) +
                             fmt(" (%.0f N", r.peakExp) + fmt(" at %.2f s)", r.peakTExp) +
                             fmt(", 0.6–1.0 s %.0f N", r.plateau) + fmt(" (%.0f N)", r.plateauExp) +
                             fmt("; water lost %.4f", r.lostWater) + fmt(", momentum balance %.1e", r.momentumImbalance);
                 // The flow arriving in front of the box (gauge 1), before it feels the box.
                 p.detail += fmt("; at %g m, m (MARIN):", ObstacleImpactResult::gaugeX()[1]);
                 for (double t : {0.40, 0.45, 0.50, 0.60, 0.75, 1.00}) {
                   const auto i = size_t(std::lround(t / ObstacleImpactResult::kSample));
                   if (i < r.depth[1].size())
                     p.detail += fmt(" %.3f", r.depth[1][i]) +
                                 fmt(" (%.3f)", r.depthExp[1][i / ObstacleImpactResult::kDepthEvery]);
                 }
                 return p;
               },
               {10, 15, 20},
               {10}});
  c.back().scene = obstacleSceneText; // box_edges.sh varies it
}

/// Planar granular collapses against Lube et al. (2005).
void collapseCases(std::vector<Case>& c) {
  // Planar collapses at the aspect ratios of issue 14, rate-independent and mu(I).
  for (const auto& [modelName, suffix] :
       {std::pair{GranularModel::DruckerPrager, ""}, std::pair{GranularModel::MuI, "_mu_i"}})
    for (const double a : {0.5, 2.0, 5.0, 10.0}) {
      const GranularModel model = modelName; // a structured binding cannot be captured in C++17
      const bool tall = a > 5;
      c.push_back({fmt("column_collapse_a%g", a) + suffix,
                   fmt("granular column collapse (a = %g", a) + (*suffix ? ", μ(I)" : ", Drucker–Prager") +
                       ") against Lube et al. (2005)",
                   a < 1.8 ? "|run-out / 1.2a − 1|"
                   : a > 2.8 ? "|run-out / 1.9a^(2/3) − 1|"
                             : "distance from Lube's band [1.2a, 1.9a^(2/3)] relative to its nearer edge",
                   "cells across the column length L0",
                   [a, model](const Resolution& res) {
                     const auto r = columnCollapse(a, res, model);
                     Point p = fromCost(res.cells, std::abs(r.relError), r);
                     p.detail = fmt("run-out %.3g", r.runOut) +
                                (r.lubeLow < r.lubeHigh ? fmt(" (Lube %.3g", r.lubeLow) + fmt("–%.3g", r.lubeHigh)
                                                        : fmt(" (Lube %.3g", r.reference)) +
                                fmt(", Lajeunesse %.3g)", r.lajeunesse) + fmt(", across a cell %.3g", r.runOutAcrossCell) +
                                fmt(", farthest particle %.3g", r.farthest) + fmt(", 99 %% of the volume %.3g", r.runOut99) + fmt(", half a layer %.3g", r.runOutAnyLayer) +
                                fmt("; height %.3g", r.finalHeight) +
                                fmt(" (Lube %.3g)", r.referenceHeight);
                     return p;
                   },
                   tall ? std::vector<double>{8, 12, 16} : std::vector<double>{8, 12, 16, 24},
                   {8}});
    }
}

} // namespace

std::vector<Case> cases(const std::string& shared) {
  std::vector<Case> c;
  mechanicsCases(c);
  if (!shared.empty()) damBreakCases(c, shared);
  waveCases(c);
  obstacleCase(c);
  collapseCases(c);
  return c;
}

} // namespace talus::work_precision
