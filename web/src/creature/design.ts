// The creature designer's model: a handful of settings (leg pairs, leg lengths and segments, body
// size, masses, knees, colours) turned into a creature file (creature-file.ts; native/src/body/
// creature.h), and the checks that refuse a body that cannot work before it is sent. No DOM:
// the panel (ui/creature-designer.ts) shows it, and tests/web/creature/design.test.ts tests it.
//
// Every leg frame of a design is the same, and everything the settings do not name (joint
// ranges, the foot, the spine) comes from the shipped creature files (public/creatures/), which
// all four share: those bodies are measured to walk (docs/creatures.md), so a design departs
// from them only where its settings say. Bodies of 3 and 4 leg frames walk the gait derived from
// the body (native/src/gait/derived_gait.h); 1 and 2 walk the biped's and the quadruped's presets.
import {
  CREATURE_FORMAT,
  CREATURE_FORMAT_VERSION,
  MAX_LEG_FRAMES,
  legMass,
  totalMass,
  type CreatureFile,
  type LegFrameSpec,
  type LegPairSpec,
  type Triple,
} from './creature-file';
import { mulberry32 } from '../random';

/** Which way the knees bend. */
export const KNEE_CHOICES = ['mixed', 'forward', 'backward'] as const;
/**
 * mixed: the front half's pairs point backward (a dog's front "knee", the carpus), the rest
 * forward, as every shipped body of two or more leg frames has them; forward: every knee as a
 * human's; backward: every knee as a bird's.
 */
export type KneeChoice = (typeof KNEE_CHOICES)[number];

export interface CreatureDesign {
  /** Leg pairs, which is leg frames: 1 to 4. */
  pairs: number;
  /** Upper and lower leg, hip to knee and knee to ankle (or to the hock), m. */
  upperLength: number;
  lowerLength: number;
  /**
   * A third segment, hock to ankle, m; 0 for legs of two segments. Its hock bends the other way to
   * the knee, as a bird's or a dog's hind leg (body/creature.h, "tarsus").
   */
  tarsusLength: number;
  /** The upper leg's full thickness, m (the lower leg is 6/7 of it, as in the shipped files). */
  legThickness: number;
  /** Body length: centre to centre of neighbouring leg frames, m. */
  frameSpacing: number;
  /** A leg frame's full width (x) and height (y), m. */
  bodyWidth: number;
  bodyHeight: number;
  /** Each leg frame's mass, kg. */
  frameMass: number;
  /** The legs' share of a leg frame with its pair of legs, by mass (0–1). */
  legShare: number;
  /** Each hip from the midline, m. */
  hipSpacing: number;
  knees: KneeChoice;
  /** How far each knee (and hock) bends from straight, at most, rad. */
  kneeFlexion: number;
  /**
   * How far each hip swings forward and back, at most, rad. A single pair keeps the biped's
   * shape of range, further forward than back (2.0 and 0.7 rad at 1.2).
   */
  hipSwing: number;
  /** "#rrggbb": the leg frames, the spine, the left legs, the right legs. */
  bodyColour: string;
  spineColour: string;
  leftColour: string;
  rightColour: string;
}

export type NumericSetting = Exclude<keyof CreatureDesign, 'knees' | 'bodyColour' | 'spineColour' | 'leftColour' | 'rightColour'>;

/**
 * What each number may be: the designer's sliders span these, and a value outside is refused.
 * All lie inside what the module's reader allows (sizes 2 mm to 2 m, masses 10 g to 500 kg,
 * creature.cpp); the rest of each reason is in its comment.
 */
