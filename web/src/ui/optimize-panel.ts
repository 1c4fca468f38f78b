// The optimize panel: "learning to walk" in the browser. A folded panel on the left:
// the search's options (character, method, generations, candidates, seed, threads, where it
// starts, the objective's episode settings from the module's own table), Start and Stop, the
// progress (generation i of N, evaluations, best objective, time per generation, time left), a
// live chart of the best objective per generation (uPlot), and the result: applied to the
// selected character or to every character of its type (as a gait edit: the editors show it
// and undo takes it back), or shared as a link.
//
// The search runs in a worker of its own (optimize/optimizer.worker.ts says why, with the
// measurements); the crowd keeps running meanwhile. Whenever the best improves, the host puts
// a learner in the scene that walks it (thesis Figure 3.6), so one watches it learn.
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import {
  checkOptimizeForm,
  defaultForm,
  estimateSecondsLeft,
  formatDuration,
  METHODS,
  SEARCH_FIELDS,
  type FieldProblem,
  type OptimizeForm,
  type OptimizeOptions,
  type OptimizerSchema,
} from '../optimize/options';
import { fitRange, tickLabels } from '../optimize/chart';
import type { GenerationReport, OptimizerCommand, OptimizerEvent } from '../optimize/protocol';
import { CHARACTER_TYPES, type CharacterType } from '../gait/character';
import type { GaitFile } from '../share/gait-file';
import { errorMessage, type CharacterStatus } from '../sim/protocol';
import type { GaitTransfer } from './gait-transfer';

export type OptimizeState = 'idle' | 'loading' | 'running' | 'done' | 'stopped' | 'error';

/** What window.gaitlab.optimizeStatus() returns. */
export interface OptimizeStatus {
  state: OptimizeState;
  /** The options of the current (or last) search, or null before the first. */
  options: OptimizeOptions | null;
  generation: number;
  generations: number;
  evaluations: number;
  /** Best objective so far (eq. 3.10, lower is better), or null before the first generation. */
  best: number | null;
  /** One entry per finished generation. */
  history: { generation: number; evaluations: number; best: number; seconds: number }[];
  /** Mean wall-clock seconds per generation so far, in the optimizer worker. */
  secondsPerGeneration: number | null;
  secondsLeft: number | null;
  /** Seconds the worker took to load the module and create the search. */
  loadSeconds: number | null;
  /** Points the chart is drawing (read from the chart itself). */
  chartPoints: number;
  /** The best gait so far, as a gait file with the search's provenance in meta. */
  result: GaitFile | null;
  /** What the panel says (a refused form, an error, what was applied), or null. */
  message: string | null;
  /** The name of the body the search learns for (a designed creature), or null for the kind's shipped body. */
  body: string | null;
}

/** A body to learn for: a creature file's text, its name, and the kind its leg frames make. */
export interface LearnerBody {
  json: string;
  name: string;
  character: CharacterType;
}

export interface OptimizePanelHost {
  wasmUrl: string;
  optimizerSchema: OptimizerSchema;
  /** Share links and the clipboard, as the gait editors use them. */
  transfer: GaitTransfer;
  defaultThreads: number;
  selected(): CharacterStatus | null;
  /** Character `id`'s gait as a gait file's JSON. */
  gaitJson(id: number): Promise<string>;
  /** Puts (or replaces) the learner walking `gait`, with `body` if given (else its kind's shipped body). */
  showLearner(gait: GaitFile, goal: { speed: number; turn: number }, loopSeconds: number, body: LearnerBody | null): void;
  /** Gives `gait` to the selected character or to every character of its type; says to whom. */
  apply(gait: GaitFile, target: 'selected' | 'all'): Promise<string>;
  /** Called when the panel opens or closes (the view keeps what it looks at clear of it). */
  onResize(): void;
}

/** Objective settings shown in the form's first part; the others are under "more". */
const MAIN_SETTINGS = ['seconds', 'turnRate', 'starts', 'pushImpulse'];
const LABELS: Record<string, string> = {
  seconds: 'episode (s)',
  turnRate: 'turn rate (rad/s)',
  starts: 'start states',
  pushImpulse: 'pushes (N·s)',
};

/**
 * What "Teach it to walk" searches with, written into the form: from the body's own first gait,
 * at the walking criteria's slow speed, with episodes as long as the walk a new body is judged by.
 * Episodes of the thesis's 6.7 s let the search trade a fall 10 or 25 s in for a tidier first
 * 6 s: in the learning benchmark three hexapods whose first gait walked 30 s fell after 3 minutes
 * of such a search (docs/creatures.md, "Teaching").
 */
