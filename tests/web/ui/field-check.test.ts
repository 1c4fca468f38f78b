// Reading a number field (web/src/ui/field-check.ts): only a number in range is a value.
import { describe, expect, it } from 'vitest';
import { readNumberField } from '../../../web/src/ui/field-check';

describe('readNumberField', () => {
  it('takes a number in range', () => {
    expect(readNumberField(' 0.25 ', 0, 1)).toEqual({ value: 0.25 });
    expect(readNumberField('1', 0, 1)).toEqual({ value: 1 });
  });

  it('refuses an empty field instead of reading it as 0', () => {
    expect(readNumberField('', 0, 1)).toEqual({ error: 'a number is needed' });
    expect(readNumberField('   ', -1, 1)).toEqual({ error: 'a number is needed' });
  });

  it('refuses what is out of range or not a number, saying the range', () => {
    expect(readNumberField('5', 0.1, 0.3)).toEqual({ error: '5 is outside [0.1, 0.3]' });
    expect(readNumberField('abc', 0, 1)).toEqual({ error: "'abc' is not a number" });
  });
});
