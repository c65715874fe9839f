#include "hazard/calibration.h"

#include "hazard/calibration_plots.h"
#include "hazard/surrogate_search.h"
#include "io/common/input_error.h"
#include "io/common/json_text.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace talus::calibration {

namespace fs = std::filesystem;

namespace {

struct Member {
  std::string phase;
  std::vector<double> unit; ///< every parameter, in [0, 1]
  LossTerms terms;
};

std::string exact(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string proposalsHeader(const CalibrationSettings& s) {
  std::string h = "member,phase";
  for (const auto& v : s.vary) h += "," + v.key + "[" + exact(v.low) + ":" + exact(v.high) + "]";
  return h + ",seed=" + std::to_string(s.seed);
}

/// The proposals of an earlier run of the same calibration (empty when none).
std::vector<Member> readProposals(const fs::path& file, const CalibrationSettings& s) {
  std::vector<Member> out;
  std::ifstream in(file);
  if (!in) return out;
  std::string line;
  std::getline(in, line);
  if (line != proposalsHeader(s))
    throw InputError(file.string(), "holds another calibration (other --vary or --seed): give another --out, or "
                                    "remove the folder");
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::string cell;
    Member m;
    std::getline(ls, cell, ','); // member index: the row's position
    std::getline(ls, m.phase, ',');
    while (std::getline(ls, cell, ',')) m.unit.push_back(std::stod(cell));
    if (m.unit.size() != s.vary.size()) throw InputError(file.string(), "a row without a value per parameter");
    out.push_back(m);
  }
  return out;
}

class Loop {
public:
  Loop(const fs::path& dir, const CalibrationSettings& s, ObservedEvent& event, const MemberRunner& run, FILE* log)
      : dir_(dir), s_(s), event_(event), run_(run), log_(log), stored_(readProposals(dir / "proposals.csv", s)) {}

  /// Runs the members whose unit coordinates are given (or the stored ones), then evaluates
  /// them. False when stopped.
  bool evaluate(const std::string& phase, std::vector<std::vector<double>> units) {
    std::vector<MemberRequest> reqs;
    for (auto& u : units) {
      const size_t m = members_.size();
      if (m < stored_.size()) u = stored_[m].unit; // as proposed before: resume the same members
      else appendProposal(phase, u);
      members_.push_back({phase, u, {}});
      MemberRequest r;
      r.index = m;
      r.dir = (dir_ / ensemble::memberName(m)).string();
      for (size_t p = 0; p < s_.vary.size(); ++p) r.overrides.push_back(s_.vary[p].key + "=" + parameterText(s_.vary[p], u[p]));
      reqs.push_back(r);
    }
    if (!run_(reqs)) return false;
    for (const auto& r : reqs) members_[r.index].terms = event_.evaluate(r.dir);
    writeTable();
    if (log_) {
      double best = NAN;
      for (const auto& m : members_)
        if (std::isfinite(m.terms.total) && !(best <= m.terms.total)) best = m.terms.total;
      std::fprintf(log_, "talus calibrate: %s: %zu member(s) run, %zu in all, best loss %.4g\n", phase.c_str(),
                   reqs.size(), members_.size(), best);
    }
    return true;
  }

  const std::vector<Member>& members() const { return members_; }

  /// The finite evaluations projected on the kept dimensions.
  std::vector<Evaluated> evaluated(const std::vector<bool>& kept) const {
    std::vector<Evaluated> out;
    for (const auto& m : members_) {
      Evaluated e;
      e.x = project(m.unit, kept);
      e.loss = m.terms.total;
      out.push_back(e);
    }
    return out;
  }

  static Eigen::VectorXd project(const std::vector<double>& unit, const std::vector<bool>& kept) {
    std::vector<double> x;
    for (size_t p = 0; p < unit.size(); ++p)
      if (kept[p]) x.push_back(unit[p]);
    return Eigen::Map<const Eigen::VectorXd>(x.data(), Eigen::Index(x.size()));
  }

private:
  void appendProposal(const std::string& phase, const std::vector<double>& u) {
    const fs::path file = dir_ / "proposals.csv";
    const bool fresh = !fs::exists(file);
    std::ofstream out(file, std::ios::app);
    if (fresh) out << proposalsHeader(s_) << "\n";
    out << members_.size() << "," << phase;
    for (double v : u) out << "," << exact(v);
    out << "\n";
  }

  void writeTable() const {
    std::ofstream out(dir_ / "calibration.csv");
    out << "member,phase";
    for (const auto& v : s_.vary) out << "," << v.key;
    out << "," << event_.csvHeader() << "\n";
    for (size_t m = 0; m < members_.size(); ++m) {
      out << ensemble::memberName(m) << "," << members_[m].phase;
      for (size_t p = 0; p < s_.vary.size(); ++p) out << "," << parameterText(s_.vary[p], members_[m].unit[p]);
      out << "," << event_.csvValues(members_[m].terms) << "\n";
    }
  }

