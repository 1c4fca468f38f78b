// The demo page: a sim worker simulates a crowd in real time; this main thread draws it, reading
// the newest transforms out of shared WASM memory each animation frame (README.md, architecture),
// and turns clicks, drags, keys and the control panel into commands for the worker.
import './style.css';
import * as THREE from 'three';
import { CrowdMesh } from './render/crowd-mesh';
import { PointerInteraction, SelectionRing } from './render/pointer';
import { Stage } from './render/stage';
import {
  defaultThreads,
  errorMessage,
  MAX_CHARACTERS,
  simOptionsFromQuery,
  type CharacterStatus,
  type SceneCommand,
  type TimeScale,
} from './sim/protocol';
import { SimClient } from './sim/sim-client';
import { groundHeight, isTerrainKind, type TerrainKind } from './sim/terrain-grid';
import { CHARACTER_TYPES, typeOfLegFrames, type CharacterType } from './gait/character';
import { ControlPanel, MAX_TURN_DEGREES, speedValue, type SteerTarget } from './ui/control-panel';
import { CreatureDesigner } from './ui/creature-designer';
import { GaitEditors } from './ui/gait-editors';
import { GaitTransfer } from './ui/gait-transfer';
import { LEARNER_COLOUR, OptimizePanel } from './ui/optimize-panel';
import type { OptimizerSchema } from './optimize/options';
import { Overlay } from './ui/overlay';
import { RateMeter } from './ui/rate-meter';
import { installTestHook } from './test-hook';
import { isolationMode, reloadWhenControlled } from './isolation';

const canvas = document.querySelector<HTMLCanvasElement>('#scene');
if (!canvas) throw new Error('index.html has no <canvas id="scene">');

const overlay = new Overlay(document.body);
/** Phones: the layout of style.css's `max-width: 480px` (drawer, one-line heads-up, bottom sheet). */
const phone = window.matchMedia('(max-width: 480px)');
let client: SimClient | null = null;
/** Mirrors of the worker's reports: the UI follows what the worker confirms, not the clicks. */
const state = {
  threads: 0,
  ready: false,
  error: null as string | null,
  paused: false,
  timeScale: 1 as TimeScale,
  lastStats: 0,
  drawCalls: 0,
  characters: [] as CharacterStatus[],
  selected: null as number | null,
  /** The camera follows the selected character (on by default; the panel and F switch it). */
  follow: true,
  /** Arena wandering as the worker last reported it. */
  wander: { on: true, arenaRadius: 12 },
  terrain: 'flat' as TerrainKind,
};
/** Without statistics from the worker for this long, it is stuck (it reports 4 times a second). */
const STALL_MS = 15_000;
const fpsMeter = new RateMeter();
const realtimeMeter = new RateMeter();
let frames = 0;
const crowd = new CrowdMesh();
const ring = new SelectionRing();
/** Marks the optimize panel's learner: a wider ring, in the chart's colour. */
const learnerRing = new SelectionRing(new THREE.Color(LEARNER_COLOUR).getHex(), 0.7);
let gaits: GaitEditors | null = null;
let optimizer: OptimizePanel | null = null;
/** The learner's id as the worker last reported it. */
let learnerId: number | null = null;
/** How this page got its threads; fixed for the page's life (isolation.ts). */
const isolation = isolationMode();

function showError(title: string, detail: string): void {
  state.error = `${title}: ${detail}`;
  overlay.showNotice(title, detail);
}

// Anything that goes wrong later is shown on the page as well as in the console.
window.addEventListener('error', (event) => showError('Unexpected error', errorMessage(event.error ?? event.message)));
window.addEventListener('unhandledrejection', (event) => showError('Unexpected error', errorMessage(event.reason)));

/** The speed creatures spawned by name walk at, m/s (the quadruped's cruise speed, the walking criteria's first). */
const CREATURE_SPEED = 0.4;
const send = (command: SceneCommand) => client?.send({ type: 'scene', command });
const selectedStatus = () => state.characters.find((c) => c.id === state.selected) ?? null;

function select(id: number | null): void {
  state.selected = id !== null && state.characters.some((c) => c.id === id) ? id : null;
  panel.setSelection(selectedStatus());
  gaits?.select(selectedStatus());
}

