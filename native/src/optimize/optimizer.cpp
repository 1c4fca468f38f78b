#include "optimize/optimizer.h"

#include "optimize/cma_es.h"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gaitlab::optimize {

const char* methodName(Method m) { return m == Method::Greedy ? "greedy" : "cmaes"; }

bool parseMethod(const std::string& name, Method* out) {
  for (Method m : {Method::Greedy, Method::CmaEs}) {
    if (name == methodName(m)) {
      *out = m;
      return true;
    }
  }
  return false;
}

std::vector<double> perturb(const std::vector<double>& x, const std::vector<double>& lo,
                            const std::vector<double>& hi, double probability, double scale, Random& rng) {
  std::vector<double> y = x;
  for (size_t i = 0; i < y.size(); ++i) {
    // Both numbers are drawn for every coordinate, changed or not, so that coordinate i's fate
    // does not shift the random stream of the coordinates after it.
    const double u = rng.uniform();
    const double step = rng.uniform(-scale, scale) * (hi[i] - lo[i]);
    if (u < probability) y[i] = std::clamp(y[i] + step, lo[i], hi[i]);
  }
  return y;
}

int tunedKey(const gait::Gait& gait, const std::vector<double>& speeds) {
  double mean = 0;
  for (double v : speeds) mean += std::abs(v) / static_cast<double>(speeds.size());
  return gait.nearestKey(mean);
}

std::string heldCoordinates(gait::Character c, const std::vector<std::string>& names, std::vector<bool>* mask) {
  const std::vector<gait::ParamSpec>& specs = gait::paramSpecs(c);
  std::vector<bool> held(gait::paramDimension(c), false);
  for (const std::string& name : names) {
    bool found = false;
    size_t at = 0;
    for (const gait::ParamSpec& spec : specs) {
      if (spec.name == name || spec.field == name) {
        found = true;
        for (int k = 0; k < spec.knots; ++k) held[at + k] = true;
      }
      at += spec.knots;
    }
    if (!found)
      return "'" + name + "' is not a parameter of the " + gait::characterName(c) +
             " (a name such as those `gaitlab schema` lists, or a field every leg has, such as stepTrigger)";
  }
  *mask = std::move(held);
  return "";
}

Optimizer::Optimizer(const SearchOptions& options, const gait::GaitParams& start)
    : options_(options), rng_(options.seed), start_(start), best_(start),
      bestObjective_(std::numeric_limits<double>::infinity()), pool_(std::max(1, options.threads)) {
  gait::bounds(options.character, &lo_, &hi_);
  // A start outside the bounds (hand-edited in code, not loaded from a file) is brought inside.
  bestVector_ = gait::toVector(options.character, start);
  gait::clampToBounds(options.character, &bestVector_);
  // Held: what the caller holds, and what the episodes cannot measure (unmeasuredParameters).
  std::vector<std::string> held = options.held;
  for (const std::string& name : unmeasuredParameters(options.character, options.objective)) held.push_back(name);
  // A name that is not a parameter is the caller's mistake (the CLI checks --hold first): a
  // search that went on would quietly move what it was asked to keep.
  const std::string error = heldCoordinates(options.character, held, &held_);
  if (!error.empty()) throw std::invalid_argument(error);
}

ObjectiveTerms Optimizer::score(const gait::GaitParams& params) const {
  // The same episodes (start states, push phases) for every candidate of every generation, so
  // objectives are comparable; they follow from the search seed.
  const uint32_t episodeSeed = static_cast<uint32_t>(options_.seed * 2654435761u + 12345u);
  return evaluate(options_.character, gaitWith(params), options_.objective, episodeSeed,
                  options_.body ? &*options_.body : nullptr);
}

gait::Gait Optimizer::gaitWith(const gait::GaitParams& params) const {
  if (options_.gait.keys.empty()) return gait::Gait::single(params);
  gait::Gait gait = options_.gait;
  gait.keys[options_.key].params = params;
  return gait;
}

const ObjectiveTerms& Optimizer::startTerms() {
  if (!startTerms_) {
    // The start as the search sees it: within the bounds, as bestVector_ holds it.
    gait::fromVector(options_.character, bestVector_, &best_);
    startTerms_ = score(best_);
    bestTerms_ = *startTerms_;
    bestObjective_ = bestTerms_.total;
  }
  return *startTerms_;
}

