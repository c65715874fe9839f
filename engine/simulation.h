// The explicit MPM time loop: bin -> P2G -> grid update -> G2P (+ constitutive update) -> cull.
#pragma once

#include "engine/collider.h"
#include "engine/flow_thickness.h"
#include "engine/domain_decomposition.h"
#include "engine/erodible_bed.h"
#include "engine/particle_source.h"
#include "engine/grid_update.h"
#include "engine/halo_exchange.h"
#include "engine/periodic.h"
#include "engine/contact_laws.h"
#include "engine/material_group.h"
#include "engine/sparse_grid.h"
#include "engine/state_archive.h"
#include "engine/sdf.h"

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

namespace talus {

/// A structure in the flow: a dam, a wall, a gallery roof, a gate (see engine/collider.h).
struct StructureSpec {
  std::string name;
  std::shared_ptr<const Sdf> geometry;   ///< rest pose, local frame
  std::shared_ptr<const ContactLaw> law;
  ColliderMotion motion;
  Vec3d momentPoint = Vec3d::Zero();     ///< moments are about this point (local frame, rest pose)
};

/// A part of a closed domain face whose load is reported on its own: a pressure sensor or gauge
/// panel on a wall. It holds the face's nodes whose two in-plane coordinates lie within
/// [lo, hi] (local frame; the normal component is ignored), acts on them with the face's law
/// just before the face does, so the face keeps the rest and the two loads add up to the whole.
struct PanelSpec {
  std::string name;
  int face = 0; ///< index into faceNames()
  Vec3d lo = Vec3d::Zero(), hi = Vec3d::Zero();
};

/// Names of the six domain faces, in the order of SimulationSettings::faces.
inline const std::array<const char*, 6>& faceNames() {
  static const std::array<const char*, 6> n{"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};
  return n;
}

struct SimulationSettings {
  double dx = 0.1;
  double cfl = 0.4;                 ///< dt = cfl dx / (c_max + |v|_max)
  double maxDt = std::numeric_limits<double>::infinity();
  Vec3d gravity{0, 0, -9.81};
  /// Gravity grows smoothly (1 - cos) from 0 to full over this time (s). Loading a body gradually
  /// lets it reach its static stress state without the undamped ringing a sudden load causes.
  double gravityRamp = 0;
  /// Grid velocity damping rate (1/s): v <- v / (1 + damping dt) every step. Dynamic relaxation
  /// for reaching equilibrium states quasi-statically (a settled heap, a prestressed snowpack);
  /// it removes momentum, so leave it at 0 for the dynamics themselves.
  double damping = 0;
  /// AFLIP blend (Fei et al. 2021, the paper group's `flip_ratio`): a particle's new velocity is
  /// v_PIC + flip (v_p - v_old at p), carrying back a share of what the grid's interpolation
  /// removed; positions still move with v_PIC. 0 is pure APIC (the default); costs 3 grid channels.
  double flip = 0;
  /// F-bar (engine/fbar.h): each solid particle's volume change per step is the grid's
  /// mass-weighted average around it, not its own; against volumetric locking of plastic flow.
  /// Costs a gather and a scatter pass over the solids and 2 grid channels; one process, no periodic axes.
  bool fbar = false;
  Vec3d origin = Vec3d::Zero();     ///< world coordinates of the local frame's origin
  DomainBox domain;                 ///< local frame
  /// Contact law of each face of the domain box (x_min, x_max, y_min, y_max, z_min, z_max);
  /// null leaves the face open (material passes and is removed).
  std::array<std::shared_ptr<const ContactLaw>, 6> faces{
      makeContactLaw(SlipLaw{}), makeContactLaw(SlipLaw{}), makeContactLaw(SlipLaw{}),
      makeContactLaw(SlipLaw{}), makeContactLaw(SlipLaw{}), makeContactLaw(SlipLaw{})};
  std::shared_ptr<const Sdf> terrain; ///< optional ground
  std::shared_ptr<const ContactLaw> terrainLaw = makeContactLaw(CoulombLaw{Real(0.3)});
  /// The terrain law's parameters by region (`[[terrain.regions]]`), or null: its own everywhere.
  std::shared_ptr<const ParameterField> terrainParameters;
  std::vector<StructureSpec> structures;
  std::vector<PanelSpec> panels;    ///< on closed, non-periodic faces
  /// Erodible covers thinner than a cell, as fields on the terrain (engine/erodible_bed.h); the
  /// Simulation moves them into bed(). Any rank count; no periodic axes.
  std::vector<ErodibleCover> covers;
  /// Where particles enter after the start: secondary releases, inflow hydrographs
  /// (engine/particle_source.h), called in this order after every step. One process.
  std::vector<std::shared_ptr<ParticleSource>> sources;
  /// Periodic axes (the domain's extent along them a multiple of 8 dx; no faces there).
  std::array<bool, 3> periodic{false, false, false};
};

/// Wall-clock seconds spent in each phase of the step, summed over the run.
struct PhaseTimes {
  double bin = 0, colliders = 0, p2g = 0, grid = 0, g2p = 0, cull = 0;
  double halo = 0; ///< MPI ranks: migration, the P2G halo and the reductions (waiting included)
  double total() const { return bin + colliders + p2g + grid + g2p + cull + halo; }
};

/// Thrown when a particle's velocity or stress becomes NaN/inf; the message names the step,
/// particle, material and position.
class NumericalError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

class Simulation {
public:
  Simulation(SimulationSettings settings, std::vector<std::unique_ptr<MaterialGroup>> groups);
  ~Simulation();
  Simulation(const Simulation&) = delete; // the step's phases hold a reference to it
  Simulation& operator=(const Simulation&) = delete;

  /// Collective over comm's ranks: from here on this process holds and steps only the particles
  /// of its range of blocks (engine/domain_decomposition.h). Every rank must have built the same
  /// scene (all particles, or its part with seedIndex); results are bit-identical to one
  /// process's at any rank count.
  /// @param imbalance  rebalance when a rank holds more than (1 + imbalance) x the mean particles
  /// @param seedIndex  when each rank built only its part of the particles: per group index
  ///                   (MaterialGroup::index()), each particle's index in one process's arrays
  void distribute(std::shared_ptr<Communicator> comm, double imbalance = 0.1,
                  const std::vector<std::vector<uint64_t>>* seedIndex = nullptr);
  /// The ranks, or null for one process.
  const DomainDecomposition* ranks() const { return ranks_.get(); }
  /// Collective, same values on every rank: the fraction of the particles each rank should own
  /// (DomainDecomposition::setShares); ranks rebalance toward them when they pass the threshold.
  void setRankShares(std::vector<double> shares) { ranks_->setShares(std::move(shares)); }
  const HaloExchange& halo() const { return halo_; }
  /// Rank 0's view of a run on ranks: a Simulation of the same settings, materials, colliders,
  /// terrain (shared, not built again) and erodible bed, with no particles and never stepped;
  /// gatherSeededInto and gatherInto fill it. Call before the first step.
  std::unique_ptr<Simulation> emptyView() const;
  /// Collective, before distribute: rank 0's `view` (from emptyView) gets every rank's particles
  /// as seeded, in one process's order, with the initial mass and largest speed one process
  /// computes from them. `seedIndex` as distribute's, or null when every rank holds every
  /// particle (then rank 0 copies its own). Other ranks pass a null view. Throws
  /// std::logic_error when the view is passed elsewhere than on rank 0.
  void gatherSeededInto(Communicator& comm, Simulation* view, const std::vector<std::vector<uint64_t>>* seedIndex) const;
  /// Collective: rank 0's `view` (from emptyView, never stepped) gets
  /// every rank's particles in one process's order, the clock, counters, loads and mass ledger,
  /// so outputs written from it are one process's files. Other ranks pass null. The per-step
  /// outputs never need it (they step in parts); frames, checkpoints and the end's files do.
  /// Rank 0 appends one rank's particles at a time into arrays sized for all: it holds the run
  /// once (plus one rank's part in flight), not also in a gathered buffer. With
  /// ViewContents::WithoutParticles the view gets all of that but the particles (its groups are
  /// left empty): a checkpoint whose particles every rank writes itself (particleRecords).
  enum class ViewContents { Everything, WithoutParticles };
  void gatherInto(Simulation* view, ViewContents what = ViewContents::Everything);
  /// This process's particles of group `group` as records (packParticles' layout), split where
  /// one process's order splits them: `settled` (every rank's in rank order), then `fresh` (made
  /// by the bed since binning, every rank's after all the settled ones). gatherInto's order.
  void particleRecords(size_t group, std::vector<char>& settled, std::vector<char>& fresh) const;
  /// How many of group `group`'s particles (its last ones) particleRecords counts as fresh.
  size_t freshParticles(size_t group) const { return group < fresh_.size() ? fresh_[group] : 0; }
  /// Appends particleRecords' records to group `group` (a resumed checkpoint's parts, in one
  /// process's order). Throws std::runtime_error when they are not whole records.
  void appendParticleRecords(size_t group, std::string_view records);
  /// Throws std::runtime_error naming the first particle outside the domain or without mass:
  /// what load() checks, for particles appended after it.
  void checkParticles() const;
  /// Every group empty, its memory returned (MaterialGroup::release): a view between the files
  /// written from it, so rank 0 holds every particle only while it writes (gatherInto refills it).
  void releaseParticles() {
    for (MaterialGroup* g : groupPtrs_) g->release();
  }
  /// Particles on all ranks (this process's count without ranks).
  size_t globalParticleCount() const;

  /// Stable step from the CFL condition of the materials present, capped by maxDt.
  double stableDt() const;
  /// Advances by min(stableDt(), dtCap); returns the step taken.
  double step(double dtCap = std::numeric_limits<double>::infinity());
  /// One step of advanceTo(t)'s sequence (call only while time() < t): the stable step, or the
  /// remainder when it is within one, or half of it when within two. Returns the step taken.
  double stepToward(double t);
  /// Steps until time() reaches t exactly (the last two steps share the remainder evenly, so
  /// there is no sliver step); calls onStep after each step.
  void advanceTo(double t, const std::function<void()>& onStep = {});

  double time() const { return time_; }
  /// Sets the clock without stepping: for a copy holding another simulation's particles at its
  /// time (a part of them, as a rank holds). Expects t >= 0; changes nothing else.
  void setTime(double t) { time_ = t; }
  uint64_t steps() const { return steps_; }
  const SimulationSettings& settings() const { return settings_; }
  const std::vector<MaterialGroup*>& groups() const { return groupPtrs_; }
  const SparseGrid& grid() const { return grid_; }
  const PhaseTimes& phaseTimes() const { return times_; }
  size_t particleCount() const;
  uint64_t particleSteps() const { return particleSteps_; }
  double maxSpeed() const { return maxSpeed_; }
  double maxWaveSpeed() const;

  /// Every collider (terrain, structures, closed faces, in the order they act) and the load each
  /// took in the last step.
  const std::vector<std::unique_ptr<Collider>>& colliders() const { return colliders_; }
  /// With ranks: rank 0 holds the totals (one process's, bit for bit), other ranks partial sums.
  const std::vector<ColliderLoad>& colliderLoads() const { return loads_; }
  /// The erodible covers on the terrain, or null when the scene has none.
  const ErodibleBed* bed() const { return bed_.get(); }
  /// The particle sources (secondary releases, inflows) as the scene gave them.
  const std::vector<std::shared_ptr<ParticleSource>>& sources() const { return settings_.sources; }

  /// Per material group (in groups() order): mass, kinetic energy and gravitational potential
  /// energy -m g.x about the local origin, summed in fixed chunks (the same at any thread count).
  struct GroupSums {
    double mass = 0, kinetic = 0, potential = 0;
  };
  std::vector<GroupSums> groupSums() const;

  double initialMass() const { return initialMass_; }
  double totalMass() const;
  /// Mass of particles that left the domain, per material index.
  const std::vector<double>& massRemoved() const { return massRemoved_; }
  double totalMassRemoved() const;

  Vec3d linearMomentum() const;
  /// Mass-weighted mean position (local frame) and velocity.
  Vec3d centreOfMass() const;
  Vec3d meanVelocity() const { return linearMomentum() / totalMass(); }
  /// About the local origin, including APIC's affine part m (dx^2/4) (C32-C23, C13-C31, C21-C12).
  Vec3d angularMomentum() const;
  double kineticEnergy() const;
  /// Gravitational potential energy -m g.x relative to the local origin.
  double potentialEnergy() const;


  /// Bytes held by particles (including model state) and by the grid and terrain cache.
  size_t particleBytes() const;
  size_t gridBytes() const;
  /// Bytes the terrain holds in memory (Sdf::residentBytes: an on-demand level set's loaded
  /// leaves), beside its per-block samples that gridBytes counts. 0 without terrain.
  size_t terrainBytes() const;
  /// Bytes of the buffers binning keeps between steps (about 44 per particle of the largest group).
  size_t scratchBytes() const { return reorder_.bytes(); }

  /// Everything needed to continue the run bit for bit: clock, counters, speeds, mass ledger and
  /// every group's particles and model state (groups are matched by name and model).
  void save(StateArchive& a) const;
  /// Restores a state written by save() into a simulation built from the same scene.
  void load(const StateArchive& a);

private:
  // The step's parts that differ between one process and MPI ranks (engine/simulation_phases.h).
  class Phases;
  class LocalPhases;
  class RankPhases;

  double stepBy(double dt); ///< the step itself, by dt (at most the stable step)
  void buildColliders();
  void prepareColliders(double dt);
  void updateGrid(double dt, const std::vector<uint8_t>* counted);
  void cullEscaped();
  void checkFinite(size_t nonFinite) const;
  void releaseEroded();
  std::string nonFiniteMessage() const; ///< the first non-finite particle here, or empty

  SimulationSettings settings_;
  std::vector<std::unique_ptr<MaterialGroup>> groups_;
  std::vector<MaterialGroup*> groupPtrs_;
  SparseGrid grid_;
  ReorderScratch reorder_; ///< binning buffers kept between steps
  std::vector<std::unique_ptr<Collider>> colliders_;
  std::vector<Collider*> colliderPtrs_;
  std::vector<ColliderLoad> loads_;
  bool needsThickness_ = false;
  std::vector<MaterialLaw> materialLaws_; ///< materials with their own basal law
  Periodicity periodic_;
  FlowColumns columns_;
  double time_ = 0;
  uint64_t steps_ = 0, particleSteps_ = 0;
  double maxSpeed_ = 0;
  double initialMass_ = 0;
  std::vector<double> massRemoved_;
  PhaseTimes times_;
  std::unique_ptr<DomainDecomposition> ranks_;
  HaloExchange halo_;
  std::unique_ptr<Phases> phases_; ///< LocalPhases, or RankPhases once distributed
  std::unique_ptr<ErodibleBed> bed_;
  /// Per group: particles the bed appended at the arrays' end since the last binning (binning on
  /// ranks puts them after every rank's particles, where one process has them).
  std::vector<size_t> fresh_;
};

} // namespace talus
