// Bayesian optimisation over the unit cube: a Gaussian process (hazard/gaussian_process.h)
// fitted to the losses evaluated so far proposes where to evaluate next by expected improvement.
// Several proposals per round (runs go in parallel) come from the "constant liar" (Ginsbourger,
// Le Riche & Carraro 2010): each proposal is added as if its loss were the best seen, which
// pushes the next one elsewhere (the hyperparameters refitted each time).
#pragma once

#include "hazard/gaussian_process.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace talus::calibration {

struct Evaluated {
  Eigen::VectorXd x; ///< in [0, 1]^k
  double loss = 0;   ///< NaN: the evaluation failed (left out of the fit)
};

/// The surrogate of the finite evaluations. Throws std::invalid_argument when there are none.
GaussianProcess fitSurrogate(const std::vector<Evaluated>& done);

/// `n` new points by expected improvement on `gp` (fitted to `done`), constant liar between them.
/// `maxEi` receives the first proposal's expected improvement (the search's own estimate of what
/// is left to gain, in loss units).
std::vector<Eigen::VectorXd> proposeBatch(const GaussianProcess& gp, const std::vector<Evaluated>& done, size_t n,
                                          double& maxEi);

/// Per dimension, the smallest and largest coordinate of the points where the surrogate's mean
/// is at most `level` (the parameters a loss tolerance cannot tell apart), from a dense sample
/// of the cube (a grid of 401 / 161 / 41 levels for k = 1 / 2 / 3, else 40 000 seeded random
/// points) and the best evaluated point. NaN bounds when no point qualifies.
void plausibleRanges(const GaussianProcess& gp, const Eigen::VectorXd& best, double level, Eigen::VectorXd& lo,
                     Eigen::VectorXd& hi);

/// The whole loop for an in-process function (tests, examples): `initial` Latin-hypercube
/// points (seeded), then rounds of `batch` proposals until `budget` evaluations or until the
/// largest expected improvement falls below `eiStop`. Returns every evaluation in order.
std::vector<Evaluated> minimise(const std::function<double(const Eigen::VectorXd&)>& f, int dims, size_t initial,
                                size_t budget, size_t batch, double eiStop, uint64_t seed);

} // namespace talus::calibration