const panel = new ControlPanel({
  togglePause: () => client?.send({ type: state.paused ? 'resume' : 'pause' }),
  step: () => client?.send({ type: 'step' }),
  timeScale: (scale) => client?.send({ type: 'timeScale', scale }),
  newScene: () => client?.reset(),
  add: (kind, count) => {
    // The page's limit (MAX_CHARACTERS, protocol.ts): refused here with the limit, nothing added.
    const room = MAX_CHARACTERS - state.characters.length;
    if (count > room) {
      panel.showCrowdLimit(`Not added: the page holds at most ${MAX_CHARACTERS} characters; ${room > 0 ? `${room} more fit` : 'it is full'}.`);
      return;
    }
    panel.showCrowdLimit(null);
    send({ type: 'add', kind, count });
  },
  removeSelected: () => {
    if (state.selected === null) return;
    send({ type: 'remove', id: state.selected });
    select(null);
  },
  resetSelected: () => state.selected !== null && send({ type: 'resetCharacter', id: state.selected }),
  resetFallen: () => send({ type: 'resetFallen' }),
  autoReset: (seconds) => send({ type: 'autoReset', seconds }),
  steer: (target, goal) => steer(target, goal),
  wander: (on, target) => send({ type: 'wander', on, ...(target === 'all' ? {} : { id: target.id }) }),
  follow: (on) => (state.follow = on),
  deselect: () => select(null),
  terrain: (kind) => send({ type: 'setTerrain', terrain: kind }),
});

const creatureUrl = (name: string) => new URL(`${import.meta.env.BASE_URL}creatures/${name}.json`, location.href);
const designer = new CreatureDesigner(panel.gui, {
  send,
  spawn: (command) => (client ? client.spawnCreature(command) : Promise.reject(new Error('the simulation has not started'))),
  select,
  creatureUrl,
  // "Teach it to walk": the optimize panel searches a gait for the designed body.
  teach: (file, values) => {
    const character = typeOfLegFrames(file.legFrames.length);
    if (!optimizer) throw new Error('the optimize panel is not ready yet');
    if (!character) throw new Error(`a body of ${file.legFrames.length} leg frames is no kind of character`);
    optimizer.element.open = true;
    return optimizer.teach({ json: JSON.stringify(file), name: file.name, character }, values);
  },
});

// On a phone the panel is a drawer: folded to its title until opened.
if (phone.matches) panel.gui.close();

installTestHook({
  stats: () => ({
    characters: state.characters.length,
    fallen: state.characters.filter((c) => c.fallen).length,
    simTime: crowd.frame?.simTime ?? 0,
    realtimeFactor: realtimeMeter.rate,
    fps: fpsMeter.rate,
    threads: state.threads,
    crossOriginIsolated: window.crossOriginIsolated,
    drawCalls: state.drawCalls,
    isolation,
    bodies: crowd.frame?.bodyCount ?? 0,
    paused: state.paused,
    timeScale: state.timeScale,
    ready: state.ready,
    error: state.error,
    gaits: gaits !== null,
    selected: state.selected,
    terrain: state.terrain,
    drawnTerrain: stage?.terrain?.kind ?? null,
    wander: { ...state.wander },
  }),
  characters: () => state.characters,
  editors: () => gaits,
  optimizer: () => optimizer,
  optimizerMissing,
  send,
  control: (command) => client?.send(command),
  select,
  throwBox: (target) => pointer?.throwAt(new THREE.Vector3(...target)),
  learner: () => learnerId,
  screenPosition: (id) => {
    const index = crowd.firstBodyOf(id);
    if (index < 0 || !stage) return null;
    const p = crowd.bodyPosition(index, new THREE.Vector3()).project(stage.camera);
    const rect = stage.renderer.domElement.getBoundingClientRect();
    return { x: rect.left + ((p.x + 1) / 2) * rect.width, y: rect.top + ((1 - p.y) / 2) * rect.height };
  },
  setTerrain: (kind) => {
    if (!isTerrainKind(kind)) throw new Error(`'${String(kind)}' is not flat, slope or bumps`);
    send({ type: 'setTerrain', terrain: kind });
  },
  groundHeight: (x, z) => (stage?.terrain ? groundHeight(stage.terrain, x, z) : null),
  view: (from, to) => stage?.view(new THREE.Vector3(...from), new THREE.Vector3(...to)),
  ownerAt: (x, y) => pointer?.ownerAt(x, y) ?? null,
  designer: () => designer,
  camera: () => ({
    distance: stage ? stage.camera.position.distanceTo(stage.controls.target) : 0,
    azimuth: stage ? stage.controls.getAzimuthalAngle() : 0,
  }),
  bodies: () => {
    // The newest published frame, read now rather than at the next animation frame: a test that
    // steps the paused scene and looks after each step is not held to the drawn frame rate.
    crowd.update();
    const { count } = crowd.matrices();
    const p = new THREE.Vector3();
    const { array } = crowd.matrices();
    return Array.from({ length: count }, (_, i) => ({
      owner: crowd.owners[i] ?? -1,
      position: crowd.bodyPosition(i, p).toArray() as [number, number, number],
      matrix: Array.from(array.subarray(i * 16, i * 16 + 16)),
    }));
  },
});

