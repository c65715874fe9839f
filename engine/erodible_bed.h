// Erodible covers thinner than a cell, as a field on the terrain instead of particles.
//
// A snow or sediment cover of a few decimetres is a tenth of a cell at the resolutions real paths
// run at: its particles would be flat slabs sliding on their own. Here a cover is a mass per node
// column (i, j) of the grid (kg over the column's dx x dx plan area). Where the flow slides over
// it, it erodes as AvaFrame's com1DFA erodes (docs/theoryCom1DFA, "Entrainment"): the erosion
// rate per area is tau_b |u| / e_b, the basal shear power over the specific erosion energy e_b
// (J/kg). A contact node's share of tau_b A dt is the tangential impulse its basal law removed
// this step, so the node asks for (impulse x sliding speed) / e_b kilograms, and no plan area
// enters.
//
// Mass and momentum are conserved exactly: the eroded mass dm leaves the column and the node,
// of mass m, slows to v m / (m + dm), the momentum that accelerates the eroded mass from rest to
// the flow's velocity. That mass and momentum wait in the column's pool until the pool reaches
// one particle's mass (or the flow stops eroding there), then become a particle of the cover's
// material in the cell the mass came from, on the ground, moving with the pool's velocity.
#pragma once

#include "engine/material_group.h"
#include "engine/sdf.h"
#include "engine/sparse_grid.h"
#include "engine/state_archive.h"

#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace talus {

/// One cover as the scene gives it: its material and erosion law, and its mass per node column.
struct ErodibleCover {
  std::string name;        ///< the body's label (series columns, messages)
  int group = 0;           ///< position in Simulation::groups() of the cover's material
  double erosionEnergy = 5000; ///< e_b (J/kg): AvaFrame's entEroEnergy
  double particleMass = 0; ///< kg: a pool at least this heavy becomes a particle
  struct Column {
    int32_t i = 0, j = 0; ///< node column: plan position (i dx, j dx) in the local frame
    double mass = 0;      ///< kg over the column's dx x dx plan area
  };
  std::vector<Column> columns;
};

class ErodibleBed {
public:
  /// @param covers  eroded in list order where they overlap (the first is the top one)
  /// @param ground  the terrain, to put new particles on it
  /// @throws std::invalid_argument for a cover without columns, a non-positive erosion energy or
  ///         particle mass, or a column of negative mass
  ErodibleBed(std::vector<ErodibleCover> covers, std::shared_ptr<const Sdf> ground, double dx);

  const std::vector<ErodibleCover>& covers() const { return covers_; }

  /// Grid update scratch: per node of every active block, the basal work (J) of the ground's
  /// law this step, |tangential impulse| x sliding speed. Sized and zeroed by prepare().
  std::vector<float>& basalWork() { return work_; }
  void prepare(size_t blocks) { work_.assign(blocks * kBlockNodes, 0.f); }

  /// A node that did basal work over a cover this step, with its mass and velocity after the
  /// grid update: what the columns' sums and the pools read.
  struct WorkingNode {
    BlockCoord block;
    int32_t node = 0; ///< index in the block
    float work = 0;   ///< J
    uint32_t first = 0, end = 0; ///< its column's covers, [first, end) (the same on every rank)
    Vec4 value;       ///< mass, velocity
  };
  /// The ranks' seam: handed this rank's working nodes (of the blocks it counts), leaves every
  /// rank's in one process's order (blocks in tree order, then nodes). Empty for one process.
  using ShareNodes = std::function<void(std::vector<WorkingNode>&)>;

  /// After the grid update: takes each column's eroded mass, slows its contact nodes so that
  /// momentum is conserved, and adds mass and momentum to the columns' pools. Deterministic: the
  /// sums run over the nodes in block (tree) then node order, on one process or shared by the
  /// ranks, so every rank keeps the same columns and pools (they are replicated) and slows the
  /// nodes it holds alike.
  /// @param counted  on ranks, per block, 1 where this rank adds the block's sums (each block on
  ///                 one rank); null: every block
  void erode(SparseGrid& grid, double dt, const std::vector<uint8_t>* counted = nullptr, const ShareNodes& share = {});
  /// After G2P: a pool becomes one particle of its cover's group (appended, model state
  /// undeformed) when it holds a particle's mass, when its column is eroded to the ground, when
  /// its column has eroded nothing for as long as the pool's mass takes to travel kWaitCells cells
  /// (the flow has passed), or when it has waited kMaxWaits times that (a deposit creeping on,
  /// eroding a little, releases a pool now and then rather than a small particle every step).
  /// Particles are appended in tree order of their blocks (pools' order within a block), so new
  /// particles made by the ranks, each for its own blocks, are one process's in rank order.
  /// @param mine  on ranks, whether this rank makes the particle at x (it owns x's block); every
  ///              rank updates every pool alike. Empty: one process, which makes them all.
  /// Returns the particles made here.
  static constexpr double kWaitCells = 4, kMaxWaits = 8;
  size_t release(const std::vector<MaterialGroup*>& groups, const std::function<bool(const Vec3&)>& mine = {});

  /// Per cover: mass given at the start, still on the ground, and waiting in pools (kg).
  double initialMass(size_t cover) const;
  double remainingMass(size_t cover) const;
  double pooledMass(size_t cover) const;
  Vec3d pooledMomentum(size_t cover) const;
  /// Mass taken by the flow so far (initial - remaining), pooled or already particles.
  double entrainedMass(size_t cover) const { return initialMass(cover) - remainingMass(cover); }
  /// Mass (kg) the flow has taken from cover `cover` at node column (i, j); 0 where it has none.
  double erodedMass(int32_t i, int32_t j, size_t cover) const;

  /// Checkpointing: the columns' remaining mass and pools, bit for bit.
  void save(StateArchive& a) const;
  /// @throws std::runtime_error when the archive's bed does not fit this one
  void load(const StateArchive& a);

private:
  /// One cover at one column, sorted by (column, cover).
  struct Entry {
    int32_t i, j, cover;
    double initial, remaining;
    double pool = 0;                     ///< eroded mass not yet a particle (kg)
    Vec3d momentum = Vec3d::Zero();      ///< its momentum (kg m/s)
    Vec3d moment = Vec3d::Zero();        ///< sum of dm x where it was eroded (kg m, local)
    double age = 0;                      ///< time since the pool began to fill (s)
    double idle = 0;                     ///< time since the column last eroded (s)
  };
  /// f(entry) summed over the entries of one cover, in entry order.
  template <class T, class F> T sum(size_t cover, T s, F&& f) const {
    for (const Entry& e : entries_)
      if (size_t(e.cover) == cover) s += f(e);
    return s;
  }

  std::vector<ErodibleCover> covers_;
  std::shared_ptr<const Sdf> ground_;
  double dx_;
  std::vector<Entry> entries_;
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> columns_; ///< key -> [first, end) entries
  const std::pair<uint32_t, uint32_t>* columnOf(const BlockCoord& c, int n) const; ///< null: no cover
  double nodeShare(const std::pair<uint32_t, uint32_t>& col, double work) const;  ///< kg a node takes

  std::vector<float> work_;
  std::vector<WorkingNode> working_; ///< scratch: this step's working nodes
  std::vector<double> columnWork_; ///< scratch: per column (at its first entry), the work this step
  std::vector<double> scratch_;    ///< scratch: per entry, the mass it gives per joule of its column's work
};

} // namespace talus
