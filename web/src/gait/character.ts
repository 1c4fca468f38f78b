// The kinds of character: the page's one list of them. Their order is the module's numbering
// (GL_KIND_BIPED = 0, GL_KIND_QUADRUPED = 1 in native/src/api/c_api.h, gait::Character in
// native/src/gait/schema.h; the exported schema's morphologies carry the same number as "kind"),
// so the number of a type is its index here.
export const CHARACTER_TYPES = ['biped', 'quadruped'] as const;
export type CharacterType = (typeof CHARACTER_TYPES)[number];

export function isCharacterType(value: unknown): value is CharacterType {
  return (CHARACTER_TYPES as readonly unknown[]).includes(value);
}

/** The module's kind number of a character type (gl_sim_spawn, gl_sim_set_params...). */
export function kindOf(type: CharacterType): number {
  return CHARACTER_TYPES.indexOf(type);
}

/** The character type of a module kind number, or null for a kind that is not a character (a box). */
export function typeOfKind(kind: number): CharacterType | null {
  return CHARACTER_TYPES[kind] ?? null;
}
