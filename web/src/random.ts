// A seeded random number generator: the same seed, the same numbers, so that a random body
// (creature/design.ts, randomDesign) or a failing generated test case can be made again.
// mulberry32 (T. Ettinger, 2017): a 32-bit state advanced by a Weyl sequence and mixed by two
// multiply-xorshift rounds; fast, and plenty for drawing settings and test inputs (not for
// anything that needs cryptographic or statistical strength).

/** A generator of numbers in [0, 1) from `seed` (taken as an unsigned 32-bit integer). */
export function mulberry32(seed: number): () => number {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}
