// The kinds of character: the page's one list of them (gait::Character in
// native/src/gait/schema.h). A kind is a layout of legs, a pair on each of one to four leg frames:
// the biped, the quadruped, and the six- and eight-legged kinds, whose shipped bodies are the
// insect and the spider (public/creatures/). The module numbers them GL_KIND_BIPED 0,
// GL_KIND_QUADRUPED 1, GL_KIND_HEXAPOD 4 and GL_KIND_OCTOPOD 5 (native/src/api/c_api.h: 2 is the
// box, 3 the alternating layout), and the exported schema's morphologies carry the same number as
// "kind".
export const CHARACTER_TYPES = ['biped', 'quadruped', 'hexapod', 'octopod'] as const;
export type CharacterType = (typeof CHARACTER_TYPES)[number];

/** The module's kind number of each character type (GL_KIND_*). */
export const KIND_NUMBERS: Readonly<Record<CharacterType, number>> = { biped: 0, quadruped: 1, hexapod: 4, octopod: 5 };

export function isCharacterType(value: unknown): value is CharacterType {
  return (CHARACTER_TYPES as readonly unknown[]).includes(value);
}

/** The module's kind number of a character type (gl_sim_spawn, gl_sim_set_params...). */
export function kindOf(type: CharacterType): number {
  return KIND_NUMBERS[type];
}

/** The character type of a module kind number, or null for a kind that is not a character (a box). */
export function typeOfKind(kind: number): CharacterType | null {
  return CHARACTER_TYPES.find((t) => KIND_NUMBERS[t] === kind) ?? null;
}

/** The kind a body of `legFrames` leg frames is (one pair of legs on each), or null for none. */
export function typeOfLegFrames(legFrames: number): CharacterType | null {
  return CHARACTER_TYPES[legFrames - 1] ?? null;
}
