// A group of columns of series.csv (energies, a section's discharge, a path's front, ...).
#pragma once

#include "engine/simulation.h"
#include "io/common/names.h"
#include "engine/state_archive.h"
#include "io/output/step_parts.h"

#include <string>
#include <vector>

namespace talus {

class SeriesColumns {
public:
  virtual ~SeriesColumns() = default;
  /// Called once before the first sample; the header may depend on the materials present.
  virtual void onStart(const Simulation& sim) {}
  /// Instead of onStart on a process other than rank 0, with its own particles only: what its
  /// parts need. A Shared column then gets rank 0's state (takeState).
  virtual void prepareParts(const Simulation& local) { onStart(local); }
  /// Column names with their units (valid after onStart).
  virtual std::vector<std::string> header() const = 0;
  /// After every step: accumulate whatever must not be missed between samples.
  virtual void onStep(const Simulation& sim, double dt) {}
  /// Appends this group's values at a sample; `elapsed` is the time since the previous sample
  /// (0 at the first sample).
  virtual void sample(const Simulation& sim, double elapsed, std::vector<double>& row) = 0;
  /// How sample() reads the particles (every column chooses; none reads them all in one place).
  /// Parts: only through part() on each process and
  /// sampleParts() merging them exactly (io/output/step_parts.h). Shared: a state that moves
  /// every step by exact sums over every particle (a probe): every process sends its sums to
  /// every process (sharedPart) and each moves its copy alike (sharedStep); sample() reads that
  /// state. None: not at all (figures rank 0 holds itself, such as the collider loads; onStep
  /// must read no particles either).
  enum class Reads { Parts, Shared, None };
  virtual Reads reads() const = 0;
  /// Reads::Parts: this process's contribution from its own particles.
  virtual void part(const Simulation& local, const PartBounds& b, std::vector<char>& out) const {}
  /// Reads::Parts and None: the sample from every process's part (rank order). None: sample().
  virtual void sampleParts(const Simulation& sim, double elapsed, const PartBounds& b,
                           const std::vector<std::string_view>& parts, std::vector<double>& row) {
    sample(sim, elapsed, row);
  }
  /// Reads::Shared, every step on every process: this process's sums from its own particles,
  /// then the step from every process's (rank order), the same on every process.
  virtual void sharedPart(const Simulation& local, const PartBounds& b, std::vector<char>& out) const {}
  virtual void sharedStep(const Simulation& sim, double dt, const PartBounds& b,
                          const std::vector<std::string_view>& parts) {}
  /// Reads::Shared: rank 0's state for the other processes, after the start or a resume.
  virtual void shareState(std::vector<char>& out) const {}
  virtual void takeState(std::string_view in) {}
  /// Reads::Parts columns that must see every step, not only the sampled ones (a section's
  /// crossings): after every step, on every process with its own particles (one process: all of
  /// them), before any part. What it adds up stays on that process for its part().
  virtual void stepLocal(const Simulation& local, double dt) {}
  /// Whether stepLocal adds up a running total. Under ranks, before rank 0 saves a checkpoint or
  /// writes the end, every other process hands its total over (handOver, then starting from
  /// zero) and rank 0 adds it (takeOver): the sum over the processes is unchanged and rank 0's
  /// save() holds all of it, so a run resumes at any rank count.
  virtual bool accumulates() const { return false; }
  virtual void handOver(std::vector<char>& out) {}
  /// @throw std::runtime_error if `in` is not what handOver writes for this column
  virtual void takeOver(std::string_view in) {}
  /// sample() of a Reads::Parts column: its own part, merged alone (PartsColumns' sample).
  void sampleOwnPart(const Simulation& sim, double elapsed, std::vector<double>& row) {
    std::vector<char> own;
    const PartBounds b = PartBounds::of(sim);
    part(sim, b, own);
    sampleParts(sim, elapsed, b, {std::string_view(own.data(), own.size())}, row);
  }
  /// Checkpointing of what sample() depends on besides the simulation.
  virtual void save(StateArchive& a, const std::string& prefix) const {}
  virtual void load(const StateArchive& a, const std::string& prefix) {}
};

/// A group of columns read in parts only: its sample() is its own part merged alone, so one
/// process and rank 0 of many write the same bytes through the same calls.
class PartsColumns : public SeriesColumns {
public:
  Reads reads() const final { return Reads::Parts; }
  void sample(const Simulation& sim, double elapsed, std::vector<double>& row) final {
    sampleOwnPart(sim, elapsed, row);
  }
};

} // namespace talus
