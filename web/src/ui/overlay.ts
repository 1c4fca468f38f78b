// What is written over the canvas: the heads-up line (frame rate, real-time factor, characters,
// threads, how the page runs, draw calls), a one-line help, passing messages (a refused link,
// an imported file) and the notice shown instead of a silent blank page when something is wrong.

export interface HudFigures {
  fps: number;
  realtimeFactor: number;
  characters: number;
  fallen: number;
  threads: number;
  /** How the page gets its threads: see isolation.ts. */
  mode: string;
  drawCalls: number;
  /** Dynamic resolution's scale (1 = full). */
  renderScale: number;
  paused: boolean;
  timeScale: number;
  selected: string | null;
}

function element<K extends keyof HTMLElementTagNameMap>(tag: K, className: string, text = ''): HTMLElementTagNameMap[K] {
  const node = document.createElement(tag);
  node.className = className;
  node.textContent = text;
  return node;
}

export class Overlay {
  private readonly hud: HTMLElement;
  private readonly line: HTMLElement;
  private readonly messages: HTMLElement;
  private readonly notice: HTMLElement;
  /** Under the heads-up line and above the messages: where the optimize panel sits. */
  readonly column: HTMLElement;

  constructor(parent: HTMLElement) {
    this.hud = element('div', 'hud');
    this.line = element('div', 'hud-line', 'gaitlab — starting…');
    this.line.setAttribute('data-testid', 'hud');
    const help = element(
      'div',
      'hud-help',
      'click the ground: throw a box · shift-click: throw at a character · click a character: select · drag a body: pull it · ' +
        'W/S speed · A/D turn · F follow · space pause · . step · R reset · Del remove · Esc deselect',
    );
    this.messages = element('div', 'messages');
    this.messages.setAttribute('role', 'status');
    this.column = element('div', 'hud-column');
    this.hud.append(this.line, help, this.column, this.messages);

    this.notice = element('div', 'notice');
    this.notice.hidden = true;
    this.notice.setAttribute('role', 'alert');
    parent.append(this.hud, this.notice);
  }

  /**
   * The heads-up line; `compact` (phones) keeps it to one short line: frame rate, real-time
   * factor, characters and the selection.
   */
  show(f: HudFigures, compact = false): void {
    if (compact) {
      const rate = f.paused ? 'paused' : `${f.realtimeFactor.toFixed(2)}×`;
      const down = f.fallen ? ` (${f.fallen} down)` : '';
      this.line.textContent = [`${f.fps.toFixed(0)} FPS`, rate, `${f.characters} characters${down}`, ...(f.selected ? [f.selected] : [])].join(' · ');
      return;
    }
    const rate = f.paused ? 'paused' : `${f.realtimeFactor.toFixed(2)}× real time${f.timeScale !== 1 ? ` (slow motion ${f.timeScale}×)` : ''}`;
    const parts = [
      `${f.fps.toFixed(0)} FPS`,
      rate,
      `${f.characters} characters${f.fallen ? ` (${f.fallen} down)` : ''}`,
      `${f.threads} thread${f.threads === 1 ? '' : 's'}`,
      f.mode,
      `${f.drawCalls} draw calls`,
    ];
    if (f.renderScale < 1) parts.push(`render scale ${Math.round(f.renderScale * 100)}%`);
    if (f.selected) parts.push(`selected: ${f.selected}`);
    this.line.textContent = parts.join(' · ');
  }

  /**
   * A message that stays until dismissed: refused links and files say what was wrong, so the
   * user knows why the presets run instead.
   */
  message(text: string, kind: 'info' | 'problem' = 'info'): void {
    const item = element('div', `message message-${kind}`);
    item.append(element('span', '', text));
    const close = element('button', 'message-close', '×');
    close.type = 'button';
    close.title = 'dismiss';
    close.addEventListener('click', () => item.remove());
    item.append(close);
    this.messages.append(item);
    // Informational messages go by themselves; problems stay until read.
    if (kind === 'info') setTimeout(() => item.remove(), 12_000);
  }

  /** Shows a problem in plain words on the page (not only in the console). */
  showNotice(title: string, detail: string): void {
    this.notice.replaceChildren(element('strong', '', title), element('p', '', detail));
    this.notice.hidden = false;
  }
}
