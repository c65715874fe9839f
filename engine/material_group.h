// All particles of one material, and the interface through which the engine updates them.
//
// The engine never calls a constitutive model per particle through a virtual function: it
// calls MaterialGroup::gridToParticles once per (block, material) range, and the group's
// template code (materials/solid_group.h, materials/fluid_group.h) runs the model inline.
#pragma once

#include "engine/contact_law.h"
#include "engine/padded_block.h"
#include "engine/particle_set.h"
#include "engine/state_archive.h"
#include "engine/types.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace talus {

/// What G2P needs to know about one block: grid velocities of its padded neighbourhood.
struct G2PBlock {
  const Vec4* nodes;    ///< kPadNodes grid nodes (mass, velocity), padIndex order
  int origin[3];        ///< global index of the block's first node
  Real dt, dx, invDx;
  const Vec4* old = nullptr; ///< AFLIP: (0, velocity before forces) of the same nodes, else null
  Real flip = 0;             ///< AFLIP blend (SimulationSettings::flip)
  /// F-bar: the step's mass-weighted mean of the solids' volume change minus one, ΔJ̄ - 1, at the
  /// same nodes; null when F-bar is off.
  const Real* meanVolumeChange = nullptr;
  /// For a group that averagesState(): the mass-weighted mean of its J - 1 after the step at the
  /// same nodes (GatheredChunk::meanJ); else null.
  const Real* meanJ = nullptr;
};

/// Per-thread results of a G2P pass.
struct G2PStats {
  Real maxSpeed = 0;
  size_t nonFinite = 0; ///< particles whose velocity or stress became NaN/inf
  void merge(const G2PStats& o) {
    if (o.maxSpeed > maxSpeed) maxSpeed = o.maxSpeed;
    nonFinite += o.nonFinite;
  }
};

class MaterialGroup {
public:
  MaterialGroup(std::string name, int index, double density)
      : name_(std::move(name)), index_(index), density_(density) {}
  virtual ~MaterialGroup() = default;

  const std::string& name() const { return name_; }
  int index() const { return index_; }     ///< position in the scene's material list
  double density() const { return density_; } ///< reference density (kg/m3)
  size_t size() const { return particles.size(); }

  /// This material's own law at every collider (`[[materials]] basal`), or null: the collider's.
  std::shared_ptr<const ContactLaw> basalLaw;

  ParticleSet particles;
  /// Particles of active block b are [blockStart[b], blockStart[b+1]) after binning.
  std::vector<uint32_t> blockStart;

  virtual const char* modelName() const = 0;
  /// The same material (name, index, density, model, basal law) without particles: rank 0's view
  /// of a run on ranks (Simulation::emptyView).
  virtual std::unique_ptr<MaterialGroup> emptyCopy() const = 0;
  /// Fastest elastic/acoustic wave speed (m/s); limits the time step.
  virtual double waveSpeed() const = 0;
  /// Any other limit on dt (s) this material imposes at grid spacing dx (e.g. viscosity).
  virtual double stableDtLimit(double dx) const { return std::numeric_limits<double>::infinity(); }
  /// Called once per step after G2P (e.g. a fluid updates the compression its sound speed uses).
  virtual void afterStep() {}
  /// Group-wide values MPI ranks reduce to their minimum after each step (a fluid's most
  /// compressed J, which sets its sound speed); none for most models.
  virtual std::vector<double> rankMinima() const { return {}; }
  virtual void setRankMinima(const std::vector<double>&) {}
  /// Called once before the first step: e.g. fluids start in hydrostatic equilibrium.
  virtual void initialize(const Vec3d& gravity, double dx) {}
  /// Whether F-bar (SimulationSettings::fbar) averages this material's volume change (solids).
  virtual bool averagesVolume() const { return false; }
  /// Whether this material's J itself (not its step's increment) is replaced every step by the
  /// grid's mass-weighted mean around each particle (water's `smooth_pressure`); then
  /// averagedState() is J - 1 per particle, in particle order.
  virtual bool averagesState() const { return false; }
  virtual const float* averagedState() const { return nullptr; }
  /// The largest J - 1 the group's own update keeps (its tension cut): the average takes each
  /// particle's J after the step cut there, as the particle would hold it.
  virtual double averagedStateMax() const { return 0; }
  /// Gather velocities for particles [begin, end), update deformation, stress and position.
  virtual void gridToParticles(const G2PBlock& block, size_t begin, size_t end, G2PStats& stats) = 0;