export const SETTING_RANGES: Record<NumericSetting, { min: number; max: number; step: number; unit: string; label: string }> = {
  pairs: { min: 1, max: MAX_LEG_FRAMES, step: 1, unit: '', label: 'leg pairs' },
  // From half to about 1.4 times the biped's 0.42 m segments: shorter, the foot (scaled with the
  // leg) becomes a few millimetres; the range the checks below were measured over.
  upperLength: { min: 0.1, max: 0.6, step: 0.01, unit: 'm', label: 'upper leg' },
  lowerLength: { min: 0.1, max: 0.6, step: 0.01, unit: 'm', label: 'lower leg' },
  // 0: two segments. Up to TARSUS_SHARE of the leg (the checks below).
  tarsusLength: { min: 0, max: 0.3, step: 0.01, unit: 'm', label: 'third segment' },
  // The shipped legs are 0.07 m (creatures) and 0.12 m (biped) thick.
  legThickness: { min: 0.02, max: 0.14, step: 0.005, unit: 'm', label: 'leg thickness' },
  // The spider's frames are 0.18 m apart, the quadruped's 0.8 m.
  frameSpacing: { min: 0.1, max: 1.0, step: 0.01, unit: 'm', label: 'body length' },
  // The shipped frames are 0.2–0.34 m wide and 0.14–0.56 m high (the biped's is its torso).
  bodyWidth: { min: 0.08, max: 0.5, step: 0.01, unit: 'm', label: 'body width' },
  bodyHeight: { min: 0.06, max: 0.6, step: 0.01, unit: 'm', label: 'body height' },
  // The shipped frames weigh 7–12 kg (the biped's torso 36 kg).
  frameMass: { min: 1, max: 60, step: 0.5, unit: 'kg', label: 'leg frame mass' },
  legShare: { min: 0.05, max: 0.7, step: 0.01, unit: '', label: 'leg mass share' },
  // Hips at most 0.3 m out: beyond any shipped body's (0.09–0.12 m) and the bodyWidth's half.
  hipSpacing: { min: 0.02, max: 0.3, step: 0.005, unit: 'm', label: 'hip spacing' },
  // Joint ranges: the sliders reach below what walks (the checks say why) and up to a knee
  // folded to 160° and a hip swinging 86° each way. The module reads up to π.
  kneeFlexion: { min: 0.5, max: 2.8, step: 0.05, unit: 'rad', label: 'knee bends up to' },
  hipSwing: { min: 0.3, max: 1.5, step: 0.05, unit: 'rad', label: 'hip swings up to' },
};

/** The insect's proportions (public/creatures/insect.json, its frames' mean mass): what the designer starts from. */
export const DEFAULT_DESIGN: CreatureDesign = {
  pairs: 3,
  upperLength: 0.22,
  lowerLength: 0.22,
  tarsusLength: 0,
  legThickness: 0.07,
  frameSpacing: 0.36,
  bodyWidth: 0.2,
  bodyHeight: 0.14,
  frameMass: 25 / 3,
  legShare: 12 / 37,
  hipSpacing: 0.1,
  knees: 'mixed',
  kneeFlexion: 2.4,
  hipSwing: 1.2,
  bodyColour: '#4a3b2a',
  spineColour: '#6b5338',
  leftColour: '#4e8fd9',
  rightColour: '#5fb36b',
};

// ---- What a design takes from the shipped files, which share these numbers. ----

/** kg·m², as every shipped file. */
const ARMATURE = 0.05;
/**
 * The creatures' hip ranges at a swing of 1.2 rad (DEFAULT_DESIGN.hipSwing); a single pair takes
 * the biped's, a person's (its preset gait stops the forward swing at 0.7 rad itself, with its
 * hipForwardStop). The swing scales the flexion (x) limits.
 */
const HIP_RANGE: { lower: Triple; upper: Triple } = { lower: [-1.2, -0.3, -0.35], upper: [1.2, 0.3, 0.35] };
const BIPED_HIP_RANGE: { lower: Triple; upper: Triple } = { lower: [-2.0, -0.6, -0.5], upper: [0.7, 0.6, 0.5] };
/** The hip range a body of `pairs` leg pairs has at the shipped swing. */
const shippedHipRange = (pairs: number) => (pairs === 1 ? BIPED_HIP_RANGE : HIP_RANGE);
const KNEE_HYPEREXTENSION = 0.05;
const ANKLE_PITCH = 0.9;
const ANKLE_ROLL = 0.4;
/**
 * The creatures' legs (0.22 + 0.22 m): their foot's half extents, its centre ahead of the ankle
 * and the ankle's pivot above it. A design's foot is these scaled by its leg length over this
 * one, as the derived gait scales its steps (dynamic similarity, Alexander and Jayes 1983).
 */
const REFERENCE_FOOT = { leg: 0.44, halfExtents: [0.035, 0.02, 0.05] as Triple, forward: 0.015, ankleAboveFoot: 0.005 };
/**
 * A single pair's: the biped's foot on its 0.42 + 0.42 m legs (public/creatures/biped.json),
 * whose preset gait a single pair walks. Its foot is longer for its leg than the creatures': with
 * theirs, the designer's bird (0.84 m legs) fell at 0.8 m/s after 6.2 s; with the biped's it walks
 * 0.8 m/s (30 s, native CLI).
 */
const BIPED_FOOT = { leg: 0.84, halfExtents: [0.05, 0.03, 0.12] as Triple, forward: 0.04, ankleAboveFoot: 0.01 };
/** The reference foot of `design`'s legs, and the scale its leg length gives it. */
function footOf(design: CreatureDesign): { foot: typeof REFERENCE_FOOT; scale: number } {
  const foot = design.pairs === 1 ? BIPED_FOOT : REFERENCE_FOOT;
  return { foot, scale: legLength(design) / foot.leg };
}
/**
 * How a leg's mass is split among upper leg, lower leg and foot: 0.6, 0.3, 0.1, as in every
 * shipped file (the creatures' 1.2, 0.6, 0.2 kg; the biped's 7, 3.5, 1 kg within 2 %).
 */
