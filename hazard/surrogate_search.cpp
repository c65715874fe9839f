#include "hazard/surrogate_search.h"

#include "hazard/ensemble_plan.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace talus::calibration {

GaussianProcess fitSurrogate(const std::vector<Evaluated>& done) {
  std::vector<const Evaluated*> ok;
  for (const auto& e : done)
    if (std::isfinite(e.loss)) ok.push_back(&e);
  if (ok.empty()) throw std::invalid_argument("surrogate: no evaluation succeeded");
  Eigen::MatrixXd x(ok.size(), ok.front()->x.size());
  Eigen::VectorXd y(ok.size());
  for (size_t i = 0; i < ok.size(); ++i) x.row(Eigen::Index(i)) = ok[i]->x.transpose(), y[Eigen::Index(i)] = ok[i]->loss;
  GaussianProcess gp;
  gp.fit(x, y);
  return gp;
}

std::vector<Eigen::VectorXd> proposeBatch(const GaussianProcess& fitted, const std::vector<Evaluated>& done, size_t n,
                                          double& maxEi) {
  std::vector<Evaluated> lied;
  std::vector<Eigen::VectorXd> starts;
  for (const auto& e : done)
    if (std::isfinite(e.loss)) lied.push_back(e);
  // Local searches also start from the three best points: EI often peaks right beside them.
  std::vector<Evaluated> sorted = lied;
  std::sort(sorted.begin(), sorted.end(), [](const Evaluated& a, const Evaluated& b) { return a.loss < b.loss; });
  for (size_t i = 0; i < std::min<size_t>(3, sorted.size()); ++i) starts.push_back(sorted[i].x);
  const double best = fitted.bestValue();
  GaussianProcess gp = fitted;
  std::vector<Eigen::VectorXd> out;
  for (size_t i = 0; i < n; ++i) {
    double ei = 0;
    const Eigen::VectorXd x = maximiseExpectedImprovement(gp, best, starts, ei);
    if (i == 0) maxEi = ei;
    out.push_back(x);
    if (i + 1 == n) break;
    lied.push_back({x, best});
    Eigen::MatrixXd xs(lied.size(), x.size());
    Eigen::VectorXd ys(lied.size());
    for (size_t j = 0; j < lied.size(); ++j) xs.row(Eigen::Index(j)) = lied[j].x.transpose(), ys[Eigen::Index(j)] = lied[j].loss;
    gp.fit(xs, ys); // refitted: a dozen points, a fraction of a second
  }
  return out;
}

void plausibleRanges(const GaussianProcess& gp, const Eigen::VectorXd& best, double level, Eigen::VectorXd& lo,
                     Eigen::VectorXd& hi) {
  const int k = gp.dims();
  lo = Eigen::VectorXd::Constant(k, std::numeric_limits<double>::quiet_NaN());
  hi = lo;
  auto consider = [&](const Eigen::VectorXd& x) {
    double mean = 0, sd = 0;
    gp.predict(x, mean, sd);
    if (!(mean <= level)) return;
    for (int d = 0; d < k; ++d) {
      if (!(x[d] >= lo[d])) lo[d] = x[d];
      if (!(x[d] <= hi[d])) hi[d] = x[d];
    }
  };
  consider(best);
  const int levels = k == 1 ? 401 : k == 2 ? 161 : k == 3 ? 41 : 0;
  if (levels) {
    long total = 1;
    for (int d = 0; d < k; ++d) total *= levels;
    Eigen::VectorXd x(k);
    for (long i = 0; i < total; ++i) {
      long r = i;
      for (int d = 0; d < k; ++d) x[d] = double(r % levels) / (levels - 1), r /= levels;
      consider(x);
    }
    return;
  }
  std::mt19937_64 rng(12345);
  Eigen::VectorXd x(k);
  for (int i = 0; i < 40000; ++i) {
    for (int d = 0; d < k; ++d) x[d] = double(rng() >> 11) * 0x1.0p-53;
    consider(x);
  }
}

std::vector<Evaluated> minimise(const std::function<double(const Eigen::VectorXd&)>& f, int dims, size_t initial,
                                size_t budget, size_t batch, double eiStop, uint64_t seed) {
  std::vector<ensemble::VarySpec> unitBox(static_cast<size_t>(dims));
  for (int d = 0; d < dims; ++d) unitBox[size_t(d)] = {"x" + std::to_string(d), 0.0, 1.0, ""};
  const ensemble::Plan start = ensemble::makePlan(unitBox, ensemble::Method::Lhs, initial, seed);
  std::vector<Evaluated> done;
  for (size_t m = 0; m < start.members() && done.size() < budget; ++m) {
    Evaluated e;
    e.x = Eigen::Map<const Eigen::VectorXd>(start.unit[m].data(), dims);
    e.loss = f(e.x);
    done.push_back(e);
  }
  while (done.size() < budget) {
    double maxEi = 0;
    const auto next = proposeBatch(fitSurrogate(done), done, std::min(batch, budget - done.size()), maxEi);
    if (maxEi < eiStop) break;
    for (const auto& x : next) done.push_back({x, f(x)});
  }
  return done;
}

} // namespace talus::calibration