export const TEACHING: OptimizeForm = { start: 'preset', speeds: '0.4', seconds: 30 };

function el<K extends keyof HTMLElementTagNameMap>(tag: K, props: Partial<HTMLElementTagNameMap[K]> = {}, ...children: (Node | string)[]): HTMLElementTagNameMap[K] {
  const node = Object.assign(document.createElement(tag), props);
  node.append(...children);
  return node;
}

/**
 * The learner starts over after an episode's length (what the objective scores), but not more
 * often than every 2 s, which would show nothing but standing up.
 */
const learnerLoop = (o: OptimizeOptions) => Math.max(2, o.settings.seconds ?? 0);

const fmt = (x: number) => (x === 0 ? '0' : Math.abs(x) >= 1000 || Math.abs(x) < 0.01 ? x.toExponential(2) : x.toPrecision(4));
/** The chart's line, and the learner's ring in the scene (main.ts): one colour for one idea. */
export const LEARNER_COLOUR = '#7b4fd6';

/** The objective's terms as the C ABI reports them (optimize/objective.h's kTermNames), with their
 *  names in the thesis's notation and whether the line always shows them. */
const OBJECTIVE_TERMS: [key: string, name: string, always: boolean][] = [
  ['fd', 'f_d', true], ['fv', 'f_v', true], ['fa', 'f_a', true], ['fr', 'f_r', true],
  ['ft', 'f_t', false], ['ff', 'f_f', false], ['fk', 'f_k', false], ['fs', 'f_s', false],
  ['fp', 'f_p', false], ['fo', 'f_o', false], ['fall', 'fall', false],
];

export class OptimizePanel {
  readonly element: HTMLDetailsElement;
  private readonly inputs = new Map<string, HTMLInputElement | HTMLSelectElement>();
  private readonly startButton: HTMLButtonElement;
  private readonly stopButton: HTMLButtonElement;
  private readonly applyButton: HTMLButtonElement;
  private readonly shareButton: HTMLButtonElement;
  private readonly applyTarget: HTMLSelectElement;
  private readonly followBox: HTMLInputElement;
  private readonly linkField: HTMLInputElement;
  private readonly messageLine: HTMLElement;
  private readonly progressLine: HTMLElement;
  private readonly bestLine: HTMLElement;
  private readonly learnerLine: HTMLElement;
  private readonly chartHolder: HTMLElement;
  private readonly bodyLine: HTMLElement;
  private plot: uPlot | null = null;
  /** The body the search learns for (useBody), or null for the kind's shipped body. */
  private body: LearnerBody | null = null;
  /** The body the current (or last) search learnt for: the result's, which its link carries. */
  private resultBody: LearnerBody | null = null;

  private state: OptimizeState = 'idle';
  private options: OptimizeOptions | null = null;
  private history: GenerationReport[] = [];
  private loadSeconds: number | null = null;
  private result: GaitFile | null = null;
  private message: string | null = null;
  private worker: Worker | null = null;
  /** Settles the promise of the run in progress (the test hook's optimize()). */
  private settle: { resolve: (s: OptimizeStatus) => void; reject: (e: Error) => void } | null = null;
  /** Provenance of the result (merged into the best gait's meta). */
  private startedFrom = 'preset';

