// Where particles enter (or leave) a run after the start: secondary releases held until the flow
// reaches them (engine/secondary_release.h), inflow hydrographs through a cross-section
// (engine/inflow_source.h), and, as a source of negative mass, a forest's detrainment
// (engine/detrainment.h). The step calls every source once, after G2P, with the grid still
// holding the step's node data; a source appends particles to material groups (or takes mass from
// them). A new kind of source is one class and a line where the scene builds it.
#pragma once

#include "engine/material_group.h"
#include "engine/sparse_grid.h"
#include "engine/state_archive.h"

#include <string>
#include <vector>

namespace talus {

class ParticleSource {
public:
  virtual ~ParticleSource() = default;
  /// After the step [time - dt, time]: appends what entered to `groups`; returns particles made.
  virtual size_t emit(const SparseGrid& grid, double time, double dt, const std::vector<MaterialGroup*>& groups) = 0;
  /// Checkpointing of what emit() depends on besides the groups (keys prefixed by `prefix`).
  virtual void save(StateArchive& a, const std::string& prefix) const = 0;
  virtual void load(const StateArchive& a, const std::string& prefix) = 0;
};

} // namespace talus
