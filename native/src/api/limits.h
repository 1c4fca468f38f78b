// The limits on what a user, a link or a file may send gaitlab, stated once. Everything that
// enters from outside (the CLI's files and options, the C ABI, and through it the sim worker's
// messages, share links and imported gait files) is checked against these before it is used, and
// a value beyond them is refused with a message that names it: no input can crash the module,
// hang it, exhaust its memory or leave a character in a state that is not finite.
//
// web/src/sim/limits.ts is the page's copy (tests/web/sim/limits.test.ts reads this file and
// compares), so the page can refuse a link or a message before it reaches the module.
//
// Why these figures (README, "Limits"):
//   - Gait files. A full gait file is 8-12 kB, a share link's JSON 2-4 kB, and the deepest
//     nesting a valid one has is 3 (document, "params", a motion graph's knots); "meta" holds
//     provenance (the optimiser writes objects two levels deep). The caps leave ample room for
//     hand-edited files, and bound what a hostile one costs: the text is read at most once,
//     iteratively, and nothing deeper than kMaxJsonDepth is ever built, copied or printed (a
//     recursive copy of a 10,000-deep document overflows the stack).
//   - Numbers a scene command carries. A goal the controller can follow, places within the
//     ground the terrain grid and Bullet's broadphase are built for, and a thrown box's speed
//     that keeps the collision of an 8 kg box with a 60 kg figure within what the 120 Hz step
//     resolves.
//   - Memory. The WASM module has a fixed heap (native/CMakeLists.txt, INITIAL_MEMORY, no
//     growth): a spawn the heap cannot afford is refused before it allocates (capacity.h).
#pragma once

namespace gaitlab::limits {

// ---- Gait files, patches, objective settings: JSON text --------------------------------------
constexpr long kMaxJsonBytes = 256 * 1024;  // bytes of one document (the CLI reads no more)
constexpr int kMaxJsonDepth = 16;           // nested objects and arrays, the document itself being 1
constexpr long kMaxJsonString = 16 * 1024;  // bytes of one string or key
constexpr long kMaxJsonArray = 4096;        // elements of one array, members of one object

// ---- Scene commands (C ABI, sim worker) ----------------------------------------------------
constexpr double kMaxGoalSpeed = 5.0;       // |forward speed|, m/s (a running human: 5 m/s)
constexpr double kMaxGoalTurn = 3.0;        // |turn rate|, rad/s
constexpr double kMaxCoordinate = 1000.0;   // |x|, |y|, |z| of a spawn, a throw or a drag target, m
constexpr double kMaxHeading = 1000.0;      // |heading|, rad (any angle; the bound keeps it exact)
constexpr double kMaxThrowSpeed = 100.0;    // |velocity| of a thrown box, m/s
constexpr double kMinAimSpeed = 1.0;        // speed of a box aimed at a character, m/s (to kMaxThrowSpeed)
constexpr double kMinThrowHalf = 0.03;      // half size of a thrown box, m
constexpr double kMaxThrowHalf = 0.5;
constexpr double kMaxDragLocal = 10.0;      // |local| of a drag's point in its segment, m
constexpr double kMaxAutoReset = 3600.0;    // seconds a fallen character waits to be reset
constexpr int kMaxStepsPerCall = 12000;     // fixed steps of one gl_sim_step call (100 s)

// ---- What a simulation holds ---------------------------------------------------------------
// Boxes (props: the scene's, spawned and thrown). Boxes dropped on one spot all touch each
// other: n boxes make n(n-1)/2 contact pairs, so 1000 on one spot cost 420 MB and 6.5 s for a
// step natively, and 256 took 97 MB of the WASM build's heap; 64 take 4 MB.
constexpr int kMaxBoxes = 64;
// Characters: as many as the render buffer has room for (RenderPublisher::kCapacity bodies) and,
// in the WASM build, as the heap can afford (capacity.h, which holds the measured costs).

// ---- Benchmark points (gl_bench_point): the samples are allocated up front -----------------
constexpr int kMaxBenchSteps = 100000;
constexpr int kMaxBenchRuns = 1000;
constexpr long kMaxBenchSamples = 2000000;  // steps × runs

}  // namespace gaitlab::limits