  fs::path dir_;
  const CalibrationSettings& s_;
  ObservedEvent& event_;
  const MemberRunner& run_;
  FILE* log_;
  std::vector<Member> stored_, members_;
};

size_t bestOf(const std::vector<Member>& ms) {
  size_t best = ms.size();
  for (size_t m = 0; m < ms.size(); ++m)
    if (std::isfinite(ms[m].terms.total) && (best == ms.size() || ms[m].terms.total < ms[best].terms.total)) best = m;
  return best;
}

/// Morris screening: which parameters to keep, and the unit values of the others (the best
/// screening member's).
std::vector<bool> screen(Loop& loop, const CalibrationSettings& s, std::vector<double>& fixedUnit, const fs::path& dir,
                         bool& stopped) {
  std::vector<bool> kept(s.vary.size(), true);
  if (s.screen == 0 || s.vary.size() < 2) return kept;
  const ensemble::Plan plan = ensemble::makePlan(s.vary, ensemble::Method::Morris, s.screen, s.seed);
  if (!loop.evaluate("screening", plan.unit)) return stopped = true, kept;
  std::vector<double> loss;
  for (size_t m = 0; m < plan.members(); ++m) loss.push_back(loop.members()[m].terms.total);
  const auto effects = ensemble::morrisEffects(plan, loss);
  double largest = 0;
  for (const auto& e : effects) largest = std::max(largest, e.muStar);
  const size_t best = bestOf(loop.members());
  std::ofstream out(dir / "screening.csv");
  out << "key,mu_star,mu,sigma,effects,kept\n";
  for (size_t p = 0; p < effects.size(); ++p) {
    kept[p] = !(effects[p].muStar < s.screenKeep * largest);
    if (!kept[p] && best < loop.members().size()) fixedUnit[p] = loop.members()[best].unit[p];
    out << effects[p].key << "," << effects[p].muStar << "," << effects[p].mu << "," << effects[p].sigma << ","
        << effects[p].effects << "," << (kept[p] ? "yes" : "no") << "\n";
  }
  return kept;
}

std::vector<double> fullUnit(const Eigen::VectorXd& x, const std::vector<bool>& kept, const std::vector<double>& fixed) {
  std::vector<double> u = fixed;
  Eigen::Index d = 0;
  for (size_t p = 0; p < kept.size(); ++p)
    if (kept[p]) u[p] = x[d++];
  return u;
}

void writeResult(const fs::path& dir, const CalibrationSettings& s, const CalibrationResult& r, const ObservedEvent& e) {
  std::ofstream out(dir / "result.json");
  out << "{\n  \"best_member\": " << jsonString(ensemble::memberName(r.best)) << ",\n  \"loss\": " << exact(r.terms.total)
      << ",\n  \"members\": " << r.members << ",\n  \"tolerance\": " << s.tolerance
      << ",\n  \"surrogate_mean_at_best\": " << (std::isfinite(r.predicted) ? exact(r.predicted) : "null")
      << ",\n  \"surrogate_sd_at_best\": " << (std::isfinite(r.sd) ? exact(r.sd) : "null")
      << ",\n  \"expected_improvement_at_stop\": " << (std::isfinite(r.lastEi) ? exact(r.lastEi) : "null")
      << ",\n  \"loss_terms\": \"" << e.csvHeader() << "\",\n  \"loss_values\": \"" << e.csvValues(r.terms)
      << "\",\n  \"parameters\": [\n";
  for (size_t p = 0; p < s.vary.size(); ++p)
    out << "    {\"key\": " << jsonString(s.vary[p].key) << ", \"value\": " << exact(r.values[p])
        << ", \"searched\": " << (r.kept[p] ? "true" : "false") << ", \"plausible_low\": "
        << (std::isfinite(r.low[p]) ? exact(r.low[p]) : "null") << ", \"plausible_high\": "
        << (std::isfinite(r.high[p]) ? exact(r.high[p]) : "null") << "}" << (p + 1 < s.vary.size() ? "," : "") << "\n";
  out << "  ]\n}\n";
}

} // namespace

std::string parameterText(const ensemble::VarySpec& v, double u) {
  char b[40];
  std::snprintf(b, sizeof b, "%.9g", v.low + u * (v.high - v.low));
  return b;
}

