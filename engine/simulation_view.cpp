// Rank 0's view of a run on MPI ranks (io/run/run.cpp): a Simulation that is never stepped and
// holds every particle only while files are written from it. It shares the run's terrain and
// colliders' geometry, and is filled from the ranks' parts in one process's order, so a file
// written from it is one process's file.
#include "engine/simulation.h"

#include "engine/gathered_parts.h"

#include <numeric>
#include <string_view>

namespace talus {

std::unique_ptr<Simulation> Simulation::emptyView() const {
  std::vector<std::unique_ptr<MaterialGroup>> groups;
  for (const MaterialGroup* g : groupPtrs_) groups.push_back(g->emptyCopy());
  auto view = std::make_unique<Simulation>(settings_, std::move(groups)); // the covers are in bed_
  if (bed_) view->bed_ = std::make_unique<ErodibleBed>(*bed_);
  return view;
}

void Simulation::gatherSeededInto(Communicator& comm, Simulation* view,
                                  const std::vector<std::vector<uint64_t>>* seedIndex) const {
  if ((comm.rank() == 0) != (view != nullptr)) throw std::logic_error("gatherSeededInto: rank 0 and only rank 0 passes a view");
  for (size_t gi = 0; gi < groupPtrs_.size(); ++gi) {
    const MaterialGroup& g = *groupPtrs_[gi];
    MaterialGroup* to = view ? view->groupPtrs_[gi] : nullptr;
    if (!seedIndex) { // every rank holds every particle
      if (!to) continue;
      std::vector<char> records;
      std::vector<uint32_t> idx(g.size());
      std::iota(idx.begin(), idx.end(), 0u);
      packParticles(g, idx, records);
      to->release();
      to->reserve(g.size());
      appendParticles(*to, records);
      continue;
    }
    static const std::vector<uint64_t> none;
    const auto& key = size_t(g.index()) < seedIndex->size() ? (*seedIndex)[size_t(g.index())] : none;
    if (key.size() != g.size()) throw std::logic_error("gatherSeededInto: one index per particle");
    // In windows of one process's indices, each one message at most, so rank 0 holds the view
    // and one window, not every rank's records besides.
    const size_t rec = ParticleSet::bytesPerParticle() + g.stateBytesPerParticle();
    const uint64_t total = comm.sumOf(uint64_t(key.size()));
    const uint64_t window = std::max<uint64_t>(1, comm.maxMessageBytes / (sizeof(uint64_t) + rec));
    if (to) to->release(), to->reserve(size_t(total));
    for (uint64_t first = 0; first < total; first += window) {
      std::vector<uint32_t> idx;
      for (size_t p = 0; p < key.size(); ++p)
        if (key[p] >= first && key[p] - first < window) idx.push_back(uint32_t(p));
      std::vector<char> mine;
      packKeyed(g, idx, key, mine);
      const GatheredParts all = gatherParts(comm, mine);
      if (to) appendInKeyOrder(*to, all.parts);
    }
  }
  if (!view) return;
  // What the constructor computes from the particles, as one process computes it from all of them.
  view->initialMass_ = view->totalMass();
  view->maxSpeed_ = 0;
  for (const MaterialGroup* g : view->groupPtrs_)
    for (const Vec3& v : g->particles.v) view->maxSpeed_ = std::max(view->maxSpeed_, double(v.norm()));
}

void Simulation::gatherInto(Simulation* view, ViewContents what) {
  Communicator& comm = ranks_->comm();
  if ((comm.rank() == 0) != (view != nullptr)) throw std::logic_error("gatherInto: rank 0 and only rank 0 passes a view");
  for (size_t gi = 0; gi < groupPtrs_.size(); ++gi) {
    const MaterialGroup& g = *groupPtrs_[gi];
    MaterialGroup* to = view ? view->groupPtrs_[gi] : nullptr;
    if (to) to->particles.resize(0), to->resizeState(0);
    // The particles the bed made since binning come after every rank's others, as one process
    // has them: gathered as a second part when there is a bed.
    const size_t fresh = gi < fresh_.size() ? fresh_[gi] : 0;
    const uint64_t made = bed_ && what == ViewContents::Everything ? comm.sumOf(uint64_t(fresh)) : 0;
    const size_t record = ParticleSet::bytesPerParticle() + g.stateBytesPerParticle();
    // Rank 0 appends one rank's particles at a time to arrays sized for all of them at once, so
    // it holds the whole run once, not a second time in a gathered buffer.
    auto gatherRange = [&](size_t begin, size_t end, uint64_t after) {
      std::vector<char> mine;
      std::vector<uint32_t> idx(end - begin);
      for (size_t i = 0; i < idx.size(); ++i) idx[i] = uint32_t(begin + i);
      packParticles(g, idx, mine);
      comm.gatherEach(
          mine,
          [&](const std::vector<size_t>& counts) {
            size_t bytes = 0;
            for (size_t c : counts) bytes += c;
            to->reserve(to->size() + bytes / record + size_t(after));
          },
          [&](int, std::string_view part) { appendParticles(*to, part); });
    };
    if (what == ViewContents::Everything) {
      gatherRange(0, g.size() - fresh, made);
      if (bed_) gatherRange(g.size() - fresh, g.size(), 0);
    }
    if (to) to->setRankMinima(g.rankMinima());
  }
  std::vector<double> removed = massRemoved_;
  if (!removed.empty()) comm.sum(removed.data(), removed.size());
  if (!view) return;
  view->time_ = time_, view->steps_ = steps_, view->particleSteps_ = particleSteps_, view->maxSpeed_ = maxSpeed_;
  view->loads_ = loads_;
  if (bed_) *view->bed_ = *bed_; // replicated on every rank
  view->massRemoved_ = removed;
  view->times_ = times_;
}

void Simulation::particleRecords(size_t group, std::vector<char>& settled, std::vector<char>& fresh) const {
  const MaterialGroup& g = *groupPtrs_.at(group);
  const size_t made = group < fresh_.size() ? fresh_[group] : 0;
  std::vector<uint32_t> idx(g.size() - made);
  std::iota(idx.begin(), idx.end(), 0u);
  packParticles(g, idx, settled);
  idx.resize(made);
  std::iota(idx.begin(), idx.end(), uint32_t(g.size() - made));
  packParticles(g, idx, fresh);
}

void Simulation::appendParticleRecords(size_t group, std::string_view records) {
  MaterialGroup& g = *groupPtrs_.at(group);
  if (records.size() % (ParticleSet::bytesPerParticle() + g.stateBytesPerParticle()) != 0)
    throw std::runtime_error("the particles of '" + g.name() + "' are not whole records");
  appendParticles(g, records);
}

} // namespace talus