const UPPER_SHARE = 0.6;
const LOWER_SHARE = 0.3;
const FOOT_SHARE = 0.1;
/** The lower leg's thickness over the upper's: 0.03 / 0.035 and the biped's 0.05 / 0.06. */
const LOWER_THICKNESS = 6 / 7;
/**
 * A tarsus's thickness over the lower leg's (the bird's 0.035 / 0.045). A leg of three segments
 * shares LOWER_SHARE between its lower leg and its tarsus by their lengths (the bird: 3.5 and 1 kg).
 */
const TARSUS_THICKNESS = 7 / 9;
const FOOT_COLOUR = '#3a3a40';
/**
 * Hips 3 cm above a leg frame's underside (the insect's, the spider's and the biped's): a
 * frame's centre sits its half height less 3 cm above its hips.
 */
const HIPS_ABOVE_UNDERSIDE = 0.03;
/** The thesis's spine joint limit, ±0.05π on each axis (Larsson 2015, §3.1), as every shipped file. */
const SPINE_LIMIT = 0.05 * Math.PI;
/** The shipped spines' links are 0.06–0.16 m long: a section has as many as make them about this. */
const SPINE_LINK_LENGTH = 0.15;
/** Each spine link weighs this share of a leg frame (the shipped files: 0.22–0.29). */
const SPINE_LINK_MASS = 0.25;
/**
 * The spine's cross-section against the leg frames': the insect's and the spider's exactly (the
 * other shipped files: 0.6–0.65 of the width, 0.6–0.71 of the height).
 */
const SPINE_WIDTH = 0.6;
const SPINE_HEIGHT = 5 / 7;
/** A single leg frame is this long for its width (the biped's torso: 0.22 m long, 0.34 m wide). */
const SINGLE_FRAME_LENGTH = 0.65;

// ---- The checks' numbers. ----

/**
 * The speed the checks take a design to walk at, m/s: the walking criteria's slow speed, which
 * the page's creatures (`?creature=`) and the designer's preview walk at.
 */
export const DESIGN_SPEED = 0.4;
/**
 * The derived gait's period for the creatures' legs (0.44 m), s: the quadruped preset's at 0.8 m/s,
 * between its 0.45 and 1.6 m/s speed keys' 0.30 and 0.46 s (public/presets/quadruped.json);
 * the gait scales it by √(L / L₀) (derived_gait.h). The quadruped's own preset at 0.4 m/s is
 * about the same, between its 0.15 and 0.45 m/s keys.
 */
const REFERENCE_PERIOD = 0.35;
/** Each foot is down this share of the cycle (kDerivedDutyFactor, derived_gait.h). */
const DUTY_FACTOR = 0.55;
/** Left and right feet at least this far apart, m: their roll (±0.4 rad) tips their edges towards each other. */
const FEET_APART = 0.01;
// The ranges below were measured with the native CLI (`gaitlab walk --creature FILE --speed V
// --seconds 30`), walking designs made from the four shipped creatures' settings with one
// setting changed, at 0.4 and 0.8 m/s on flat ground. Every design inside them walked 30 s at
// both speeds without a fall (some slower than asked at 0.8 m/s). Every design walks with the
// quadruped preset's gains and forces (derived_gait.h) or the biped's, unscaled, which is why the
// mass a leg carries matters.

/**
 * Body mass per leg, kg, for two leg frames or more. In range: 4.4–4.6 kg and 16.8–20.2 kg per
 * leg of every shipped plan (the shipped bodies carry 6.3–10); fallen: the insect at 3.3, the
 * spider at 3.5 (both at 0.8 m/s), the quadruped at 30, the dragon at 28 and the spider at 35.
 */
export const MASS_PER_LEG = { min: 4.5, max: 20 };
/**
 * The same for a single pair, which walks the biped's preset, tuned on its 59 kg (29.5 kg a
 * leg): at 20.5 kg a leg it walks, at 16.5 it turned in circles at 0.8 m/s, at 36–37 it fell.
 */