  constructor(private readonly host: OptimizePanelHost, parent: HTMLElement) {
    this.element = el('details', { className: 'optimize-panel' });
    this.element.dataset.testid = 'optimize-panel';
    this.element.append(el('summary', { className: 'optimize-heading', title: 'Search a gait (thesis §3.3) and watch a character learn to walk' }, 'Optimize: learning to walk'));
    this.element.addEventListener('toggle', () => {
      if (this.element.open) this.ensurePlot();
      // The gait editors (bottom left) move right of the open panel instead of under it.
      document.body.classList.toggle('optimize-open', this.element.open);
      host.onResize();
    });

    const form = defaultForm(host.optimizerSchema, host.defaultThreads);
    const grid = el('div', { className: 'opt-grid' });
    grid.append(
      this.select('character', 'character', CHARACTER_TYPES, form.character, 'the type of character whose gait is searched'),
      this.select('method', 'method', METHODS, form.method, 'greedy: the thesis\'s greedy stochastic search (§3.3); cmaes: CMA-ES'),
      this.select('start', 'start from', ['preset', 'selected'], form.start, 'the type\'s preset gait, or the selected character\'s gait as it is now'),
    );
    for (const [name, f] of Object.entries(SEARCH_FIELDS)) grid.append(this.field(name, f.label, form[name], f.description));
    grid.append(this.field('speeds', 'goal speeds (m/s)', form.speeds, `${host.optimizerSchema.speeds.description}; comma-separated, ${host.optimizerSchema.speeds.min} to ${host.optimizerSchema.speeds.max}`));
    const shippedBody = el('button', { type: 'button', textContent: 'use the shipped body' });
    shippedBody.addEventListener('click', () => this.useBody(null));
    this.bodyLine = el('div', { className: 'opt-body', hidden: true }, el('span', {}), shippedBody);
    this.bodyLine.dataset.testid = 'optimize-body';
    const more = el('div', { className: 'opt-grid' });
    for (const s of host.optimizerSchema.settings) {
      const label = LABELS[s.name] ?? `${s.name}${s.unit && s.unit !== '1' ? ` (${s.unit})` : ''}`;
      const node = this.field(s.name, label, form[s.name], `${s.description} (${s.min} to ${s.max}${s.unit && s.unit !== '1' ? ` ${s.unit}` : ''})`);
      (MAIN_SETTINGS.includes(s.name) ? grid : more).append(node);
    }
    const advanced = el('details', { className: 'opt-more' }, el('summary', {}, 'objective weights and more'), more);

    this.startButton = el('button', { type: 'button', textContent: 'Start' });
    this.stopButton = el('button', { type: 'button', textContent: 'Stop', disabled: true });
    this.startButton.addEventListener('click', () => void this.start().catch(() => {}));
    this.stopButton.addEventListener('click', () => this.stop());
    this.followBox = el('input', { type: 'checkbox', checked: true });
    const follow = el('label', { className: 'opt-check', title: 'the camera follows the learner: the character that walks the best gait so far' }, this.followBox, 'follow the learner');

    this.messageLine = el('div', { className: 'opt-message' });
    this.messageLine.setAttribute('aria-live', 'polite');
    this.messageLine.dataset.testid = 'optimize-message';
    this.progressLine = el('div', { className: 'opt-progress', textContent: 'No search yet.' });
    this.progressLine.dataset.testid = 'optimize-progress';
    this.bestLine = el('div', { className: 'opt-best' });
    this.learnerLine = el('div', { className: 'opt-learner' });
    this.chartHolder = el('div', { className: 'opt-chart' });
    this.chartHolder.dataset.testid = 'optimize-chart';

    this.applyTarget = el('select', {});
    this.applyTarget.setAttribute('aria-label', 'apply to');
    this.applyButton = el('button', { type: 'button', textContent: 'Apply', disabled: true });
    this.shareButton = el('button', { type: 'button', textContent: 'Share result', disabled: true });
    this.applyButton.addEventListener('click', () => void this.applyResult(this.applyTarget.value as 'selected' | 'all').catch(() => {}));
    this.shareButton.addEventListener('click', () => void this.share().catch(() => {}));
    this.linkField = el('input', { type: 'text', readOnly: true, placeholder: 'share link of the result' });
    this.linkField.setAttribute('aria-label', 'result link');
    this.updateTargets();

    this.element.append(
      this.bodyLine,
      grid,
      advanced,
      el('div', { className: 'opt-buttons' }, this.startButton, this.stopButton, follow),
      this.messageLine,
      this.progressLine,
      this.bestLine,
      this.learnerLine,
      el('div', { className: 'opt-caption' }, 'best objective per generation (eq. 3.10, lower is better)'),
      this.chartHolder,
      el('div', { className: 'opt-buttons' }, 'apply to', this.applyTarget, this.applyButton, this.shareButton),
      this.linkField,
    );
    parent.append(this.element);
  }

  // ---- the form ----

  private field(name: string, label: string, value: string, title: string): HTMLElement {
    const input = el('input', { type: 'text', value, name, title });
    input.inputMode = 'decimal';
    input.setAttribute('aria-label', label);
    input.addEventListener('input', () => input.removeAttribute('aria-invalid'));
    this.inputs.set(name, input);
    return el('label', { title }, el('span', {}, label), input);
  }

  private select(name: string, label: string, choices: readonly string[], value: string, title: string): HTMLElement {
    const select = el('select', { name, title }, ...choices.map((c) => el('option', { value: c, textContent: c })));
    select.value = value;
    select.setAttribute('aria-label', label);
    select.addEventListener('change', () => this.updateTargets());
    this.inputs.set(name, select);
    return el('label', { title }, el('span', {}, label), select);
  }

