// The [ensemble] section of a scene: how `talus ensemble` summarises its members (exceedance
// thresholds, quantiles, the run-out criterion and the path it is measured along). A plain
// `talus run` checks these keys and otherwise ignores them. docs/hazard.md lists them.
#pragma once

#include "io/config/config_table.h"

#include <Eigen/Dense>
#include <map>
#include <string>
#include <vector>

namespace talus {

struct EnsembleSettings {
  /// Exceedance thresholds per AvaFrame result type: P(peak > threshold) maps (AvaFrame's
  /// probAna uses a strict >). Default pft 1 m, ppr 1, 3 and 30 kPa.
  std::map<std::string, std::vector<double>> thresholds{{"pft", {1.0}}, {"ppr", {1.0, 3.0, 30.0}}};
  std::vector<double> quantiles{0.05, 0.5, 0.95};
  std::string runoutResult = "ppr"; ///< AIMEC's runoutResType
  double runoutThreshold = 1.0;     ///< AIMEC's thresholdValue (kPa for ppr)
  std::vector<Eigen::Vector2d> path; ///< the thalweg; empty = no run-out analysis
  double domainWidth = 600;          ///< AIMEC's domainWidth (m)
};

/// Reads [ensemble] (nullptr = defaults); `path` is "file" (a line, relative to the scene) or
/// [[x, y], ...]. Without one, the first [[output.paths]] entry is used. Throws InputError.
EnsembleSettings readEnsembleSettings(const ConfigTable* ensemble, const std::vector<Eigen::Vector2d>& fallbackPath);

} // namespace talus
