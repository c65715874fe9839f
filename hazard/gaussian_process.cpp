#include "hazard/gaussian_process.h"

#include <nlopt.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace talus::calibration {

namespace {

constexpr double kSqrt5 = 2.23606797749979;
// Hyperparameter bounds (log space). Lengths from 1/50 of the range (a loss that changes within
// a few percent of the range is not resolved by a dozen runs) to 20 ranges (flat); the noise from
// almost none (runs are deterministic) to half the standardised variance.
constexpr double kLogLengthLo = -3.912, kLogLengthHi = 2.996;
constexpr double kLogSignalLo = -3.0, kLogSignalHi = 3.0;
constexpr double kLogNoiseLo = -13.8, kLogNoiseHi = -0.69;

double kernel(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const GpHyper& h) {
  double r2 = 0;
  for (Eigen::Index d = 0; d < a.size(); ++d) {
    const double t = (a[d] - b[d]) / h.lengths[d];
    r2 += t * t;
  }
  return h.signal * matern52(std::sqrt(r2));
}

Eigen::MatrixXd covariance(const Eigen::MatrixXd& x, const GpHyper& h) {
  const Eigen::Index n = x.rows();
  Eigen::MatrixXd k(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j <= i; ++j) k(i, j) = k(j, i) = kernel(x.row(i).transpose(), x.row(j).transpose(), h);
  k.diagonal().array() += h.noise;
  return k;
}

GpHyper fromLog(const std::vector<double>& t, int dims) {
  GpHyper h;
  h.lengths.resize(dims);
  for (int d = 0; d < dims; ++d) h.lengths[d] = std::exp(t[size_t(d)]);
  h.signal = std::exp(t[size_t(dims)]);
  h.noise = std::exp(t[size_t(dims) + 1]);
  return h;
}

double normalPdf(double z) { return 0.3989422804014327 * std::exp(-0.5 * z * z); }
double normalCdf(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

} // namespace

double matern52(double r) { return (1.0 + kSqrt5 * r + 5.0 * r * r / 3.0) * std::exp(-kSqrt5 * r); }

double GaussianProcess::logMarginal(const GpHyper& h) const {
  const Eigen::LLT<Eigen::MatrixXd> llt(covariance(x_, h));
  if (llt.info() != Eigen::Success) return -std::numeric_limits<double>::infinity();
  const Eigen::VectorXd a = llt.solve(yStd_);
  const Eigen::MatrixXd& l = llt.matrixLLT();
  double logDet = 0;
  for (Eigen::Index i = 0; i < l.rows(); ++i) logDet += std::log(l(i, i));
  return -0.5 * yStd_.dot(a) - logDet - 0.5 * double(yStd_.size()) * std::log(2 * M_PI);
}

void GaussianProcess::factor() {
  chol_.compute(covariance(x_, hyper_));
  if (chol_.info() != Eigen::Success) throw std::runtime_error("Gaussian process: covariance not positive definite");
  alpha_ = chol_.solve(yStd_);
  logLik_ = logMarginal(hyper_);
}

void GaussianProcess::fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const GpHyper* fixed) {
  if (x.rows() < 1 || x.cols() < 1 || x.rows() != y.size())
    throw std::invalid_argument("Gaussian process: need n >= 1 points of k >= 1 dimensions and one value each");
  if (!x.allFinite() || !y.allFinite()) throw std::invalid_argument("Gaussian process: non-finite point or value");
  x_ = x;
  yMean_ = y.mean();
  yMin_ = y.minCoeff();
  const double var = y.size() > 1 ? (y.array() - yMean_).square().sum() / double(y.size() - 1) : 0.0;
  yScale_ = var > 0 ? std::sqrt(var) : 1.0;
  yStd_ = (y.array() - yMean_) / yScale_;
  const int k = int(x.cols());
  if (fixed) {
    if (fixed->lengths.size() != k) throw std::invalid_argument("Gaussian process: one length per dimension");
    hyper_ = *fixed;
    factor();
    return;
  }
  nlopt::opt opt(nlopt::LN_BOBYQA, unsigned(k + 2));
  std::vector<double> lo(size_t(k) + 2, kLogLengthLo), hi(size_t(k) + 2, kLogLengthHi);
  lo[size_t(k)] = kLogSignalLo, hi[size_t(k)] = kLogSignalHi;
  lo[size_t(k) + 1] = kLogNoiseLo, hi[size_t(k) + 1] = kLogNoiseHi;
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  auto objective = [](unsigned, const double* t, double*, void* self) {
    auto* gp = static_cast<GaussianProcess*>(self);
    const double v = gp->logMarginal(fromLog(std::vector<double>(t, t + gp->x_.cols() + 2), int(gp->x_.cols())));
    return std::isfinite(v) ? v : -1e30;
  };
  opt.set_max_objective(objective, this);
  opt.set_xtol_abs(1e-4);
  opt.set_maxeval(600);
  double bestValue = -std::numeric_limits<double>::infinity();
  std::vector<double> best;
  // Fixed starts: short, medium and long length scales, little noise.
  for (double logLength : {-1.6, -0.5, 0.7}) {
    std::vector<double> t(size_t(k) + 2, logLength);
    t[size_t(k)] = 0.0;
    t[size_t(k) + 1] = -9.2;
    double v = -std::numeric_limits<double>::infinity();
    try {
      opt.optimize(t, v);
    } catch (const nlopt::roundoff_limited&) {
      v = objective(0, t.data(), nullptr, this); // the point reached is still usable
    } catch (const std::runtime_error&) {
      continue;
    }
    if (v > bestValue) bestValue = v, best = t;
  }
  if (best.empty()) throw std::runtime_error("Gaussian process: the likelihood could not be maximised");
  hyper_ = fromLog(best, k);
  factor();
}

