#include "io/output/step_parts.h"

#include <algorithm>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace talus {

PartBounds PartBounds::of(const Simulation& sim) {
  PartBounds b;
  for (const auto* g : sim.groups()) {
    const ParticleSet& P = g->particles;
    // Maxima are exact in any order, so the split between threads does not matter.
    const PartBounds m = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, P.size(), 16384), PartBounds{},
        [&](const tbb::blocked_range<size_t>& r, PartBounds acc) {
          for (size_t i = r.begin(); i != r.end(); ++i) {
            acc.maxMass = std::max(acc.maxMass, double(P.mass[i]));
            acc.maxSpeed2 = std::max(acc.maxSpeed2, double(P.v[i].squaredNorm()));
            acc.maxCoord = std::max(acc.maxCoord, double(P.x[i].cwiseAbs().maxCoeff()));
          }
          return acc;
        },
        [](PartBounds a, const PartBounds& c) {
          a.maxMass = std::max(a.maxMass, c.maxMass);
          a.maxSpeed2 = std::max(a.maxSpeed2, c.maxSpeed2);
          a.maxCoord = std::max(a.maxCoord, c.maxCoord);
          return a;
        });
    b.maxMass = std::max(b.maxMass, m.maxMass);
    b.maxSpeed2 = std::max(b.maxSpeed2, m.maxSpeed2);
    b.maxCoord = std::max(b.maxCoord, m.maxCoord);
  }
  return b;
}

} // namespace talus
