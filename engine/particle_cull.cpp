#include "engine/particle_cull.h"

#include "engine/collider.h"

#include <cmath>
#include <functional>
#include <limits>
#include <tbb/parallel_reduce.h>

namespace talus {

CullBox cullBox(const DomainBox& domain, const std::array<std::shared_ptr<const ContactLaw>, 6>& faces,
                const Periodicity& periodic, double dx) {
  CullBox box;
  for (int d = 0; d < 3; ++d) {
    const double wallLo = double(Collider::faceRow(domain.min[d], dx, false)) * dx; // the node rows the faces hold
    const double wallHi = double(Collider::faceRow(domain.max[d], dx, true)) * dx;
    box.lo[d] = Real(faces[size_t(2 * d)] ? wallLo - 0.5 * dx : domain.min[d]);
    box.hi[d] = Real(faces[size_t(2 * d + 1)] ? wallHi + 0.5 * dx : domain.max[d]);
    if (periodic.axis[d]) box.lo[d] = -std::numeric_limits<Real>::max(), box.hi[d] = std::numeric_limits<Real>::max();
  }
  return box;
}

double cullOutside(MaterialGroup& group, const CullBox& box, const Periodicity& periodic, Real dx) {
  ParticleSet& P = group.particles;
  const size_t n = P.size();
  if (periodic.any())
    for (size_t p = 0; p < n; ++p)
      for (int a = 0; a < 3; ++a)
        if (periodic.axis[a]) P.x[p][a] = periodic.wrap(a, P.x[p][a], dx);
  std::vector<uint8_t> keep(n);
  const size_t kept = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 8192), size_t(0),
      [&](const auto& r, size_t acc) {
        for (size_t p = r.begin(); p != r.end(); ++p) {
          const Vec3& x = P.x[p];
          keep[p] = (x.array() >= box.lo.array()).all() && (x.array() <= box.hi.array()).all();
          acc += keep[p];
        }
        return acc;
      },
      std::plus<size_t>());
  if (kept == n) return 0.0;
  double removed = 0;
  for (size_t p = 0; p < n; ++p)
    if (!keep[p]) removed += double(P.mass[p]);
  P.forEachArray([&](auto& a) { compactInPlace(a, keep); });
  group.compactState(keep);
  return removed;
}

} // namespace talus
