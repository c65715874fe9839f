#include "engine/collider.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace talus {

void ColliderMotion::pose(double t, Mat3d& R, Vec3d& d) const {
  const double tau = std::clamp(t - start, 0.0, stop - start); // time spent moving
  const double w = angularVelocity.norm();
  R = w > 0 ? Eigen::AngleAxisd(w * tau, angularVelocity / w).toRotationMatrix() : Mat3d::Identity();
  d = velocity * tau;
}

Vec3d ColliderMotion::velocityAt(const Vec3d& x, double t) const {
  if (t < start || t >= stop) return Vec3d::Zero();
  Mat3d R;
  Vec3d d;
  pose(t, R, d);
  return velocity + angularVelocity.cross(x - (pivot + d));
}

Collider::Collider(std::string name, std::shared_ptr<const Sdf> sdf, std::shared_ptr<const ContactLaw> law,
                   ColliderMotion motion, const Vec3d& reference)
    : name_(std::move(name)), law_(std::move(law)), sdf_(std::move(sdf)), motion_(motion), reference_(reference) {
  sdf_->bounds(restLo_, restHi_);
}

Collider Collider::face(std::string name, int axis, bool upper, double at, std::shared_ptr<const ContactLaw> law) {
  Collider c(std::move(name), std::move(law));
  c.axis_ = axis, c.upper_ = upper, c.at_ = at;
  return c;
}

Collider Collider::panel(std::string name, int axis, bool upper, double at, std::shared_ptr<const ContactLaw> law,
                         const Vec3d& lo, const Vec3d& hi) {
  Collider c = face(std::move(name), axis, upper, at, std::move(law));
  c.windowed_ = true, c.windowLo_ = lo, c.windowHi_ = hi;
  return c;
}

double Collider::panelArea(double dx, const Vec3d& lo, const Vec3d& hi) const {
  if (!windowed_) return 0;
  double area = 1;
  const double tol = 1e-6 * dx;
  for (int a = 0; a < 3; ++a) {
    if (a == axis_) continue;
    // The nodes gatherFace takes on this axis, each with its cell around it clipped to the domain.
    const double from = std::max(windowLo_[a], lo[a]), to = std::min(windowHi_[a], hi[a]);
    double width = 0;
    for (long j = long(std::ceil((from - tol) / dx)); double(j) * dx <= to + tol; ++j)
      width += std::max(0.0, std::min(hi[a], (double(j) + 0.5) * dx) - std::max(lo[a], (double(j) - 0.5) * dx));
    area *= width;
  }
  return area;
}

Vec3d Collider::reference(double t) const {
  if (axis_ >= 0 || !motion_.moves()) return reference_;
  Mat3d R;
  Vec3d d;
  motion_.pose(t, R, d);
  return R * (reference_ - motion_.pivot) + motion_.pivot + d;
}

void Collider::prepare(const BlockTopology& topology, double dx, double t) {
  time_ = t;
  if (axis_ >= 0) return;
  if (motion_.moves()) {
    motion_.pose(t, R_, d_);
    return;
  }
  if (!cache_) cache_ = std::make_unique<SdfCache>(sdf_, dx, focusSolid_);
  cache_->attach(topology, blocks_);
  if (!params_) return;
  // Parameters of the nodes of blocks near the surface, sampled the first time a block is active.
  const int P = params_->count();
  paramBlocks_.assign(blocks_.size(), nullptr);
  for (uint32_t b = 0; b < blocks_.size(); ++b) {
    if (!blocks_[b]) continue;
    const BlockCoord& c = topology.coord(b);
    auto [it, fresh] = paramCache_.try_emplace(blockKey(c));
    if (fresh) {
      it->second.resize(size_t(kBlockNodes) * size_t(P));
      for (int n = 0; n < kBlockNodes; ++n)
        params_->sample(dx * Vec3d(c.x * kBlockDim + (n >> (2 * kBlockLog2)), c.y * kBlockDim + ((n >> kBlockLog2) & 7),
                                   c.z * kBlockDim + (n & 7)),
                        it->second.data() + size_t(n) * size_t(P));
    }
    paramBlocks_[b] = it->second.data();
  }
}

