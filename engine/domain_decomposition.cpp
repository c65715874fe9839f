#include "engine/domain_decomposition.h"

#include "engine/bspline.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace talus {

DomainDecomposition::DomainDecomposition(std::shared_ptr<Communicator> comm, double imbalance)
    : comm_(std::move(comm)), threshold_(imbalance) {
  // Until balance(): everything on rank 0 (the ranges start empty, at the largest coordinate).
  const BlockCoord top{INT32_MAX, INT32_MAX, INT32_MAX};
  first_.assign(size_t(comm_->size() - 1), top);
}

int DomainDecomposition::owner(const BlockCoord& c) const {
  return int(std::upper_bound(first_.begin(), first_.end(), c,
                              [](const BlockCoord& a, const BlockCoord& b) { return treeOrderLess(a, b); }) -
             first_.begin());
}

void DomainDecomposition::balance(std::vector<std::pair<BlockCoord, uint64_t>> blocks) {
  std::sort(blocks.begin(), blocks.end(), [](const auto& a, const auto& b) { return treeOrderLess(a.first, b.first); });
  ++generation_;
  uint64_t total = 0;
  for (const auto& b : blocks) total += b.second;
  const int n = comm_->size();
  const BlockCoord top{INT32_MAX, INT32_MAX, INT32_MAX};
  first_.assign(size_t(n - 1), top);
  // Rank r's range starts at the first block whose cumulative count reaches start[r].
  std::vector<double> start(size_t(n), 0.0);
  for (int r = 1; r < n; ++r)
    start[size_t(r)] = shares_.empty() ? double(r) / n * double(total) : start[size_t(r - 1)] + shares_[size_t(r - 1)] * double(total);
  uint64_t before = 0;
  int r = 1;
  for (const auto& [c, count] : blocks) {
    // The block starting at `before` goes to the rank whose share of the total holds it.
    while (r < n && (shares_.empty() ? before * uint64_t(n) >= uint64_t(r) * total : double(before) >= start[size_t(r)]))
      first_[size_t(r++ - 1)] = c;
    before += count;
  }
  // What these ranges leave: the floor of the next rebalance's trigger (wantsRebalance).
  std::vector<double> counts(size_t(n), 0.0);
  for (const auto& [c, count] : blocks) counts[size_t(owner(c))] += double(count);
  settled_ = std::max(0.0, imbalanceOf(counts));
  sinceBalance_ = 0;
}

void DomainDecomposition::setShares(std::vector<double> shares) {
  if (!shares.empty() && shares.size() != size_t(comm_->size())) throw std::invalid_argument("setShares: one share per rank");
  shares_ = std::move(shares);
}

double DomainDecomposition::imbalance(size_t localParticles) const {
  // One collective: every rank's count, as a sum of vectors each holding one rank's (exact in
  // doubles below 2^53), then the total and the largest ratio on every rank alike.
  const int n = comm_->size();
  std::vector<double> counts(size_t(n), 0.0);
  counts[size_t(comm_->rank())] = double(localParticles);
  comm_->sum(counts.data(), counts.size());
  return imbalanceOf(counts);
}

double DomainDecomposition::imbalanceOf(const std::vector<double>& counts) const {
  const size_t n = counts.size();
  double total = 0;
  for (double c : counts) total += c;
  if (total <= 0) return 0;
  double largest = 0;
  for (size_t r = 0; r < n; ++r) {
    const double share = shares_.empty() ? 1.0 / double(n) : shares_[r];
    // A rank meant to hold nothing that holds something is as unbalanced as it gets.
    largest = std::max(largest, share > 0 ? counts[r] / (share * total) : counts[r] > 0 ? 1e30 : 0);
  }
  return largest - 1;
}

bool DomainDecomposition::wantsRebalance(double imbalance) {
  ++sinceBalance_;
  return imbalance > threshold_ && (imbalance > threshold_ + settled_ || sinceBalance_ >= kRetrySteps);
}

namespace {

/// Bytes of one particle's record: the common arrays, then the model's state.
size_t recordBytes(const MaterialGroup& g) { return ParticleSet::bytesPerParticle() + g.stateBytesPerParticle(); }

template <class T> void put(char*& out, const T& v) {
  std::memcpy(out, &v, sizeof(T));
  out += sizeof(T);
}
template <class T> void take(const char*& in, T& v) {
  std::memcpy(static_cast<void*>(&v), in, sizeof(T));
  in += sizeof(T);
}

} // namespace

