// What com1DFA writes beside its peak files, so that AvaFrame's tools read a Talus run as one of
// theirs (ana3AIMEC's mass analysis, its ordering and filtering of runs by parameter):
//
//   mass_<simName>.txt                 "time, current, entrained, detrained, detrainedTotal,
//                                      stopped", a row every 0.1 s from 0 (com1DFA's mass log,
//                                      read by AIMEC with flagMass = True)
//   configurationFiles/<simName>.ini   the run's configuration as cfgUtils reads it: [GENERAL]
//                                      with com1DFA's names for what Talus has an equivalent of,
//                                      [TALUS] with every scene key after overrides
//
// current: the mass of every particle in the domain except those of [output.maps] erodible
// covers, plus what the covers lost (entrained), plus mass eroded from erodible fields that has
// not yet become a particle; entrained: the covers' and fields' mass entrained since the last row
// (AIMEC sums the column); detrained: what forests detrained since the last row
// (engine/detrainment.h), detrainedTotal: since the start; stopped: 0 (Talus stops no particle).
// A row is the state after the step that reaches its time. Written with the peak files
// ([output] peak_files).
#pragma once

#include "io/output/entrained_mass.h"
#include "io/output/output_observer.h"
#include "io/output/output_settings.h"
#include "io/output/run_context.h"

namespace talus {

class AvaFrameRunFiles final : public OutputObserver {
public:
  AvaFrameRunFiles(std::string outDir, const OutputSettings& settings, const RunContext& run);
  std::string name() const override { return "avaframe_run_files"; }
  void onStart(const Simulation& sim) override;
  void onStep(const Simulation& sim, double dt) override;
  /// In parts (the particles' mass and the erodible covers' columns, io/output/step_parts.h).
  bool readsEveryStep() const override { return true; }
  void prepareParts(const Simulation& sim) override { entrained_.prepareParts(sim); }
  bool partDue(const Simulation& sim) const override;
  void part(const Simulation& local, const PartBounds& b, bool keep, std::vector<char>& out) override;
  void onStepParts(const Simulation& sim, double dt, const PartBounds& b,
                   const std::vector<std::string_view>& parts) override;
  void onFinish(const Simulation& sim, bool completed) override;
  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;

  /// com1DFA's interval between rows of the mass file (s).
  static constexpr double kInterval = 0.1;

private:
  /// A row at `t` from the particles' mass and the covers' entrained mass (EntrainedMassColumns).
  void sample(const Simulation& sim, double t, double particleMass, const std::vector<double>& covers);
  std::string configuration() const;

  std::string outDir_, simName_, simType_, sceneKeys_;
  std::vector<std::string> erodible_;
  double dx_, endTime_;
  EntrainedMassColumns entrained_;
  std::vector<double> rows_; ///< time, current, entrained and detrained so far, per row
  long next_ = 0;            ///< the next row's time in intervals
};

} // namespace talus