export const MASS_PER_LEG_SINGLE = { min: 20, max: 32 };
/**
 * A single leg frame's least moment of inertia about its pitch axis (side to side), kg·m²: the
 * biped's torso (36 kg, 0.56 m tall, 0.22 m long) has 1.09. A single pair's hips push against
 * its frame alone, with no spine or other frames to share the load: the biped and the bird with
 * their frame cut to 0.25 m tall (0.33, and 0.24 when also narrowed to 0.2 m) walked 30 s at 0.4
 * m/s; at 0.8 m/s the 0.24 fell at 1.7 and 2.4 s, the 0.33 walked; at 0.15 m tall (0.21 and
 * 0.12) both fell within 1.3 s. A random design's 25 kg frame 8 cm tall (0.05) tipped over in
 * its first 0.1 s.
 */
export const SINGLE_FRAME_INERTIA_MIN = 0.3;
/**
 * The legs' share of a leg frame with its legs (the shipped bodies' 0.19–0.39). The insect
 * walked from 0.08 to 0.7 at 0.4 m/s; at 0.05 it fell at 0.8 m/s, and from 0.55 up it ran 14 %
 * slow and more (0.7: 35 %). A light leg frame on heavy legs is swung about by them, a heavy one
 * on light legs pushes its feet out of place.
 */
export const LEG_SHARE_RANGE = { min: 0.1, max: 0.5 };
/**
 * Leg length, hip to ankle, m, for two leg frames or more (the creatures' 0.44). 0.32 and 0.7
 * walked on every plan; at 0.28 the quadruped fell at 0.8 m/s, at 0.24 the insect barely moved
 * (0.06 m/s for 0.8), at 0.8 the dragon fell and at 0.9 the insect.
 */
export const LEG_LENGTH = { min: 0.32, max: 0.7 };
/** The same for a single pair (the biped's 0.84): from 0.6 down it drifted 38° in 30 s at 0.4 m/s. */
export const LEG_LENGTH_SINGLE = { min: 0.7, max: 1.1 };
/**
 * Upper leg over lower leg. 0.5 and 2 walked; 0.4 (0.12 + 0.3 m) fell at 0.8 m/s (the insect),
 * 3 (0.3 + 0.1 m) fell too (the dragon). The controller's inverse kinematics is two-link: a
 * short segment leaves the knee little to do.
 */
export const SEGMENT_RATIO = { min: 0.5, max: 2 };
/**
 * A third segment's share of the leg, hip to ankle, at most. Measured with the native CLI (30 s at
 * 0.4 and 0.8 m/s, the tarsus held parallel to the thigh, gait/ik.h): the insect with tarsi of
 * 0.05, 0.1, 0.2 and 0.3 of its leg, the spider, dragon and quadruped at 0.25 and the biped at 0.25
 * walked at both speeds; longer ones were not tried.
 */
export const TARSUS_SHARE = 0.3;
/**
 * The least knee range that walks, rad (DEFAULT_DESIGN's 2.4 is the shipped files'), for two leg
 * frames or more and for a single pair. Measured as above on the insect (also with a third
 * segment), spider, dragon and quadruped: from 1.4 rad up every one walked as with 2.4 (the knee
 * does not reach its limit); at 1.1 every one fell at 0.8 m/s (and walked at 0.4), at
 * 0.8 and 0.5 at 0.4 m/s too: a knee that cannot fold cannot lift its foot clear in swing. The
 * biped, whose preset folds its swing knee further, fell at 1.4 at both speeds and walked from 1.6;
 * the bird walked from 1.4.
 */
export const KNEE_FLEXION_MIN = { frames: 1.4, single: 1.6 };
/**
 * The least hip swing that walks, rad (1.2 is the shipped files'). Measured as above: from 0.9
 * every body of two leg frames or more walked as with 1.2; at 0.7 the insect walked 0.39 m/s for
 * 0.8 and the spider 0.59, at 0.5 the dragon and the insect fell at 0.8 m/s, at 0.3 the
 * quadruped fell: a hip that cannot swing cannot take the steps the gait asks for. A single pair
 * walks the biped's preset, which reaches its hips' range: with a swing of 0.9 to 1.1 the bird ran
 * 0.97–1.28 m/s when asked for 0.8 (and drifted 21° at 1.1); from 1.2 to 1.5 it and the biped
 * walked within 1 %.
 */
export const HIP_SWING_MIN = { frames: 0.9, single: 1.2 };

// ---- Designs to files. ----

/** A problem with a design: the setting to change, and why. */
export interface DesignProblem {
  setting: keyof CreatureDesign;
  message: string;
}

/** A creature file from `design` and what is wrong with it (a file is made either way). */
export interface DesignResult {
  file: CreatureFile;
  problems: DesignProblem[];
}

/** Names by leg frame count, as the shipped files name theirs. */
const FRAME_NAMES: Record<number, string[]> = {
  1: [''],
  2: ['front', 'back'],
  3: ['front', 'middle', 'back'],
  4: ['first', 'second', 'third', 'fourth'],
};

