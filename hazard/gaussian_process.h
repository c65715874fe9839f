// A small Gaussian-process surrogate for calibration (Rasmussen & Williams 2006, ch. 2 and 5):
// a handful of expensive runs, each a loss at a point of the unit cube [0, 1]^k, fitted with a
// Matérn 5/2 kernel with one length scale per parameter (ARD),
//
//   k(x, x') = s2 (1 + sqrt(5) r + 5 r^2 / 3) exp(-sqrt(5) r),  r^2 = sum_d ((x_d - x'_d) / l_d)^2,
//
// plus a noise variance on the diagonal (runs at neighbouring parameters scatter by a cell's
// worth of footprint). The outputs are standardised (mean 0, variance 1) before fitting; the
// hyperparameters (l_d, s2, noise) maximise the log marginal likelihood (NLopt's BOBYQA from a
// few fixed starts: deterministic). Predictions are of the latent function (no noise added).
//
// Expected improvement (Jones, Schonlau & Welch 1998) for minimisation at a prediction (mu, sd)
// below the best value f*: EI = (f* - mu) Phi(z) + sd phi(z), z = (f* - mu) / sd.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace talus::calibration {

struct GpHyper {
  Eigen::VectorXd lengths; ///< one per dimension (unit-cube lengths)
  double signal = 1.0;     ///< s2, in standardised output units
  double noise = 1e-6;     ///< noise variance, standardised units
};

/// Matérn 5/2 of r (distance already scaled by the lengths), for unit signal variance.
double matern52(double r);

class GaussianProcess {
public:
  /// Fits to points `x` (n x k, n >= 1, rows in [0, 1]^k) and values `y` (n, finite). With
  /// `fixed`, those hyperparameters are used as given; else they are fitted. Throws
  /// std::invalid_argument on empty or mismatched inputs or non-finite values.
  void fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const GpHyper* fixed = nullptr);

  /// Mean and standard deviation of the latent function at `x` (size k), in y's units.
  void predict(const Eigen::VectorXd& x, double& mean, double& sd) const;
  /// The fitted hyperparameters (standardised units) and the log marginal likelihood.
  const GpHyper& hyper() const { return hyper_; }
  double logLikelihood() const { return logLik_; }
  int dims() const { return int(x_.cols()); }
  /// Smallest value fitted (in y's units).
  double bestValue() const { return yMin_; }

private:
  double logMarginal(const GpHyper& h) const; ///< -inf when the matrix is not positive definite
  void factor(); ///< Cholesky and weights for hyper_

  Eigen::MatrixXd x_;
  Eigen::VectorXd yStd_; ///< standardised values
  double yMean_ = 0, yScale_ = 1, yMin_ = 0;
  GpHyper hyper_;
  Eigen::LLT<Eigen::MatrixXd> chol_;
  Eigen::VectorXd alpha_;
  double logLik_ = 0;
};

/// EI of a prediction (mean, sd) below `best` (minimisation); `mean` and `best` in the same
/// units. sd <= 0 gives max(0, best - mean).
double expectedImprovement(double mean, double sd, double best);

/// The point of [0, 1]^k with the largest expected improvement below `best` (NLopt's DIRECT-L
/// over the cube, then BOBYQA from its result and from each of `starts`); `ei` receives the
/// value. Deterministic.
Eigen::VectorXd maximiseExpectedImprovement(const GaussianProcess& gp, double best,
                                            const std::vector<Eigen::VectorXd>& starts, double& ei);

} // namespace talus::calibration