void Collider::gather(uint32_t b, const BlockCoord& c, double dx, const Vec4* nodes, ContactBatch& out) const {
  out.count = out.held = 0;
  if (axis_ >= 0) return gatherFace(c, dx, nodes, out);
  if (motion_.moves()) return gatherMoving(c, dx, nodes, out);
  const SdfBlock* s = blocks_[b];
  if (!s) return;
  for (int n = 0; n < kBlockNodes; ++n) {
    if (nodes[n][0] <= Real(0) || s->phi[n] > 0.f) continue;
    const Vec3 nrm(Real(s->normal[n][0]), Real(s->normal[n][1]), Real(s->normal[n][2]));
    // Deep inside a narrow band the distance is flat and has no normal: the node is held still.
    if (!(nrm.squaredNorm() > Real(0.25))) {
      out.node[kBlockNodes - 1 - out.held++] = int16_t(n);
      continue;
    }
    const int i = out.count++;
    out.node[i] = int16_t(n);
    out.contact[i].n = nrm;
    out.contact[i].params = paramBlocks_.empty() ? nullptr : paramBlocks_[b] + size_t(n) * size_t(params_->count());
  }
}

void Collider::gatherFace(const BlockCoord& c, double dx, const Vec4* nodes, ContactBatch& out) const {
  // Node index threshold: node i is on or beyond the lower face when i <= at/dx (and the upper
  // face when i >= at/dx), within rounding.
  const int limit = int(faceRow(at_, dx, upper_));
  const int o = (axis_ == 0 ? c.x : axis_ == 1 ? c.y : c.z) * kBlockDim;
  if (upper_ ? o + kBlockDim - 1 < limit : o > limit) return;
  Vec3 nrm = Vec3::Zero();
  nrm[axis_] = upper_ ? Real(-1) : Real(1);
  const int shift = axis_ == 0 ? 2 * kBlockLog2 : axis_ == 1 ? kBlockLog2 : 0;
  for (int n = 0; n < kBlockNodes; ++n) {
    const int idx = o + ((n >> shift) & (kBlockDim - 1));
    if (nodes[n][0] <= Real(0) || (upper_ ? idx < limit : idx > limit)) continue;
    if (windowed_) {
      const Vec3d x = dx * Vec3d(c.x * kBlockDim + (n >> (2 * kBlockLog2)), c.y * kBlockDim + ((n >> kBlockLog2) & 7),
                                 c.z * kBlockDim + (n & 7));
      const double tol = 1e-6 * dx;
      bool inside = true;
      for (int a = 0; a < 3; ++a)
        if (a != axis_) inside &= x[a] >= windowLo_[a] - tol && x[a] <= windowHi_[a] + tol;
      if (!inside) continue;
    }
    const int i = out.count++;
    out.node[i] = int16_t(n);
    out.contact[i].n = nrm;
    out.contact[i].params = nullptr;
  }
}

void Collider::gatherMoving(const BlockCoord& c, double dx, const Vec4* nodes, ContactBatch& out) const {
  // Skip blocks away from the moved rest bounds (a node counts when its phi <= 0).
  const Vec3d blo = Vec3d(c.x, c.y, c.z) * (kBlockDim * dx), bhi = blo + Vec3d::Constant((kBlockDim - 1) * dx);
  if (restLo_.allFinite() && restHi_.allFinite()) {
    Vec3d lo = Vec3d::Constant(INFINITY), hi = Vec3d::Constant(-INFINITY);
    for (int k = 0; k < 8; ++k) {
      const Vec3d corner((k & 4) ? restHi_.x() : restLo_.x(), (k & 2) ? restHi_.y() : restLo_.y(),
                         (k & 1) ? restHi_.z() : restLo_.z());
      const Vec3d p = R_ * (corner - motion_.pivot) + motion_.pivot + d_;
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
    if ((bhi.array() < lo.array()).any() || (blo.array() > hi.array()).any()) return;
  }
  for (int n = 0; n < kBlockNodes; ++n) {
    if (nodes[n][0] <= Real(0)) continue;
    const Vec3d x = blo + dx * Vec3d(n >> (2 * kBlockLog2), (n >> kBlockLog2) & (kBlockDim - 1), n & (kBlockDim - 1));
    const Vec3d rest = R_.transpose() * (x - motion_.pivot - d_) + motion_.pivot;
    if (sdf_->distance(rest) > 0) continue;
    const Vec3d nrm = R_ * sdf_->normal(rest, 0.25 * dx);
    const Vec3 vc = motion_.velocityAt(x, time_).cast<Real>();
    if (!(nrm.squaredNorm() > 0.25)) {
      const int h = kBlockNodes - 1 - out.held++;
      out.node[h] = int16_t(n);
      out.velocity[h] = vc;
      continue;
    }
    const int i = out.count++;
    out.node[i] = int16_t(n);
    out.contact[i].n = nrm.cast<Real>();
    out.contact[i].params = nullptr;
    out.velocity[i] = vc;
  }
}

} // namespace talus