/** A number as the file states it: no float noise (1e-6 m and kg are far below anything that matters). */
const tidy = (x: number) => Math.round(x * 1e6) / 1e6;

/** The leg's length, hip to ankle, m. */
export function legLength(design: CreatureDesign): number {
  return design.upperLength + design.lowerLength + design.tarsusLength;
}

/** A leg frame's half length along the body, m. */
function frameHalfLength(design: CreatureDesign): number {
  const halfWidth = design.bodyWidth / 2;
  // As long as it is wide (the insect's and the quadruped's frames), but no longer than a third
  // of the spacing, which leaves at least a third for the spine (the spider's 0.12 m long
  // frames 0.18 m apart).
  return design.pairs === 1 ? SINGLE_FRAME_LENGTH * halfWidth : Math.min(halfWidth, design.frameSpacing / 3);
}

/**
 * The fore-aft distance a foot sweeps under its hip while it stands, at DESIGN_SPEED, m: the
 * body moves speed × stance time over it, the stance time being the duty factor of the period.
 */
export function stanceSweep(design: CreatureDesign): number {
  const period = REFERENCE_PERIOD * Math.sqrt(legLength(design) / REFERENCE_FOOT.leg);
  return DESIGN_SPEED * period * DUTY_FACTOR;
}

const isColour = (s: unknown): s is string => typeof s === 'string' && /^#[0-9a-fA-F]{6}$/.test(s);

/** The knee of pair `k` of `pairs`. */
export function kneePoints(design: CreatureDesign, k: number): 'forward' | 'backward' {
  if (design.knees === 'forward' || design.pairs === 1) return 'forward';
  if (design.knees === 'backward') return 'backward';
  // mixed: the front half backward (the insect's first of three, the spider's first two of four).
  return k < Math.floor(design.pairs / 2) ? 'backward' : 'forward';
}

