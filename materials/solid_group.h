// Material group for elastoplastic solids: stores F^E and the model's plastic state per particle.
#pragma once

#include "engine/material_group.h"
#include "engine/transfer_g2p.h"
#include "materials/hencky.h"
#include "materials/solid_lanes.h"

namespace talus {

template <class Model>
class SolidGroup final : public MaterialGroup {
public:
  SolidGroup(std::string name, int index, double density, const Model& model)
      : MaterialGroup(std::move(name), index, density), model(model) {}

  Model model;
  std::vector<Mat3> F;                        ///< elastic deformation gradient
  std::vector<typename Model::State> state;   ///< plastic state
  typename Model::State initialState{};       ///< state of newly seeded particles

  const char* modelName() const override { return Model::kName; }
  std::unique_ptr<MaterialGroup> emptyCopy() const override {
    auto g = std::make_unique<SolidGroup>(name(), index(), density(), model);
    g->initialState = initialState;
    g->basalLaw = basalLaw;
    return g;
  }
  double waveSpeed() const override { return model.waveSpeed(density()); }

  bool averagesVolume() const override { return true; }

  void gridToParticles(const G2PBlock& blk, size_t begin, size_t end, G2PStats& stats) override {
    const double dt = blk.dt;
    SolidLaneParams lanes;
    if (solidLaneParams(model, lanes)) {
      gatherParticleChunks(blk, particles, begin, end, stats, [&](const GatheredChunk& c) { updateInLanes(lanes, dt, c); });
      return;
    }
    gatherParticles(blk, particles, begin, end, stats, [&](size_t p, const Mat3& C, double fbar) {
      const Mat3d Ftrial =
          (fbar * (Mat3d::Identity() + dt * C.template cast<double>())) * F[p].template cast<double>();
      updateSolid(model, Ftrial, state[p], F[p], particles.tau[p], dt);
    });
  }

  void saveState(StateArchive& a, const std::string& prefix) const override {
    a.putVector(prefix + "F", F);
    a.putVector(prefix + "state", state);
  }
  void loadState(const StateArchive& a, const std::string& prefix) override {
    a.getVector(prefix + "F", F);
    a.getVector(prefix + "state", state);
  }
  size_t stateSize() const override { return F.size() == state.size() ? F.size() : size_t(-1); }

  void permuteState(const Permutation& perm, ReorderScratch& scratch) override {
    gatherInPlace(F, perm, scratch);
    gatherInPlace(state, perm, scratch);
  }
  void compactState(const std::vector<uint8_t>& keep) override {
    compactInPlace(F, keep);
    compactInPlace(state, keep);
  }
  void resizeState(size_t n) override {
    F.resize(n, Mat3::Identity());
    state.resize(n, initialState);
  }
  void reserveState(size_t n) override {
    F.reserve(n);
    state.reserve(n);
  }
  void releaseState() override {
    decltype(F)().swap(F);
    decltype(state)().swap(state);
  }
  void packState(const std::vector<uint32_t>& idx, char* out) const override { packRecords(idx, out, F, state); }
  void appendState(const char* in, size_t n) override { appendRecords(in, n, F, state); }
  /// "pressure" (Cauchy, Pa, compression positive) and the model's own state variables.
  std::vector<std::string> scalarNames() const override {
    std::vector<std::string> n{"pressure"};
    for (const auto& s : Model::stateScalarNames()) n.push_back(s);
    return n;
  }
  void scalar(const std::string& name, std::vector<float>& out) const override {
    out.assign(size(), 0.0f);
    if (name == "pressure") {
      for (size_t i = 0; i < size(); ++i)
        out[i] = float(-particles.tau[i].trace() / (3.0 * double(F[i].determinant())));
      return;
    }
    const auto names = Model::stateScalarNames();
    for (size_t k = 0; k < names.size(); ++k)
      if (names[k] == name)
        for (size_t i = 0; i < size(); ++i) out[i] = model.stateScalar(state[i], particles.tau[i], k);
  }

  size_t stateBytesPerParticle() const override {
    return sizeof(Mat3) + sizeof(typename Model::State);
  }

private:
  /// One chunk's update in SIMD lanes (materials/solid_lanes.h); a lane off the usual path takes
  /// the scalar updateSolid on the trial F the kernel formed.
  void updateInLanes(const SolidLaneParams& prm, double dt, const GatheredChunk& c) {
    SolidLanes io;
    for (int k = 0; k < kSolidLanes; ++k) {
      const bool live = k < c.count;
      const size_t p = c.first + size_t(live ? k : 0);
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q) {
          io.C[3 * r + q][k] = live ? double(particles.C[p](r, q)) : 0.0;
          io.F[3 * r + q][k] = live ? double(F[p](r, q)) : double(r == q);
        }
      io.fbar[k] = live ? c.fbar[k] : 1.0;
      io.strain[k] = io.extra[k] = 0;
      if (live) laneState(state[p], io.strain[k], io.extra[k]);
    }
    updateSolidLanes(prm, dt, c.count, io);
    for (int k = 0; k < c.count; ++k) {
      const size_t p = c.first + size_t(k);
      if (io.scalar[k] != 0) {
        Mat3d Ftrial;
        for (int r = 0; r < 9; ++r) Ftrial(r / 3, r % 3) = io.Ftrial[r][k];
        updateSolid(model, Ftrial, state[p], F[p], particles.tau[p], dt);
        continue;
      }
      for (int r = 0; r < 9; ++r) F[p](r / 3, r % 3) = Real(io.F[r][k]);
      Sym3& t = particles.tau[p];
      t.xx = Real(io.tau[0][k]), t.yy = Real(io.tau[1][k]), t.zz = Real(io.tau[2][k]);
      t.xy = Real(io.tau[3][k]), t.xz = Real(io.tau[4][k]), t.yz = Real(io.tau[5][k]);
      setLaneState(state[p], io.strain[k], io.extra[k]);
    }
  }
};

} // namespace talus