  /** The form's values as typed. */
  private readForm(): OptimizeForm {
    const form: OptimizeForm = {};
    for (const [name, input] of this.inputs) form[name] = input.value;
    return form;
  }

  /** Writes values into the form (the test hook), as if typed. */
  setForm(values: OptimizeForm): void {
    for (const [name, value] of Object.entries(values)) {
      const input = this.inputs.get(name);
      if (!input) throw new Error(`the optimize panel has no field '${name}'`);
      input.value = String(value);
      input.removeAttribute('aria-invalid');
    }
    this.updateTargets();
  }

  private setDisabled(disabled: boolean): void {
    for (const input of this.inputs.values()) input.disabled = disabled;
    // A body's kind is its leg frames': the character is not a choice while one is set.
    const character = this.inputs.get('character');
    if (character && this.body) character.disabled = true;
    for (const button of this.bodyLine.querySelectorAll('button')) button.disabled = disabled;
  }

  /**
   * Learns for `body` (a designed creature) from now on, or with null for each kind's shipped
   * body: the character is set to the body's kind, and the search starts, unless the form's start
   * is the selected character, from the gait the body walks when spawned.
   */
  useBody(body: LearnerBody | null): void {
    if (this.running) throw new Error('a search is running: stop it first');
    this.body = body;
    if (body) this.setForm({ character: body.character });
    this.bodyLine.hidden = body === null;
    this.bodyLine.querySelector('span')!.textContent = body ? `Learning for ${body.name} (${body.character}, its own body)` : '';
    this.setDisabled(false);
  }

  /**
   * "Teach it to walk": a search for `body` with the teaching settings (TEACHING, then `values`
   * over them), shown as any other (the test hook awaits it).
   */
  teach(body: LearnerBody, values?: OptimizeForm): Promise<OptimizeStatus> {
    this.useBody(body);
    return this.start({ ...TEACHING, ...values });
  }

  private say(text: string | null, kind: 'info' | 'problem' = 'info'): void {
    this.message = text;
    this.messageLine.textContent = text ?? '';
    this.messageLine.className = `opt-message${kind === 'problem' && text ? ' opt-problem' : ''}`;
  }

  private showProblems(problems: FieldProblem[]): void {
    for (const input of this.inputs.values()) input.removeAttribute('aria-invalid');
    for (const p of problems) this.inputs.get(p.field)?.setAttribute('aria-invalid', 'true');
    this.say(problems.map((p) => p.message).join('\n'), 'problem');
    this.inputs.get(problems[0].field)?.focus();
  }

  // ---- a run ----

  get followLearner(): boolean {
    return this.followBox.checked;
  }

  get running(): boolean {
    return this.state === 'loading' || this.state === 'running';
  }

  /**
   * Starts a search with the form's values (after `values` are written into it, if given).
   * Resolves with the status when it ends (done or stopped); rejects with the panel's message
   * if the form is refused or the search fails.
   */
  async start(values?: OptimizeForm): Promise<OptimizeStatus> {
    if (this.running) throw new Error('a search is running: stop it first');
    if (values) this.setForm(values);
    const selected = this.host.selected();
    const checked = checkOptimizeForm(this.readForm(), this.host.optimizerSchema, selected?.type ?? null);
    if (!checked.ok) {
      this.showProblems(checked.problems);
      throw new Error(this.message ?? 'the options were refused');
    }
    for (const input of this.inputs.values()) input.removeAttribute('aria-invalid');
    const options = checked.options;
    let startJson: string | null = null;
    this.startedFrom = 'preset';
    if (options.start === 'selected' && selected) {
      try {
        startJson = await this.host.gaitJson(selected.id);
      } catch (error) {
        this.say(`Could not read the selected character's gait: ${errorMessage(error)}`, 'problem');
        throw new Error(this.message!);
      }
      this.startedFrom = `${selected.type} #${selected.id}`;
    }

    this.options = options;
    this.resultBody = this.body;
    this.history = [];
    this.result = null;
    this.loadSeconds = null;
    this.linkField.value = '';
    this.state = 'loading';
    this.say(`Loading the optimiser (a module of its own, ${options.threads} thread${options.threads === 1 ? '' : 's'})…`);
    this.setDisabled(true);
    // A search started from elsewhere (the test hook) shows itself too.
    this.element.open = true;
    this.resetPlot();
    this.update();

    const done = new Promise<OptimizeStatus>((resolve, reject) => (this.settle = { resolve, reject }));
    const worker = new Worker(new URL('../optimize/optimizer.worker.ts', import.meta.url), { type: 'module', name: 'gaitlab-optimizer' });
    this.worker = worker;
    worker.onmessage = (event: MessageEvent<OptimizerEvent>) => {
      if (this.worker === worker) this.receive(event.data);
    };
    worker.onerror = (event) => {
      event.preventDefault();
      if (this.worker === worker) this.finish('error', `the optimizer worker failed: ${event.message || 'see the browser console'}`);
    };
    const command: OptimizerCommand = { type: 'start', wasmUrl: this.host.wasmUrl, options, startJson, creature: this.body?.json ?? null };
    worker.postMessage(command);
    return done;
  }

