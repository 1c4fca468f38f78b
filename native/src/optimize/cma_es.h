// CMA-ES, the covariance matrix adaptation evolution strategy (Hansen, "The CMA Evolution
// Strategy: A Tutorial", 2016), as an ask/tell core: it proposes a generation of points, is told
// what they cost, and moves its search distribution N(mean, σ² C). It knows nothing of gaits or
// episodes, so the gait search (optimize/optimizer.cpp) and the get-up search probe
// (probes/getup_search.cpp) run the same update.
//
// Every constant is the tutorial's default for n coordinates and λ points a generation: the
// recombination weights w_i ∝ ln(μ + ½) − ln i over the best μ = ⌊λ/2⌋, the learning rates c_σ,
// d_σ, c_c, c_1, c_μ, and the expected length of an n-dimensional standard normal vector.
//
// The caller chooses the coordinates. Both callers search the unit box [0, 1]ⁿ of their
// parameters' ranges, so σ is a share of each range and is kept at most maxSigma (a step wider
// than the box means nothing). Points may fall outside the box; what a caller evaluates there
// (the gait search: the projection, with the squared distance added to the cost) is its own.
//
//   CmaEs cma(mean, 0.1, 10);
//   for (...) {
//     const std::vector<Eigen::VectorXd>& x = cma.ask([&] { return normal(rng); });
//     cma.tell(costs of x);  // lower is better
//   }
#pragma once
#include <Eigen/Dense>
#include <functional>
#include <limits>
#include <vector>

namespace gaitlab::optimize {

class CmaEs {
 public:
  CmaEs(const Eigen::VectorXd& mean, double sigma, int lambda,
        double maxSigma = std::numeric_limits<double>::infinity());

  // The next generation's λ points, each mean + σ B D z with z drawn from `normal` (a standard
  // normal deviate per call, coordinates in order, point after point: the caller's generator
  // makes the search reproducible).
  const std::vector<Eigen::VectorXd>& ask(const std::function<double()>& normal);

  // The costs of the points ask() returned, in its order; lower is better, ties go to the
  // earlier point. Moves the mean, the evolution paths, C and σ.
  void tell(const std::vector<double>& costs);

  const Eigen::VectorXd& mean() const { return mean_; }
  double sigma() const { return sigma_; }
  int lambda() const { return lambda_; }

 private:
  int n_, lambda_;
  double maxSigma_;
  Eigen::VectorXd weights_;
  double muEff_, cSigma_, dSigma_, cc_, c1_, cMu_, chiN_;
  Eigen::VectorXd mean_, pSigma_, pc_, D_;
  Eigen::MatrixXd C_, B_;
  double sigma_;
  int generation_ = 0;  // generations told so far
  std::vector<Eigen::VectorXd> samples_;
};

}  // namespace gaitlab::optimize
