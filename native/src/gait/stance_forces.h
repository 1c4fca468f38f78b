// Ground forces for a body standing on several feet (beyond the thesis, for characters with
// more than one leg frame).
//
// The thesis (§3.1.3–3.1.4) gives each leg frame its own stance forces and delivers its torque
// through its own stance hips. A quadruped's two leg frames stand on one foot each in every
// phase of a trot, and a single small foot returns neither a roll nor a yaw torque: that scheme
// left roll, yaw and sideways force to friction at one sole and the trot drifted sideways and
// in heading until it fell (docs/controller-notes.md §8–§9). Legged robots solve the same
// problem by treating the body as one rigid body and choosing the ground force at each stance
// foot so that together they give it the wrench it needs (the "balance controller" of Gehring
// et al. 2013, Focchi et al. 2017 and MIT Cheetah 3, Bledt et al. 2018). With two diagonal feet
// the roll about the diagonal cannot be produced by point feet: the least-squares solution
// leaves it out, and foot placement (§3.1.6) balances it, as Raibert's trotting machines did.
//
// Physics-free; fixed-size storage (no heap) so it runs inside the parallel controller loop.
#pragma once
#include <Eigen/Dense>

namespace gaitlab::gait {

struct StanceForceSettings {
  // Weight of a torque error (N·m) against a force error (N) in the fit: about the body's half
  // length (m⁻¹ inverted), so that a pitch torque is not sacrificed to the last newton of lift.
  double torqueWeight = 3.0;
  // Tikhonov weight on the forces themselves: the fit prefers small, evenly shared forces in
  // directions the wrench does not fix (e.g. two feet squeezing each other).
  double regularisation = 1e-4;
  // Friction coefficient the forces are kept within (below the contact's, for a margin), and the
  // least vertical force a stance foot is asked for (N): feet pull on nothing.
  double friction = 0.6;
  double minNormal = 1.0;
};

constexpr int kMaxStanceFeet = 8;

// Forces f_i (world, N, exerted BY the ground ON the body through foot i at `points[i]`) that
// best give the body the force `force` and the torque `torque` about `com`:
//     minimise |Σ f_i − F|² + w² |Σ (p_i − c) × f_i − T|² + λ Σ |f_i|²,
// then each force is brought into its friction cone (+y is up): f_y ≥ minNormal and the
// horizontal part no longer than μ f_y. `count` ≤ kMaxStanceFeet; returns false (out untouched)
// for a count out of range.
bool distributeStanceForces(const Eigen::Vector3d& com, const Eigen::Vector3d& force,
                            const Eigen::Vector3d& torque, const Eigen::Vector3d* points,
                            int count, const StanceForceSettings& settings, Eigen::Vector3d* out);

}  // namespace gaitlab::gait