  /** Stops the search at once; the best of the generations finished so far is kept. */
  stop(): void {
    if (!this.running) return;
    if (this.result?.meta) this.result.meta.interrupted = true;
    this.finish('stopped', this.result ? 'Stopped: the best so far is kept.' : 'Stopped before the first generation finished: no result.');
  }

  private receive(event: OptimizerEvent): void {
    switch (event.type) {
      case 'started':
        this.state = 'running';
        this.loadSeconds = event.loadSeconds;
        this.say(`Searching (module loaded in ${event.loadSeconds.toFixed(1)} s).`);
        break;
      case 'generation':
        this.onGeneration(event);
        break;
      case 'done':
        this.finish('done', `Done: ${this.history.length} generations.`);
        return;
      case 'error':
        this.finish('error', event.message);
        return;
    }
    this.update();
  }

  private onGeneration(report: GenerationReport): void {
    this.history.push(report);
    const o = this.options!;
    if (report.gait !== null) {
      let gait: GaitFile;
      try {
        // The module's own gait file (gl_opt_best_json): nothing for the page to check.
        gait = JSON.parse(report.gait) as GaitFile;
      } catch (error) {
        this.finish('error', `the optimiser's best gait could not be read: ${errorMessage(error)}`);
        return;
      }
      gait.meta = {
        ...(gait.meta ?? {}),
        source: 'gaitlab demo: optimize panel (gl_opt)',
        candidates: o.candidates,
        objective_settings: { ...o.settings, speeds: o.speeds },
        start: this.startedFrom,
        ...(this.body ? { creature: this.body.name } : {}),
        found_in_generation: report.generation,
      };
      this.result = gait;
      this.host.showLearner(gait, { speed: o.speeds[0], turn: o.settings.turnRate ?? 0 }, learnerLoop(o), this.body);
    }
    if (this.result?.meta) {
      Object.assign(this.result.meta, { generations: report.generation, evaluations: report.evaluations, interrupted: false, date: new Date().toISOString() });
    }
    this.updatePlot();
  }

  private finish(state: OptimizeState, message: string): void {
    this.worker?.terminate();
    this.worker = null;
    this.state = state;
    this.setDisabled(false);
    this.say(message, state === 'error' ? 'problem' : 'info');
    this.update();
    const settle = this.settle;
    this.settle = null;
    if (state === 'error') settle?.reject(new Error(message));
    else settle?.resolve(this.status());
  }

  // ---- what it shows ----

  status(): OptimizeStatus {
    const seconds = this.history.map((h) => h.seconds);
    const total = this.options?.generations ?? 0;
    const last = this.history[this.history.length - 1];
    return {
      state: this.state,
      options: this.options ? structuredClone(this.options) : null,
      generation: last?.generation ?? 0,
      generations: total,
      evaluations: last?.evaluations ?? 0,
      best: last?.best ?? null,
      history: this.history.map(({ generation, evaluations, best, seconds: s }) => ({ generation, evaluations, best, seconds: s })),
      secondsPerGeneration: seconds.length ? seconds.reduce((a, b) => a + b, 0) / seconds.length : null,
      secondsLeft: this.running ? estimateSecondsLeft(seconds, total) : null,
      loadSeconds: this.loadSeconds,
      chartPoints: this.plot ? this.plot.data[0].length : 0,
      result: this.result ? structuredClone(this.result) : null,
      message: this.message,
      body: this.body?.name ?? null,
    };
  }

