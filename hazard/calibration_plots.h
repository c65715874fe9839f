// The pictures of a calibration: the loss surface as the surrogate sees it, one slice per
// searched parameter through the best member (mean, +-2 sd, the members, the plausible level),
// and the best run's footprint against the observed one on AIMEC's path grid.
#pragma once

#include "hazard/calibration_loss.h"
#include "hazard/ensemble_plan.h"
#include "hazard/surrogate_search.h"

#include <string>
#include <vector>

namespace talus::calibration {

struct LossSlices {
  const GaussianProcess* gp = nullptr;
  Eigen::VectorXd best;                  ///< the best member, unit coordinates of the searched parameters
  std::vector<ensemble::VarySpec> specs; ///< the searched parameters, in the surrogate's order
  std::vector<Evaluated> members;        ///< every member (their loss against each parameter)
  double level = 0;                      ///< best loss + tolerance
};

/// DIR/loss_<key>.png per searched parameter (key's '.' as '_'). Throws std::runtime_error when
/// a PNG cannot be written.
void writeLossSlices(const std::string& dir, const LossSlices& slices);

/// `path`: the classes of `event.classes(runDir)` (event only, both, run only) over a hillshade of
/// the path grid, the path running top to bottom. Nothing when the event has no area observation.
void writeRunAgainstEvent(const std::string& path, ObservedEvent& event, const std::string& runDir,
                          const std::string& label);

} // namespace talus::calibration
