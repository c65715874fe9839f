// Structure-of-arrays storage of the state every particle has, whatever its material.
#pragma once

#include "engine/types.h"

#include <tbb/parallel_for.h>
#include <vector>

namespace talus {

/// Positions are relative to the scene's local origin (see Simulation::origin()).
struct ParticleSet {
  std::vector<Vec3> x;    ///< position (m, local frame)
  std::vector<Vec3> v;    ///< velocity (m/s)
  std::vector<Mat3> C;    ///< APIC affine velocity matrix (1/s)
  std::vector<Sym3> tau;  ///< Kirchhoff stress used by the next P2G (Pa)
  std::vector<Real> mass; ///< kg, constant per particle

  size_t size() const { return x.size(); }

  template <class F> void forEachArray(F&& f) {
    f(x); f(v); f(C); f(tau); f(mass);
  }
  void resize(size_t n) {
    forEachArray([n](auto& a) { a.resize(n); });
  }
  static constexpr size_t bytesPerParticle() {
    return 2 * sizeof(Vec3) + sizeof(Mat3) + sizeof(Sym3) + sizeof(Real);
  }
};

/// a[i] <- a[perm[i]] for every i (perm is a gather permutation).
template <class T>
void gatherInPlace(std::vector<T>& a, const std::vector<uint32_t>& perm) {
  std::vector<T> tmp(a.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, a.size(), 8192), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) tmp[i] = a[perm[i]];
  });
  a.swap(tmp);
}

/// Keep the elements whose mask entry is non-zero, preserving order.
template <class T>
void compactInPlace(std::vector<T>& a, const std::vector<uint8_t>& keep) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (keep[i]) a[n++] = a[i];
  a.resize(n);
}

} // namespace talus
