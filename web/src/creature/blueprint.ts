// The creature designer's blueprint: a side view and a top view of a design, drawn from the
// creature file it makes (design.ts, buildFile), with handles that are dragged to change the
// settings they stand for: a leg's segments by their joints, the body's length by its last leg
// frame, its height by its top, the hips' spacing and the body's width in the top view. No DOM:
// the designer's canvas (ui/design-blueprint.ts) draws it and moves the handles, and
// tests/web/creature/blueprint.test.ts tests it.
//
// Both views are in metres, with the front leg frame's hips at the origin: the side view looks at
// the body's left (x forward along the body, y up), the top view from above (x to the body's
// right, y forward). What a drag changes is measured from a point the drag does not move (the
// hips for the thigh, the knee for the lower leg, the front frame for the body's length), so a
// handle stays under the pointer, or on a circle through it where a leg's pose bends to its new
// lengths.
import { type CreatureDesign, kneePoints, type NumericSetting, SETTING_RANGES, buildFile } from './design';
import type { CreatureFile } from './creature-file';

export interface Point {
  x: number;
  y: number;
}

/** An axis-aligned rectangle, by centre and half sizes, m. */
export interface Box {
  centre: Point;
  half: Point;
  colour: string;
}

/** The handles, by what they stand for. */
export const HANDLES = ['knee', 'hock', 'ankle', 'frame', 'top', 'hip', 'side'] as const;
export type HandleName = (typeof HANDLES)[number];

export interface Handle {
  name: HandleName;
  view: 'side' | 'top';
  at: Point;
  /** The setting the handle changes. */
  setting: NumericSetting;
  /** What a person is told the handle does. */
  label: string;
}

/** A leg as drawn: its joints from the hip down, and its foot. */
export interface DrawnLeg {
  joints: Point[];
  foot: Box;
  colour: string;
}

export interface View {
  boxes: Box[];
  legs: DrawnLeg[];
  handles: Handle[];
  /** Height of the ground, m (the side view's; the top view has none). */
  ground: number | null;
}

export interface Blueprint {
  side: View;
  top: View;
}

/**
 * The standing pose the side view draws: the thigh (and a tarsus, parallel to it as the
 * controller holds it, gait/ik.h) this far from vertical towards where the knee points, the
 * lower leg back under the hip. Enough to show which way each knee bends.
 */
const THIGH_TILT = (20 * Math.PI) / 180;

const add = (a: Point, b: Point, s = 1): Point => ({ x: a.x + s * b.x, y: a.y + s * b.y });
const distance = (a: Point, b: Point) => Math.hypot(a.x - b.x, a.y - b.y);

/**
 * A leg's joints standing, from its hip: hip, knee, (hock,) ankle. The ankle is straight below
 * the hip: the thigh and tarsus lean THIGH_TILT one way, the lower leg as far back as makes up
 * for them (or straight down, for legs whose lower leg is too short to: the checks refuse those).
 */
function legJoints(hip: Point, upper: number, lower: number, tarsus: number, forward: boolean): Point[] {
  const s = forward ? 1 : -1;
  const thigh = { x: s * Math.sin(THIGH_TILT), y: -Math.cos(THIGH_TILT) };
  const back = Math.asin(Math.min(1, ((upper + tarsus) * Math.sin(THIGH_TILT)) / lower));
  const shin = { x: -s * Math.sin(back), y: -Math.cos(back) };
  const knee = add(hip, thigh, upper);
  const below = add(knee, shin, lower);
  return tarsus > 0 ? [hip, knee, below, add(below, thigh, tarsus)] : [hip, knee, below];
}

