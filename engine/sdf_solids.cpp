#include "engine/sdf_solids.h"

#include <algorithm>
#include <limits>

namespace talus {

bool UnionSdf::sampleBlock(const BlockCoord& c, double dx, SdfBlock& out) const {
  bool any = false;
  SdfBlock part;
  for (const auto& p : parts_) {
    if (!p->sampleBlock(c, dx, any ? part : out)) continue;
    if (any)
      for (int n = 0; n < kBlockNodes; ++n)
        if (part.phi[n] < out.phi[n]) {
          out.phi[n] = part.phi[n];
          std::copy(part.normal[n], part.normal[n] + 3, out.normal[n]);
        }
    any = true;
  }
  return any;
}

double UnionSdf::distance(const Vec3d& x) const {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& p : parts_) d = std::min(d, p->distance(x));
  return d;
}

std::string UnionSdf::describe() const {
  std::string s = "union of";
  for (size_t i = 0; i < parts_.size(); ++i) s += (i ? "; " : " ") + parts_[i]->describe();
  return s;
}


} // namespace talus