/** Everything wrong with `design`, each with the setting to change (empty: it can be built and walk). */
export function checkDesign(design: CreatureDesign): DesignProblem[] {
  const problems: DesignProblem[] = [];
  for (const [key, range] of Object.entries(SETTING_RANGES) as [NumericSetting, (typeof SETTING_RANGES)[NumericSetting]][]) {
    const value = design[key];
    if (typeof value !== 'number' || !Number.isFinite(value)) {
      problems.push({ setting: key, message: `${range.label}: expected a number, got ${JSON.stringify(value)}` });
    } else if (value < range.min || value > range.max) {
      problems.push({ setting: key, message: `${range.label}: ${value} is outside [${range.min}, ${range.max}]${range.unit ? ` ${range.unit}` : ''}` });
    }
  }
  if (Number.isFinite(design.pairs) && !Number.isInteger(design.pairs)) {
    problems.push({ setting: 'pairs', message: `leg pairs: ${design.pairs} is not a whole number` });
  }
  if (!(KNEE_CHOICES as readonly unknown[]).includes(design.knees)) {
    problems.push({ setting: 'knees', message: `knees: expected ${KNEE_CHOICES.join(', ')}, got ${JSON.stringify(design.knees)}` });
  }
  for (const key of ['bodyColour', 'spineColour', 'leftColour', 'rightColour'] as const) {
    if (!isColour(design[key])) problems.push({ setting: key, message: `${key}: expected a colour "#rrggbb", got ${JSON.stringify(design[key])}` });
  }
  // The relations below need every number to be one.
  if (problems.length > 0) return problems;

  // Neighbouring leg frames' legs would collide: a side's neighbouring legs are in opposite
  // groups (derived_gait.h), so as one foot ends its stance at the back of its sweep the other
  // lands at the front of its own; they pass within (spacing − sweep), which must leave a
  // foot's length between them.
  const { foot, scale } = footOf(design);
  const footLength = 2 * foot.halfExtents[2] * scale;
  if (design.pairs > 1) {
    const reach = stanceSweep(design) + footLength;
    if (design.frameSpacing < reach) {
      problems.push({
        setting: 'frameSpacing',
        message:
          `the legs of neighbouring leg frames would collide: at ${DESIGN_SPEED} m/s a foot sweeps ${fmt(stanceSweep(design))} m under its hip ` +
          `and is ${fmt(footLength)} m long, so the frames must be at least ${fmt(reach)} m apart (they are ${fmt(design.frameSpacing)} m)`,
      });
    }
  }
  // Feet under the body: a thigh's top must touch its leg frame's box, or the leg hangs beside
  // the body from nothing that is drawn.
  const thighHalf = design.legThickness / 2;
  const hipLimit = design.bodyWidth / 2 + thighHalf;
  if (design.hipSpacing > hipLimit) {
    problems.push({
      setting: 'hipSpacing',
      message: `the hips are outside the body: at most ${fmt(hipLimit)} m from the midline (half the body width plus half a leg's thickness), they are ${fmt(design.hipSpacing)} m`,
    });
  }
  // Left and right feet must not overlap.
  const footHalfWidth = foot.halfExtents[0] * scale;
  const hipLeast = Math.max(footHalfWidth, thighHalf) + FEET_APART / 2;
  if (design.hipSpacing < hipLeast) {
    problems.push({
      setting: 'hipSpacing',
      message: `the left and right legs would overlap: each hip must be at least ${fmt(hipLeast)} m from the midline (half a foot's or a leg's width and 5 mm), it is ${fmt(design.hipSpacing)} m`,
    });
  }
  // Leg frame against leg mass.
  if (design.legShare < LEG_SHARE_RANGE.min || design.legShare > LEG_SHARE_RANGE.max) {
    problems.push({
      setting: 'legShare',
      message:
        `leg mass share ${fmt(design.legShare)}: the legs must be ${LEG_SHARE_RANGE.min}–${LEG_SHARE_RANGE.max} of a leg frame with its legs ` +
        `(${design.legShare < LEG_SHARE_RANGE.min ? 'lighter legs are pushed out of place by the body' : 'heavier legs swing the body about'})`,
    });
  }
  const single = design.pairs === 1;
  const length = legLength(design);
  const lengths = single ? LEG_LENGTH_SINGLE : LEG_LENGTH;
  if (length < lengths.min || length > lengths.max) {
    problems.push({
      setting: length < lengths.min ? 'lowerLength' : 'upperLength',
      message:
        `legs of ${fmt(length)} m (hip to ankle): ${single ? "a single pair walks the biped's gait, which needs" : 'the gait needs'} ` +
        `${lengths.min}–${lengths.max} m (${length < lengths.min ? 'shorter legs barely move the body' : 'longer legs fall'})`,
    });
  }
  if (design.tarsusLength > TARSUS_SHARE * length) {
    problems.push({
      setting: 'tarsusLength',
      message: `a third segment of ${fmt(design.tarsusLength)} m is more than ${TARSUS_SHARE} of the leg (${fmt(length)} m); longer ones have not been measured to walk`,
    });
  }
  const kneeMin = single ? KNEE_FLEXION_MIN.single : KNEE_FLEXION_MIN.frames;
  if (design.kneeFlexion < kneeMin) {
    problems.push({
      setting: 'kneeFlexion',
      message: `knees that bend up to ${fmt(design.kneeFlexion)} rad: ${single ? 'a single pair\'s' : 'they'} must bend at least ${kneeMin} rad, or the swinging leg cannot fold to lift its foot clear`,
    });
  }
  const swingMin = single ? HIP_SWING_MIN.single : HIP_SWING_MIN.frames;
  if (design.hipSwing < swingMin) {
    problems.push({
      setting: 'hipSwing',
      message: `hips that swing up to ${fmt(design.hipSwing)} rad: ${single ? 'a single pair\'s' : 'they'} must swing at least ${swingMin} rad, or the legs cannot take the gait's steps`,
    });
  }
  const ratio = design.upperLength / design.lowerLength;
  if (ratio < SEGMENT_RATIO.min || ratio > SEGMENT_RATIO.max) {
    problems.push({
      setting: ratio < SEGMENT_RATIO.min ? 'upperLength' : 'lowerLength',
      message: `upper leg ${fmt(ratio)} times the lower: it must be ${SEGMENT_RATIO.min}–${SEGMENT_RATIO.max} times (a short segment leaves the knee too little to do)`,
    });
  }
  if (single) {
    const [w, h, l] = [design.bodyWidth, design.bodyHeight, 2 * frameHalfLength(design)];
    const pitch = (design.frameMass * (h * h + l * l)) / 12;
    if (pitch < SINGLE_FRAME_INERTIA_MIN) {
      problems.push({
        setting: 'bodyHeight',
        message:
          `a single leg frame of ${fmt(design.frameMass)} kg, ${fmt(h)} m tall and ${fmt(l)} m long is too easily tipped by its legs ` +
          `(moment of inertia ${pitch.toFixed(2)} kg·m², at least ${SINGLE_FRAME_INERTIA_MIN} needed; ${fmt(w)} m wide): make it taller, heavier or wider`,
      });
    }
  }
  // Total mass, as the mass each leg carries.
  const perLeg = totalMass(buildFile(design)) / (2 * design.pairs);
  const carry = single ? MASS_PER_LEG_SINGLE : MASS_PER_LEG;
  if (perLeg < carry.min || perLeg > carry.max) {
    problems.push({
      setting: 'frameMass',
      message:
        `the body weighs ${(perLeg * 2 * design.pairs).toFixed(1)} kg, ${perLeg.toFixed(1)} kg a leg: each leg must carry ${carry.min}–${carry.max} kg ` +
        `(${single ? "the biped's gait" : "the quadruped's gains"} ${perLeg < carry.min ? 'toss a lighter body about' : 'cannot hold a heavier one up'}; ` +
        `change the leg frame mass or the leg mass share)`,
    });
  }
  return problems;
}

