#include "engine/line_ranks.h"

#include "engine/flow_thickness.h"

namespace talus {

namespace {
int32_t& along(BlockCoord& c, int axis) { return axis == 0 ? c.x : axis == 1 ? c.y : c.z; }
/// The two in-plane axes of a line along `axis`.
void inPlane(int axis, int& u, int& v) { u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2; }
} // namespace

const std::vector<uint64_t>& LineRanks::lineOwners(const BlockCoord& c, int axis) {
  auto [it, fresh] = owners_[axis].try_emplace(FlowColumns::lineKey(c, axis));
  if (!fresh) return it->second;
  std::vector<uint64_t>& bits = it->second;
  bits.assign((size_t(ranks_.size()) + 63) / 64, 0);
  int u, v;
  inPlane(axis, u, v);
  BlockCoord p = c, lo = lo_, hi = hi_;
  // Outside the domain's in-plane extent no rank owns blocks: the line is empty.
  if (along(p, u) < along(lo, u) || along(p, u) > along(hi, u) || along(p, v) < along(lo, v) || along(p, v) > along(hi, v))
    return bits;
  for (int32_t i = along(lo, axis); i <= along(hi, axis); ++i) {
    along(p, axis) = i;
    const int r = ranks_.owner(p);
    bits[size_t(r) / 64] |= uint64_t(1) << (r % 64);
  }
  return bits;
}

const std::vector<int>& LineRanks::holders(const BlockCoord& c, int axis) {
  if (generation_ != ranks_.generation()) {
    for (auto& o : owners_) o.clear();
    for (auto& h : holders_) h.clear();
    generation_ = ranks_.generation();
  }
  auto [at, fresh] = holders_[axis].try_emplace(FlowColumns::lineKey(c, axis));
  std::vector<int>& out = at->second;
  if (!fresh) return out;
  mask_.assign((size_t(ranks_.size()) + 63) / 64, 0);
  int u, v;
  inPlane(axis, u, v);
  for (int du = -kReach; du <= kReach; ++du)
    for (int dv = -kReach; dv <= kReach; ++dv) {
      BlockCoord n = c;
      along(n, u) += du, along(n, v) += dv;
      const std::vector<uint64_t>& bits = lineOwners(n, axis);
      for (size_t w = 0; w < bits.size(); ++w) mask_[w] |= bits[w];
    }
  for (int r = 0; r < ranks_.size(); ++r)
    if (mask_[size_t(r) / 64] >> (r % 64) & 1) out.push_back(r);
  return out;
}

} // namespace talus
