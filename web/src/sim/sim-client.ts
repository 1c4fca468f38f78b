// Main-thread side of the sim worker: starts it, sends typed commands, and keeps the newest
// statistics and render-buffer reader. It never steps anything itself (docs/design.md, data flow).
import { errorMessage, type CharacterType, type SceneCommand, type SimCommand, type SimEvent, type SimOptions, type SimStats } from './protocol';
import type { ParamPatch, SpeedKeys } from '../share/gait-file';
import { RenderBufferReader } from './render-buffer';
import type { TerrainGrid } from './terrain-grid';

export interface SimClientEvents {
  /** A new scene's render buffer is ready to be drawn (after start and after every reset). */
  onScene?: (
    reader: RenderBufferReader,
    info: Pick<Extract<SimEvent, { type: 'ready' }>, 'generation' | 'threads' | 'version' | 'schema' | 'optimizerSchema' | 'speedRanges'>,
  ) => void;
  /** The simulation refused a command (the message says why). */
  onCommandError?: (message: string) => void;
  /** The current render buffer is about to be freed: stop reading it, synchronously. */
  onRelease?: () => void;
  onStats?: (stats: SimStats) => void;
  /** The ground changed (or a new scene has one): draw it from these samples. */
  onTerrain?: (grid: TerrainGrid, generation: number) => void;
  onError?: (message: string) => void;
}

export class SimClient {
  private readonly worker: Worker;
  private readonly events: SimClientEvents;
  /** The render buffer being drawn, or null before the first scene. */
  reader: RenderBufferReader | null = null;
  stats: SimStats | null = null;
  error: string | null = null;

  constructor(options: SimOptions, events: SimClientEvents) {
    this.events = events;
    // Vite recognises this pattern and bundles the worker as a module worker of its own.
    this.worker = new Worker(new URL('./sim.worker.ts', import.meta.url), { type: 'module', name: 'gaitlab-sim' });
    this.worker.onmessage = (event: MessageEvent<SimEvent>) => this.receive(event.data);
    this.worker.onerror = (event) => {
      event.preventDefault();
      this.fail(event.message || 'the sim worker failed to start (see the browser console)');
    };
    this.worker.onmessageerror = () => this.fail('a message from the sim worker could not be read');
    this.send({ type: 'init', options });
  }

  send(command: SimCommand): void {
    this.worker.postMessage(command);
  }

  private nextRequest = 1;
  private readonly requests = new Map<number, { resolve: (json: string) => void; reject: (error: Error) => void }>();

  /** Character `id`'s gait parameters (a gait file's JSON), from the worker. */
  getParams(id: number): Promise<string> {
    return this.request((request) => ({ type: 'getParams', request, id }));
  }

  /** A type's preset gait (a gait file's JSON). */
  getPreset(character: CharacterType): Promise<string> {
    return this.request((request) => ({ type: 'getPreset', request, character }));
  }

  /** A gait file's JSON normalised by the module; rejects with the module's "FIELD: WHAT". */
  normalize(json: string): Promise<string> {
    return this.request((request) => ({ type: 'normalize', request, json }));
  }

  /**
   * An edit of character `id`'s parameters (or of every character of the type): resolves when
   * the simulation accepted it, rejects with its refusal (the command and the parameter named).
   */
  patchParams(id: number | 'all', character: CharacterType, patch: ParamPatch, speedKeys?: SpeedKeys): Promise<ParamPatch> {
    const command = { type: 'patchParams' as const, id, character, patch, ...(speedKeys ? { speedKeys } : {}) };
    return this.request((request) => ({ type: 'scene', command: { ...command, request } })).then(
      (accepted) => JSON.parse(accepted) as ParamPatch,
    );
  }

  /**
   * A creature (the spawnCreature command, its request filled in): resolves with the new
   * character's id, rejects with the refusal (the file's field named, or the page full).
   */
  spawnCreature(spawn: Omit<Extract<SceneCommand, { type: 'spawnCreature' }>, 'type' | 'request'>): Promise<number> {
    return this.request((request) => ({ type: 'scene', command: { type: 'spawnCreature', ...spawn, request } })).then(Number);
  }

  private request(make: (request: number) => SimCommand): Promise<string> {
    const request = this.nextRequest++;
    return new Promise((resolve, reject) => {
      this.requests.set(request, { resolve, reject });
      this.send(make(request));
    });
  }

  pause(): void {
    this.send({ type: 'pause' });
  }

  resume(): void {
    this.send({ type: 'resume' });
  }

  reset(): void {
    this.send({ type: 'reset' });
  }

  private receive(event: SimEvent): void {
    switch (event.type) {
      case 'ready':
        try {
          this.reader = new RenderBufferReader(event.memory, event.header);
        } catch (error) {
          this.fail(errorMessage(error));
          return;
        }
        this.events.onScene?.(this.reader, event);
        return;
      case 'release':
        // After this returns nothing on this thread reads the old buffer (one thread, no awaits).
        this.reader = null;
        this.events.onRelease?.();
        this.send({ type: 'released', generation: event.generation });
        return;
      case 'stats':
        this.stats = event;
        this.events.onStats?.(event);
        return;
      case 'error':
        this.fail(event.message);
        return;
      case 'params': {
        const pending = this.requests.get(event.request);
        this.requests.delete(event.request);
        if (!pending) return;
        if (event.json !== null) pending.resolve(event.json);
        else pending.reject(new Error(event.error ?? 'no parameters'));
        return;
      }
      case 'patched': {
        const pending = this.requests.get(event.request);
        this.requests.delete(event.request);
        if (!pending) return;
        if (event.accepted !== null) pending.resolve(JSON.stringify(event.accepted));
        else pending.reject(new Error(event.error ?? 'the edit was refused'));
        return;
      }
      case 'spawned': {
        const pending = this.requests.get(event.request);
        this.requests.delete(event.request);
        if (!pending) return;
        if (event.id !== null) pending.resolve(String(event.id));
        else pending.reject(new Error(event.error ?? 'the creature was refused'));
        return;
      }
      case 'terrain':
        this.events.onTerrain?.(event.grid, event.generation);
        return;
      case 'commandError':
        this.events.onCommandError?.(event.message);
        return;
      default: {
        const unknown: never = event;
        this.fail(`unknown message from the sim worker: ${JSON.stringify(unknown)}`);
      }
    }
  }

  private fail(message: string): void {
    this.error = message;
    this.events.onError?.(message);
  }
}