const fmt = (x: number) => String(Math.round(x * 1000) / 1000);

/** The creature file of `design` (unchecked: see checkDesign), named `name`. */
export function buildFile(design: CreatureDesign, name = 'designed'): CreatureFile {
  const n = design.pairs;
  const names = FRAME_NAMES[n] ?? FRAME_NAMES[3];
  const { foot, scale } = footOf(design);
  const massOfLeg = (design.frameMass * design.legShare) / (1 - design.legShare) / 2;
  const halfWidth = design.bodyWidth / 2;
  const halfHeight = design.bodyHeight / 2;
  const halfLength = frameHalfLength(design);
  // The lower leg's part of LOWER_SHARE: all of it, or with a tarsus its share by length.
  const lowerShare = design.lowerLength / (design.lowerLength + design.tarsusLength);
  const legs = (k: number): LegPairSpec => ({
    name: names[k],
    hipSpacing: tidy(design.hipSpacing),
    hip: hipRange(design),
    knee: { points: kneePoints(design, k), flexion: tidy(design.kneeFlexion), hyperextension: KNEE_HYPEREXTENSION },
    ankle: { pitch: ANKLE_PITCH, roll: ANKLE_ROLL },
    upper: { length: tidy(design.upperLength), halfThickness: tidy(design.legThickness / 2), mass: tidy(UPPER_SHARE * massOfLeg) },
    lower: { length: tidy(design.lowerLength), halfThickness: tidy((LOWER_THICKNESS * design.legThickness) / 2), mass: tidy(lowerShare * LOWER_SHARE * massOfLeg) },
    ...(design.tarsusLength > 0
      ? {
          tarsus: {
            length: tidy(design.tarsusLength),
            halfThickness: tidy((TARSUS_THICKNESS * LOWER_THICKNESS * design.legThickness) / 2),
            mass: tidy((1 - lowerShare) * LOWER_SHARE * massOfLeg),
            hock: { flexion: tidy(design.kneeFlexion), hyperextension: KNEE_HYPEREXTENSION },
          },
        }
      : {}),
    foot: {
      halfExtents: foot.halfExtents.map((h) => tidy(h * scale)) as Triple,
      forward: tidy(foot.forward * scale),
      mass: tidy(FOOT_SHARE * massOfLeg),
      ankleAboveFoot: tidy(foot.ankleAboveFoot * scale),
    },
    colours: { left: design.leftColour, right: design.rightColour, foot: FOOT_COLOUR },
  });
  // Frames centred on the body's middle, front (+z) to back.
  const z = (k: number) => tidy(((n - 1) / 2 - k) * design.frameSpacing);
  const legFrames: LegFrameSpec[] = Array.from({ length: n }, (_, k) => ({
    name: names[k] === '' ? 'legframe' : `legframe.${names[k]}`,
    z: z(k),
    halfExtents: [tidy(halfWidth), tidy(halfHeight), tidy(halfLength)],
    mass: tidy(design.frameMass),
    aboveHips: tidy(halfHeight - HIPS_ABOVE_UNDERSIDE),
    colour: design.bodyColour,
    legs: legs(k),
  }));
  // A spine section spans the gap between two frames' boxes, in links of about SPINE_LINK_LENGTH.
  const spine = Array.from({ length: n - 1 }, (_, k) => {
    const from = tidy(z(k) - halfLength);
    const to = tidy(z(k + 1) + halfLength);
    return {
      from,
      to,
      links: Math.min(8, Math.max(1, Math.round((from - to) / SPINE_LINK_LENGTH))),
      halfWidth: tidy(SPINE_WIDTH * halfWidth),
      halfHeight: tidy(SPINE_HEIGHT * halfHeight),
      mass: tidy(SPINE_LINK_MASS * design.frameMass),
      limit: SPINE_LIMIT,
      colour: design.spineColour,
    };
  });
  return { format: CREATURE_FORMAT, version: CREATURE_FORMAT_VERSION, name, armature: ARMATURE, legFrames, spine };
}

