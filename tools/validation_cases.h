// Validation cases with analytic or published references, runnable at any resolution: the
// test suite runs them at one resolution and asserts tolerances; `talus work-precision` refines
// them to measure error against cost.
#pragma once

#include <string>
#include <vector>

namespace talus::validation {

struct Resolution {
  double cells = 1;  ///< case-specific resolution (cells across the characteristic length)
  int particlesPerCell = 8;
  double cfl = 0.4;
  double flip = 0; ///< AFLIP blend (0: APIC)
  bool fbar = false; ///< F-bar ([simulation] fbar)
  double bedOffset = 0; ///< column collapse: its bed raised by this many cells off the node plane
  double soundSpeed = 0; ///< water cases: the softened water's c (m/s); 0: the case's own
};

/// What every run reports, besides its error.
struct RunCost {
  size_t particles = 0;
  unsigned long long steps = 0;
  double wallSeconds = 0;
};

/// Block on a 30-degree plane turned 20 degrees off the grid axes, Coulomb mu through the
/// terrain SDF. cells = cells across the block's 0.2 m height (2 -> dx 0.1). s_exact =
/// g t^2 (sin - mu cos) / 2, or its integral under the gravity ramp when there is one.
struct SlidingBlockResult : RunCost {
  std::vector<double> t, s, exact; ///< samples every 0.05 s; exact follows the gravity ramp
  /// max |s / exact - 1| once exact > `distance` (m). A fixed distance: one in cells (5 dx)
  /// reaches back into the start-up as dx falls.
  double maxRelErrorBeyond(double distance) const;
  double restDisplacement = 0;     ///< |s| at the end when the block should stay (mu > tan)
  double restSpeed = 0;
};
SlidingBlockResult slidingBlock(double mu, const Resolution& r, double endTime = 0.9, double gravityRamp = 0);

/// Fixed-free elastic bar (L = 1 m, nu = 0), first mode excited. cells = cells along the bar.
/// Error: |T / (4L/c) - 1|.
struct ElasticBarResult : RunCost {
  double period = 0, exact = 0, relError = 0;
};
ElasticBarResult elasticBar(const Resolution& r);

/// Dam break of a water column twice as high as wide (n^2 = 2), quasi-2-D, in Martin & Moyce's
/// normalisation (T = t sqrt(2g/a), Z = z/a). cells = cells across the column width a.
struct DamBreakResult : RunCost {
  std::vector<double> T, Z;  ///< the surge front every 0.05 in T, until Z > 8.2
};
DamBreakResult damBreak(const Resolution& r);
/// A dam break's front against a digitised surge front in the same normalisation: Martin & Moyce
/// (1952) or Koshizuka & Oka (1996), same geometry.
struct FrontComparison {
  std::vector<double> T, Z, Zexp;  ///< at the data's instants with T <= 3
  double meanRelError = 0, maxRelError = 0;
  /// Front speed dZ/dT, least squares over the samples with kSpeedZ[0] <= Z <= kSpeedZ[1], of
  /// the simulation and of the data: a start-up lag shifts Z(T) in T but not this slope.
  static constexpr double kSpeedZ[2] = {2.0, 8.0};
  double frontSpeed = 0, frontSpeedExp = 0;
  size_t speedPointsExp = 0;  ///< data points inside the fit's range (0: no speed to compare)
};
FrontComparison compareFront(const DamBreakResult& run, const std::string& dataFile);
/// Dam break onto a wall in Marrone et al. (2011)'s layout of Buchner (2002)'s experiment: a
/// column H high and 2H wide at one end of a tank 5.366 H long; the pressure at sensor P1 on
/// the far wall (centred 0.2592 H above the floor) as P = p / (rho g H) against T = t sqrt(g/H).
/// cells = cells across H. Two sensors: `wall`, the force the water puts on the far wall's node
/// rows within 2 dx of P1's height ([[panels]], each row's normal force over its dx x depth,
/// weighted by a tent of half-width 2 dx; a transducer measures the force on its membrane too),
/// and `cell`, the mean pressure of the particles in the cell next to the wall
/// within dx/2 of that height (noisy: fewer particles, closer to the wall as dx shrinks). Each
/// is averaged over 0.01 in T, then filtered by a centred moving average over kFilterT (49 ms at
/// H = 0.6 m; the digitised data are smooth at that scale, the impact rising over 0.3).
/// The softened water's c is r.soundSpeed, or 200 m/s (40 times the front's 2 sqrt(gH)); the
/// real 1480 m/s would need 7 times more steps.
struct PressureSignal {
  std::vector<double> P, PFiltered;  ///< every 0.01 in T
  double onsetT = 0;                 ///< the first T with P >= 0.1
  double peak = 0, peakT = 0;        ///< the impact: filtered maximum for T <= 3.3
  double plateau = 0;                ///< mean over 3.5 <= T <= 5 (the run-up's weight)
};
struct WallImpactResult : RunCost {
  static constexpr double kFilterT = 0.2;
  /// The plateau's window 3.5 <= T <= 5 (within rounding of the 0.01 samples).
  static bool inPlateau(double T) { return T >= 3.5 - 1e-9 && T <= 5 + 1e-9; }
  std::vector<double> T;
  PressureSignal wall, cell;          ///< the two sensors (above)
  PressureSignal exp;                 ///< the digitised data (onset, peak, plateau; P and PFiltered empty)
  /// Momentum balance over the run: the impulse every collider took along x against the x
  /// momentum the water lost, |difference| over the largest momentum the water had (no particle
  /// may leave without loading a wall), and the mass culled (kg).
  double momentumImbalance = 0, massRemoved = 0;
  /// The water levels at Lobovsky et al. (2014)'s four gauges in the same layout
  /// (tools/validation_lobovsky_data.h): per gauge, h/H every 0.01 in T (the water column in a
  /// footprint a cell wide); Σ|h − h_exp| / Σ h_exp over the experiment's samples (every 0.1,
  /// T ≤ 5.2, the sheet before the wall's wave returns); and the mean h/H over the plateau's
  /// window 3.5 ≤ T ≤ 5, the run's and the experiment's (the flow arriving at the wall: gauge 4
  /// stands 0.83 H before it).
  std::vector<std::vector<double>> level;
  std::vector<double> levelError, levelMean, levelMeanExp;
  std::vector<double> levelErrorExp; ///< per gauge: the experiment's own, its records' half difference the same way
  /// The wave the far wall throws back, per gauge from T = kReturnFrom: when the level first
  /// exceeds kReturnLevel (linear between samples; -1: not by 7.5) and its highest level.
  static constexpr double kReturnFrom = 5.5, kReturnLevel = 0.4;
  struct Return {
    double T = -1, peak = 0;
  };
  std::vector<Return> back, backExp;
  /// The wall's pressure over 3.5 <= T <= 5 at Lobovsky et al.'s four sensor heights (kSensorZ),
  /// read from the wall's node rows as the wall sensor is.
  std::vector<double> profile;
};
WallImpactResult wallImpact(const std::string& pressureFile, const Resolution& r);
/// Quasi-2-D granular column collapse (phi 32, rough bed mu 0.625) of a column a L0 high and L0
/// long, run-out (L_inf - L0)/L0 against Lube et al. (2005): 1.2 a for a < 1.8, 1.9 a^(2/3)
/// for a > 2.8 and between the two laws in their transition; Lajeunesse et al. (2005), as
/// consolidated by Lagree, Staron & Popinet (2011): 1.8 a below their transition, 2.3 a^(2/3)
/// above (the smaller of the two). Final height H_inf/L0 against Lube's a for a <= 1.15,
/// a^(2/5) above. cells = cells across L0.
enum class GranularModel {
  DruckerPrager, ///< rate-independent, plane-strain cone
  MuI,           ///< mu(I): mu_s = tan 32, mu_2 = tan 44 (Jop's 12-degree span), I0 0.279, d 1 mm
};
struct ColumnCollapseResult : RunCost {
  double runOut = 0;        ///< from the continuous deposit (>= 0.025 L0 thick, no gap)
  double reference = 0;     ///< Lube's law (the middle of its band in the transition)
  double lubeLow = 0, lubeHigh = 0; ///< Lube's band: equal outside the transition 1.8 < a < 2.8
  double relError = 0;      ///< signed distance from Lube's band, relative to its nearer edge
  double lajeunesse = 0;    ///< the second law
  double runOutAcrossCell = 0; ///< the same deposit allowing gaps up to a cell (measure study)
  double farthest = 0;      ///< farthest particle, (x_max - L0)/L0: what a threshold-free measure gives
  double runOutAnyLayer = 0; ///< the continuous deposit at least half a particle layer thick (any dx)
  double runOut99 = 0;      ///< (x_99 - L0)/L0, 99 % of the deposit's volume behind x_99: blind to stray fragments
  double finalHeight = 0, referenceHeight = 0; ///< H_inf/L0: the thickest cell-wide bin; Lube's law
  double finalRmsSpeed = 0, collapseSpeedScale = 0;
};
ColumnCollapseResult columnCollapse(double aspect, const Resolution& r, GranularModel model = GranularModel::DruckerPrager);

/// A granular slide into still water in a quasi-2-D flume (Fritz, Hager & Minor 2004's set-up):
/// the largest wave against Heller & Hager (2010, VAW-Mitteilung 211; J. Waterway Port Coastal
/// Ocean Eng. 136(3):145), whose impulse product P = F S^(1/2) M^(1/4) cos(6 alpha / 7)^(1/2),
/// F = V_s / sqrt(g h), S = s / h, M = m_s / (rho_w b h^2), predicts a_M / h = 4/9 P^0.8,
/// H_M / h = 5/9 P^0.8, x_M / h = 11/2 P^(1/2), T_M sqrt(g / h) = 9 P^(1/2) and beyond x_M
/// H / h = 3/4 (P X^(-1/3))^0.8. Water h = 0.3 m; the slide a rectangle of thickness s and length
/// L_s along a ramp of angle alpha, its lower front edge at the still-water line, moving at V_s
/// (its centroid's velocity at impact, as Heller & Hager define it); Fritz's PP-BaSO4 granulate:
/// bulk density 1620 kg/m3, friction angle 43 degrees, 24 degrees of bed friction on the ramp and
/// the floor. cells = cells across h.
struct ImpulseWaveCase {
  const char* name;
  double alphaDeg, F, S;
  double slideLength; ///< L_s / h
  /// M and P of the configuration (M from the slide's cross-section: rho_s s L_s / (rho_w h^2)).
  double M() const;
  double P() const;
};
/// The five configurations of `talus work-precision`: P from 0.4 to 5, alpha 30 to 90 degrees,
/// all inside Heller & Hager's ranges (F 0.86-6.83, S 0.09-1.64, M 0.11-10.02, alpha 30-90).
const std::vector<ImpulseWaveCase>& impulseWaveCases();
struct ImpulseWaveResult : RunCost {
  double P = 0, soundSpeed = 0;
  std::vector<double> X;             ///< gauge positions x / h from the still-water shoreline
  std::vector<double> crest, height; ///< per gauge: largest crest a_c / h and leading wave height H / h
  std::vector<double> crestT;        ///< per gauge: T = t sqrt(g/h) of the largest crest
  double aM = 0, HM = 0, xM = 0, TM = 0; ///< simulated (x_M: the gauge of H_M; T_M sqrt(g/h) there)
  double aMRef = 0, HMRef = 0, xMRef = 0, TMRef = 0; ///< Heller & Hager's
  double decayError = 0; ///< mean |H / H_ref(X) - 1| over the gauges beyond x_M
  double decayExponent = 0; ///< least-squares slope of ln H against ln X beyond x_M (H & H: -0.8/3)
  /// The slide's mean velocity when its centroid reaches the still-water shoreline (L_s/2 after
  /// the front did), over V_s: the slide accelerates on the ramp while it enters, and a P taken at
  /// that instant is P times this ratio.
  double centroidSpeedRatio = 0;
  double lostWater = 0;  ///< share of the water's mass that left the domain (splash over the top)
};
/// Runs one configuration; r.soundSpeed overrides the water's c (default max(160 sqrt(gh), 8 V_s)).
ImpulseWaveResult impulseWave(const ImpulseWaveCase& c, const Resolution& r);

/// One gauge of the spatial case (impulseWave3d).
struct ImpulseWave3dGauge {
  double r = 0, gammaDeg = 0; ///< radial distance from the impact point / h, angle off the slide's axis
  double crest = 0, crestT = 0; ///< the first crest a_c1 / h (0: none above 0.02 h) and its T
  double ref = 0;               ///< Evers et al. (2019)'s a_c1 / h there; 0 inside the impact zone
};
struct ImpulseWave3dResult : RunCost {
  double P = 0, B = 0, soundSpeed = 0;
  double a0 = 0; ///< the relations' initial first-crest amplitude a_0,c1 / h
  double impactRadius0 = 0, impactRadius90 = 0; ///< the impact zone's radius r_0 / h at 0 and 90 degrees
  std::vector<ImpulseWave3dGauge> gauges;
  /// Mean |a_c1 / ref - 1| over the gauges beyond the impact zone: all of them, those on the
  /// slide's axis, and those 30 and 60 degrees off it (the wave's spreading).
  double error = 0, axisError = 0, offAxisError = 0;
  double lostWater = 0;
};
/// A granular slide (P 1.39, alpha 45 degrees, F 2.5, S 0.4, M 0.97) two depths wide (B = 2) into
/// a basin 9 h across, mirrored about the slide's axis; the first crest at r/h = 3, 4.5, 6, 7.5
/// and 0, 30, 60 degrees against Evers, Heller, Fuchs, Hager & Boes (2019, VAW-Mitteilung 254),
/// the successor of Heller & Hager's manual. r.cells: cells across the depth h.
ImpulseWave3dResult impulseWave3d(const Resolution& r);

/// Dam break onto a box standing in its way, MARIN's experiment (Kleefsman, Fekken, Veldman,
/// Iwanowski & Buchner 2005, J. Comput. Phys. 206:363; SPHERIC Test 2): 0.55 m of water released
/// down a 3.22 m tank against a box 0.161 m high and 0.403 m wide. The water depth at the four
/// gauges (x = 0.496 m behind the box, 0.992 m in front of it, 1.488 m, and 2.638 m in the
/// reservoir) and the box's horizontal load against the experiment's records
/// (tools/validation_kleefsman_data.h). Half the tank is run, mirrored about its centre line.
/// r.cells: about the cells across the water depth 0.55 m (dx is the half width 0.5 m over the
/// nearest whole number, so the walls lie on node rows); r.soundSpeed: the water's c (default 50 m/s).
struct ObstacleImpactResult : RunCost {
  static constexpr double kSample = 0.01;      ///< s between samples (the load: its mean over each)
  static constexpr int kDepthEvery = 5;         ///< depths are compared every 5th sample (0.05 s)
  static constexpr double kArrivalDepth = 0.01; ///< m: a gauge is reached
  /// The load: a centred moving average of 5 samples (0.05 s), its peak for t <= kImpactEnd and
  /// its mean over kPlateau (the flow pressing on the box before the reflection from the far wall
  /// returns).
  static constexpr int kFilterHalf = 2;
  static constexpr double kImpactEnd = 1.0, kPlateau[2] = {0.6, 1.0};
  static const std::vector<double>& gaugeX(); ///< the gauges' x (m)
  double soundSpeed = 0;
  std::vector<double> t;                           ///< every kSample from 0
  std::vector<std::vector<double>> depth;         ///< per gauge, at t (m)
  std::vector<std::vector<double>> depthExp;      ///< per gauge, every kDepthEvery-th t (m; NaN past the record)
  std::vector<double> depthError;                  ///< per gauge: sum |d - d_exp| / sum d_exp over those
  std::vector<double> arrival, arrivalExp;         ///< per gauge: first t with depth > kArrivalDepth (-1: never)
  std::vector<double> force, forceFiltered;        ///< the box's load along -x (N), whole tank
  std::vector<double> forceExp, forceExpFiltered;  ///< the same from the front face's sensors (N; 0 before the record)
  double peak = 0, peakT = 0, plateau = 0;         ///< of forceFiltered (N, s, N)
  double peakExp = 0, peakTExp = 0, plateauExp = 0; ///< the same from the front face's pressure sensors
  double lostWater = 0;
  /// |every collider's x impulse - the x momentum the water lost| over the largest x momentum it had
  double momentumImbalance = 0;
};
ObstacleImpactResult obstacleImpact(const Resolution& r, double endTime = 6);
/// The scene file obstacleImpact runs at r (its dx and sound speed; r's CFL and particles per
/// cell and the gauges are set by the case, not written here): for studies that vary it with
/// `--set` (tools/studies/box_edges.sh).
std::string obstacleSceneText(const Resolution& r);
/// Fills the comparison fields of `res` from its t, depth and force.
void compareWithExperiment(ObstacleImpactResult& res);

/// A one-cell-thick elastic layer (dx = 5 m, one particle per cell, 5 m thick at z = 500 m) over
/// a layerSide square in a domainSide x domainSide x domainHeight box: what the sparse grid must
/// store in proportion to the layer, not the box (test_sparse_grid, `talus work-precision`).
std::string thinLayerScene(double layerSide, double domainSide, double domainHeight);

} // namespace talus::validation
