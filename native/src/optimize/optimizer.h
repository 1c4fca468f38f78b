// Parameter search over a character's gait (thesis §3.3), one generation at a time so that the
// CLI, the tests and the browser (through the C ABI) can all drive it and stop it between
// generations.
//
// The search space is the schema's flat vector (gait/schema.h): every parameter the character
// uses, a motion graph contributing its four knots, each within its schema bounds.
//
//   greedy  the thesis's greedy stochastic local search: each generation evaluates the current
//           best unchanged plus K−1 perturbed copies of it; the lowest objective wins if it
//           beats the best.
//   cmaes   CMA-ES (Hansen's (μ/μ_w, λ) covariance matrix adaptation, beyond the thesis; its
//           §2.3 names it as used by related work), λ = K samples per generation.
//
// Candidates of a generation are evaluated in parallel on a thread pool, one evaluation (its
// own single-threaded Simulation) per task; all random numbers are drawn on the calling thread
// before the evaluations start, so the search does not depend on the thread count.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gait/params.h"
#include "gait/schema.h"
#include "optimize/objective.h"
#include "optimize/random.h"
#include "sim/thread_pool.h"

namespace gaitlab::optimize {

enum class Method { Greedy, CmaEs };
const char* methodName(Method m);             // "greedy", "cmaes"
bool parseMethod(const std::string& name, Method* out);

// Candidates per generation a search accepts (`gaitlab optimize --candidates`, gl_opt_create).
constexpr int kMinCandidates = 2, kMaxCandidates = 1000;

struct SearchOptions {
  gait::Character character = gait::Character::Biped;
  // The body every episode walks with (a creature file's, whose kind is `character`); empty: the
  // kind's shipped body (gait::shippedBody).
  std::optional<body::Morphology> body;
  Method method = Method::Greedy;
  int candidates = 10;  // K per generation (thesis: the best + 9 perturbed copies)
  uint64_t seed = 1;
  int threads = 1;
  ObjectiveSettings objective;
  // Greedy perturbation (§3.3): each coordinate changes with this probability, by
  // U(−stepScale, stepScale)·(max − min), then is clamped to its bounds.
  double perturbProbability = 0.2;
  double stepScale = 0.1;
  // CMA-ES initial step size, as a share of each coordinate's range.
  double cmaSigma = 0.1;
  // A gait of several speed keys (gait/speed_keys.h): the search tunes key `key` and every episode
  // walks with the whole gait, its other keys as they are. Empty: the tuned parameters are the
  // whole gait. By default (tunedKey) the key the episodes walk with most.
  gait::Gait gait;
  int key = 0;
  // Parameters the search leaves as they start, each a schema name ("frontLeft.stepTrigger") or a
  // field every leg or leg frame has ("stepTrigger": every leg's): a search for a canter keeps its
  // footfall pattern this way, where a free search moves the triggers back to a gait it already
  // knows (docs/controller-notes.md §33). Checked by heldCoordinates.
  std::vector<std::string> held;
};

// The key a search tunes unless told which: the one nearest the mean of the goal speeds'
// magnitudes, the key those episodes walk with most (a walk at 0.4 m/s blends the keys around it
// and barely uses a key at 1.4 m/s, so tuning that one would leave every candidate scoring alike).
int tunedKey(const gait::Gait& gait, const std::vector<double>& speeds);

// Marks the coordinates of the flat parameter vector (gait::toVector) that `names` hold: mask has
// gait::paramDimension(c) entries, a graph's knots all held with it. Returns "'NAME' is not a
// parameter of the CHARACTER (...)" for a name that is neither a parameter nor a field, empty on
// success.
std::string heldCoordinates(gait::Character c, const std::vector<std::string>& names, std::vector<bool>* mask);

// §3.3's perturbation of a flat parameter vector: each coordinate independently, with
// probability `probability`, moves by U(−scale, scale)·(hi − lo), then is clamped to [lo, hi].
std::vector<double> perturb(const std::vector<double>& x, const std::vector<double>& lo,
                            const std::vector<double>& hi, double probability, double scale, Random& rng);

struct Generation {
  int index = 0;            // 1-based
  double bestObjective = 0;  // after this generation
  ObjectiveTerms bestTerms;
  bool improved = false;
  int evaluations = 0;      // total so far
  double seconds = 0;       // wall-clock of this generation
};

class Optimizer {
 public:
  virtual ~Optimizer() = default;

  // Runs one generation: K evaluations on the pool. Returns what it reached.
  Generation step();

  // The start's own objective, evaluated once (here or before the first generation, outside the
  // evaluation count) on the search's episodes. The start is the best until a candidate scores
  // lower, so a search never returns a gait scoring worse than the one it was given: CMA-ES
  // samples around the start without evaluating it, and from a gait near its optimum a search of
  // 200 candidates had written out one that scored worse than its start (docs/controller-notes.md
  // §66). The greedy search re-evaluates it as its first candidate, its determinism check.
  const ObjectiveTerms& startTerms();

  const gait::GaitParams& best() const { return best_; }
  // The whole gait with the tuned key set to `params` (SearchOptions::gait; without keys, `params`
  // alone): what every episode walks with, and what a search writes out.
  gait::Gait gaitWith(const gait::GaitParams& params) const;
  double bestObjective() const { return bestObjective_; }
  const ObjectiveTerms& bestTerms() const { return bestTerms_; }
  int generation() const { return generation_; }
  int evaluations() const { return evaluations_; }
  const SearchOptions& options() const { return options_; }
  // Greedy only: times the re-evaluated best scored differently from before (must stay 0:
  // the thesis used this re-evaluation as its determinism check).
  int determinismMismatches() const { return mismatches_; }

  // The objective of any parameter set on this search's episodes (the same start states and
  // push phases every candidate gets); e.g. the start's, for comparison.
  ObjectiveTerms score(const gait::GaitParams& params) const;

  static std::unique_ptr<Optimizer> create(const SearchOptions& options, const gait::GaitParams& start);

 protected:
  Optimizer(const SearchOptions& options, const gait::GaitParams& start);
  // The K points of the next generation (flat vectors, within bounds).
  virtual std::vector<std::vector<double>> propose() = 0;
  // Told their objectives, in the same order.
  virtual void tell(const std::vector<std::vector<double>>& points, const std::vector<ObjectiveTerms>& results) = 0;

  SearchOptions options_;
  std::vector<double> lo_, hi_;
  std::vector<bool> held_;  // per coordinate: left as it starts (SearchOptions::held)
  Random rng_;
  gait::GaitParams start_;  // fields the schema does not cover (a biped's unused ones) come from here
  gait::GaitParams best_;
  std::vector<double> bestVector_;
  double bestObjective_;
  ObjectiveTerms bestTerms_;
  int generation_ = 0, evaluations_ = 0, mismatches_ = 0;
  std::optional<ObjectiveTerms> startTerms_;  // startTerms(), once scored

 private:
  sim::ThreadPool pool_;
};

}  // namespace gaitlab::optimize