/** Why window.gaitlab's optimize functions cannot work (the panel is made with the first scene). */
function optimizerMissing(): string {
  if (!state.ready && !state.error) return 'the page is still starting';
  return 'this build of the module has no optimiser settings (gl_opt_settings_json) or no parameter schema';
}

let stage: Stage | null = null;
let pointer: PointerInteraction | null = null;
try {
  stage = new Stage(canvas);
  stage.scene.add(crowd.group, ring.mesh, learnerRing.mesh);
  pointer = new PointerInteraction(stage, crowd, {
    send,
    select,
    // The last report's horizontal speed along its heading (a walker moves where it faces).
  });
} catch (error) {
  showError('WebGL is not available', `${errorMessage(error)}\nThe demo needs a browser with WebGL 2.`);
}

/**
 * Steering acts on what the panel says: the selected character (steered by hand from then on: it
 * leaves the wandering crowd), or everyone, each type at its own speed.
 */
function steer(target: SteerTarget, goal: { speed: Record<CharacterType, number>; turn: number }): void {
  if (target !== 'all') {
    send({ type: 'setGoal', id: target.id, speed: goal.speed[target.type], turn: goal.turn });
    panel.values.wander = false;
    return;
  }
  for (const type of CHARACTER_TYPES) send({ type: 'setGoal', id: 'all', character: type, speed: goal.speed[type], turn: goal.turn });
}

/** Keys steer the selected character (or all), within the ranges the panel's sliders have. */
function onKey(event: KeyboardEvent): void {
  if (event.target instanceof HTMLInputElement || event.target instanceof HTMLSelectElement || event.ctrlKey || event.metaKey) return;
  const v = panel.values;
  const keySteer = (dSpeed: number, dTurn: number) => {
    const target = panel.steerTarget;
    const clamp = (x: number, lo: number, hi: number) => Math.min(hi, Math.max(lo, Math.round(x * 100) / 100));
    for (const type of CHARACTER_TYPES) {
      if (target !== 'all' && target.type !== type) continue;
      const key = speedValue(type);
      v[key] = clamp(v[key] + dSpeed, panel.speedRange(type).min, panel.speedRange(type).max);
    }
    v.turnDegrees = clamp(v.turnDegrees + dTurn, -MAX_TURN_DEGREES, MAX_TURN_DEGREES);
    steer(target, { speed: panel.speeds(), turn: (v.turnDegrees * Math.PI) / 180 });
  };
  switch (event.key) {
    case 'w': case 'W': case 'ArrowUp': keySteer(0.1, 0); break;
    case 's': case 'S': case 'ArrowDown': keySteer(-0.1, 0); break;
    case 'a': case 'A': case 'ArrowLeft': keySteer(0, 5); break;
    case 'd': case 'D': case 'ArrowRight': keySteer(0, -5); break;
    case ' ': client?.send({ type: state.paused ? 'resume' : 'pause' }); break;
    case '.': client?.send({ type: 'step' }); break;
    case 'f': case 'F': v.follow = state.follow = !state.follow; break;
    case 'r': case 'R': if (state.selected !== null) send({ type: 'resetCharacter', id: state.selected }); break;
    case 'Delete': case 'Backspace':
      if (state.selected !== null) {
        send({ type: 'remove', id: state.selected });
        select(null);
      }
      break;
    case 'Escape': select(null); break;
    default: return;
  }
  event.preventDefault();
}

