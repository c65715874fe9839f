// Loads on colliders in series.csv: for every collider (the terrain, each structure, each
// closed face of the domain) the force and moment the material exerts on it, from the momentum
// its contacts removed each step (engine/grid_update.cpp).
//
// Per row: the mean force and moment over the row's interval (impulse / time, like discharge, so
// no step is missed), its magnitude, and the largest single-step force magnitude in the interval
// (impacts are brief). The run's peak single-step force goes to summary.json. A [[panels]] window
// of a face also reports its normal load as a pressure over its area (Collider::panelArea): the
// mean over the interval and the largest of a step.
#pragma once

#include "io/output/series_columns.h"

namespace talus {

class ColliderLoadColumns final : public SeriesColumns {
public:
  void onStart(const Simulation& sim) override;
  std::vector<std::string> header() const override;
  void onStep(const Simulation& sim, double dt) override;
  Reads reads() const override { return Reads::None; } // rank 0's reduced loads
  void sample(const Simulation& sim, double elapsed, std::vector<double>& row) override;
  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;
  /// {"<collider>": {"peak_force_N": |F|, "time_s": t, "force_N": [Fx, Fy, Fz]}, ...}
  std::string summaryJson() const;

private:
  struct Acc {
    double impulse[6] = {0, 0, 0, 0, 0, 0}; ///< force and moment times time since the last row
    double intervalMax = 0;                  ///< largest |F| of a step since the last row
    double intervalMaxNormal = 0;            ///< a panel: largest normal force of a step since the last row
    double peak = 0, peakTime = 0;           ///< largest |F| of a step in the run, and when
    double peakForce[3] = {0, 0, 0};
  };
  std::vector<std::string> names_;
  std::vector<Acc> acc_;
  /// Per collider: a panel's area (m2) and its normal's axis and sign; area 0 for the others.
  struct Panel {
    double area = 0;
    int axis = 0;
    double sign = 1;
  };
  std::vector<Panel> panels_;
};

} // namespace talus
