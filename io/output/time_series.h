// series.csv: one row every series_interval seconds (and at the end) with time, step size,
// kinetic energy and mass per material, potential energy, mass removed, maximum speed, then the
// discharge of every section, the front of every path and the highest water surface; PNG plots
// of them in plots/ at the end. Rewritten at every frame, so a long run can be watched.
#pragma once

#include "io/output/output_settings.h"
#include "io/output/output_observer.h"
#include "io/output/series_columns.h"

#include <memory>

namespace talus {

struct SeriesTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  /// Index of a column, or -1.
  int column(const std::string& name) const;
};

class TimeSeries final : public OutputObserver {
public:
  /// `particleSpacing` (m) is the default front threshold of paths.
  TimeSeries(std::string outDir, const OutputSettings& settings, double endTime, double particleSpacing);
  ~TimeSeries() override;

  std::string name() const override { return "time_series"; }
  void onStart(const Simulation& sim) override;
  void onStep(const Simulation& sim, double dt) override;
  bool readsEveryStep() const override { return true; }
  /// In parts when no column reads the particles whole (none does now).
  /// By owner when it has probes (Reads::Shared): every process then gets every process's sums
  /// each step and moves its probes alike; only rank 0 makes rows.
  bool partsByOwner() const override { return shared_; }
  void partByOwner(const Simulation& local, const PartBounds& b, int self, std::vector<std::vector<char>>& outs) override;
  bool sharesState() const override { return shared_; }
  void shareState(std::vector<char>& out) const override;
  void takeState(std::string_view in) override;
  void stepLocal(const Simulation& local, double dt) override;
  bool accumulatesOnRanks() const override;
  void ownedResult(bool state, std::vector<char>& out) override;
  void mergeResults(const Simulation& sim, bool state, const std::vector<std::string_view>& others) override;
  void prepareParts(const Simulation& sim) override;
  bool partDue(const Simulation& sim) const override;
  void part(const Simulation& local, const PartBounds& b, bool keep, std::vector<char>& out) override;
  void onStepParts(const Simulation& sim, double dt, const PartBounds& b,
                   const std::vector<std::string_view>& parts) override;
  void onFrame(const Simulation& sim, int index) override;
  void onFinish(const Simulation& sim, bool completed) override;
  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;

  std::vector<std::pair<std::string, std::string>> summary() const override;
  const SeriesTable& table() const { return table_; }
  double interval() const { return interval_; }

private:
  void prepare(const Simulation& sim, bool whole);
  bool sampleDue(const Simulation& sim) const;
  void sample(const Simulation& sim);
  void endSample(const Simulation& sim, std::vector<double>&& row);
  void advanceClock(const Simulation& sim);
  /// The Shared columns' parts, then (`samples`) the Parts columns', each after its length.
  void putParts(const Simulation& local, const PartBounds& b, bool samples, std::vector<char>& out) const;
  void writeCsv();

  std::string outDir_;
  bool plots_;
  double interval_;
  std::vector<std::unique_ptr<SeriesColumns>> columns_;
  class ColliderLoadColumns* loads_ = nullptr; ///< one of columns_, when loads are written
  SeriesTable table_;
  double lastSample_ = 0, nextSample_ = 0, lastDt_ = 0;
  bool shared_ = false; ///< some column is Reads::Shared (a probe)
  bool root_ = false;   ///< makes the rows (onStart ran here: rank 0, or one process)
};

} // namespace talus