reloadWhenControlled();
if (!window.crossOriginIsolated) {
  // SharedArrayBuffer (hence WASM threads and the shared render buffer) needs isolation. On a
  // host without the headers, coi-serviceworker installs a service worker and the page reloads
  // (isolation.ts); give it a moment before saying it could not.
  overlay.message('Not cross-origin isolated: enabling it through a service worker, the page reloads…');
  setTimeout(() => {
    showError(
      'This page must be served with cross-origin isolation',
      'The simulation uses WebAssembly threads, which browsers only allow when the page is sent with the headers ' +
        '"Cross-Origin-Opener-Policy: same-origin" and "Cross-Origin-Embedder-Policy: require-corp". ' +
        'On a static host the page installs a service worker that adds them (coi-serviceworker), but this browser ' +
        'did not allow it (service workers need https or localhost, and are off in private windows of some browsers). ' +
        'Serve it with `npm start` (or `node scripts/serve.mjs`), or from https.',
    );
  }, navigator.serviceWorker && window.isSecureContext ? 5000 : 0);
} else if (stage) {
  const queryNotes: string[] = [];
  const options = simOptionsFromQuery(
    location.search,
    {
      wasmUrl: new URL(`${import.meta.env.BASE_URL}wasm/gaitlab.mjs`, location.href).href,
      threads: defaultThreads(navigator.hardwareConcurrency),
      seed: 1,
      // A dozen bipeds and a dozen quadrupeds.
      characters: 24,
    },
    queryNotes,
  );
  // A query parameter out of range runs with the nearest valid value, and says so.
  for (const note of queryNotes) overlay.message(note, 'problem');
  // Creatures by name (`?creature=insect,spider`): the shipped creature files (public/creatures/),
  // fetched once and spawned into every scene, in a row right of the crowd (or at the middle
  // when there is no crowd), walking at the quadruped's cruise speed.
  const creatureNames = (new URLSearchParams(location.search).get('creature') ?? '').split(',').filter((n) => n !== '');
  const creatureFiles = Promise.all(creatureNames.map(async (name) => {
    if (!/^[a-z0-9-]{1,40}$/.test(name)) throw new Error(`?creature=${name}: not a creature's name`);
    const response = await fetch(creatureUrl(name));
    if (!response.ok) throw new Error(`?creature=${name}: no such creature (creatures/${name}.json: ${response.status})`);
    return response.text();
  }));
  // A creature a link carries (share/link.ts: its body and the gait it learnt), read once the
  // module can judge the gait, and spawned after the named ones.
  let linkCreature: Promise<{ json: string; gait: string } | null> | null = null;
  const readLinkCreature = async (): Promise<{ json: string; gait: string } | null> => {
    if (!transfer.creatureInPage()) return null;
    try {
      const json = await transfer.readCreatureLink();
      const gait = await transfer.readLink();
      overlay.message(`Shared ${gait.character} loaded from the link: it walks right of the crowd with the gait it learnt.`);
      return { json, gait: JSON.stringify(gait) };
    } catch (error) {
      overlay.message(`The creature link was refused: ${error instanceof Error ? error.message : String(error)}. Running without it.`, 'problem');
      return null;
    }
  };
  const spawnCreatures = (crowd: number) => {
    const place = (k: number, count: number) => (crowd === 0 ? (k - (count - 1) / 2) * 2.5 : 6 + 2.5 * k);
    linkCreature ??= readLinkCreature();
    Promise.all([creatureFiles, linkCreature]).then(([files, shared]) => {
      const count = files.length + (shared ? 1 : 0);
      files.forEach((json, k) => send({ type: 'spawnCreature', json, x: place(k, count), z: 0, heading: 0, speed: CREATURE_SPEED }));
      if (shared) send({ type: 'spawnCreature', json: shared.json, gait: shared.gait, x: place(files.length, count), z: 0, heading: 0, speed: CREATURE_SPEED });
    }, (error: unknown) => overlay.message(error instanceof Error ? error.message : String(error), 'problem'));
  };
  let framed = false;
  // Gaits in and out of the page (links, files), judged by the module in the sim worker.
  const transfer = new GaitTransfer((json) => client!.normalize(json));
  client = new SimClient(options, {
    onScene: (reader, info) => {
      crowd.attach(reader);
      state.threads = info.threads;
      panel.setSpeedRanges(info.speedRanges);
      state.lastStats = performance.now(); // the stall watchdog counts from here
      realtimeMeter.reset();
      framed = false;
      if (stage) stage.autoZoom = true;
      select(null);
      console.info(`gaitlab ${info.version}: scene ${info.generation}, ${reader.capacity} body slots, ${info.threads} threads`);
      if (!gaits) gaits = GaitEditors.create(info.schema, client!, transfer, panel.gaitFolder, overlay);
      spawnCreatures(options.characters);
      designer.sceneReset();
      if (!optimizer && gaits && info.optimizerSchema) optimizer = createOptimizePanel(info.optimizerSchema);
    },
    onRelease: () => crowd.detach(),
    onStats: (stats) => {
      state.lastStats = performance.now();
      state.paused = stats.paused;
      state.timeScale = stats.timeScale;
      state.characters = stats.characters;
      if (stats.wander) {
        state.wander = stats.wander;
        stage?.setArena(stats.wander.on ? stats.wander.arenaRadius : null);
        panel.setCrowdWander(stats.wander.on);
      }
      learnerId = stats.learner;
      if (stats.terrain !== state.terrain) {
        state.terrain = stats.terrain;
        panel.setTerrain(stats.terrain);
      }
      panel.setPaused(stats.paused);
      // The selected character may have been removed.
      if (state.selected !== null && !selectedStatus()) select(null);
      gaits?.tick(selectedStatus(), stats.characters);
      designer.tick(stats.characters);
    },
    onTerrain: (grid) => {
      stage?.setTerrain(grid);
      panel.setTerrain(grid.kind);
    },
    onError: (message) => showError('The simulation stopped', message),
    onCommandError: (message) => overlay.message(message, 'problem'),
  });

  const activeStage = stage;
  /** Centre and radius of the crowd's leg frames as last reported (standing characters), or null. */
  const crowdRegion = (): THREE.Sphere | null => {
    const box = new THREE.Box3();
    const p = new THREE.Vector3();
    for (const c of state.characters) if (c.id !== learnerId && !c.fallen) box.expandByPoint(p.set(c.position[0], 0.6, c.position[2]));
    return box.isEmpty() ? null : box.getBoundingSphere(new THREE.Sphere());
  };
  const focus = new THREE.Vector3();
  let lastFrame = performance.now() / 1000;
  const frame = (): void => {
    const now = performance.now() / 1000;
    const dt = Math.min(0.1, now - lastFrame);
    lastFrame = now;
    if (crowd.update() && !framed) {
      const bounds = crowd.bounds();
      if (bounds) {
        // Look at the whole scene once, when its first frame arrives.
        activeStage.frame(new THREE.Vector3(bounds.center.x, 0.6, bounds.center.z), bounds.radius);
        framed = true;
      }
    }
    const index = state.selected === null ? -1 : crowd.firstBodyOf(state.selected);
    const following = index >= 0 && state.follow;
    if (index >= 0) {
      crowd.bodyPosition(index, focus);
      ring.place(focus);
      if (state.follow) activeStage.follow(focus, dt);
    } else {
      ring.place(null);
    }
    // Otherwise the camera keeps the crowd in view as it wanders (not the learner, which the
    // optimize panel frames itself).
    if (!following && (learnerId === null || !optimizer?.followLearner)) {
      const region = crowdRegion();
      if (region) activeStage.keepInView(region.center, region.radius, dt);
    }
    const learnerIndex = learnerId === null ? -1 : crowd.firstBodyOf(learnerId);
    if (learnerIndex >= 0) {
      crowd.bodyPosition(learnerIndex, focus);
      learnerRing.place(focus);
      // The camera follows the selected character if asked to, else the learner if asked to.
      if (!following && optimizer?.followLearner) activeStage.follow(focus, dt);
    } else {
      learnerRing.place(null);
    }
    if (crowd.frame) {
      state.ready = true;
      // Sampled on every display frame, new simulation frame or not: wall time passes either way.
      realtimeMeter.sample(crowd.frame.simTime, now);
    }
    gaits?.animate(!state.paused);
    activeStage.render();
    state.drawCalls = activeStage.renderer.info.render.calls;
    fpsMeter.sample(++frames, now);
    requestAnimationFrame(frame);
  };

  const resize = () => {
    // Keep the crowd clear of the control panel (and the optimize panel, open) on wide windows.
    activeStage.rightInset = window.innerWidth > 700 ? panel.gui.domElement.offsetWidth + 10 : 0;
    if (phone.matches) activeStage.rightInset = 0;
    activeStage.leftInset = window.innerWidth > 900 && optimizer?.element.open ? optimizer.element.offsetWidth + 10 : 0;
    activeStage.resize();
  };

  /** The optimize panel, once the module has said what the optimiser accepts. */
  function createOptimizePanel(optimizerJson: string): OptimizePanel | null {
    try {
      return new OptimizePanel(
        {
          wasmUrl: options.wasmUrl,
          transfer,
          optimizerSchema: JSON.parse(optimizerJson) as OptimizerSchema,
          // One thread fewer than the cores (at least one), so the search does not take the
          // core the crowd's real-time loop and the renderer need; the panel lets one choose
          // more (bench/optimize-panel.mjs measures both ways).
          defaultThreads: Math.max(1, defaultThreads(navigator.hardwareConcurrency) - 1),
          selected: selectedStatus,
          gaitJson: (id) => client!.getParams(id),
          showLearner: (gait, goal, loopSeconds, body) =>
            send({
              type: 'learner',
              character: gait.character,
              json: JSON.stringify(gait),
              speed: goal.speed,
              turn: goal.turn,
              loopSeconds,
              ...(body ? { creature: body.json } : {}),
            }),
          apply: async (gait, target) => {
            if (!gaits) throw new Error('this build has no parameter schema');
            if (target === 'all') {
              select(null);
              await gaits.applyGait(gait, 'all');
              return `every ${gait.character}`;
            }
            const chosen = selectedStatus();
            if (!chosen) throw new Error('no character is selected (click one, or apply to every character of the type)');
            if (chosen.type !== gait.character) throw new Error(`the selected character is a ${chosen.type}; the result is a ${gait.character}'s gait`);
            await gaits.applyGait(gait, chosen.id);
            return `${chosen.type} #${chosen.id}`;
          },
          onResize: () => resize(),
        },
        overlay.column,
      );
    } catch (error) {
      overlay.message(`The optimize panel could not be made: ${errorMessage(error)}`, 'problem');
      return null;
    }
  }
  window.addEventListener('resize', resize);
  window.addEventListener('keydown', onKey);
  resize();
  requestAnimationFrame(frame);

  // Dynamic resolution: every 2 s, a frame rate below 24 FPS lowers the render scale and one
  // above 50 raises it again (the thresholds far apart, so it does not oscillate).
  setInterval(() => {
    if (document.visibilityState !== 'visible' || fpsMeter.rate <= 0) return;
    if (fpsMeter.rate < 24 && activeStage.scale > 0.35) activeStage.setRenderScale(activeStage.scale * 0.75);
    else if (fpsMeter.rate > 50 && activeStage.scale < 1) activeStage.setRenderScale(activeStage.scale / 0.75);
  }, 2000);

  setInterval(() => {
    // A worker blocked inside the module (e.g. waiting on a pthread that cannot start) cannot
    // report an error itself: notice its silence. Hidden pages are skipped (timers throttle).
    const silent = performance.now() - state.lastStats;
    if (state.lastStats > 0 && !state.error && document.visibilityState === 'visible' && silent > STALL_MS) {
      showError('The simulation stopped responding', `The sim worker has sent nothing for ${(silent / 1000).toFixed(0)} s.`);
    }
    const selected = selectedStatus();
    overlay.show({
      fps: fpsMeter.rate,
      realtimeFactor: realtimeMeter.rate,
      characters: state.characters.length,
      fallen: state.characters.filter((c) => c.fallen).length,
      threads: state.threads,
      // One thread is serial, whatever the isolation allows.
      mode: `${state.threads > 1 ? 'multi-threaded' : 'serial'} (isolated by ${isolation})`,
      drawCalls: state.drawCalls,
      renderScale: activeStage.scale,
      paused: state.paused,
      timeScale: state.timeScale,
      selected: selected ? `${selected.type} #${selected.id}${selected.fallen ? ' (down)' : ''}` : null,
    }, phone.matches);
    // On a phone the gait editors are a bottom sheet: keep the view's centre above it.
    const sheet = phone.matches ? document.querySelector<HTMLDetailsElement>('details.editors[open]') : null;
    const inset = sheet ? sheet.offsetHeight : 0;
    if (inset !== activeStage.bottomInset) {
      activeStage.bottomInset = inset;
      activeStage.resize();
    }
  }, 250);
}

// Without isolation (or WebGL) the page still draws the empty stage behind the notice, if it can.
if (stage && !client) {
  const still = stage;
  still.resize();
  still.render();
  window.addEventListener('resize', () => {
    still.resize();
    still.render();
  });
}
