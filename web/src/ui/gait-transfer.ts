// How a gait leaves and enters the page: a share link (web/src/share/link.ts) copied to the
// clipboard, a JSON file exported or imported, a gait file shipped beside the page. Shared by the
// gait editors and the optimize panel.
//
// Whatever comes in is judged by the module alone: its text goes to the sim worker, which asks
// gl_gait_normalize, and comes back normalised (current schema version, every parameter) or
// refused with the module's "FIELD: WHAT", which the page shows as it is.
import { GaitError, type GaitFile } from '../share/gait-file';
import { decodeCreatureHash, decodeGaitHash, encodeGaitHash, hasCreature, hasGait } from '../share/link';
import { MAX_JSON_BYTES } from '../sim/limits';

/** The sim worker's normaliser: the module's answer for a gait file's text. */
export type NormalizeJson = (json: string) => Promise<string>;

export class GaitTransfer {
  constructor(private readonly normalizeJson: NormalizeJson) {}

  /** A gait file's text, validated and normalised by the module; rejects with its refusal. */
  async normalize(json: string): Promise<GaitFile> {
    return JSON.parse(await this.normalizeJson(json)) as GaitFile;
  }

  /** A link to this page that carries `gait`, and the body of `creature` (a creature file's text) if given. */
  async shareUrl(gait: GaitFile, creature?: string): Promise<string> {
    return `${location.origin}${location.pathname}${location.search}${await encodeGaitHash(gait, creature)}`;
  }

  /**
   * Makes `gait`'s link and copies it to the clipboard if the browser lets the page (an insecure
   * origin or a headless browser does not; the link is returned either way, to show).
   */
  async share(gait: GaitFile, creature?: string): Promise<{ url: string; copied: boolean; message: string }> {
    const url = await this.shareUrl(gait, creature);
    let copied = false;
    try {
      await navigator.clipboard.writeText(url);
      copied = true;
    } catch {
      // No clipboard permission: the caller shows the link.
    }
    return { url, copied, message: `${copied ? 'Link copied' : 'Link ready (copy it from the page)'}: ${url.length} characters.` };
  }

  /** Whether the page's address carries a gait. */
  linkInPage(): boolean {
    return hasGait(location.hash);
  }

  /** Whether the page's address carries a creature's body (its gait then is that creature's). */
  creatureInPage(): boolean {
    return hasCreature(location.hash);
  }

  /** The creature file's text the page's address carries; throws a GaitError for a bad link. */
  readCreatureLink(): Promise<string> {
    return decodeCreatureHash(location.hash);
  }

  /** The gait the page's address carries; throws a GaitError (the module's refusal as problem 'refused'). */
  readLink(): Promise<GaitFile> {
    return decodeGaitHash(location.hash, (json) => this.normalize(json));
  }

  /** Downloads `gait` as a JSON file, with where it came from in "meta". */
  exportFile(gait: GaitFile): void {
    const file: GaitFile = { ...gait, meta: { ...(gait.meta ?? {}), exportedBy: 'gaitlab demo', exportedAt: new Date().toISOString() } };
    const blob = new Blob([`${JSON.stringify(file, null, 2)}\n`], { type: 'application/json' });
    const a = document.createElement('a');
    a.href = URL.createObjectURL(blob);
    a.download = `${gait.character}-gait.json`;
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  }

  /**
   * Asks for a JSON file and reads it through the module. `done` gets the gait and the file's
   * name, or the file's name and the reason it was refused (the module's "FIELD: WHAT").
   */
  importFile(done: (result: { name: string; gait: GaitFile } | { name: string; problem: string }) => void): void {
    const input = document.createElement('input');
    input.type = 'file';
    input.accept = 'application/json,.json';
    input.addEventListener('change', async () => {
      const file = input.files?.[0];
      if (!file) return;
      // Not read at all past the most a gait file may have (a 50 MB file would be read whole,
      // copied to the worker and into the module only to be refused there).
      if (file.size > MAX_JSON_BYTES) {
        done({ name: file.name, problem: `the file is ${file.size} bytes long; a gait file has at most ${MAX_JSON_BYTES}` });
        return;
      }
      try {
        done({ name: file.name, gait: await this.normalize(await file.text()) });
      } catch (error) {
        done({ name: file.name, problem: error instanceof GaitError || error instanceof Error ? error.message : String(error) });
      }
    });
    // Tests find the input this way (a file chooser needs a user gesture otherwise).
    input.dataset.testid = 'import-gait';
    input.click();
  }

  /** A gait file shipped beside the page (public/), read through the module like any gait from outside. */
  async fromServer(path: string): Promise<GaitFile> {
    const response = await fetch(new URL(path, document.baseURI));
    if (!response.ok) throw new Error(`${path}: HTTP ${response.status}`);
    return this.normalize(await response.text());
  }
}