  /// Keep per-particle model state aligned with `particles`.
  virtual void permuteState(const Permutation& perm, ReorderScratch& scratch) = 0;
  virtual void compactState(const std::vector<uint8_t>& keep) = 0;
  /// Initialise model state for particles appended to `particles` (undeformed, unyielded).
  virtual void resizeState(size_t n) = 0;
  /// The state's room for n particles (reserveState), or none: empty with its memory returned
  /// (releaseState). Used by reserve() and release() below.
  virtual void reserveState(size_t n) = 0;
  virtual void releaseState() = 0;
  /// Room for n particles with their state: appending up to n (appendParticles) allocates no more.
  void reserve(size_t n) {
    particles.reserve(n);
    reserveState(n);
  }
  /// No particles, their memory returned: a copy held only while it is read (rank 0's view of the
  /// run between the files written from it).
  void release() {
    particles.release();
    releaseState();
  }
  virtual size_t stateBytesPerParticle() const = 0;
  /// Migration between ranks: the state of particles idx, stateBytesPerParticle() each, into out;
  /// and n such records appended after the last particle.
  virtual void packState(const std::vector<uint32_t>& idx, char* out) const = 0;
  virtual void appendState(const char* in, size_t n) = 0;

  /// Checkpointing: every array, bit for bit, under names prefixed by `prefix`.
  void save(StateArchive& a, const std::string& prefix) const {
    a.putVector(prefix + "x", particles.x);
    a.putVector(prefix + "v", particles.v);
    a.putVector(prefix + "C", particles.C);
    a.putVector(prefix + "tau", particles.tau);
    a.putVector(prefix + "mass", particles.mass);
    saveState(a, prefix);
  }
  void load(const StateArchive& a, const std::string& prefix) {
    a.getVector(prefix + "x", particles.x);
    a.getVector(prefix + "v", particles.v);
    a.getVector(prefix + "C", particles.C);
    a.getVector(prefix + "tau", particles.tau);
    a.getVector(prefix + "mass", particles.mass);
    loadState(a, prefix);
    // Every per-particle array must have one entry per particle, or the next step reads past one.
    const size_t n = particles.x.size();
    if (particles.v.size() != n || particles.C.size() != n || particles.tau.size() != n ||
        particles.mass.size() != n || stateSize() != n)
      throw std::runtime_error(prefix + ": per-particle arrays of different lengths");
  }
  virtual void saveState(StateArchive& a, const std::string& prefix) const = 0;
  virtual void loadState(const StateArchive& a, const std::string& prefix) = 0;
  /// Particles the model state holds (per array; -1 when its arrays disagree).
  virtual size_t stateSize() const = 0;

  /// Optional per-particle scalar outputs of the model (e.g. plastic strain, pressure).
  virtual std::vector<std::string> scalarNames() const { return {}; }
  virtual void scalar(const std::string& name, std::vector<float>& out) const { out.clear(); }

private:
  std::string name_;
  int index_;
  double density_;
};

/// Elements idx of each array into out, one particle's values together (packState's layout).
template <class... A>
void packRecords(const std::vector<uint32_t>& idx, char* out, const A&... arrays) {
  for (uint32_t p : idx)
    ((std::memcpy(out, &arrays[p], sizeof(arrays[p])), out += sizeof(arrays[p])), ...);
}
/// n records of packRecords' layout appended to the arrays.
template <class... A>
void appendRecords(const char* in, size_t n, A&... arrays) {
  for (size_t i = 0; i < n; ++i)
    ((arrays.emplace_back(), std::memcpy(static_cast<void*>(&arrays.back()), in, sizeof(arrays.back())), in += sizeof(arrays.back())), ...);
}

} // namespace talus