/** The hip's range of `design`: the shipped range, its flexion limits scaled by the swing. */
function hipRange(design: CreatureDesign): { lower: Triple; upper: Triple } {
  const range = structuredClone(shippedHipRange(design.pairs));
  const scale = design.hipSwing / DEFAULT_DESIGN.hipSwing;
  range.lower[0] = tidy(range.lower[0] * scale);
  range.upper[0] = tidy(range.upper[0] * scale);
  return range;
}

/** The file of `design` and what is wrong with it. */
export function designCreature(design: CreatureDesign, name?: string): DesignResult {
  const problems = checkDesign(design);
  return { file: buildFile(design, name), problems };
}

/** Most draws randomDesign makes before it gives up (none of 20 seeds needs more than a few hundred). */
const MAX_DRAWS = 100_000;

/**
 * A random body within the designer's limits: every numeric setting drawn uniformly over its
 * slider's range (on the slider's steps), the knees at random, drawn again until the design passes
 * every check. The third leg segment is a fair coin first: none, or a length drawn the same way
 * over the slider's steps above 0 (drawn over the whole slider, 0 would come up once in 31 and
 * nearly every body would have legs of three segments). The same seed gives the same body. What
 * "random bodies" means where the learning benchmark (bench/learning.mjs) reports how many of
 * them learn to walk.
 */
export function randomDesign(seed: number): CreatureDesign {
  const next = mulberry32(seed);
  const onStep = (r: { min: number; max: number; step: number }, from: number) =>
    Number((from + Math.floor(next() * (Math.round((r.max - from) / r.step) + 1)) * r.step).toFixed(6));
  for (let draw = 0; draw < MAX_DRAWS; draw++) {
    const design: CreatureDesign = { ...DEFAULT_DESIGN };
    for (const [key, r] of Object.entries(SETTING_RANGES) as [NumericSetting, (typeof SETTING_RANGES)[NumericSetting]][]) {
      design[key] = key === 'tarsusLength' ? (next() < 0.5 ? 0 : onStep(r, r.min + r.step)) : onStep(r, r.min);
    }
    design.knees = KNEE_CHOICES[Math.floor(next() * KNEE_CHOICES.length)];
    if (checkDesign(design).length === 0) return design;
  }
  throw new Error(`no design passed the checks in ${MAX_DRAWS} draws (seed ${seed})`);
}

/**
 * The settings that describe a creature file best (the presets: public/creatures/NAME.json):
 * its first leg pair's legs, its frames' mean size, mass and hip spacing, the mean spacing of its
 * frames. A file whose frames are all alike (the insect, the spider) comes back the same but
 * for what the settings do not name; the dragon's frames of three sizes become three of their
 * mean. Throws on what is not a creature file.
 */
export function designFromFile(file: CreatureFile): CreatureDesign {
  const frames = file?.legFrames;
  if (!Array.isArray(frames) || frames.length < 1 || frames.length > MAX_LEG_FRAMES) {
    throw new Error('not a creature file: expected 1 to 4 leg frames');
  }
  const n = frames.length;
  const mean = (f: (frame: LegFrameSpec) => number) => frames.reduce((sum, frame) => sum + f(frame), 0) / n;
  const legs = frames[0].legs;
  const frameMass = mean((f) => f.mass);
  const legPairMass = mean((f) => 2 * legMass(f.legs));
  const points = frames.map((f) => f.legs.knee.points);
  // The hip's flexion range against the shipped one of its kind, as a swing (hipRange).
  const base = shippedHipRange(n);
  const swing = (legs.hip.upper[0] - legs.hip.lower[0]) / (base.upper[0] - base.lower[0]);
  return {
    pairs: n,
    upperLength: legs.upper.length,
    lowerLength: legs.lower.length,
    tarsusLength: legs.tarsus?.length ?? 0,
    legThickness: 2 * legs.upper.halfThickness,
    frameSpacing: n > 1 ? (frames[0].z - frames[n - 1].z) / (n - 1) : DEFAULT_DESIGN.frameSpacing,
    bodyWidth: 2 * mean((f) => f.halfExtents[0]),
    bodyHeight: 2 * mean((f) => f.halfExtents[1]),
    frameMass,
    legShare: legPairMass / (frameMass + legPairMass),
    hipSpacing: mean((f) => f.legs.hipSpacing),
    knees: points.every((p) => p === 'forward') ? 'forward' : points.every((p) => p === 'backward') ? 'backward' : 'mixed',
    kneeFlexion: legs.knee.flexion,
    hipSwing: Number((swing * DEFAULT_DESIGN.hipSwing).toFixed(6)),
    bodyColour: frames[0].colour,
    spineColour: file.spine[0]?.colour ?? DEFAULT_DESIGN.spineColour,
    leftColour: legs.colours.left,
    rightColour: legs.colours.right,
  };
}
