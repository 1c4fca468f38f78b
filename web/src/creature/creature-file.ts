// Creature files as the page writes them: the "gaitlab-creature" format, version 3, whose one
// reader and every range live in native/src/body/creature.h (docs/creatures.md). These types only
// name its fields for TypeScript; the module judges a file, and refuses it with the field named.

export const CREATURE_FORMAT = 'gaitlab-creature';
/**
 * The version the page writes. Version 1 is version 2 without legs of three segments; both are
 * read, their hip ranges mirrored, as the physics simulated them (body/creature.h).
 */
export const CREATURE_FORMAT_VERSION = 3;
/** Most leg frames a body may have (kMaxCreatureLegFrames, body/creature.h). */
export const MAX_LEG_FRAMES = 4;

export type Triple = [number, number, number];

export interface LimbSpec {
  /** m */
  length: number;
  /** m */
  halfThickness: number;
  /** kg */
  mass: number;
}

/** A leg's third segment (version 2): a limb below the lower leg, and its hock, which bends the other way to the knee. */
export interface TarsusSpec extends LimbSpec {
  hock: { flexion: number; hyperextension: number };
}

export interface LegPairSpec {
  /** Prefix of the legs' names, may be "". */
  name: string;
  /** Each hip from the midline, m. */
  hipSpacing: number;
  /** The hip's ball joint: flexion (about x), abduction, twist, rad. */
  hip: { lower: Triple; upper: Triple };
  knee: { points: 'forward' | 'backward'; flexion: number; hyperextension: number };
  ankle: { pitch: number; roll: number };
  upper: LimbSpec;
  lower: LimbSpec;
  /** Legs of three segments only. */
  tarsus?: TarsusSpec;
  foot: { halfExtents: Triple; forward: number; mass: number; ankleAboveFoot: number };
  colours: { left: string; right: string; foot: string };
}

export interface LegFrameSpec {
  name: string;
  /** Its centre, forward of the body's middle, m. */
  z: number;
  halfExtents: Triple;
  mass: number;
  /** Its centre above its hips, m. */
  aboveHips: number;
  colour: string;
  legs: LegPairSpec;
}

export interface SpineSection {
  /** z of its first and last joint, m. */
  from: number;
  to: number;
  links: number;
  halfWidth: number;
  halfHeight: number;
  /** Each link's, kg. */
  mass: number;
  /** Each axis of each joint, rad. */
  limit: number;
  colour: string;
}

export interface CreatureFile {
  format: typeof CREATURE_FORMAT;
  version: 1 | 2 | typeof CREATURE_FORMAT_VERSION;
  name: string;
  /** kg·m² */
  armature: number;
  /** Front to back. */
  legFrames: LegFrameSpec[];
  /** One section between each two leg frames. */
  spine: SpineSection[];
}

/** A leg's mass: its upper and lower segments, its tarsus if it has one, and its foot. */
export function legMass(legs: LegPairSpec): number {
  return legs.upper.mass + legs.lower.mass + (legs.tarsus?.mass ?? 0) + legs.foot.mass;
}

/** The whole body's mass, kg. */
export function totalMass(file: CreatureFile): number {
  const frames = file.legFrames.reduce((sum, f) => sum + f.mass + 2 * legMass(f.legs), 0);
  return frames + file.spine.reduce((sum, s) => sum + s.links * s.mass, 0);
}

/** Its legs' hip height when standing straight (body/creature.cpp's hipHeight), m. */
export function hipHeight(legs: LegPairSpec): number {
  return 2 * legs.foot.halfExtents[1] + legs.foot.ankleAboveFoot + (legs.tarsus?.length ?? 0) + legs.lower.length + legs.upper.length;
}
