// The CMA-ES core (optimize/cma_es.h) on its own, on functions whose minimum is known: it must
// find the minimum of an ill-conditioned ellipsoid, which needs the covariance's adaptation (with
// C held at the identity, the same budget ends at f = 0.5–3.3 on these seeds, not below 1e-8),
// adapt σ both ways, and rank ties by the order the points were asked in.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "optimize/cma_es.h"

using gaitlab::optimize::CmaEs;

namespace {

// f(x) = Σ 10^(4 i/(n−1)) (x_i − 0.3)²: axis scales spanning a factor 100, minimum 0 at 0.3.
double ellipsoid(const Eigen::VectorXd& x) {
  const int n = static_cast<int>(x.size());
  double f = 0;
  for (int i = 0; i < n; ++i) f += std::pow(10.0, 4.0 * i / (n - 1)) * (x[i] - 0.3) * (x[i] - 0.3);
  return f;
}

// Runs `generations` of CMA-ES from every coordinate at 0.8; returns the best value seen.
double minimise(double (*f)(const Eigen::VectorXd&), int n, int generations, unsigned seed, CmaEs* out = nullptr) {
  CmaEs cma(Eigen::VectorXd::Constant(n, 0.8), 0.2, 10);
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  double best = INFINITY;
  for (int g = 0; g < generations; ++g) {
    const std::vector<Eigen::VectorXd>& x = cma.ask([&] { return normal(rng); });
    std::vector<double> costs;
    for (const Eigen::VectorXd& p : x) costs.push_back(f(p));
    for (double c : costs) best = std::min(best, c);
    cma.tell(costs);
  }
  if (out) *out = cma;
  return best;
}

}  // namespace

TEST(CmaEs, FindsTheMinimumOfAnIllConditionedEllipsoid) {
  for (unsigned seed : {1u, 2u, 3u}) {
    CmaEs cma(Eigen::VectorXd::Zero(1), 1, 2);
    const double best = minimise(ellipsoid, 6, 300, seed, &cma);
    EXPECT_LT(best, 1e-8) << "seed " << seed;
    EXPECT_NEAR(cma.mean()[0], 0.3, 1e-3);
    EXPECT_NEAR(cma.mean()[5], 0.3, 1e-3);
    // σ shrank as the search closed in, from its start of 0.2.
    EXPECT_LT(cma.sigma(), 0.01);
  }
}

// 20 generations on the slope f(x) = x_0, where the best steps all point one way; returns the
// largest σ it reached.
static double descendSlope(CmaEs* cma) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  double largest = cma->sigma();
  for (int g = 0; g < 20; ++g) {
    const std::vector<Eigen::VectorXd>& x = cma->ask([&] { return normal(rng); });
    std::vector<double> costs;
    for (const Eigen::VectorXd& p : x) costs.push_back(p[0]);
    cma->tell(costs);
    largest = std::max(largest, cma->sigma());
  }
  return largest;
}

TEST(CmaEs, StepSizeGrowsOnALinearSlope) {
  // p_σ grows longer than a random walk's, so σ must grow (the path-length control of Hansen
  // 2016, §4).
  CmaEs cma(Eigen::VectorXd::Zero(4), 0.1, 8);
  descendSlope(&cma);
  EXPECT_GT(cma.sigma(), 0.3);
  EXPECT_LT(cma.mean()[0], -1.0);
}

TEST(CmaEs, MaxSigmaBoundsTheStepSize) {
  CmaEs cma(Eigen::VectorXd::Zero(4), 0.1, 8, /*maxSigma=*/0.15);
  EXPECT_DOUBLE_EQ(descendSlope(&cma), 0.15);
}

TEST(CmaEs, TiesGoToTheEarlierPoint) {
  // Every cost equal: the best μ are the first μ asked, so the new mean is their weighted mean.
  CmaEs cma(Eigen::VectorXd::Zero(3), 0.5, 6);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  const std::vector<Eigen::VectorXd> x = cma.ask([&] { return normal(rng); });
  cma.tell(std::vector<double>(6, 1.0));
  // The tutorial's weights for μ = 3: ln 3.5 − ln i, normalised.
  const double w[3] = {std::log(3.5) - std::log(1.0), std::log(3.5) - std::log(2.0), std::log(3.5) - std::log(3.0)};
  const double sum = w[0] + w[1] + w[2];
  const Eigen::VectorXd expected = (w[0] * x[0] + w[1] * x[1] + w[2] * x[2]) / sum;
  EXPECT_LT((cma.mean() - expected).norm(), 1e-12);
}
