// The parts of Simulation::step that differ between one process and MPI ranks, behind one seam:
// the step calls them at fixed points without asking which it has. One process's versions
// (LocalPhases) are in engine/simulation.cpp, the ranks' (RankPhases) in simulation_ranks.cpp;
// Simulation::distribute swaps the first for the second. Private to the engine's step.
#pragma once

#include "engine/line_ranks.h"
#include "engine/simulation.h"

#include <memory>

namespace talus {

class Simulation::Phases {
public:
  virtual ~Phases() = default;
  /// The largest wave speed and the smallest model limit on dt, agreed by every process.
  virtual void agreeOnDt(double& wave, double& limit) const = 0;
  /// Bins the particles into blocks (ranks: migrates them first, rebalances when due).
  virtual void bin() = 0;
  /// Exchanges P2G's halo; returns it for P2G, or null when there is none.
  virtual const HaloExchange* exchangeHalo(Real dt) = 0;
  /// Blocks whose node sums this process counts (loads, erosion), or null for every block.
  virtual const std::vector<uint8_t>* counted() const = 0;
  /// The flow-thickness columns from the grid's thickness channel (ranks: every rank's blocks).
  virtual void buildColumns() = 0;
  /// How the erodible bed shares its working nodes; empty when there is no one to share with.
  virtual ErodibleBed::ShareNodes shareWorkingNodes() = 0;
  /// The colliders' loads of the step as one process adds them (ranks: on rank 0).
  virtual void reduceLoads(Real dt) = 0;
  /// The step's figures over every process: largest speed, groups' minima, counts.
  virtual void reduceStepFigures(G2PStats& stats, size_t& stepped) = 0;
  /// Whether a particle released at x is made here; empty: every particle is.
  virtual std::function<bool(const Vec3&)> makesHere() const = 0;
  /// Throws the NumericalError naming the first non-finite particle (ranks: the lowest rank's).
  [[noreturn]] virtual void throwNonFinite() const = 0;
};

/// One process: serial binning, nothing to exchange or reduce.
class Simulation::LocalPhases final : public Simulation::Phases {
public:
  explicit LocalPhases(Simulation& sim) : sim_(sim) {}
  void agreeOnDt(double&, double&) const override {}
  void bin() override;
  const HaloExchange* exchangeHalo(Real) override { return nullptr; }
  const std::vector<uint8_t>* counted() const override { return nullptr; }
  void buildColumns() override { sim_.columns_.build(sim_.grid_, sim_.grid_.channels.thickness); }
  ErodibleBed::ShareNodes shareWorkingNodes() override { return {}; }
  void reduceLoads(Real) override {}
  void reduceStepFigures(G2PStats&, size_t&) override {}
  std::function<bool(const Vec3&)> makesHere() const override { return {}; }
  [[noreturn]] void throwNonFinite() const override;

private:
  Simulation& sim_;
};

/// MPI ranks (engine/domain_decomposition.h, halo_exchange.h): every phase bit for bit one
/// process's.
class Simulation::RankPhases final : public Simulation::Phases {
public:
  explicit RankPhases(Simulation& sim) : sim_(sim) {}
  void agreeOnDt(double& wave, double& limit) const override;
  void bin() override;
  const HaloExchange* exchangeHalo(Real dt) override;
  const std::vector<uint8_t>* counted() const override { return &sim_.halo_.counted(); }
  void buildColumns() override;
  ErodibleBed::ShareNodes shareWorkingNodes() override;
  void reduceLoads(Real dt) override;
  void reduceStepFigures(G2PStats& stats, size_t& stepped) override;
  std::function<bool(const Vec3&)> makesHere() const override;
  [[noreturn]] void throwNonFinite() const override;

private:
  LineRanks& lineRanks(); ///< made at the first use (the domain's extent)
  /// buildColumns' answers: per asking rank, this rank's counted blocks with flow on the lines it
  /// asked for (records in lineRecords_); `mine` gets the indices of those it asked itself.
  std::vector<std::vector<char>> answerLines(const std::vector<std::vector<char>>& asked, std::vector<uint32_t>& mine);
  Simulation& sim_;
  std::unique_ptr<LineRanks> lineRanks_;
  std::vector<char> lineRecords_; ///< this rank's blocks with flow (buildColumns), kept between steps
  std::vector<Real> lineMasses_;
  double imbalance_ = 0; ///< of the particle counts after the last step's G2P (0 before the first)
};

} // namespace talus
