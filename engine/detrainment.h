// Detrainment in resistance areas (forests, AvaFrame's RES/ with `detrainment = True`): where a
// flow in a forest is slow or thin, the trees hold part of it back. AvaFrame com1DFA takes the
// rate from Feistl et al. (2014),
//
//   dm/dt = -detK A / |u|      (detK in Pa, AvaFrame's default 5; A a particle's basal area),
//
// applied where the flow is slower than forestVMin (6 m/s) or thinner than forestThMin (0.6 m),
// and not where it is faster than forestVMax (40 m/s) or thicker than forestThMax (10 m), which
// break the trees; between these, the forest's drag acts instead (engine/resistance_law.h).
//
// In Talus the depth-averaged quantities are those of a cell column (the particles whose x and y
// fall in one grid cell): its thickness h = sum(V) / dx^2, its speed u = |sum(m v)| / sum(m). A
// particle's basal area is its share of the column's, A = V / h, so every particle of a column
// loses the same fraction f = detK dt dx^2 / (u sum(m)) of its mass per step (its volume follows:
// volume is mass over density), and the column as a whole loses detK dx^2 dt / u, AvaFrame's
// rate. At f >= 1 (a stalled column) the column's particles are removed whole. The detrained
// mass is counted per material; it leaves the run as it leaves AvaFrame's (its mass log's
// `detrained` column).
//
// detK per column is the terrain's `detrainment` parameter field, scaled by nothing: a polygon's
// value is already weighted by the part of a cell it covers (io/scene/region_reader.cpp), and a
// column with no `resistance` does not detrain. Sampled once per column and kept.
//
// Runs as a particle source after G2P (engine/particle_source.h), in particle order on one thread:
// bit-identical at any thread count. One process only, as every source.
#pragma once

#include "engine/parameter_field.h"
#include "engine/particle_source.h"
#include "engine/resistance_law.h"

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace talus {

struct DetrainmentThresholds {
  /// AvaFrame's forestVMin, forestThMin (below either: detrain) and forestVMax, forestThMax (above
  /// either: the forest breaks), the drag's own (engine/resistance_law.h).
  double minSpeed = ResistedLaw::kMinSpeed, minThickness = ResistedLaw::kMinThickness;
  double maxSpeed = ResistedLaw::kMaxSpeed, maxThickness = ResistedLaw::kMaxThickness;
};

class Detrainment final : public ParticleSource {
public:
  /// `field` samples the terrain law's parameters; `resistance` and `detrainment` are the indices
  /// of cResH and detK in them. Throws std::invalid_argument for a null field or an index outside
  /// field->count().
  Detrainment(std::shared_ptr<const ParameterField> field, int resistance, int detrainment, double dx,
              DetrainmentThresholds thresholds = {});

  /// Removes the step's detrained mass from the particles of every column that detrains; returns 0
  /// (no particle is made).
  size_t emit(const SparseGrid& grid, double time, double dt, const std::vector<MaterialGroup*>& groups) override;

  /// Mass detrained so far from the material group with that index (kg); 0 for one never touched.
  double detrainedMass(size_t group) const { return group < detrained_.size() ? detrained_[group] : 0.0; }
  double detrainedMass() const;

  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;

  /// Whether a column of thickness h (m) and speed u (m/s) detrains (AvaFrame's rule, above).
  static bool detrains(double h, double u, const DetrainmentThresholds& t) {
    if (u > t.maxSpeed || h > t.maxThickness) return false;
    return u <= t.minSpeed || h <= t.minThickness;
  }

private:
  struct Column {
    double mass = 0, volume = 0;
    Vec3d momentum = Vec3d::Zero();
    double fraction = 0; ///< of each particle's mass detrained this step
  };
  float coefficient(uint64_t column, int32_t i, int32_t j); ///< detK of a column (0: none), cached

  std::shared_ptr<const ParameterField> field_;
  int resistance_, detrainment_;
  double dx_;
  DetrainmentThresholds thresholds_;
  std::unordered_map<uint64_t, float> coefficient_; ///< column -> detK
  std::unordered_map<uint64_t, Column> columns_;   ///< this step's detraining columns
  std::vector<double> detrained_;                  ///< per material group (kg)
};

} // namespace talus