Generation Optimizer::step() {
  const auto t0 = std::chrono::steady_clock::now();
  startTerms();  // scored once, before the first generation
  std::vector<std::vector<double>> points = propose();
  const int k = static_cast<int>(points.size());
  // Held coordinates are evaluated as they started, whatever the method proposed for them (the
  // best vector keeps the start's values there, so the greedy copies and every winner do too;
  // CMA-ES's distribution moves along them without effect).
  for (std::vector<double>& p : points)
    for (size_t i = 0; i < held_.size() && i < p.size(); ++i)
      if (held_[i]) p[i] = bestVector_[i];
  std::vector<gait::GaitParams> candidates(k, start_);
  for (int i = 0; i < k; ++i) gait::fromVector(options_.character, points[i], &candidates[i]);

  std::vector<ObjectiveTerms> results(k);
  // One task per evaluation, each thread taking the next until none are left (falls end
  // episodes early, so evaluations differ in cost). Results land in their own slot.
  pool_.forEach(k, [&](int i) { results[i] = score(candidates[i]); });
  evaluations_ += k;
  ++generation_;

  Generation g;
  g.index = generation_;
  int winner = -1;
  for (int i = 0; i < k; ++i) {
    if (results[i].total < bestObjective_ && (winner < 0 || results[i].total < results[winner].total)) winner = i;
  }
  g.improved = winner >= 0;
  if (g.improved) {
    bestObjective_ = results[winner].total;
    bestTerms_ = results[winner];
    bestVector_ = points[winner];
    best_ = candidates[winner];
  }
  tell(points, results);
  g.bestObjective = bestObjective_;
  g.bestTerms = bestTerms_;
  g.evaluations = evaluations_;
  g.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return g;
}

namespace {

// ---- greedy stochastic local search (thesis §3.3) ------------------------------------------
class Greedy : public Optimizer {
 public:
  Greedy(const SearchOptions& o, const gait::GaitParams& start) : Optimizer(o, start) {}

 protected:
  std::vector<std::vector<double>> propose() override {
    // The current best unchanged (it doubles as a determinism check), then K−1 perturbed copies.
    std::vector<std::vector<double>> points = {bestVector_};
    for (int i = 1; i < options_.candidates; ++i)
      points.push_back(perturb(bestVector_, lo_, hi_, options_.perturbProbability, options_.stepScale, rng_));
    incumbent_ = bestObjective_;
    return points;
  }
  void tell(const std::vector<std::vector<double>>&, const std::vector<ObjectiveTerms>& results) override {
    if (std::isfinite(incumbent_) && results[0].total != incumbent_) ++mismatches_;
  }

 private:
  double incumbent_ = std::numeric_limits<double>::infinity();
};

// ---- CMA-ES (optimize/cma_es.h) ------------------------------------------------------------
// Works in normalised coordinates u = (x − lo)/(hi − lo) ∈ [0, 1]ⁿ. A sample outside the box is
// evaluated at its projection onto the box, and ranked with the squared distance to it added,
// so the distribution is drawn back inside (a common boundary handling).
class CmaEsSearch : public Optimizer {
 public:
  CmaEsSearch(const SearchOptions& o, const gait::GaitParams& start)
      : Optimizer(o, start), cma_(normalised(bestVector_), o.cmaSigma, std::max(2, o.candidates), /*maxSigma=*/1.0) {}

 protected:
  std::vector<std::vector<double>> propose() override {
    const std::vector<Eigen::VectorXd>& samples = cma_.ask([this] { return rng_.normal(); });
    std::vector<std::vector<double>> points(samples.size(), std::vector<double>(lo_.size()));
    for (size_t k = 0; k < samples.size(); ++k)
      for (size_t i = 0; i < lo_.size(); ++i)
        points[k][i] = lo_[i] + std::clamp(samples[k][i], 0.0, 1.0) * (hi_[i] - lo_[i]);
    samples_.assign(samples.begin(), samples.end());
    return points;
  }

  void tell(const std::vector<std::vector<double>>&, const std::vector<ObjectiveTerms>& results) override {
    std::vector<double> costs(results.size());
    for (size_t k = 0; k < results.size(); ++k) {
      const Eigen::VectorXd inside = samples_[k].cwiseMax(0.0).cwiseMin(1.0);
      costs[k] = results[k].total + (samples_[k] - inside).squaredNorm();
    }
    cma_.tell(costs);
  }

 private:
  Eigen::VectorXd normalised(const std::vector<double>& x) const {
    Eigen::VectorXd u(x.size());
    for (size_t i = 0; i < x.size(); ++i) u[i] = (x[i] - lo_[i]) / (hi_[i] - lo_[i]);
    return u;
  }

  CmaEs cma_;
  std::vector<Eigen::VectorXd> samples_;  // this generation's, in unit-box coordinates (some outside it)
};

}  // namespace

std::unique_ptr<Optimizer> Optimizer::create(const SearchOptions& options, const gait::GaitParams& start) {
  if (options.method == Method::CmaEs) return std::unique_ptr<Optimizer>(new CmaEsSearch(options, start));
  return std::unique_ptr<Optimizer>(new Greedy(options, start));
}

}  // namespace gaitlab::optimize
