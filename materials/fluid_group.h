// Material group for the weakly compressible fluid: stores J = det F per particle, nothing else.
#pragma once

#include "engine/material_group.h"
#include "engine/transfer_g2p.h"
#include "materials/tait_water.h"
#include "materials/water_lanes.h"

#include <atomic>
#include <cmath>
#include <unordered_map>

namespace talus {

class FluidGroup final : public MaterialGroup {
public:
  FluidGroup(std::string name, int index, double density, const TaitWaterModel& model)
      : MaterialGroup(std::move(name), index, density), model(model) {}

  TaitWaterModel model;
  std::vector<float> dJ; ///< J - 1 per particle

  const char* modelName() const override { return TaitWaterModel::kName; }
  bool averagesState() const override { return model.smoothPressure; }
  const float* averagedState() const override { return dJ.data(); }
  double averagedStateMax() const override { return model.maxTension > 0 ? model.maxJ() - 1 : 0.0; }
  std::unique_ptr<MaterialGroup> emptyCopy() const override {
    auto g = std::make_unique<FluidGroup>(name(), index(), density(), model);
    g->hydrostatic = hydrostatic;
    g->basalLaw = basalLaw;
    g->minJ_ = minJ_;
    return g;
  }
  double waveSpeed() const override { return model.soundSpeed(density(), minJ_); }
  double stableDtLimit(double dx) const override {
    // Explicit viscous diffusion is stable for dt < rho dx^2 / (6 eta) in 3-D; keep half of it.
    return model.viscosity > 0 ? 0.5 * density() * dx * dx / (6 * model.viscosity) : MaterialGroup::stableDtLimit(dx);
  }

  void gridToParticles(const G2PBlock& blk, size_t begin, size_t end, G2PStats& stats) override {
    const double dt = blk.dt;
    float minDJ = 0;
    // The equation of state of 16 particles side by side in SIMD lanes (materials/water_lanes.h).
    gatherParticleChunks(blk, particles, begin, end, stats, [&](const GatheredChunk& c) {
      WaterLanes io;
      for (int k = 0; k < kWaterLanes; ++k) {
        const bool live = k < c.count;
        const Mat3& C = particles.C[c.first + size_t(live ? k : 0)];
        io.dJ[k] = live ? double(dJ[c.first + size_t(k)]) : 0.0;
        // smooth_pressure: F-bar's scale of the increment to the mean J over this particle's J, so
        // that J lands on the grid's mean (engine/fbar.h).
        const double s = live && model.smoothPressure ? fbarScale(C, Real(dt), (1 + c.meanJ[k]) / (1 + io.dJ[k]) - 1) : 1.0;
        for (int r = 0; r < 9; ++r) io.C[r][k] = live ? double(C(r / 3, r % 3)) : 0.0;
        if (s != 1.0)
          for (int r = 0; r < 9; ++r) io.C[r][k] = s * io.C[r][k] + (r % 4 == 0 ? (s - 1) / dt : 0.0);
      }
      updateWaterLanes(model, dt, c.count, io);
      for (int k = 0; k < c.count; ++k) {
        const size_t p = c.first + size_t(k);
        dJ[p] = float(io.dJ[k]);
        minDJ = std::min(minDJ, dJ[p]);
        Sym3& t = particles.tau[p];
        t.xx = Real(io.tau[0][k]), t.yy = Real(io.tau[1][k]), t.zz = Real(io.tau[2][k]);
        t.xy = Real(io.tau[3][k]), t.xz = Real(io.tau[4][k]), t.yz = Real(io.tau[5][k]);
      }
    });
    // This group's most compressed particle of the step (a minimum: independent of block order).
    float cur = stepMinJ_.load(std::memory_order_relaxed);
    while (1 + minDJ < cur && !stepMinJ_.compare_exchange_weak(cur, 1 + minDJ, std::memory_order_relaxed)) {
    }
  }
  void afterStep() override {
    minJ_ = std::max(0.5f, std::min(1.0f, stepMinJ_.load()));
    stepMinJ_ = 1;
  }

  std::vector<double> rankMinima() const override { return {double(minJ_)}; }
  void setRankMinima(const std::vector<double>& v) override { minJ_ = float(v.at(0)); }

  bool hydrostatic = true; ///< start at rest under hydrostatic pressure (gravity along -z)

  /// Water at rest: every particle gets the J and stress of the hydrostatic pressure at its
  /// depth below the top of its own water column (columns dx wide, surface half a particle
  /// spacing above the highest particle), so reservoirs and dam-break columns start still.
  void initialize(const Vec3d& gravity, double dx) override {
    const double g = -gravity.z();
    if (!hydrostatic || !(g > 0) || particles.size() == 0) return;
    std::unordered_map<uint64_t, double> top;
    auto key = [&](const Vec3& x) {
      return (uint64_t(uint32_t(int32_t(std::floor(x.x() / dx)))) << 32) | uint32_t(int32_t(std::floor(x.y() / dx)));
    };
    for (const Vec3& x : particles.x) {
      auto [it, fresh] = top.try_emplace(key(x), double(x.z()));
      if (!fresh) it->second = std::max(it->second, double(x.z()));
    }
    for (size_t p = 0; p < particles.size(); ++p) {
      const double spacing = std::cbrt(double(particles.mass[p]) / density());
      const double depth = top[key(particles.x[p])] + 0.5 * spacing - double(particles.x[p].z());
      const double Jp = model.restJ(density() * g * depth);
      dJ[p] = float(Jp - 1);
      particles.tau[p] = Sym3::fromMatrix(Mat3d::Identity() * (-Jp * model.pressureOfStrain(dJ[p])));
    }
  }

  void saveState(StateArchive& a, const std::string& prefix) const override {
    a.putVector(prefix + "dJ", dJ);
    a.putValue(prefix + "minJ", minJ_);
  }
  void loadState(const StateArchive& a, const std::string& prefix) override {
    a.getVector(prefix + "dJ", dJ);
    minJ_ = a.getValue<float>(prefix + "minJ");
  }
  size_t stateSize() const override { return dJ.size(); }

  void permuteState(const Permutation& perm, ReorderScratch& scratch) override {
    gatherInPlace(dJ, perm, scratch);
  }
  void compactState(const std::vector<uint8_t>& keep) override { compactInPlace(dJ, keep); }
  void resizeState(size_t n) override { dJ.resize(n, 0.0f); }
  void reserveState(size_t n) override { dJ.reserve(n); }
  void releaseState() override { decltype(dJ)().swap(dJ); }
  size_t stateBytesPerParticle() const override { return sizeof(float); }
  void packState(const std::vector<uint32_t>& idx, char* out) const override { packRecords(idx, out, dJ); }
  void appendState(const char* in, size_t n) override { appendRecords(in, n, dJ); }

  std::vector<std::string> scalarNames() const override { return {"pressure", "J"}; }
  void scalar(const std::string& name, std::vector<float>& out) const override {
    out.resize(dJ.size());
    for (size_t i = 0; i < dJ.size(); ++i) out[i] = name == "J" ? 1 + dJ[i] : float(model.pressureOfStrain(dJ[i]));
  }

private:
  float minJ_ = 1;                  ///< most compressed particle of the last step (sets the sound speed)
  std::atomic<float> stepMinJ_{1};
};

} // namespace talus
