// Honest number fields: a field shows the value that is applied, and a value that cannot be
// applied (empty, not a number, outside the field's range) is refused with a message beside the
// field and changes nothing. lil-gui's own number fields clamp silently (5 typed into a field
// whose most is 0.3 applies 0.3 and keeps showing 5) and read an empty field as nothing at all;
// the gait editors' knot fields did the same by hand.
import type { Controller } from 'lil-gui';

/** The value typed, or why it is refused. */
export type FieldReading = { value: number } | { error: string };

/** Reads a number field's text against its range [min, max]. */
export function readNumberField(text: string, min: number, max: number): FieldReading {
  const trimmed = text.trim();
  if (trimmed === '') return { error: 'a number is needed' };
  const value = Number(trimmed);
  if (!Number.isFinite(value)) return { error: `'${trimmed}' is not a number` };
  if (value < min || value > max) return { error: `${trimmed} is outside [${min}, ${max}]` };
  return { value };
}

/** The message element beside `field` (made on first use). */
function messageFor(field: HTMLElement): HTMLElement {
  const next = field.nextElementSibling;
  if (next instanceof HTMLElement && next.classList.contains('field-message')) return next;
  const message = document.createElement('div');
  message.className = 'field-message';
  message.setAttribute('role', 'alert');
  field.after(message);
  return message;
}

/** Shows (or with null clears) a refusal beside `field`. */
export function showFieldMessage(field: HTMLElement, text: string | null): void {
  if (text === null) {
    const next = field.nextElementSibling;
    if (next instanceof HTMLElement && next.classList.contains('field-message')) next.remove();
    field.classList.remove('field-refused');
    return;
  }
  messageFor(field).textContent = text;
  field.classList.add('field-refused');
}

/**
 * Makes a lil-gui number controller honest: what is typed is applied only when it is a number in
 * [min, max]; otherwise a message beside the field says why, nothing changes, and the field shows
 * the applied value again when it loses focus (lil-gui's blur redraws it).
 */
export function guardNumberController(
  controller: Controller,
  min: number | (() => number),
  max: number | (() => number),
  label: string,
): void {
  const bound = (b: number | (() => number)) => (typeof b === 'function' ? b() : b);
  const input = controller.domElement.querySelector('input');
  if (!input) return;
  // Capture: before lil-gui's own 'input' listener on the same element, which would clamp.
  input.addEventListener(
    'input',
    (event) => {
      const reading = readNumberField(input.value, bound(min), bound(max));
      if ('error' in reading) {
        event.stopImmediatePropagation();
        showFieldMessage(controller.domElement, `${label}: ${reading.error}; not applied (still ${Number(controller.getValue())})`);
      } else {
        showFieldMessage(controller.domElement, null);
      }
    },
    { capture: true },
  );
  input.addEventListener('blur', () => {
    // The field shows the applied value again; a refusal's message stays until the next edit.
    input.value = String(controller.getValue());
  });
}
