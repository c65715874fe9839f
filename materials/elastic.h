// Purely elastic solid: Hencky St. Venant-Kirchhoff, no plasticity.
#pragma once

#include "materials/hencky.h"

#include <string>
#include <vector>

namespace talus {

struct ElasticModel {
  static constexpr const char* kName = "elastic";
  struct State {
    uint8_t unused = 0; ///< an empty struct still takes a byte: make it a defined one (see cam_clay.h)
  };

  HenckyElasticity elastic;

  bool project(Vec3d&, State&, double /*dt*/) const { return false; }
  Vec3d stress(const Vec3d& eps, const State&) const { return elastic.stress(eps); }
  double waveSpeed(double rho) const { return elastic.waveSpeed(rho); }
  static std::vector<std::string> stateScalarNames() { return {}; }
  float stateScalar(const State&, const Sym3&, size_t) const { return 0; }
};

} // namespace talus