void GaussianProcess::predict(const Eigen::VectorXd& x, double& mean, double& sd) const {
  Eigen::VectorXd ks(x_.rows());
  for (Eigen::Index i = 0; i < x_.rows(); ++i) ks[i] = kernel(x, x_.row(i).transpose(), hyper_);
  const Eigen::VectorXd v = chol_.matrixL().solve(ks);
  mean = yMean_ + yScale_ * ks.dot(alpha_);
  sd = yScale_ * std::sqrt(std::max(0.0, hyper_.signal - v.squaredNorm()));
}

double expectedImprovement(double mean, double sd, double best) {
  const double d = best - mean;
  if (!(sd > 0)) return std::max(0.0, d);
  const double z = d / sd;
  return d * normalCdf(z) + sd * normalPdf(z);
}

Eigen::VectorXd maximiseExpectedImprovement(const GaussianProcess& gp, double best,
                                            const std::vector<Eigen::VectorXd>& starts, double& ei) {
  const unsigned k = unsigned(gp.dims());
  struct Context {
    const GaussianProcess* gp;
    double best;
  } ctx{&gp, best};
  auto objective = [](unsigned n, const double* t, double*, void* data) {
    const auto* c = static_cast<const Context*>(data);
    double mean = 0, sd = 0;
    c->gp->predict(Eigen::Map<const Eigen::VectorXd>(t, n), mean, sd);
    return expectedImprovement(mean, sd, c->best);
  };
  auto run = [&](nlopt::algorithm a, std::vector<double>& t, int evals) {
    nlopt::opt opt(a, k);
    opt.set_lower_bounds(std::vector<double>(k, 0.0));
    opt.set_upper_bounds(std::vector<double>(k, 1.0));
    opt.set_max_objective(objective, &ctx);
    opt.set_maxeval(evals);
    opt.set_xtol_abs(1e-5);
    double v = 0;
    try {
      opt.optimize(t, v);
    } catch (const std::runtime_error&) {
    }
    return objective(k, t.data(), nullptr, &ctx);
  };
  std::vector<double> global(k, 0.5);
  double bestEi = run(nlopt::GN_DIRECT_L, global, int(std::min(4000u, 400u * k)));
  std::vector<double> arg = global;
  std::vector<std::vector<double>> locals{global};
  for (const auto& s : starts) locals.emplace_back(s.data(), s.data() + s.size());
  for (auto& t : locals) {
    for (auto& v : t) v = std::clamp(v, 0.0, 1.0);
    const double v = run(nlopt::LN_NELDERMEAD, t, 200 * int(k));
    if (v > bestEi) bestEi = v, arg = t;
  }
  ei = bestEi;
  return Eigen::Map<const Eigen::VectorXd>(arg.data(), k);
}

} // namespace talus::calibration