void packParticles(const MaterialGroup& g, const std::vector<uint32_t>& idx, std::vector<char>& out) {
  const size_t rec = recordBytes(g), common = ParticleSet::bytesPerParticle();
  out.resize(idx.size() * rec);
  const ParticleSet& P = g.particles;
  for (size_t i = 0; i < idx.size(); ++i) {
    char* o = out.data() + i * rec;
    const uint32_t p = idx[i];
    put(o, P.x[p]), put(o, P.v[p]), put(o, P.C[p]), put(o, P.tau[p]), put(o, P.mass[p]);
  }
  std::vector<char> state(idx.size() * g.stateBytesPerParticle());
  g.packState(idx, state.data());
  for (size_t i = 0; i < idx.size(); ++i)
    std::memcpy(out.data() + i * rec + common, state.data() + i * g.stateBytesPerParticle(), g.stateBytesPerParticle());
}

void appendParticles(MaterialGroup& g, std::string_view in) {
  const size_t rec = recordBytes(g), common = ParticleSet::bytesPerParticle(), sb = g.stateBytesPerParticle();
  const size_t n = in.size() / rec, base = g.particles.size();
  if (!n) return;
  ParticleSet& P = g.particles;
  P.resize(base + n);
  std::vector<char> state(n * sb);
  for (size_t i = 0; i < n; ++i) {
    const char* s = in.data() + i * rec;
    const size_t p = base + i;
    take(s, P.x[p]), take(s, P.v[p]), take(s, P.C[p]), take(s, P.tau[p]), take(s, P.mass[p]);
    std::memcpy(state.data() + i * sb, in.data() + i * rec + common, sb);
  }
  g.appendState(state.data(), n);
}

size_t DomainDecomposition::migrate(const std::vector<MaterialGroup*>& groups, Real dx, const std::vector<size_t>* fresh) {
  const int n = comm_->size(), me = comm_->rank();
  const Real invDx = Real(1) / dx;
  size_t sent = 0;
  order_.assign(groups.size(), {});
  // Every material's leavers go in one message per rank (per material: its byte count, then its
  // records), so a step migrates with one exchange, not one per material. A rank no particle
  // goes to gets no message at all, as before.
  std::vector<std::vector<char>> send(static_cast<size_t>(n));
  std::vector<uint8_t> anyTo(static_cast<size_t>(n), 0);
  std::vector<std::vector<uint8_t>> stays(groups.size());
  std::vector<size_t> leaving(groups.size(), 0);
  std::vector<char> records;
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    const auto& x = groups[gi]->particles.x;
    std::vector<std::vector<uint32_t>> to(static_cast<size_t>(n));
    stays[gi].resize(x.size());
    BlockCoord last{INT32_MIN, 0, 0};
    int dest = me;
    for (size_t p = 0; p < x.size(); ++p) {
      const BlockCoord b = owningBlock(x[p], invDx);
      if (b != last) last = b, dest = owner(b);
      stays[gi][p] = dest == me;
      if (dest != me) to[size_t(dest)].push_back(uint32_t(p)), ++leaving[gi];
    }
    for (int r = 0; r < n; ++r) {
      if (r == me) continue;
      packParticles(*groups[gi], to[size_t(r)], records);
      const uint64_t bytes = records.size();
      std::vector<char>& out = send[size_t(r)];
      out.insert(out.end(), reinterpret_cast<const char*>(&bytes), reinterpret_cast<const char*>(&bytes) + sizeof bytes);
      out.insert(out.end(), records.begin(), records.end());
      sent += to[size_t(r)].size();
      anyTo[size_t(r)] |= !to[size_t(r)].empty();
    }
  }
  for (int r = 0; r < n; ++r)
    if (!anyTo[size_t(r)]) send[size_t(r)].clear();
  const auto recv = comm_->exchange(send);
  std::vector<size_t> at(static_cast<size_t>(n), 0); // where each rank's next material starts
  auto next = [&](int r) {
    const std::vector<char>& in = recv[size_t(r)];
    if (in.empty()) return std::string_view(); // nothing from r, in any material
    uint64_t bytes = 0;
    std::memcpy(&bytes, in.data() + at[size_t(r)], sizeof bytes);
    const std::string_view part(in.data() + at[size_t(r)] + sizeof bytes, size_t(bytes));
    at[size_t(r)] += sizeof bytes + size_t(bytes);
    return part;
  };
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    MaterialGroup* g = groups[gi];
    // Only what moves is copied: leavers are compacted out, arrivals appended (lower ranks'
    // first), and binning's stable sort takes the lower ranks' arrivals before our own particles.
    const size_t made = fresh && gi < fresh->size() ? (*fresh)[gi] : 0;
    const size_t madeStaying = size_t(std::count(stays[gi].end() - long(made), stays[gi].end(), uint8_t(1)));
    if (leaving[gi]) {
      g->particles.forEachArray([&](auto& a) { compactInPlace(a, stays[gi]); });
      g->compactState(stays[gi]);
    }
    const size_t own = g->size(), ownBefore = own - madeStaying;
    for (int r = 0; r < me; ++r) appendParticles(*g, next(r));
    const size_t lower = g->size() - own;
    for (int r = me + 1; r < n; ++r) appendParticles(*g, next(r));
    // One process's order: lower ranks' particles, ours, higher ranks', then the ones made since.
    if (lower || madeStaying)
      order_[gi] = {{own, own + lower}, {0, ownBefore}, {own + lower, g->size()}, {ownBefore, own}};
  }
  return sent;
}

