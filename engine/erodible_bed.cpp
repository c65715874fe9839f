#include "engine/erodible_bed.h"

#include "engine/bspline.h"
#include "engine/domain_decomposition.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace talus {

ErodibleBed::ErodibleBed(std::vector<ErodibleCover> covers, std::shared_ptr<const Sdf> ground, double dx)
    : covers_(std::move(covers)), ground_(std::move(ground)), dx_(dx) {
  if (!ground_) throw std::invalid_argument("an erodible cover lies on the terrain: the scene has none");
  for (size_t c = 0; c < covers_.size(); ++c) {
    const ErodibleCover& cv = covers_[c];
    if (cv.columns.empty()) throw std::invalid_argument("erodible cover '" + cv.name + "' covers no node column");
    if (!(cv.erosionEnergy > 0) || !(cv.particleMass > 0))
      throw std::invalid_argument("erodible cover '" + cv.name + "': erosion energy and particle mass must be positive");
    for (const auto& col : cv.columns) {
      if (!(col.mass >= 0) || !std::isfinite(col.mass))
        throw std::invalid_argument("erodible cover '" + cv.name + "': a column of negative or non-finite mass");
      if (col.mass > 0) entries_.push_back(Entry{col.i, col.j, int32_t(c), col.mass, col.mass});
    }
  }
  // Sorted by column, then cover: the order every pass visits them in, whatever the input order.
  std::stable_sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
    return a.i != b.i ? a.i < b.i : a.j != b.j ? a.j < b.j : a.cover < b.cover;
  });
  for (uint32_t e = 0; e < entries_.size(); ++e) {
    auto [it, fresh] = columns_.try_emplace(columnKey(entries_[e].i, entries_[e].j), e, e + 1);
    if (!fresh) it->second.second = e + 1;
  }
  columnWork_.assign(entries_.size(), 0.0);
}

namespace {
/// Node n of block c: its column (i, j) and its position (local frame).
void nodeColumn(const BlockCoord& c, int n, int32_t& i, int32_t& j) {
  i = c.x * kBlockDim + (n >> (2 * kBlockLog2));
  j = c.y * kBlockDim + ((n >> kBlockLog2) & (kBlockDim - 1));
}
Vec3d nodePosition(const BlockCoord& c, int n, double dx) {
  int32_t i, j;
  nodeColumn(c, n, i, j);
  return Vec3d(i, j, c.z * kBlockDim + (n & (kBlockDim - 1))) * dx;
}
} // namespace

const std::pair<uint32_t, uint32_t>* ErodibleBed::columnOf(const BlockCoord& c, int n) const {
  int32_t i, j;
  nodeColumn(c, n, i, j);
  const auto it = columns_.find(columnKey(i, j));
  return it == columns_.end() ? nullptr : &it->second;
}

double ErodibleBed::nodeShare(const std::pair<uint32_t, uint32_t>& col, double work) const {
  double dm = 0;
  for (uint32_t e = col.first; e < col.second; ++e) dm += scratch_[e] * work;
  return dm;
}

void ErodibleBed::erode(SparseGrid& grid, double dt, const std::vector<uint8_t>* counted, const ShareNodes& share) {
  const size_t nBlocks = grid.blockCount();
  for (Entry& e : entries_) {
    e.idle += dt;
    if (e.pool > 0) e.age += dt;
  }
  // Calls f(block, node, column's [first, end)) for every node here that did basal work over a
  // cover, in block then node order.
  auto forEachWorkingNode = [&](auto&& f) {
    for (uint32_t b = 0; b < nBlocks; ++b) {
      const float* w = &work_[size_t(b) * kBlockNodes];
      for (int n = 0; n < kBlockNodes; ++n)
        if (w[n] > 0.f)
          if (const auto* col = columnOf(grid.topology.coord(b), n)) f(b, n, *col);
    }
  };
  std::vector<WorkingNode>& nodes = working_;
  nodes.clear();
  forEachWorkingNode([&](uint32_t b, int n, const std::pair<uint32_t, uint32_t>& col) {
    if (!counted || (*counted)[b])
      nodes.push_back({grid.topology.coord(b), n, work_[size_t(b) * kBlockNodes + size_t(n)], col.first, col.second, grid.block(b)[n]});
  });
  if (share) share(nodes);
  std::fill(columnWork_.begin(), columnWork_.end(), 0.0);
  for (const WorkingNode& wn : nodes) columnWork_[wn.first] += double(wn.work);
  // Each column's work erodes its covers top first: e_b dm of it per kilogram taken. What a cover
  // takes is stored as its share per joule of the column's work, so the nodes' shares sum to it.
  std::vector<double>& perJoule = scratch_;
  perJoule.assign(entries_.size(), 0.0);
  for (const auto& [k, col] : columns_) {
    const double W = columnWork_[col.first];
    if (!(W > 0)) continue;
    double left = W;
    for (uint32_t e = col.first; e < col.second && left > 0; ++e) {
      Entry& en = entries_[e];
      const double eb = covers_[size_t(en.cover)].erosionEnergy;
      const double dm = std::min(en.remaining, left / eb);
      en.remaining -= dm;
      left -= dm * eb;
      perJoule[e] = dm / W;
    }
  }
  // A node of mass m taking dm slows to v m / (m + dm): the same on every rank holding it.
  auto slowed = [](const Vec4& node, double dm) {
    const double m = double(node[0]);
    return Vec3((node.tail<3>().cast<double>() * (m / (m + dm))).cast<Real>());
  };
  for (const WorkingNode& wn : nodes) { // the pools, in one process's node order
    const double w = double(wn.work), dmNode = nodeShare({wn.first, wn.end}, w);
    if (!(dmNode > 0)) continue;
    const Vec3d v = slowed(wn.value, dmNode).cast<double>(), x = nodePosition(wn.block, wn.node, dx_);
    for (uint32_t e = wn.first; e < wn.end; ++e) {
      const double dm = perJoule[e] * w;
      if (!(dm > 0)) continue;
      Entry& en = entries_[e];
      en.pool += dm;
      en.idle = 0;
      en.momentum += dm * v;
      en.moment += dm * x;
    }
  }
  forEachWorkingNode([&](uint32_t b, int n, const std::pair<uint32_t, uint32_t>& col) { // every node held here
    Vec4& node = grid.block(b)[n];
    const double dmNode = nodeShare(col, double(work_[size_t(b) * kBlockNodes + size_t(n)]));
    if (dmNode > 0) node.tail<3>() = slowed(node, dmNode);
  });
}

