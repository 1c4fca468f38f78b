#include "optimize/cma_es.h"

#include <algorithm>
#include <cmath>

namespace gaitlab::optimize {

CmaEs::CmaEs(const Eigen::VectorXd& mean, double sigma, int lambda, double maxSigma)
    : n_(static_cast<int>(mean.size())), lambda_(lambda), maxSigma_(maxSigma), mean_(mean), sigma_(sigma) {
  const int mu = lambda_ / 2;
  weights_.resize(mu);
  for (int i = 0; i < mu; ++i) weights_[i] = std::log(mu + 0.5) - std::log(i + 1.0);
  weights_ /= weights_.sum();
  muEff_ = 1.0 / weights_.squaredNorm();
  const double n = n_;
  cSigma_ = (muEff_ + 2) / (n + muEff_ + 5);
  dSigma_ = 1 + 2 * std::max(0.0, std::sqrt((muEff_ - 1) / (n + 1)) - 1) + cSigma_;
  cc_ = (4 + muEff_ / n) / (n + 4 + 2 * muEff_ / n);
  c1_ = 2 / ((n + 1.3) * (n + 1.3) + muEff_);
  cMu_ = std::min(1 - c1_, 2 * (muEff_ - 2 + 1 / muEff_) / ((n + 2) * (n + 2) + muEff_));
  chiN_ = std::sqrt(n) * (1 - 1 / (4 * n) + 1 / (21 * n * n));
  C_ = Eigen::MatrixXd::Identity(n_, n_);
  B_ = C_;
  D_ = Eigen::VectorXd::Ones(n_);
  pSigma_ = pc_ = Eigen::VectorXd::Zero(n_);
}

const std::vector<Eigen::VectorXd>& CmaEs::ask(const std::function<double()>& normal) {
  samples_.assign(lambda_, Eigen::VectorXd(n_));
  for (int k = 0; k < lambda_; ++k) {
    Eigen::VectorXd z(n_);
    for (int i = 0; i < n_; ++i) z[i] = normal();
    samples_[k] = mean_ + sigma_ * (B_ * D_.asDiagonal() * z);
  }
  return samples_;
}

void CmaEs::tell(const std::vector<double>& costs) {
  ++generation_;
  std::vector<int> order(lambda_);
  for (int k = 0; k < lambda_; ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return costs[a] < costs[b]; });

  // The new mean: the best μ points, weighted.
  const int mu = static_cast<int>(weights_.size());
  const Eigen::VectorXd old = mean_;
  mean_.setZero();
  for (int i = 0; i < mu; ++i) mean_ += weights_[i] * samples_[order[i]];
  const Eigen::VectorXd step = (mean_ - old) / sigma_;

  // The evolution paths: p_σ of the whitened step, C^(-1/2) = B D^(-1) Bᵀ, and p_c, whose update
  // stalls (h_σ) while p_σ is long, so that C does not grow too fast after a large step.
  const Eigen::VectorXd whitened = B_ * (D_.cwiseInverse().asDiagonal() * (B_.transpose() * step));
  pSigma_ = (1 - cSigma_) * pSigma_ + std::sqrt(cSigma_ * (2 - cSigma_) * muEff_) * whitened;
  const double gens = generation_;
  const bool hSigma = pSigma_.norm() / std::sqrt(1 - std::pow(1 - cSigma_, 2 * gens)) <
                      (1.4 + 2 / (n_ + 1.0)) * chiN_;
  pc_ = (1 - cc_) * pc_ + (hSigma ? std::sqrt(cc_ * (2 - cc_) * muEff_) : 0.0) * step;

  // C: the rank-one update from p_c and the rank-μ update from this generation's best steps.
  Eigen::MatrixXd rankMu = Eigen::MatrixXd::Zero(n_, n_);
  for (int i = 0; i < mu; ++i) {
    const Eigen::VectorXd y = (samples_[order[i]] - old) / sigma_;
    rankMu += weights_[i] * y * y.transpose();
  }
  C_ = (1 - c1_ - cMu_) * C_ +
       c1_ * (pc_ * pc_.transpose() + (hSigma ? 0.0 : cc_ * (2 - cc_)) * C_) + cMu_ * rankMu;
  // σ grows while p_σ is longer than a random walk's, and shrinks while it is shorter.
  sigma_ *= std::exp((cSigma_ / dSigma_) * (pSigma_.norm() / chiN_ - 1));
  sigma_ = std::min(sigma_, maxSigma_);

  // C = B D² Bᵀ; symmetrised first so rounding cannot make the solver see an asymmetric C.
  C_ = 0.5 * (C_ + C_.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(C_);
  B_ = eig.eigenvectors();
  D_ = eig.eigenvalues().cwiseMax(1e-20).cwiseSqrt();
}

}  // namespace gaitlab::optimize
