// Back-analysis of an observed event (`talus calibrate`), AvaFrame's ana6Optimisation done on
// Talus's ensemble machinery: runs of the scene at parameters chosen in three phases, each a
// member folder DIR/member_NNN run as an ensemble member (parallel, resumable):
//
//   1. screening (optional, two or more parameters): Morris trajectories (hazard/ensemble_plan.h);
//      parameters whose mean absolute elementary effect on the loss is below `screenKeep` of the
//      largest are fixed at the best screening member's value;
//   2. an initial Latin hypercube over the parameters kept;
//   3. rounds of `batch` members proposed by expected improvement on a Gaussian-process surrogate
//      of the loss (hazard/surrogate_search.h), until `budget` members or until the largest
//      expected improvement is below `eiStop` times the range of the losses seen so far.
//
// The loss is hazard/calibration_loss.h's. The result: the best member's parameters, the
// surrogate's plausible ranges (every parameter value whose predicted loss is within `tolerance`
// of the best), calibration.csv (every member, its parameters, loss terms and loss),
// screening.csv, result.json and the plots of hazard/calibration_plots.h.
//
// Resume: proposals.csv records every member proposed; a re-run with the same settings takes
// the members from it (completed ones are kept, killed ones resumed) before proposing more.
#pragma once

#include "hazard/calibration_loss.h"
#include "hazard/ensemble_plan.h"

#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace talus::calibration {

struct CalibrationSettings {
  std::vector<ensemble::VarySpec> vary;
  size_t screen = 0;       ///< Morris trajectories (0: no screening; ignored for one parameter)
  double screenKeep = 0.1; ///< a parameter is kept when its mu* >= screenKeep x the largest
  size_t initial = 0;      ///< Latin-hypercube members; 0: 2k + 2 (k + 1 after screening), k kept
  size_t budget = 20;      ///< members in all
  size_t batch = 1;        ///< members proposed per round (run at once)
  double tolerance = 0.05; ///< loss above the best within which parameters are plausible
  double eiStop = 1e-3;    ///< stop when EI < eiStop x (largest - smallest loss seen)
  uint64_t seed = 1;
};

struct MemberRequest {
  size_t index = 0;
  std::string dir;                    ///< DIR/member_NNN
  std::vector<std::string> overrides; ///< KEY=VALUE per varied key
};
/// Runs the members (blocking). False when stopped (a signal): the calibration stops after
/// saving what it has.
using MemberRunner = std::function<bool(const std::vector<MemberRequest>&)>;

struct CalibrationResult {
  size_t members = 0;               ///< evaluated (finite loss)
  size_t proposed = 0;
  size_t best = 0;                  ///< member index
  std::vector<double> values;       ///< best parameters
  LossTerms terms;                  ///< of the best member
  std::vector<bool> kept;           ///< per parameter: searched (true) or fixed by screening
  std::vector<double> low, high;    ///< plausible range per parameter (a fixed one: its value)
  double predicted = NAN, sd = NAN; ///< surrogate mean and sd at the best member
  double lastEi = NAN;              ///< expected improvement when the search stopped
  bool stopped = false;             ///< a signal stopped it: run again to continue
  std::vector<std::string> overrides; ///< KEY=VALUE of the best parameters
};

/// Runs the calibration in `dir` (created). `log` (may be null) receives a line per phase and
/// round. Throws InputError when `dir` holds another calibration (other keys, ranges or seed),
/// std::runtime_error when no member completes.
CalibrationResult calibrate(const std::string& dir, const CalibrationSettings& settings, ObservedEvent& event,
                            const MemberRunner& run, FILE* log);

/// The value of unit coordinate u in [low, high] as written to --set (9 significant digits).
std::string parameterText(const ensemble::VarySpec& v, double u);

} // namespace talus::calibration
