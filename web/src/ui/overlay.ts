// The small status panel over the canvas (frame rate, real-time factor, bodies, threads, with
// pause and reset), and the notice shown instead of a silent blank page when something is wrong.

export interface OverlayFigures {
  fps: number;
  realtimeFactor: number;
  bodies: number;
  threads: number;
  stepMs: number;
  paused: boolean;
}

export interface OverlayActions {
  onPauseToggle: () => void;
  onReset: () => void;
}

function element<K extends keyof HTMLElementTagNameMap>(tag: K, className: string, text = ''): HTMLElementTagNameMap[K] {
  const node = document.createElement(tag);
  node.className = className;
  node.textContent = text;
  return node;
}

export class Overlay {
  private readonly panel: HTMLElement;
  private readonly fields: Record<'fps' | 'realtime' | 'bodies' | 'threads' | 'step', HTMLElement>;
  private readonly pauseButton: HTMLButtonElement;
  private readonly resetButton: HTMLButtonElement;
  private readonly notice: HTMLElement;

  constructor(parent: HTMLElement, actions: OverlayActions) {
    this.panel = element('div', 'overlay');
    this.panel.append(element('div', 'overlay-title', 'gaitlab'));
    const rows = element('dl', 'overlay-figures');
    const row = (label: string, title: string) => {
      const value = element('dd', '', '–');
      const term = element('dt', '', label);
      term.title = value.title = title;
      rows.append(term, value);
      return value;
    };
    this.fields = {
      fps: row('FPS', 'rendered frames per second'),
      realtime: row('real time', 'simulated seconds per wall-clock second (1× = real time)'),
      bodies: row('bodies', 'rigid bodies simulated and drawn'),
      threads: row('threads', 'threads of the simulation (navigator.hardwareConcurrency, at most 4)'),
      step: row('step', 'wall-clock time per 1/120 s physics step, in the sim worker'),
    };
    this.panel.append(rows);

    const buttons = element('div', 'overlay-buttons');
    this.pauseButton = element('button', '', 'Pause');
    this.pauseButton.type = 'button';
    this.pauseButton.addEventListener('click', actions.onPauseToggle);
    this.resetButton = element('button', '', 'Reset');
    this.resetButton.type = 'button';
    this.resetButton.addEventListener('click', actions.onReset);
    this.setControlsEnabled(false);
    buttons.append(this.pauseButton, this.resetButton);
    this.panel.append(buttons);

    this.notice = element('div', 'notice');
    this.notice.hidden = true;
    this.notice.setAttribute('role', 'alert');
    parent.append(this.panel, this.notice);
  }

  setControlsEnabled(enabled: boolean): void {
    this.pauseButton.disabled = this.resetButton.disabled = !enabled;
  }

  show(figures: OverlayFigures): void {
    this.fields.fps.textContent = figures.fps.toFixed(0);
    this.fields.realtime.textContent = figures.paused ? 'paused' : `${figures.realtimeFactor.toFixed(2)}×`;
    this.fields.bodies.textContent = String(figures.bodies);
    this.fields.threads.textContent = String(figures.threads);
    this.fields.step.textContent = figures.stepMs > 0 ? `${figures.stepMs.toFixed(2)} ms` : '–';
    this.pauseButton.textContent = figures.paused ? 'Resume' : 'Pause';
  }

  /** Shows a problem in plain words on the page (not only in the console). */
  showNotice(title: string, detail: string): void {
    this.notice.replaceChildren(element('strong', '', title), element('p', '', detail));
    this.notice.hidden = false;
  }
}