CalibrationResult calibrate(const std::string& dirIn, const CalibrationSettings& s, ObservedEvent& event,
                            const MemberRunner& run, FILE* log) {
  const fs::path dir = fs::absolute(dirIn);
  fs::create_directories(dir);
  Loop loop(dir, s, event, run, log);
  CalibrationResult r;
  std::vector<double> fixedUnit(s.vary.size(), 0.5);
  r.kept = screen(loop, s, fixedUnit, dir, r.stopped);
  const auto keptCount = size_t(std::count(r.kept.begin(), r.kept.end(), true));
  std::vector<ensemble::VarySpec> keptSpecs;
  for (size_t p = 0; p < s.vary.size(); ++p)
    if (r.kept[p]) keptSpecs.push_back(s.vary[p]);
  if (!r.stopped) {
    const size_t screened = loop.members().size();
    const size_t initial = s.initial ? s.initial : (screened ? keptCount + 1 : 2 * keptCount + 2);
    const ensemble::Plan lhs = ensemble::makePlan(keptSpecs, ensemble::Method::Lhs, initial, s.seed + 1);
    std::vector<std::vector<double>> units;
    for (const auto& u : lhs.unit)
      units.push_back(fullUnit(Eigen::Map<const Eigen::VectorXd>(u.data(), Eigen::Index(u.size())), r.kept, fixedUnit));
    units.resize(std::min(units.size(), s.budget > screened ? s.budget - screened : 0));
    r.stopped = !loop.evaluate("initial", units);
  }
  if (!r.stopped && bestOf(loop.members()) == loop.members().size())
    throw std::runtime_error(dir.string() + ": no member completed (see " + ensemble::memberName(0) +
                             "/run.log): nothing to search from");
  while (!r.stopped && loop.members().size() < s.budget) {
    const size_t n = std::min(s.batch, s.budget - loop.members().size());
    // Proposed anew even when resuming (deterministic, a fraction of a second): evaluate() then
    // takes the stored members, so a resumed search follows the same path.
    std::vector<std::vector<double>> units;
    const auto done = loop.evaluated(r.kept);
    double ei = 0;
    for (const auto& x : proposeBatch(fitSurrogate(done), done, n, ei)) units.push_back(fullUnit(x, r.kept, fixedUnit));
    r.lastEi = ei;
    double lo = INFINITY, hi = -INFINITY; // the stop is relative to the spread of the losses seen
    for (const auto& e : done)
      if (std::isfinite(e.loss)) lo = std::min(lo, e.loss), hi = std::max(hi, e.loss);
    if (ei < s.eiStop * (hi - lo)) {
      if (log) std::fprintf(log, "talus calibrate: expected improvement %.3g below %.3g of the losses' range %.3g: "
                            "search ended\n", ei, s.eiStop, hi - lo);
      break;
    }
    r.stopped = !loop.evaluate("search", units);
  }
  r.proposed = loop.members().size();
  r.best = bestOf(loop.members());
  if (r.best == loop.members().size()) throw std::runtime_error(dir.string() + ": no member completed");
  const auto& best = loop.members()[r.best];
  r.terms = best.terms;
  for (size_t p = 0; p < s.vary.size(); ++p) {
    r.values.push_back(std::stod(parameterText(s.vary[p], best.unit[p])));
    r.overrides.push_back(s.vary[p].key + "=" + parameterText(s.vary[p], best.unit[p]));
  }
  const auto done = loop.evaluated(r.kept);
  for (const auto& e : done) r.members += std::isfinite(e.loss);
  const GaussianProcess gp = fitSurrogate(done);
  const Eigen::VectorXd bestX = Loop::project(best.unit, r.kept);
  gp.predict(bestX, r.predicted, r.sd);
  Eigen::VectorXd lo, hi;
  plausibleRanges(gp, bestX, r.terms.total + s.tolerance, lo, hi);
  Eigen::Index d = 0;
  for (size_t p = 0; p < s.vary.size(); ++p) {
    const double span = s.vary[p].high - s.vary[p].low;
    r.low.push_back(r.kept[p] ? s.vary[p].low + lo[d] * span : r.values[p]);
    r.high.push_back(r.kept[p] ? s.vary[p].low + hi[d] * span : r.values[p]);
    d += r.kept[p];
  }
  writeResult(dir, s, r, event);
  LossSlices slices{&gp, bestX, {}, {}, r.terms.total + s.tolerance};
  for (size_t p = 0; p < s.vary.size(); ++p)
    if (r.kept[p]) slices.specs.push_back(s.vary[p]);
  for (const auto& e : done) slices.members.push_back(e);
  writeLossSlices(dir.string(), slices);
  writeRunAgainstEvent((dir / "best_against_observed.png").string(), event,
                       (dir / ensemble::memberName(r.best)).string(), ensemble::memberName(r.best));
  return r;
}

} // namespace talus::calibration
