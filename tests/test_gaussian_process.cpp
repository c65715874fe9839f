// The calibration's surrogate against closed forms (Rasmussen & Williams 2006, eqs. 2.25-2.26,
// 4.17; Jones et al. 1998 for expected improvement) and its search on functions whose minimum
// is known.
#include "hazard/gaussian_process.h"
#include "hazard/surrogate_search.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace talus::calibration;

TEST(GaussianProcess, Matern52HasItsClosedFormValues) {
  EXPECT_DOUBLE_EQ(matern52(0.0), 1.0);
  // (1 + sqrt 5 + 5/3) exp(-sqrt 5) = 0.523994...
  EXPECT_NEAR(matern52(1.0), 0.5239941088318203, 1e-12);
  EXPECT_LT(matern52(5.0), 1e-3);
}

TEST(GaussianProcess, OnePointPosteriorIsTheKernelRatio) {
  // Mean k(x, x0) / (k(x0, x0) + noise) y0 and variance s2 - k^2 / (s2 + noise) (eq. 2.26), in
  // standardised units: one point standardises to 0 and its mean is added back, so use two
  // points far apart (r = 10 lengths: correlation 1e-8) and check at the first one's side.
  Eigen::MatrixXd x(2, 1);
  x << 0.1, 0.9;
  Eigen::VectorXd y(2);
  y << 1.0, 3.0; // mean 2, scale sqrt(2)
  GpHyper h;
  h.lengths = Eigen::VectorXd::Constant(1, 0.08);
  h.signal = 1.5;
  h.noise = 0.01;
  GaussianProcess gp;
  gp.fit(x, y, &h);
  Eigen::VectorXd at(1);
  at << 0.15;
  double mean = 0, sd = 0;
  gp.predict(at, mean, sd);
  const double k = 1.5 * matern52(0.05 / 0.08), k00 = 1.5 + 0.01;
  const double y0 = (1.0 - 2.0) / std::sqrt(2.0);
  EXPECT_NEAR(mean, 2.0 + std::sqrt(2.0) * k / k00 * y0, 1e-6);
  EXPECT_NEAR(sd, std::sqrt(2.0) * std::sqrt(1.5 - k * k / k00), 1e-6);
}

TEST(GaussianProcess, FittedToSmoothDataInterpolatesAndKnowsWhereItIsUnsure) {
  Eigen::MatrixXd x(7, 1);
  Eigen::VectorXd y(7);
  for (int i = 0; i < 7; ++i) x(i, 0) = i / 6.0, y[i] = std::sin(6 * x(i, 0));
  GaussianProcess gp;
  gp.fit(x, y);
  double mean = 0, sd = 0;
  for (int i = 0; i < 7; ++i) {
    gp.predict(x.row(i).transpose(), mean, sd);
    EXPECT_NEAR(mean, y[i], 0.02) << "at training point " << i; // the fitted noise, at most a few 1e-4 of var
  }
  // Between points, a smooth function is predicted within 5 % of its amplitude, and the
  // standard deviation there exceeds the one at a training point.
  Eigen::VectorXd mid(1);
  mid << 0.25;
  gp.predict(mid, mean, sd);
  EXPECT_NEAR(mean, std::sin(1.5), 0.05);
  double meanAt = 0, sdAt = 0;
  gp.predict(x.row(2).transpose(), meanAt, sdAt);
  EXPECT_GT(sd, sdAt);
}

TEST(GaussianProcess, ExpectedImprovementHasItsClosedForm) {
  // At the best value, EI = sd phi(0); far below it, EI -> best - mean; no sd: the plain gain.
  EXPECT_NEAR(expectedImprovement(2.0, 0.5, 2.0), 0.5 * 0.3989422804014327, 1e-12);
  EXPECT_NEAR(expectedImprovement(0.0, 0.01, 2.0), 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(expectedImprovement(3.0, 0.0, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(expectedImprovement(1.0, 0.0, 2.0), 1.0);
  // z = 1: (best - mean) Phi(1) + sd phi(1) with Phi(1) = 0.841344746, phi(1) = 0.241970725.
  EXPECT_NEAR(expectedImprovement(1.0, 1.0, 2.0), 0.841344746 + 0.241970725, 1e-8);
}

TEST(SurrogateSearch, FindsTheMinimumOfABowlInFewEvaluations) {
  // A 2-D bowl with its minimum at (0.3, 0.7), value 0.1: 6 initial points and 14 more, two per
  // round, land within 0.03 of it (a twentieth of the initial design's spacing).
  auto bowl = [](const Eigen::VectorXd& x) { return 0.1 + std::pow(x[0] - 0.3, 2) + 2 * std::pow(x[1] - 0.7, 2); };
  const auto done = minimise(bowl, 2, 6, 20, 2, 0.0, 7);
  const auto best = *std::min_element(done.begin(), done.end(), [](auto& a, auto& b) { return a.loss < b.loss; });
  EXPECT_NEAR(best.x[0], 0.3, 0.03);
  EXPECT_NEAR(best.x[1], 0.7, 0.03);
  EXPECT_LT(best.loss, 0.1 + 1e-3);
}

TEST(SurrogateSearch, FindsTheGlobalMinimumOfAFunctionWithTwoValleys) {
  // f = sin(3 pi x) x-shaped: the deeper valley at x ~ 0.83 (value -0.8...), a shallower one at
  // x ~ 0.17. Plain descent from the middle goes either way; EI must find the deeper one.
  auto f = [](const Eigen::VectorXd& x) { return -std::sin(3 * M_PI * x[0]) * x[0]; };
  const auto done = minimise(f, 1, 4, 14, 1, 0.0, 3);
  const auto best = *std::min_element(done.begin(), done.end(), [](auto& a, auto& b) { return a.loss < b.loss; });
  // Exact minimiser of -x sin(3 pi x) near 5/6: solve tan(3 pi x) = -3 pi x -> x = 0.8379.
  EXPECT_NEAR(best.x[0], 0.8379, 0.01);
}

TEST(SurrogateSearch, PlausibleRangesBracketTheMinimumAsWideAsTheToleranceAllows) {
  // Loss 0.1 + (x - 0.4)^2 sampled densely: the range where it stays below 0.1 + 0.01 is
  // 0.4 +- 0.1, which the surrogate's ranges reproduce to its interpolation error.
  Eigen::MatrixXd x(9, 1);
  Eigen::VectorXd y(9);
  for (int i = 0; i < 9; ++i) x(i, 0) = i / 8.0, y[i] = 0.1 + std::pow(x(i, 0) - 0.4, 2);
  GaussianProcess gp;
  gp.fit(x, y);
  Eigen::VectorXd lo, hi, best(1);
  best << 0.4;
  plausibleRanges(gp, best, 0.11, lo, hi);
  EXPECT_NEAR(lo[0], 0.3, 0.01);
  EXPECT_NEAR(hi[0], 0.5, 0.01);
}