/** The blueprint of `design`. */
export function blueprint(design: CreatureDesign): Blueprint {
  const file: CreatureFile = buildFile(design);
  const frames = file.legFrames;
  const front = frames[0].z;
  const legs = frames[0].legs;
  const tarsus = legs.tarsus?.length ?? 0;
  const foot = legs.foot;
  // From the ankle down: the foot's pivot above its sole, and the sole's thickness.
  const groundBelowAnkle = foot.ankleAboveFoot + 2 * foot.halfExtents[1];

  const side: View = { boxes: [], legs: [], handles: [], ground: null };
  for (const [k, frame] of frames.entries()) {
    const x = frame.z - front;
    side.boxes.push({ centre: { x, y: frame.aboveHips }, half: { x: frame.halfExtents[2], y: frame.halfExtents[1] }, colour: frame.colour });
    const joints = legJoints({ x, y: 0 }, frame.legs.upper.length, frame.legs.lower.length, frame.legs.tarsus?.length ?? 0, kneePoints(design, k) === 'forward');
    const ankle = joints[joints.length - 1];
    side.legs.push({
      joints,
      foot: {
        centre: { x: ankle.x + foot.forward, y: ankle.y - foot.ankleAboveFoot - foot.halfExtents[1] },
        half: { x: foot.halfExtents[2], y: foot.halfExtents[1] },
        colour: legs.colours.foot,
      },
      colour: legs.colours.left,
    });
  }
  for (const section of file.spine) {
    side.boxes.push({
      centre: { x: (section.from + section.to) / 2 - front, y: frames[0].aboveHips },
      half: { x: Math.abs(section.from - section.to) / 2, y: section.halfHeight },
      colour: section.colour,
    });
  }
  const first = side.legs[0].joints;
  side.ground = first[first.length - 1].y - groundBelowAnkle;
  side.handles.push({ name: 'knee', view: 'side', at: first[1], setting: 'upperLength', label: 'drag the knee: the upper leg\'s length' });
  if (tarsus > 0) {
    side.handles.push({ name: 'hock', view: 'side', at: first[2], setting: 'lowerLength', label: 'drag the hock: the lower leg\'s length' });
    side.handles.push({ name: 'ankle', view: 'side', at: first[3], setting: 'tarsusLength', label: 'drag the ankle: the third segment\'s length' });
  } else {
    side.handles.push({ name: 'ankle', view: 'side', at: first[2], setting: 'lowerLength', label: 'drag the ankle: the lower leg\'s length' });
  }
  const top0 = side.boxes[0];
  side.handles.push({ name: 'top', view: 'side', at: { x: 0, y: top0.centre.y + top0.half.y }, setting: 'bodyHeight', label: 'drag the top: the body\'s height' });
  if (frames.length > 1) {
    const last = frames[frames.length - 1];
    side.handles.push({ name: 'frame', view: 'side', at: { x: last.z - front, y: last.aboveHips }, setting: 'frameSpacing', label: 'drag the last leg frame: the body\'s length' });
  }

  // From above: x to the right, y forward (the front frame at 0).
  const top: View = { boxes: [], legs: [], handles: [], ground: null };
  for (const frame of frames) {
    const y = frame.z - front;
    top.boxes.push({ centre: { x: 0, y }, half: { x: frame.halfExtents[0], y: frame.halfExtents[2] }, colour: frame.colour });
    for (const side of [-1, 1]) {
      const hip = { x: side * frame.legs.hipSpacing, y };
      top.legs.push({
        joints: [hip],
        foot: { centre: { x: hip.x, y: y + foot.forward }, half: { x: foot.halfExtents[0], y: foot.halfExtents[2] }, colour: legs.colours.foot },
        colour: side < 0 ? legs.colours.left : legs.colours.right,
      });
    }
  }
  for (const section of file.spine) {
    top.boxes.push({
      centre: { x: 0, y: (section.from + section.to) / 2 - front },
      half: { x: section.halfWidth, y: Math.abs(section.from - section.to) / 2 },
      colour: section.colour,
    });
  }
  top.handles.push({ name: 'hip', view: 'top', at: { x: legs.hipSpacing, y: 0 }, setting: 'hipSpacing', label: 'drag the hip: how far apart the legs are' });
  top.handles.push({ name: 'side', view: 'top', at: { x: frames[0].halfExtents[0], y: -frames[0].halfExtents[2] }, setting: 'bodyWidth', label: 'drag the side: the body\'s width' });
  return { side, top };
}

/** `value` on its setting's slider: the nearest step, within the range. */
export function onSlider(setting: NumericSetting, value: number): number {
  const r = SETTING_RANGES[setting];
  const stepped = r.min + Math.round((value - r.min) / r.step) * r.step;
  return Number(Math.min(r.max, Math.max(r.min, stepped)).toFixed(6));
}

/**
 * The change dragging handle `name` of `design` to `point` (in its view, m) makes: the one
 * setting it stands for, on its slider's steps and within its range. A third segment's handle
 * of a leg without one does nothing.
 */
export function dragTo(design: CreatureDesign, name: HandleName, point: Point): Partial<CreatureDesign> {
  const view = blueprint(design);
  const handle = [...view.side.handles, ...view.top.handles].find((h) => h.name === name);
  if (!handle) return {};
  const joints = view.side.legs[0].joints;
  let value: number;
  switch (name) {
    case 'knee':
      value = distance(point, joints[0]);
      break;
    case 'hock':
      value = distance(point, joints[1]);
      break;
    case 'ankle':
      value = distance(point, joints[joints.length - 2]);
      break;
    case 'top':
      // The frame's top is its height less the hips' fixed height above its underside.
      value = design.bodyHeight + point.y - handle.at.y;
      break;
    case 'frame':
      value = -point.x / (design.pairs - 1);
      break;
    case 'hip':
      value = point.x;
      break;
    case 'side':
      value = 2 * point.x;
      break;
  }
  return { [handle.setting]: onSlider(handle.setting, value) };
}
