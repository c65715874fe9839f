// The step on MPI ranks: distribution, and RankPhases (engine/simulation_phases.h): migration with
// rebalancing, the P2G halo, the thickness lines, the erodible bed's nodes and the reductions
// (engine/domain_decomposition.h, halo_exchange.h); the gather for rank 0's outputs.
#include "engine/simulation.h"
#include "engine/simulation_phases.h"

#include "engine/bspline.h"
#include "engine/particle_binning.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <initializer_list>
#include <map>
#include <unordered_map>
#include <unordered_set>

namespace talus {

namespace {
double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// This rank's owning blocks with their particle counts (after binning).
std::vector<std::pair<BlockCoord, uint64_t>> blockCounts(const SparseGrid& grid, const std::vector<MaterialGroup*>& groups) {
  std::vector<std::pair<BlockCoord, uint64_t>> out;
  for (uint32_t b : grid.owning) {
    uint64_t n = 0;
    for (const MaterialGroup* g : groups) n += g->blockStart[b + 1] - g->blockStart[b];
    out.push_back({grid.topology.coord(b), n});
  }
  return out;
}

/// Every rank's (block, particle count) pairs, concatenated in rank order, on every rank.
std::vector<std::pair<BlockCoord, uint64_t>> allBlockCounts(Communicator& comm,
                                                            const std::vector<std::pair<BlockCoord, uint64_t>>& mine) {
  std::vector<char> bytes(mine.size() * sizeof(mine[0]));
  if (!mine.empty()) std::memcpy(bytes.data(), mine.data(), bytes.size());
  std::vector<size_t> sizes;
  const std::vector<char> all = comm.allGather(bytes, sizes);
  std::vector<std::pair<BlockCoord, uint64_t>> out(all.size() / sizeof(mine[0]));
  if (!out.empty()) std::memcpy(static_cast<void*>(out.data()), all.data(), all.size());
  return out;
}

/// Per-block records for a gather: the block's coordinate, then the payload parts.
void appendBlockRecord(std::vector<char>& out, const BlockCoord& c,
                       std::initializer_list<std::pair<const void*, size_t>> parts) {
  size_t at = out.size(), bytes = sizeof c;
  for (const auto& part : parts) bytes += part.second;
  out.resize(at + bytes);
  std::memcpy(out.data() + at, &c, sizeof c);
  at += sizeof c;
  for (const auto& [data, n] : parts) std::memcpy(out.data() + at, data, n), at += n;
}

using BlockRecords = std::vector<std::pair<BlockCoord, const char*>>;

/// Appends the records of `rec` bytes in data[0, bytes) to `out` as (coordinate, payload).
void listRecords(const char* data, size_t bytes, size_t rec, BlockRecords& out) {
  for (size_t at = 0; at + rec <= bytes; at += rec) {
    BlockCoord c;
    std::memcpy(&c, data + at, sizeof c);
    out.push_back({c, data + at + sizeof c});
  }
}

void sortInTreeOrder(BlockRecords& r) {
  std::sort(r.begin(), r.end(), [](const auto& x, const auto& y) { return treeOrderLess(x.first, y.first); });
}

/// Gathered records of `rec` bytes each, as (coordinate, payload), in one process's block order.
BlockRecords recordsInTreeOrder(const std::vector<char>& all, size_t rec) {
  BlockRecords out;
  listRecords(all.data(), all.size(), rec, out);
  sortInTreeOrder(out);
  return out;
}
} // namespace

void Simulation::distribute(std::shared_ptr<Communicator> comm, double imbalance,
                            const std::vector<std::vector<uint64_t>>* seedIndex) {
  if (periodic_.any()) throw std::invalid_argument("periodic axes do not run on several ranks yet (run without mpirun)");
  if (settings_.fbar) throw std::invalid_argument("[simulation] fbar does not run on several ranks yet (run without mpirun)");
  if (grid_.channels.stateJ >= 0)
    throw std::invalid_argument("a water's smooth_pressure does not run on several ranks yet (run without mpirun)");
  if (!settings_.sources.empty())
    throw std::invalid_argument("secondary releases, inflows and forests' detrainment do not run on several ranks yet (run without mpirun, "
                                "or set detrainment = 0 in the resistance regions)");
  ranks_ = std::make_unique<DomainDecomposition>(std::move(comm), imbalance);
  phases_ = std::make_unique<RankPhases>(*this);
  if (!seedIndex) {
    // Every rank holds every particle here: the same binning everywhere gives the same ranges.
    binParticles(groupPtrs_, grid_, reorder_, &periodic_);
    ranks_->balance(blockCounts(grid_, groupPtrs_));
    ranks_->keepOwn(groupPtrs_, grid_.dx);
    return;
  }
  // Each rank holds a part: the ranges come from every rank's block counts added up.
  const Real invDx = Real(1) / grid_.dx;
  auto less = [](const BlockCoord& a, const BlockCoord& b) { return treeOrderLess(a, b); };
  std::map<BlockCoord, uint64_t, decltype(less)> counts(less);
  for (const MaterialGroup* g : groupPtrs_)
    for (const Vec3& x : g->particles.x) ++counts[owningBlock(x, invDx)];
  const auto all = allBlockCounts(ranks_->comm(), {counts.begin(), counts.end()});
  counts.clear();
  for (const auto& [c, count] : all) counts[c] += count; // a block seeded on several ranks
  ranks_->balance({counts.begin(), counts.end()});
  ranks_->scatterSeeded(groupPtrs_, grid_.dx, *seedIndex);
  maxSpeed_ = ranks_->comm().maxOf(maxSpeed_); // the initial velocities' largest, as one process's
}

size_t Simulation::globalParticleCount() const {
  return ranks_ ? size_t(ranks_->comm().sumOf(particleCount())) : particleCount();
}

void Simulation::RankPhases::agreeOnDt(double& wave, double& limit) const {
  double v[2] = {-wave, limit}; // one collective: the largest wave speed as the smallest -wave
  sim_.ranks_->comm().minimum(v, 2);
  wave = -v[0], limit = v[1];
}

const HaloExchange* Simulation::RankPhases::exchangeHalo(Real dt) {
  sim_.halo_.exchange(sim_.groupPtrs_, sim_.grid_, dt, *sim_.ranks_);
  return &sim_.halo_;
}

std::function<bool(const Vec3&)> Simulation::RankPhases::makesHere() const {
  const Simulation& s = sim_;
  return [&s](const Vec3& x) { return s.ranks_->owner(owningBlock(x, Real(1) / s.grid_.dx)) == s.ranks_->rank(); };
}

void Simulation::RankPhases::bin() {
  Simulation& s = sim_;
  auto t0 = std::chrono::steady_clock::now();
  s.ranks_->migrate(s.groupPtrs_, s.grid_.dx, &s.fresh_);
  s.times_.halo += secondsSince(t0);
  t0 = std::chrono::steady_clock::now();
  binParticles(s.groupPtrs_, s.grid_, s.reorder_, &s.periodic_, &s.ranks_->order());
  s.times_.bin += secondsSince(t0);
  t0 = std::chrono::steady_clock::now();
  // The imbalance of the last step's counts (reduceStepFigures), so it costs no collective here.
  if (s.ranks_->wantsRebalance(imbalance_)) {
    // New ranges from every rank's blocks; the order of the particles across ranks is unchanged.
    s.ranks_->balance(allBlockCounts(s.ranks_->comm(), blockCounts(s.grid_, s.groupPtrs_)));
    s.ranks_->migrate(s.groupPtrs_, s.grid_.dx);
    ++s.ranks_->rebalances;
    s.times_.halo += secondsSince(t0);
    t0 = std::chrono::steady_clock::now();
    binParticles(s.groupPtrs_, s.grid_, s.reorder_, &s.periodic_, &s.ranks_->order());
    s.times_.bin += secondsSince(t0);
  } else {
    s.times_.halo += secondsSince(t0);
  }
}

void Simulation::RankPhases::reduceLoads(Real dt) {
  Simulation& s = sim_;
  // One process adds every block's loads in block (tree) order. Each block's loads are counted
  // on one rank; rank 0 gathers the blocks that took any load and adds them in the same order,
  // so the loads are one process's, bit for bit (blocks without load add exact zeros there).
  const size_t K = s.loads_.size(), rec = sizeof(BlockCoord) + 6 * K * sizeof(double);
  if (!K) return;
  const auto& counted = s.halo_.counted();
  std::vector<char> mine;
  for (uint32_t b = 0; b < s.grid_.blockCount(); ++b) {
    const double* a = &s.grid_.contactImpulse[size_t(b) * K * 6];
    if (!counted[b] || std::all_of(a, a + 6 * K, [](double v) { return v == 0; })) continue;
    appendBlockRecord(mine, s.grid_.topology.coord(b), {{a, 6 * K * sizeof(double)}});
  }
  std::vector<size_t> counts;
  const std::vector<char> all = s.ranks_->comm().gather(mine, counts);
  if (s.ranks_->rank() != 0) return; // only rank 0 reports loads (its outputs)
  const auto blocks = recordsInTreeOrder(all, rec);
  s.loads_.assign(K, ColliderLoad{});
  const double invDt = 1.0 / double(dt);
  std::vector<double> a(6 * K);
  for (const auto& [c, p] : blocks) {
    std::memcpy(a.data(), p, 6 * K * sizeof(double));
    for (size_t k = 0; k < K; ++k) {
      s.loads_[k].force += Vec3d(a[k * 6], a[k * 6 + 1], a[k * 6 + 2]) * invDt;
      s.loads_[k].moment += Vec3d(a[k * 6 + 3], a[k * 6 + 4], a[k * 6 + 5]) * invDt;
    }
  }
}

LineRanks& Simulation::RankPhases::lineRanks() {
  if (!lineRanks_) {
    // The blocks a particle inside the domain can own, and one more on every side.
    const Simulation& s = sim_;
    const Real invDx = Real(1 / s.settings().dx);
    const Vec3 lo = s.settings().domain.min.cast<Real>(), hi = s.settings().domain.max.cast<Real>();
    BlockCoord a = owningBlock(lo, invDx), b = owningBlock(hi, invDx);
    a.x -= 1, a.y -= 1, a.z -= 1, b.x += 1, b.y += 1, b.z += 1;
    lineRanks_ = std::make_unique<LineRanks>(*s.ranks_, a, b);
  }
  return *lineRanks_;
}

namespace {

/// A thickness line asked for: its axis and the coordinate of one of its blocks (16 bytes).
struct LineRequest {
  int32_t axis;
  BlockCoord block;
};

/// The lines this rank's grid update reads, each once: for every node in contact with a
/// collider, the line along the axis closest to its normal (FlowColumns::axisOf) through its
/// block, and the lines next to it (the thickest-line rule). Colliders must be prepared.
std::vector<LineRequest> linesRead(const SparseGrid& grid, const std::vector<Collider*>& colliders) {
  std::vector<LineRequest> out;
  std::unordered_set<uint64_t> seen[3];
  auto batch = std::make_unique<ContactBatch>();
  for (uint32_t b = 0; b < grid.blockCount(); ++b) {
    const BlockCoord& c = grid.topology.coord(b);
    bool axes[3] = {false, false, false};
    for (const Collider* col : colliders) {
      col->gather(b, c, grid.dx, grid.block(b), *batch);
      for (int i = 0; i < batch->count; ++i) axes[FlowColumns::axisOf(batch->contact[i].n)] = true;
    }
    for (int32_t axis = 0; axis < 3; ++axis) {
      if (!axes[axis]) continue;
      for (int du = -1; du <= 1; ++du)
        for (int dv = -1; dv <= 1; ++dv) {
          BlockCoord line = c;
          (axis == 0 ? line.y : line.x) += du, (axis == 2 ? line.y : line.z) += dv; // the two in-plane axes
          if (seen[axis].insert(FlowColumns::lineKey(line, axis)).second) out.push_back({axis, line});
        }
    }
  }
  return out;
}

} // namespace

std::vector<std::vector<char>> Simulation::RankPhases::answerLines(const std::vector<std::vector<char>>& asked,
                                                                  std::vector<uint32_t>& mine) {
  Simulation& s = sim_;
  const Communicator& comm = s.ranks_->comm();
  const int me = comm.rank();
  // This rank's counted blocks with flow, as records (kept between steps: no page faults), indexed
  // by the line they lie on per axis.
  const auto& counted = s.halo_.counted();
  const size_t C = size_t(s.grid_.channels.count), T = size_t(s.grid_.channels.thickness);
  const size_t rec = sizeof(BlockCoord) + 2 * kBlockNodes * sizeof(float);
  std::vector<char>& records = lineRecords_;
  records.clear();
  std::unordered_map<uint64_t, std::vector<uint32_t>> onLine[3];
  std::vector<float> volume(kBlockNodes), mass(kBlockNodes);
  for (uint32_t b = 0; b < s.grid_.blockCount(); ++b) {
    if (!counted[b]) continue;
    const Vec4* nodes = s.grid_.block(b);
    const float* extra = s.grid_.blockExtra(b);
    bool flow = false;
    for (int n = 0; n < kBlockNodes; ++n) {
      volume[size_t(n)] = extra[size_t(n) * C + T];
      mass[size_t(n)] = float(nodes[n][0]);
      flow |= volume[size_t(n)] > 0;
    }
    if (!flow) continue;
    const BlockCoord c = s.grid_.topology.coord(b);
    const uint32_t index = uint32_t(records.size() / rec);
    appendBlockRecord(records, c, {{volume.data(), kBlockNodes * sizeof(float)}, {mass.data(), kBlockNodes * sizeof(float)}});
    for (int axis = 0; axis < 3; ++axis) onLine[axis][FlowColumns::lineKey(c, axis)].push_back(index);
  }
  // Each asking rank gets each of its lines' blocks once; this rank's own are read in place.
  std::vector<std::vector<char>> answers(size_t(comm.size()));
  std::vector<int> sentTo(records.size() / rec, -1);
  for (int r = 0; r < comm.size(); ++r) {
    const std::vector<char>& lines = asked[size_t(r)];
    for (size_t at = 0; at + sizeof(LineRequest) <= lines.size(); at += sizeof(LineRequest)) {
      LineRequest q;
      std::memcpy(&q, lines.data() + at, sizeof q);
      const auto it = onLine[q.axis].find(FlowColumns::lineKey(q.block, q.axis));
      if (it == onLine[q.axis].end()) continue;
      for (uint32_t i : it->second) {
        if (sentTo[i] == r) continue;
        sentTo[i] = r;
        if (r == me) mine.push_back(i);
        else answers[size_t(r)].insert(answers[size_t(r)].end(), records.begin() + long(i * rec), records.begin() + long((i + 1) * rec));
      }
    }
  }
  return answers;
}

void Simulation::RankPhases::buildColumns() {
  Simulation& s = sim_;
  // Lines cross the whole grid. Each rank asks the ranks that may hold blocks of the lines its
  // contact nodes read (LineRanks), and each answers with its blocks with flow on them that it
  // counts (its node sums are complete): every line a rank reads arrives whole, and it adds each
  // line's blocks in one process's order. 16 bytes per line asked, 4 KB per block sent.
  Communicator& comm = s.ranks_->comm();
  std::vector<std::vector<char>> asks(size_t(comm.size()));
  for (const LineRequest& q : linesRead(s.grid_, s.colliderPtrs_))
    for (int r : lineRanks().holders(q.block, q.axis)) {
      std::vector<char>& to = asks[size_t(r)];
      to.resize(to.size() + sizeof q);
      std::memcpy(to.data() + to.size() - sizeof q, &q, sizeof q);
    }
  const std::vector<std::vector<char>> asked = comm.exchange(asks);

  std::vector<uint32_t> mine; // this rank's own answers, read in place
  std::vector<std::vector<char>> answers = answerLines(asked, mine);
  const size_t rec = sizeof(BlockCoord) + 2 * kBlockNodes * sizeof(float);
  const std::vector<char>& records = lineRecords_;
  std::vector<float> mass(kBlockNodes);
  const std::vector<std::vector<char>> received = comm.exchange(answers);
  BlockRecords blocks;
  for (uint32_t i : mine) listRecords(records.data() + size_t(i) * rec, rec, rec, blocks);
  for (const std::vector<char>& from : received) listRecords(from.data(), from.size(), rec, blocks);
  sortInTreeOrder(blocks);
  // The volumes are read in the records (floats, 4-byte aligned); the masses become Reals.
  std::vector<Real>& masses = lineMasses_;
  masses.resize(blocks.size() * kBlockNodes);
  std::vector<FlowColumns::BlockFlow> flows;
  flows.reserve(blocks.size());
  for (size_t i = 0; i < blocks.size(); ++i) {
    const auto& [c, p] = blocks[i];
    Real* m = masses.data() + i * kBlockNodes;
    std::memcpy(mass.data(), p + kBlockNodes * sizeof(float), kBlockNodes * sizeof(float));
    std::copy(mass.begin(), mass.end(), m);
    flows.push_back({c, reinterpret_cast<const float*>(p), 1, m, 1});
  }
  s.columns_.build(flows);
}

ErodibleBed::ShareNodes Simulation::RankPhases::shareWorkingNodes() {
  Simulation& s = sim_;
  return [&s](std::vector<ErodibleBed::WorkingNode>& nodes) {
    // Every rank's nodes, each from the rank counting its block, in tree order, then node order
    // (each rank's nodes of a block are in node order already, and a block is on one rank).
    using Node = ErodibleBed::WorkingNode;
    std::vector<char> mine(nodes.size() * sizeof(Node));
    if (!nodes.empty()) std::memcpy(mine.data(), nodes.data(), mine.size());
    std::vector<size_t> counts;
    const std::vector<char> all = s.ranks_->comm().allGather(mine, counts);
    nodes.resize(all.size() / sizeof(Node));
    if (!nodes.empty()) std::memcpy(static_cast<void*>(nodes.data()), all.data(), all.size());
    std::stable_sort(nodes.begin(), nodes.end(), [](const Node& a, const Node& b) { return treeOrderLess(a.block, b.block); });
  };
}

void Simulation::RankPhases::reduceStepFigures(G2PStats& stats, size_t& particles) {
  Simulation& s = sim_;
  // One collective per step for everything the ranks must agree on after G2P: the minima (the
  // largest speed as the smallest -speed, and each group's per-rank minima, e.g. the stiffest
  // particle's time step) and the sums (non-finite particles, particles stepped, and every rank's
  // count in its own slot, for the next binning's load balance). Sums of counts below 2^53 are
  // exact in doubles, whatever the order.
  std::vector<double> mins{-double(stats.maxSpeed)};
  for (auto* g : s.groupPtrs_) {
    const std::vector<double> v = g->rankMinima();
    mins.insert(mins.end(), v.begin(), v.end());
  }
  Communicator& comm = s.ranks_->comm();
  std::vector<double> sums(2 + size_t(comm.size()), 0.0);
  sums[0] = double(stats.nonFinite), sums[1] = double(particles);
  sums[2 + size_t(comm.rank())] = double(particles);
  comm.minimumAndSum(mins.data(), mins.size(), sums.data(), sums.size());
  imbalance_ = s.ranks_->imbalanceOf(std::vector<double>(sums.begin() + 2, sums.end()));
  stats.maxSpeed = Real(-mins[0]);
  stats.nonFinite = size_t(sums[0]), particles = size_t(sums[1]);
  size_t at = 1;
  for (auto* g : s.groupPtrs_) {
    const size_t n = g->rankMinima().size();
    if (n) g->setRankMinima(std::vector<double>(mins.begin() + long(at), mins.begin() + long(at + n)));
    at += n;
  }
}

void Simulation::RankPhases::throwNonFinite() const {
  const Simulation& s = sim_;
  // Every rank stops; all report the message of the lowest rank holding a non-finite particle.
  const std::string mine = s.nonFiniteMessage();
  std::vector<size_t> counts;
  const std::vector<char> all = s.ranks_->comm().allGather(std::vector<char>(mine.begin(), mine.end()), counts);
  size_t at = 0;
  for (size_t c : counts) {
    if (c) throw NumericalError(std::string(all.data() + at, c));
    at += c;
  }
  throw NumericalError("non-finite particle state at step " + std::to_string(s.steps_));
}

} // namespace talus