  private update(): void {
    const s = this.status();
    this.startButton.disabled = this.running;
    this.stopButton.disabled = !this.running;
    this.applyButton.disabled = this.shareButton.disabled = this.result === null;
    if (s.options) {
      const last = this.history[this.history.length - 1];
      const parts = [`${this.state === 'loading' ? 'loading' : this.state === 'running' ? 'running' : this.state}: generation ${s.generation} of ${s.generations}`, `${s.evaluations} evaluations`];
      if (last) parts.push(`${formatDuration(last.seconds)} per generation (mean ${formatDuration(s.secondsPerGeneration!)})`);
      if (s.secondsLeft !== null) parts.push(`about ${formatDuration(s.secondsLeft)} left`);
      this.progressLine.textContent = parts.join(' · ');
    }
    const terms = this.result?.meta?.objective_terms as Record<string, number> | undefined;
    // The thesis's four terms always; ours and the fall penalty only when they count.
    const termText = terms && OBJECTIVE_TERMS
      .filter(([key, , always]) => always || terms[key])
      .map(([key, name]) => `${name} ${fmt(terms[key])}`).join(' · ');
    this.bestLine.textContent = s.best === null ? '' : `best ${fmt(s.best)}${termText ? ` (terms ${termText})` : ''}`;
    const o = this.options;
    this.learnerLine.textContent = this.result && o
      ? `The learner (violet ring, apart from the crowd) walks the best so far at ${o.speeds[0]} m/s and starts over every ${formatDuration(learnerLoop(o))}.`
      : '';
    this.updateTargets();
  }

  private updateTargets(): void {
    const type = (this.result?.character ?? this.inputs.get('character')?.value ?? 'biped') as CharacterType;
    const value = this.applyTarget.value || 'selected';
    this.applyTarget.replaceChildren(
      el('option', { value: 'selected', textContent: 'the selected character' }),
      el('option', { value: 'all', textContent: `every ${type}` }),
    );
    this.applyTarget.value = value;
  }

  private ensurePlot(): void {
    if (this.plot || !this.element.open) return;
    const width = Math.max(200, this.chartHolder.clientWidth || 340);
    const data = [this.history.map((h) => h.generation), this.history.map((h) => h.best)];
    this.plot = new uPlot(
      {
        width,
        height: 150,
        legend: { show: false },
        // Linear, fitted to the values: the improvements of a search are a few per cent as often
        // as they are a fall penalty's hundred, and a log scale's whole decades flatten the former.
        scales: { x: { time: false }, y: { range: (_u, min, max) => fitRange(min, max) } },
        // Whole generations on the x axis.
        axes: [
          { label: 'generation', size: 34, labelSize: 14, incrs: [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10_000, 100_000] },
          // As many decimals as the ticks need to differ, and the width the labels take (8 px a
          // character of the axis font, and the ticks beside them: 7 cut the first digit off).
          { values: (_u, splits) => tickLabels(splits), size: (_u, values) => 18 + 8 * Math.max(3, ...(values ?? []).map((v) => v.length)) },
        ],
        series: [{ label: 'generation' }, { label: 'best objective', stroke: LEARNER_COLOUR, width: 2, points: { show: true, size: 5, fill: LEARNER_COLOUR } }],
      },
      data as uPlot.AlignedData,
      this.chartHolder,
    );
  }

  private resetPlot(): void {
    this.plot?.destroy();
    this.plot = null;
    this.ensurePlot();
  }

  private updatePlot(): void {
    this.ensurePlot();
    this.plot?.setData([this.history.map((h) => h.generation), this.history.map((h) => h.best)]);
  }

  // ---- the result ----

  /** Gives the best gait to the selected character or to every character of its type. */
  async applyResult(target: 'selected' | 'all'): Promise<void> {
    if (!this.result) {
      this.say('There is no result to apply yet.', 'problem');
      throw new Error(this.message!);
    }
    try {
      const who = await this.host.apply(structuredClone(this.result), target);
      this.say(`Applied to ${who} (undo in the Gait folder takes it back).`);
    } catch (error) {
      this.say(`Not applied: ${error instanceof Error ? error.message : String(error)}`, 'problem');
      throw new Error(this.message!);
    }
  }

  /**
   * A link to this page carrying the result (the share-link codec, web/src/share/link.ts), and the
   * body it was learnt for, if it was.
   */
  async shareUrl(): Promise<string> {
    if (!this.result) throw new Error('there is no result to share yet');
    return this.host.transfer.shareUrl(this.result, this.resultBody?.json);
  }

  private async share(): Promise<void> {
    if (!this.result) throw new Error('there is no result to share yet');
    const { url, message } = await this.host.transfer.share(this.result, this.resultBody?.json);
    this.linkField.value = url;
    this.say(message);
  }
}