void DomainDecomposition::keepOwn(const std::vector<MaterialGroup*>& groups, Real dx) {
  const Real invDx = Real(1) / dx;
  for (MaterialGroup* g : groups) {
    std::vector<uint8_t> keep(g->size());
    for (size_t p = 0; p < g->size(); ++p) keep[p] = owner(owningBlock(g->particles.x[p], invDx)) == comm_->rank();
    g->particles.forEachArray([&](auto& a) { compactInPlace(a, keep); });
    g->compactState(keep);
  }
}

void packKeyed(const MaterialGroup& g, const std::vector<uint32_t>& idx, const std::vector<uint64_t>& keys,
               std::vector<char>& out) {
  std::vector<char> records;
  packParticles(g, idx, records);
  out.resize(idx.size() * sizeof(uint64_t));
  for (size_t i = 0; i < idx.size(); ++i) std::memcpy(out.data() + i * sizeof(uint64_t), &keys[idx[i]], sizeof(uint64_t));
  out.insert(out.end(), records.begin(), records.end());
}

void appendInKeyOrder(MaterialGroup& g, const std::vector<std::string_view>& parts) {
  const size_t rec = recordBytes(g);
  std::vector<std::pair<uint64_t, const char*>> all;
  for (std::string_view part : parts) {
    const size_t count = part.size() / (sizeof(uint64_t) + rec);
    for (size_t i = 0; i < count; ++i) {
      uint64_t k;
      std::memcpy(&k, part.data() + i * sizeof(uint64_t), sizeof k);
      all.push_back({k, part.data() + count * sizeof(uint64_t) + i * rec});
    }
  }
  std::sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<char> ordered(all.size() * rec);
  for (size_t i = 0; i < all.size(); ++i) std::memcpy(ordered.data() + i * rec, all[i].second, rec);
  appendParticles(g, ordered);
}

void DomainDecomposition::scatterSeeded(const std::vector<MaterialGroup*>& groups, Real dx,
                                        const std::vector<std::vector<uint64_t>>& index) {
  const int n = comm_->size(), me = comm_->rank();
  const Real invDx = Real(1) / dx;
  for (MaterialGroup* g : groups) {
    static const std::vector<uint64_t> none;
    const std::vector<uint64_t>& key = size_t(g->index()) < index.size() ? index[size_t(g->index())] : none;
    if (key.size() != g->size()) throw std::logic_error("scatterSeeded: one index per particle");
    std::vector<std::vector<uint32_t>> to(static_cast<size_t>(n));
    for (size_t p = 0; p < g->size(); ++p) to[size_t(owner(owningBlock(g->particles.x[p], invDx)))].push_back(uint32_t(p));
    std::vector<std::vector<char>> send(static_cast<size_t>(n));
    for (int r = 0; r < n; ++r) packKeyed(*g, to[size_t(r)], key, send[size_t(r)]);
    std::vector<char> own = std::move(send[size_t(me)]);
    send[size_t(me)].clear();
    std::vector<std::vector<char>> recv = comm_->exchange(send);
    recv[size_t(me)] = std::move(own);
    std::vector<std::string_view> parts;
    for (const auto& buf : recv) parts.emplace_back(buf.data(), buf.size());
    g->particles.resize(0);
    g->resizeState(0);
    appendInKeyOrder(*g, parts);
  }
}

} // namespace talus
