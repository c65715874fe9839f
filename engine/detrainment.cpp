#include "engine/detrainment.h"

#include <cmath>
#include <stdexcept>

namespace talus {

Detrainment::Detrainment(std::shared_ptr<const ParameterField> field, int resistance, int detrainment, double dx,
                         DetrainmentThresholds thresholds)
    : field_(std::move(field)), resistance_(resistance), detrainment_(detrainment), dx_(dx), thresholds_(thresholds) {
  if (!field_) throw std::invalid_argument("detrainment needs the terrain's parameter field");
  if (resistance < 0 || detrainment < 0 || resistance >= field_->count() || detrainment >= field_->count())
    throw std::invalid_argument("detrainment: parameter index outside the terrain's parameter field");
}

float Detrainment::coefficient(uint64_t column, int32_t i, int32_t j) {
  const auto it = coefficient_.find(column);
  if (it != coefficient_.end()) return it->second;
  std::vector<float> p(size_t(field_->count()));
  field_->sample(Vec3d((i + 0.5) * dx_, (j + 0.5) * dx_, 0.0), p.data()); // the cell's centre
  const float k = p[size_t(resistance_)] > 0 && p[size_t(detrainment_)] > 0 ? p[size_t(detrainment_)] : 0.f;
  coefficient_.emplace(column, k);
  return k;
}

size_t Detrainment::emit(const SparseGrid&, double, double dt, const std::vector<MaterialGroup*>& groups) {
  if (detrained_.size() < groups.size()) detrained_.resize(groups.size(), 0.0);
  const double inv = 1 / dx_;
  auto columnOf = [&](const Vec3& x, int32_t& i, int32_t& j) {
    i = int32_t(std::floor(double(x.x()) * inv)), j = int32_t(std::floor(double(x.y()) * inv));
    return columnKey(i, j);
  };
  // The columns in the forest: their mass, volume and momentum, summed in particle order.
  columns_.clear();
  for (const MaterialGroup* g : groups) {
    const ParticleSet& P = g->particles;
    const double volumePerMass = 1 / g->density();
    for (size_t p = 0; p < P.size(); ++p) {
      int32_t i, j;
      const uint64_t k = columnOf(P.x[p], i, j);
      if (!(coefficient(k, i, j) > 0)) continue;
      Column& c = columns_[k];
      const double m = double(P.mass[p]);
      c.mass += m, c.volume += m * volumePerMass, c.momentum += m * P.v[p].cast<double>();
    }
  }
  if (columns_.empty()) return 0;
  const double area = dx_ * dx_;
  for (auto& [k, c] : columns_) {
    const double h = c.volume / area, u = c.momentum.norm() / c.mass;
    if (!detrains(h, u, thresholds_)) continue;
    // AvaFrame detrains nothing from a column at rest (u = 0); one just slower stalls whole.
    c.fraction = u > 0 ? std::min(1.0, double(coefficient_.at(k)) * dt * area / (u * c.mass)) : 0.0;
  }
  for (MaterialGroup* g : groups) {
    ParticleSet& P = g->particles;
    std::vector<uint8_t> keep;
    double lost = 0;
    for (size_t p = 0; p < P.size(); ++p) {
      int32_t i, j;
      const auto it = columns_.find(columnOf(P.x[p], i, j));
      if (it == columns_.end() || !(it->second.fraction > 0)) continue;
      const double f = it->second.fraction, m = double(P.mass[p]);
      if (f >= 1) {
        if (keep.empty()) keep.assign(P.size(), 1);
        keep[p] = 0, lost += m;
      } else {
        const Real kept = Real(m * (1 - f));
        lost += m - double(kept);
        P.mass[p] = kept;
      }
    }
    detrained_[size_t(g->index())] += lost;
    if (keep.empty()) continue;
    P.forEachArray([&](auto& a) { compactInPlace(a, keep); });
    g->compactState(keep);
  }
  return 0;
}

double Detrainment::detrainedMass() const {
  double s = 0;
  for (double m : detrained_) s += m;
  return s;
}

void Detrainment::save(StateArchive& a, const std::string& prefix) const { a.putVector(prefix + "detrained", detrained_); }

void Detrainment::load(const StateArchive& a, const std::string& prefix) { a.getVector(prefix + "detrained", detrained_); }

} // namespace talus
