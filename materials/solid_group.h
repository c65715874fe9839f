// Material group for elastoplastic solids: stores F^E and the model's plastic state per particle.
#pragma once

#include "engine/material_group.h"
#include "engine/transfer_g2p.h"
#include "materials/hencky.h"

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
  double waveSpeed() const override { return model.waveSpeed(density()); }

  bool averagesVolume() const override { return true; }

  void gridToParticles(const G2PBlock& blk, size_t begin, size_t end, G2PStats& stats) override {
    const double dt = blk.dt;
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
        for (size_t i = 0; i < size(); ++i) out[i] = Model::stateScalar(state[i], k);
  }

  size_t stateBytesPerParticle() const override {
    return sizeof(Mat3) + sizeof(typename Model::State);
  }
};

} // namespace talus
