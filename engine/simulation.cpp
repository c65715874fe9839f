#include "engine/simulation.h"
#include "engine/simulation_phases.h"

#include "engine/particle_cull.h"
#include "engine/bspline.h"

#include "engine/fbar.h"
#include "engine/grid_update.h"
#include "engine/particle_binning.h"
#include "engine/transfer_g2p.h"
#include "engine/transfer_p2g.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

namespace talus {

namespace {
class ScopedTimer {
public:
  explicit ScopedTimer(double& acc) : acc_(acc), t0_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() { acc_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
private:
  double& acc_;
  std::chrono::steady_clock::time_point t0_;
};
} // namespace

Simulation::Simulation(SimulationSettings settings, std::vector<std::unique_ptr<MaterialGroup>> groups)
    : settings_(std::move(settings)), groups_(std::move(groups)) {
  grid_.dx = Real(settings_.dx);
  for (auto& g : groups_) groupPtrs_.push_back(g.get());
  buildColliders();
  for (int a = 0; a < 3; ++a)
    if (settings_.periodic[size_t(a)]) {
      periodic_.axis[a] = true;
      periodic_.lo[a] = int(std::lround(settings_.domain.min[a] / settings_.dx));
      periodic_.n[a] = int(std::lround((settings_.domain.max[a] - settings_.domain.min[a]) / settings_.dx));
      if (periodic_.n[a] % kBlockDim != 0 || std::abs(periodic_.lo[a] * settings_.dx - settings_.domain.min[a]) > 1e-6 * settings_.dx)
        throw std::invalid_argument("a periodic axis needs a domain extent of a multiple of 8 dx from a node");
    }
  if (settings_.fbar && periodic_.any())
    throw std::invalid_argument("[simulation] fbar does not work with periodic axes yet");
  if (periodic_.any() && std::any_of(groupPtrs_.begin(), groupPtrs_.end(), [](const MaterialGroup* g) { return g->averagesState(); }))
    throw std::invalid_argument("a water's smooth_pressure does not work with periodic axes yet");
  if (!settings_.covers.empty()) {
    if (periodic_.any()) throw std::invalid_argument("erodible covers do not work with periodic axes yet");
    for (const ErodibleCover& c : settings_.covers)
      if (c.group < 0 || size_t(c.group) >= groups_.size())
        throw std::invalid_argument("erodible cover '" + c.name + "' names no material group");
    bed_ = std::make_unique<ErodibleBed>(std::move(settings_.covers), settings_.terrain, settings_.dx);
    settings_.covers.clear();
  }
  int maxIndex = 0;
  for (auto* g : groupPtrs_) maxIndex = std::max(maxIndex, g->index() + 1);
  massRemoved_.assign(size_t(maxIndex), 0.0);
  for (auto* g : groupPtrs_) g->initialize(settings_.gravity, settings_.dx);
  initialMass_ = totalMass();
  for (auto* g : groupPtrs_)
    for (const Vec3& v : g->particles.v) maxSpeed_ = std::max(maxSpeed_, double(v.norm()));
  phases_ = std::make_unique<LocalPhases>(*this);
}

Simulation::~Simulation() = default;

void Simulation::buildColliders() {
  // Order of action on a node: the terrain, structures at rest, the faces (as the walls always
  // acted last; each face after its panels), then moving structures, whose prescribed motion
  // must win where they overlap.
  auto structures = [&](bool moving) {
    for (const StructureSpec& s : settings_.structures)
      if (s.motion.moves() == moving)
        colliders_.push_back(std::make_unique<Collider>(s.name, s.geometry, s.law, s.motion, s.momentPoint));
  };
  if (settings_.terrain) {
    colliders_.push_back(std::make_unique<Collider>("terrain", settings_.terrain, settings_.terrainLaw, ColliderMotion{},
                                                    Vec3d::Zero()));
    colliders_.back()->setParameters(settings_.terrainParameters);
    // An erodible bed projects its pools onto the ground wherever they lie, long after the
    // flow's blocks left them (ErodibleBed::release): the terrain then stays whole.
    colliders_.back()->setFocusSolid(settings_.covers.empty());
  }
  structures(false);
  for (int f = 0; f < 6; ++f)
    if (settings_.faces[size_t(f)] && !settings_.periodic[size_t(f / 2)]) {
      const int axis = f / 2;
      const bool upper = f % 2;
      const double at = upper ? settings_.domain.max[axis] : settings_.domain.min[axis];
      for (const PanelSpec& p : settings_.panels) // each before its face, which keeps the rest
        if (p.face == f)
          colliders_.push_back(std::make_unique<Collider>(
              Collider::panel(p.name, axis, upper, at, settings_.faces[size_t(f)], p.lo, p.hi)));
      colliders_.push_back(std::make_unique<Collider>(Collider::face(
          faceNames()[size_t(f)], axis, upper, at, settings_.faces[size_t(f)])));
    }
  structures(true);
  for (auto& c : colliders_) colliderPtrs_.push_back(c.get());
  loads_.assign(colliders_.size(), ColliderLoad{});
  // P2G's extra channels (ExtraChannels): each particle's volume when a law needs the flow
  // thickness, then the node mass of each material with its own basal law, then AFLIP's
  // stress-free momentum (3 channels), then F-bar's (2).
  for (const auto& c : colliders_) needsThickness_ |= c->law().needsThickness();
  for (const auto* g : groupPtrs_)
    if (g->basalLaw) needsThickness_ |= g->basalLaw->needsThickness();
  int channels = 0;
  if (needsThickness_) grid_.channels.thickness = channels++;
  for (const auto* g : groupPtrs_) {
    std::vector<std::pair<int, float>> to;
    if (needsThickness_) to.push_back({grid_.channels.thickness, float(1.0 / g->density())});
    if (g->basalLaw && !colliders_.empty()) {
      materialLaws_.push_back(MaterialLaw{channels, g->basalLaw.get()});
      to.push_back({channels++, 1.f});
    }
    grid_.channels.scatterOf.push_back(std::move(to));
  }
  if (settings_.flip > 0) {
    grid_.channels.momentum = channels;
    channels += 3;
  }
  // F-bar's channels only when a material averages its volume change (not for water alone).
  if (settings_.fbar && std::any_of(groupPtrs_.begin(), groupPtrs_.end(), [](const MaterialGroup* g) { return g->averagesVolume(); })) {
    grid_.channels.fbar = channels;
    channels += 2;
  }
  // A water's smooth_pressure: its J averaged over the grid, in channels of its own.
  if (std::any_of(groupPtrs_.begin(), groupPtrs_.end(), [](const MaterialGroup* g) { return g->averagesState(); })) {
    grid_.channels.stateJ = channels;
    channels += 2;
  }
  grid_.channels.count = channels;
  if (!channels) grid_.channels.scatterOf.clear();
}

double Simulation::maxWaveSpeed() const {
  double c = 0;
  for (const auto* g : groupPtrs_)
    if (g->size()) c = std::max(c, g->waveSpeed());
  return c;
}

double Simulation::stableDt() const {
  double wave = maxWaveSpeed(), limit = std::numeric_limits<double>::infinity();
  for (const auto* g : groupPtrs_)
    if (g->size()) limit = std::min(limit, g->stableDtLimit(settings_.dx));
  phases_->agreeOnDt(wave, limit);
  const double speed = wave + maxSpeed_;
  double dt = speed > 0 ? settings_.cfl * settings_.dx / speed : settings_.maxDt;
  // With no wave speed and no motion yet, gravity alone sets the scale: move at most cfl*dx.
  if (!(speed > 0)) {
    const double g = settings_.gravity.norm();
    dt = g > 0 ? std::sqrt(2 * settings_.cfl * settings_.dx / g) : 1e-3;
  }
  return std::min(std::min(dt, limit), settings_.maxDt);
}

double Simulation::step(double dtCap) { return stepBy(std::min(stableDt(), dtCap)); }

double Simulation::stepBy(double dt) {
  const Real rdt = Real(dt);
  phases_->bin();
  fresh_.clear(); // binned among the others
  prepareColliders(dt);
  const HaloExchange* halo;
  {
    ScopedTimer t(times_.halo);
    halo = phases_->exchangeHalo(rdt);
  }
  {
    ScopedTimer t(times_.p2g);
    particlesToGrid(groupPtrs_, grid_, rdt, halo);
  }
  updateGrid(dt, phases_->counted());
  {
    ScopedTimer t(times_.halo);
    phases_->reduceLoads(rdt);
  }
  if (grid_.channels.fbar >= 0 || grid_.channels.stateJ >= 0) {
    ScopedTimer t(times_.g2p);
    averageVolumeChange(groupPtrs_, grid_, rdt);
  }
  G2PStats stats;
  {
    ScopedTimer t(times_.g2p);
    stats = gridToParticles(groupPtrs_, grid_, rdt, Real(settings_.flip));
  }
  size_t stepped = particleCount();
  time_ += dt;
  ++steps_;
  for (auto* g : groupPtrs_) g->afterStep();
  {
    ScopedTimer t(times_.halo);
    phases_->reduceStepFigures(stats, stepped);
  }
  particleSteps_ += stepped;
  maxSpeed_ = stats.maxSpeed;
  checkFinite(stats.nonFinite);
  {
    ScopedTimer t(times_.cull);
    cullEscaped();
  }
  // Pools of eroded mass, secondary releases, inflows, detrainment: after the cull, which wraps
  // periodic axes, so a source sees every particle inside the domain.
  if (bed_) releaseEroded();
  for (auto& src : settings_.sources) src->emit(grid_, time_, dt, groupPtrs_);
  return dt;
}

void Simulation::prepareColliders(double dt) {
  ScopedTimer t(times_.colliders);
  for (auto& c : colliders_) c->prepare(grid_.topology, settings_.dx, time_ + dt);
}

void Simulation::updateGrid(double dt, const std::vector<uint8_t>* counted) {
  ScopedTimer t(times_.grid);
  GridUpdateParams prm;
  prm.dt = Real(dt);
  // Smooth (cosine) ramp: its residual ringing falls as (T / ramp)^2, a linear one's as T / ramp.
  const double s = settings_.gravityRamp > 0 ? std::min(1.0, (time_ + dt) / settings_.gravityRamp) : 1.0;
  const double ramp = 0.5 * (1 - std::cos(M_PI * s));
  prm.gravity = (ramp * settings_.gravity).cast<Real>();
  prm.damping = Real(settings_.damping);
  prm.materialLaws = &materialLaws_;
  prm.counted = counted;
  if (periodic_.any()) periodic_.fold(grid_);
  if (needsThickness_) phases_->buildColumns();
  if (bed_) bed_->prepare(grid_.blockCount()), prm.basalWork = bed_->basalWork().data();
  updateGridVelocities(grid_, prm, colliderPtrs_, time_ + dt, needsThickness_ ? &columns_ : nullptr, loads_);
  if (periodic_.any()) periodic_.unfold(grid_);
  if (bed_) bed_->erode(grid_, dt, counted, phases_->shareWorkingNodes()); // entrainment
}

double Simulation::stepToward(double t) {
  const double remaining = t - time_;
  const double dt = stableDt();
  // At most dt each way, so the stable step (a collective on ranks) is not asked for twice.
  const double taken = stepBy(remaining <= dt ? remaining : (remaining < 2 * dt ? 0.5 * remaining : dt));
  if (remaining <= dt) time_ = t; // exact arrival despite rounding
  return taken;
}

void Simulation::advanceTo(double t, const std::function<void()>& onStep) {
  while (time_ < t) {
    stepToward(t);
    if (onStep) onStep();
  }
}

std::string Simulation::nonFiniteMessage() const {
  for (const auto* g : groupPtrs_) {
    const auto& P = g->particles;
    for (size_t p = 0; p < P.size(); ++p) {
      const bool bad = !P.v[p].allFinite() || !P.x[p].allFinite() || !P.tau[p].matrix().allFinite();
      if (bad) {
        std::ostringstream s;
        const Vec3d xw = P.x[p].cast<double>() + settings_.origin;
        s << "non-finite state at step " << steps_ << " (t = " << time_ << " s): particle " << p
          << " of material '" << g->name() << "' (" << g->modelName() << ") at (" << xw.x() << ", "
          << xw.y() << ", " << xw.z() << "), velocity (" << P.v[p].transpose() << ")";
        if (ranks_) s << " on rank " << ranks_->rank();
        return s.str();
      }
    }
  }
  return {};
}

void Simulation::checkFinite(size_t nonFinite) const {
  if (nonFinite) phases_->throwNonFinite();
}

void Simulation::LocalPhases::bin() {
  ScopedTimer t(sim_.times_.bin);
  binParticles(sim_.groupPtrs_, sim_.grid_, sim_.reorder_, &sim_.periodic_);
}

void Simulation::LocalPhases::throwNonFinite() const {
  const std::string m = sim_.nonFiniteMessage();
  throw NumericalError(m.empty() ? "non-finite particle state at step " + std::to_string(sim_.steps_) : m);
}

void Simulation::cullEscaped() {
  const CullBox box = cullBox(settings_.domain, settings_.faces, periodic_, settings_.dx);
  for (auto* g : groupPtrs_) massRemoved_[size_t(g->index())] += cullOutside(*g, box, periodic_, Real(settings_.dx));
}

void Simulation::releaseEroded() {
  std::vector<size_t> before;
  for (const auto* g : groupPtrs_) before.push_back(g->size());
  bed_->release(groupPtrs_, phases_->makesHere()); // on ranks, each makes the particles of its own blocks
  fresh_.resize(groupPtrs_.size());
  for (size_t g = 0; g < groupPtrs_.size(); ++g) fresh_[g] = groupPtrs_[g]->size() - before[g];
}

size_t Simulation::particleCount() const {
  size_t n = 0;
  for (const auto* g : groupPtrs_) n += g->size();
  return n;
}

std::vector<Simulation::GroupSums> Simulation::groupSums() const {
  std::vector<GroupSums> out;
  const Vec3d g = settings_.gravity;
  for (const auto* grp : groupPtrs_) {
    const ParticleSet& P = grp->particles;
    out.push_back(tbb::parallel_deterministic_reduce(
        tbb::blocked_range<size_t>(0, P.size(), 8192), GroupSums{},
        [&](const tbb::blocked_range<size_t>& r, GroupSums acc) {
          for (size_t i = r.begin(); i != r.end(); ++i) {
            const double m = double(P.mass[i]);
            acc.mass += m;
            acc.kinetic += 0.5 * m * double(P.v[i].squaredNorm());
            acc.potential -= m * g.dot(P.x[i].cast<double>());
          }
          return acc;
        },
        [](GroupSums a, const GroupSums& b) {
          a.mass += b.mass, a.kinetic += b.kinetic, a.potential += b.potential;
          return a;
        }));
  }
  return out;
}

double Simulation::totalMass() const {
  double m = 0;
  for (const GroupSums& s : groupSums()) m += s.mass;
  return m;
}

double Simulation::totalMassRemoved() const {
  double m = 0;
  for (double r : massRemoved_) m += r;
  return m;
}

Vec3d Simulation::linearMomentum() const {
  Vec3d p = Vec3d::Zero();
  for (const auto* g : groupPtrs_)
    for (size_t i = 0; i < g->size(); ++i) p += double(g->particles.mass[i]) * g->particles.v[i].cast<double>();
  return p;
}

Vec3d Simulation::centreOfMass() const {
  Vec3d c = Vec3d::Zero();
  for (const auto* g : groupPtrs_)
    for (size_t i = 0; i < g->size(); ++i) c += double(g->particles.mass[i]) * g->particles.x[i].cast<double>();
  return c / totalMass();
}

Vec3d Simulation::angularMomentum() const {
  Vec3d L = Vec3d::Zero();
  const double d = 0.25 * settings_.dx * settings_.dx;
  for (const auto* g : groupPtrs_) {
    const auto& P = g->particles;
    for (size_t i = 0; i < P.size(); ++i) {
      const Vec3d x = P.x[i].cast<double>(), v = P.v[i].cast<double>();
      const Mat3d C = P.C[i].cast<double>();
      const Vec3d affine(C(2, 1) - C(1, 2), C(0, 2) - C(2, 0), C(1, 0) - C(0, 1));
      L += double(P.mass[i]) * (x.cross(v) + d * affine);
    }
  }
  return L;
}

double Simulation::kineticEnergy() const {
  double e = 0;
  for (const GroupSums& s : groupSums()) e += s.kinetic;
  return e;
}

double Simulation::potentialEnergy() const {
  double e = 0;
  for (const GroupSums& s : groupSums()) e += s.potential;
  return e;
}

size_t Simulation::particleBytes() const {
  size_t b = 0;
  for (const auto* g : groupPtrs_) b += g->size() * (ParticleSet::bytesPerParticle() + g->stateBytesPerParticle());
  return b;
}

size_t Simulation::gridBytes() const {
  size_t b = grid_.memoryBytes();
  for (const auto& c : colliders_) b += c->memoryBytes();
  return b;
}

size_t Simulation::terrainBytes() const { return settings_.terrain ? settings_.terrain->residentBytes() : 0; }

} // namespace talus

namespace talus {

void Simulation::save(StateArchive& a) const {
  a.putValue("format_version", int32_t(1));
  a.putValue("real_bytes", int32_t(sizeof(Real)));
  a.putValue("time", time_);
  a.putValue("steps", steps_);
  a.putValue("particle_steps", particleSteps_);
  a.putValue("max_speed", maxSpeed_);
  a.putValue("initial_mass", initialMass_);
  a.putVector("mass_removed", massRemoved_);
  a.putValue("groups", int32_t(groupPtrs_.size()));
  for (size_t i = 0; i < groupPtrs_.size(); ++i) {
    const std::string p = "group" + std::to_string(i) + "/";
    const std::string id = groupPtrs_[i]->name() + "|" + groupPtrs_[i]->modelName();
    a.put(p + "id", id.data(), id.size());
    groupPtrs_[i]->save(a, p);
  }
  if (bed_) bed_->save(a);
  for (size_t i = 0; i < settings_.sources.size(); ++i) settings_.sources[i]->save(a, "source" + std::to_string(i) + "/");
}

void Simulation::load(const StateArchive& a) {
  if (a.getValue<int32_t>("format_version") != 1) throw std::runtime_error("unknown checkpoint format");
  if (a.getValue<int32_t>("real_bytes") != int32_t(sizeof(Real)))
    throw std::runtime_error("checkpoint was written by a build with a different precision");
  if (a.getValue<int32_t>("groups") != int32_t(groupPtrs_.size()))
    throw std::runtime_error("checkpoint holds a different number of materials than the scene");
  for (size_t i = 0; i < groupPtrs_.size(); ++i) {
    const std::string p = "group" + std::to_string(i) + "/";
    std::string id(a.size(p + "id"), ' ');
    a.get(p + "id", id.data(), id.size());
    const std::string want = groupPtrs_[i]->name() + "|" + groupPtrs_[i]->modelName();
    if (id != want)
      throw std::runtime_error("checkpoint material " + std::to_string(i) + " is '" + id + "', the scene has '" + want + "'");
    groupPtrs_[i]->load(a, p);
  }
  time_ = a.getValue<double>("time");
  steps_ = a.getValue<uint64_t>("steps");
  particleSteps_ = a.getValue<uint64_t>("particle_steps");
  maxSpeed_ = a.getValue<double>("max_speed");
  initialMass_ = a.getValue<double>("initial_mass");
  a.getVector("mass_removed", massRemoved_);
  if (bed_) bed_->load(a);
  for (size_t i = 0; i < settings_.sources.size(); ++i) settings_.sources[i]->load(a, "source" + std::to_string(i) + "/");
  if (massRemoved_.size() != groupPtrs_.size()) throw std::runtime_error("mass ledger does not fit the materials");
  checkParticles();
  if (!(time_ >= 0) || !std::isfinite(time_)) throw std::runtime_error("the clock is not a finite time");
}

void Simulation::checkParticles() const {
  // A run only ever holds particles inside the domain (culling keeps them there) with positive
  // mass; binning a position far outside would overflow the block coordinates.
  const Vec3d lo = settings_.domain.min - Vec3d::Constant(settings_.dx), hi = settings_.domain.max + Vec3d::Constant(settings_.dx);
  for (const MaterialGroup* g : groupPtrs_)
    for (size_t p = 0; p < g->size(); ++p) {
      const Vec3d x = g->particles.x[p].cast<double>();
      if (!((x.array() >= lo.array()).all() && (x.array() <= hi.array()).all()) || !(g->particles.mass[p] > 0) ||
          !std::isfinite(g->particles.mass[p]))
        throw std::runtime_error("particle " + std::to_string(p) + " of '" + g->name() +
                                 "' lies outside the domain or has no mass");
    }
}

} // namespace talus
