// The page's copy of native/src/api/limits.h: the limits on what a user, a link or a file may
// send the simulation (the header says why each figure is what it is; README, "Limits").
// tests/web/sim/limits.test.ts reads the header and compares, so the two cannot drift apart.
// The module checks everything again where it enters (the C ABI): these let the page refuse a
// link, a file or a message before it reaches the worker, with the same words.

/** Gait files, patches, link payloads: JSON text. */
export const MAX_JSON_BYTES = 256 * 1024;
export const MAX_JSON_DEPTH = 16;
export const MAX_JSON_STRING = 16 * 1024;
export const MAX_JSON_ARRAY = 4096;

/** Numbers a scene command carries. */
export const MAX_GOAL_SPEED = 5.0;
export const MAX_GOAL_TURN = 3.0;
export const MAX_COORDINATE = 1000.0;
export const MAX_HEADING = 1000.0;
export const MAX_THROW_SPEED = 100.0;
export const MIN_AIM_SPEED = 1.0;
export const MIN_THROW_HALF = 0.03;
export const MAX_THROW_HALF = 0.5;
export const MAX_DRAG_LOCAL = 10.0;
export const MAX_AUTO_RESET = 3600.0;
export const MAX_STEPS_PER_CALL = 12000;

/** What a simulation holds. */
export const MAX_BOXES = 64;

/**
 * Whether `text` is JSON within the limits above, checked as native/src/gait/params_io.cpp's
 * checkJsonText does: one pass, one counter per open level, no recursion (JSON.parse would build
 * a 100,000-deep object that JSON.stringify then overflows the stack on). Only the limits are
 * checked here, not the syntax (JSON.parse or the module does that). Returns the problem in
 * words, or null.
 */
export function jsonLimitProblem(text: string): string | null {
  const bytes = new TextEncoder().encode(text).length;
  if (bytes > MAX_JSON_BYTES) return `the text is ${bytes} bytes long; at most ${MAX_JSON_BYTES} are accepted`;
  const commas: number[] = []; // commas so far in each open array or object: its elements - 1
  let inString = false;
  let stringStart = 0;
  for (let i = 0; i < text.length; i++) {
    const c = text.charCodeAt(i);
    if (inString) {
      if (c === 0x5c /* \ */) i++;
      else if (c === 0x22 /* " */) {
        inString = false;
        // UTF-16 units bound the UTF-8 bytes from below by a third: measure only when it matters.
        if (i - stringStart > MAX_JSON_STRING / 3 && new TextEncoder().encode(text.slice(stringStart, i)).length > MAX_JSON_STRING) {
          return `a string is longer than ${MAX_JSON_STRING} bytes`;
        }
      }
      continue;
    }
    if (c === 0x22) {
      inString = true;
      stringStart = i + 1;
    } else if (c === 0x5b /* [ */ || c === 0x7b /* { */) {
      if (commas.length >= MAX_JSON_DEPTH) return `nested deeper than ${MAX_JSON_DEPTH} levels`;
      commas.push(0);
    } else if (c === 0x5d /* ] */ || c === 0x7d /* } */) {
      commas.pop();
    } else if (c === 0x2c /* , */ && commas.length > 0) {
      if (++commas[commas.length - 1] >= MAX_JSON_ARRAY) return `an array or object has more than ${MAX_JSON_ARRAY} elements`;
    }
  }
  return null;
}