size_t ErodibleBed::release(const std::vector<MaterialGroup*>& groups, const std::function<bool(const Vec3&)>& mine) {
  struct Made {
    BlockCoord block;
    int group;
    Vec3 x, v;
    Real m;
  };
  std::vector<Made> made;
  const Real invDx = Real(1) / Real(dx_); // as binning has it
  for (Entry& e : entries_) {
    const ErodibleCover& cv = covers_[size_t(e.cover)];
    // A pool's float residue after a particle took its mass stays (about 1e-7 of it).
    if (!(e.pool > 1e-6 * cv.particleMass)) continue;
    // Slower than a shallow-water wave over one cell, sqrt(g dx), counts as that speed.
    const double speed = std::max(e.momentum.norm() / e.pool, std::sqrt(9.81 * dx_));
    const double wait = kWaitCells * dx_ / speed;
    if (e.pool < cv.particleMass && e.remaining > 0 && e.idle < wait && e.age < kMaxWaits * wait) continue;
    // On the ground below where the mass came from, a quarter cell up (half a particle spacing).
    const Vec3d at = e.moment / e.pool;
    const Vec3d n = ground_->normal(at, 0.25 * dx_);
    const Vec3 x = (at - ground_->distance(at) * n + 0.25 * dx_ * n).cast<Real>();
    const Vec3d v = e.momentum / e.pool;
    const Real m = Real(e.pool);
    if (!mine || mine(x)) made.push_back({owningBlock(x, invDx), cv.group, x, v.cast<Real>(), m});
    const double rest = e.pool - double(m);
    e.momentum -= double(m) * v;
    e.moment = rest * at;
    e.pool = rest;
    e.age = 0;
  }
  std::stable_sort(made.begin(), made.end(), [](const Made& a, const Made& b) { return treeOrderLess(a.block, b.block); });
  for (const Made& p : made) {
    ParticleSet& P = groups[size_t(p.group)]->particles;
    P.x.push_back(p.x);
    P.v.push_back(p.v);
    P.C.push_back(Mat3::Zero());
    P.tau.push_back(Sym3{});
    P.mass.push_back(p.m);
    groups[size_t(p.group)]->resizeState(P.size());
  }
  return made.size();
}

double ErodibleBed::erodedMass(int32_t i, int32_t j, size_t cover) const {
  const auto it = columns_.find(columnKey(i, j));
  if (it == columns_.end()) return 0;
  for (uint32_t e = it->second.first; e < it->second.second; ++e)
    if (size_t(entries_[e].cover) == cover) return entries_[e].initial - entries_[e].remaining;
  return 0;
}

double ErodibleBed::initialMass(size_t cover) const { return sum(cover, 0.0, [](const Entry& e) { return e.initial; }); }
double ErodibleBed::remainingMass(size_t cover) const { return sum(cover, 0.0, [](const Entry& e) { return e.remaining; }); }
double ErodibleBed::pooledMass(size_t cover) const { return sum(cover, 0.0, [](const Entry& e) { return e.pool; }); }
Vec3d ErodibleBed::pooledMomentum(size_t cover) const {
  return sum(cover, Vec3d(Vec3d::Zero()), [](const Entry& e) { return e.momentum; });
}

namespace {
constexpr size_t kSaved = 10; ///< doubles per entry in a checkpoint
} // namespace

void ErodibleBed::save(StateArchive& a) const {
  std::vector<double> v;
  v.reserve(entries_.size() * kSaved);
  for (const Entry& e : entries_) {
    v.insert(v.end(), {e.remaining, e.pool, e.momentum.x(), e.momentum.y(), e.momentum.z(), e.moment.x(),
                       e.moment.y(), e.moment.z(), e.age, e.idle});
  }
  a.putVector("bed/entries", v);
}

void ErodibleBed::load(const StateArchive& a) {
  std::vector<double> v;
  a.getVector("bed/entries", v);
  if (v.size() != entries_.size() * kSaved) throw std::runtime_error("checkpoint's erodible covers do not fit the scene's");
  for (size_t k = 0; k < entries_.size(); ++k) {
    Entry& e = entries_[k];
    const double* s = &v[k * kSaved];
    e.remaining = s[0], e.pool = s[1];
    e.momentum = Vec3d(s[2], s[3], s[4]);
    e.moment = Vec3d(s[5], s[6], s[7]);
    e.age = s[8], e.idle = s[9];
  }
}

} // namespace talus
