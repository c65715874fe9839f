// Material group for the weakly compressible fluid: stores J = det F per particle, nothing else.
#pragma once

#include "engine/material_group.h"
#include "engine/transfer_g2p.h"
#include "materials/tait_water.h"

namespace talus {

class FluidGroup final : public MaterialGroup {
public:
  FluidGroup(std::string name, int index, double density, const TaitWaterModel& model)
      : MaterialGroup(std::move(name), index, density), model(model) {}

  TaitWaterModel model;
  std::vector<float> dJ; ///< J - 1 per particle

  const char* modelName() const override { return TaitWaterModel::kName; }
  double waveSpeed() const override { return model.soundSpeed(density(), minJ_); }
  double stableDtLimit(double dx) const override {
    // Explicit viscous diffusion is stable for dt < rho dx^2 / (6 eta) in 3-D; keep half of it.
    return model.viscosity > 0 ? 0.5 * density() * dx * dx / (6 * model.viscosity) : MaterialGroup::stableDtLimit(dx);
  }

  void gridToParticles(const G2PBlock& blk, size_t begin, size_t end, G2PStats& stats) override {
    const double dt = blk.dt;
    float minDJ = 0;
    gatherParticles(blk, particles, begin, end, stats, [&](size_t p, const Mat3& C) {
      model.update(dJ[p], C, dt, particles.tau[p]);
      minDJ = std::min(minDJ, dJ[p]);
    });
    stats.minFluidJ = std::min(stats.minFluidJ, 1 + minDJ);
  }
  void afterStep(const G2PStats& stats) override { minJ_ = std::max(0.5f, std::min(1.0f, stats.minFluidJ)); }

  /// Water at rest: J and stress of the hydrostatic pressure rho0 |g| (surface - z) per particle.
  void setHydrostatic(size_t begin, size_t end, double surfaceZ, double g) override {
    for (size_t p = begin; p < end; ++p) {
      const double depth = std::max(0.0, surfaceZ - double(particles.x[p].z()));
      const double Jp = model.restJ(density() * g * depth);
      dJ[p] = float(Jp - 1);
      particles.tau[p] = Sym3::fromMatrix(Mat3d::Identity() * (-Jp * model.pressureOfStrain(dJ[p])));
    }
  }

  void permuteState(const std::vector<uint32_t>& perm) override { gatherInPlace(dJ, perm); }
  void compactState(const std::vector<uint8_t>& keep) override { compactInPlace(dJ, keep); }
  void resizeState(size_t n) override { dJ.resize(n, 0.0f); }
  size_t stateBytesPerParticle() const override { return sizeof(float); }

  std::vector<std::string> scalarNames() const override { return {"pressure", "J"}; }
  void scalar(const std::string& name, std::vector<float>& out) const override {
    out.resize(dJ.size());
    for (size_t i = 0; i < dJ.size(); ++i) out[i] = name == "J" ? 1 + dJ[i] : float(model.pressureOfStrain(dJ[i]));
  }

private:
  float minJ_ = 1;
};

} // namespace talus
