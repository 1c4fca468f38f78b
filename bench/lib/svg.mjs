// A small SVG chart writer for the benchmark's figures (bench/results/*.svg): line charts with
// optional standard-deviation bands (as the thesis's Figures 5.1-5.4 draw them) and grouped bar
// charts. Self-contained files, no fonts or scripts, readable on GitHub.

const W = 720, H = 420;
const M = { left: 72, right: 200, top: 48, bottom: 56 };
export const PALETTE = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf', '#7f7f7f', '#bcbd22'];

const esc = (s) => String(s).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;');
const num = (v) => (Number.isInteger(v) ? String(v) : Math.abs(v) >= 100 ? v.toFixed(0) : Math.abs(v) >= 10 ? v.toFixed(1) : Math.abs(v) >= 1 ? v.toFixed(2) : v.toPrecision(2));

/** "Nice" tick values from lo up to the first tick at or above hi. */
function ticks(lo, hi, count = 6) {
  if (!(hi > lo)) hi = lo + 1;
  const raw = (hi - lo) / count;
  const mag = 10 ** Math.floor(Math.log10(raw));
  const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => s >= raw) ?? 10 * mag;
  const out = [];
  let v = Math.ceil(lo / step - 1e-9) * step;
  for (;;) {
    out.push(+v.toFixed(12));
    if (v >= hi - step * 1e-9) return out;
    v += step;
  }
}

function frame({ title, subtitle, xLabel, yLabel }, x, y, xTicks, yTicks, body, legend) {
  const pw = W - M.left - M.right, ph = H - M.top - M.bottom;
  const grid = yTicks.map((t) => `<line x1="${M.left}" x2="${M.left + pw}" y1="${y(t)}" y2="${y(t)}" stroke="#e4e4e4"/>` +
    `<text x="${M.left - 6}" y="${y(t) + 4}" text-anchor="end">${num(t)}</text>`).join('');
  const xt = xTicks.map((t) => `<line x1="${x(t.v)}" x2="${x(t.v)}" y1="${M.top + ph}" y2="${M.top + ph + 4}" stroke="#444"/>` +
    `<text x="${x(t.v)}" y="${M.top + ph + 18}" text-anchor="middle">${esc(t.label)}</text>`).join('');
  const leg = legend.map((l, i) => {
    const ly = M.top + 8 + i * 18;
    const mark = l.bar
      ? `<rect x="${W - M.right + 16}" y="${ly - 8}" width="18" height="10" fill="${l.color}"/>`
      : `<line x1="${W - M.right + 14}" x2="${W - M.right + 36}" y1="${ly - 3}" y2="${ly - 3}" stroke="${l.color}" stroke-width="2.5"${l.dash ? ` stroke-dasharray="${l.dash}"` : ''}/>`;
    return `${mark}<text x="${W - M.right + 42}" y="${ly + 1}">${esc(l.name)}</text>`;
  }).join('');
  return `<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${H}" viewBox="0 0 ${W} ${H}" font-family="sans-serif" font-size="11">
<rect width="${W}" height="${H}" fill="#fff"/>
<text x="${M.left}" y="20" font-size="14" font-weight="bold">${esc(title)}</text>
${subtitle ? `<text x="${M.left}" y="36" fill="#555">${esc(subtitle)}</text>` : ''}
${grid}${body}
<line x1="${M.left}" x2="${M.left}" y1="${M.top}" y2="${M.top + ph}" stroke="#444"/>
<line x1="${M.left}" x2="${M.left + pw}" y1="${M.top + ph}" y2="${M.top + ph}" stroke="#444"/>
${xt}
<text x="${M.left + pw / 2}" y="${H - 12}" text-anchor="middle">${esc(xLabel)}</text>
<text transform="translate(16 ${M.top + ph / 2}) rotate(-90)" text-anchor="middle">${esc(yLabel)}</text>
${leg}
</svg>
`;
}

/**
 * Line chart. series: [{ name, color?, dash?, points: [{ x, y, sd? }] }]; a series with sd gets
 * a translucent band y ± sd. Options: title, subtitle, xLabel, yLabel, yMin (default 0),
 * hline: { y, label } (e.g. the 120 Hz budget).
 */
export function lineChart({ series, hline, yMin = 0, ...text }) {
  const all = series.flatMap((s) => s.points);
  const xs = all.map((p) => p.x);
  const ys = all.flatMap((p) => [p.y + (p.sd ?? 0)]).concat(hline ? [hline.y] : []);
  const x0 = Math.min(...xs), x1 = Math.max(...xs);
  const yTicks = ticks(yMin, Math.max(...ys, yMin + 1e-9) * 1.05);
  const y1 = yTicks[yTicks.length - 1];
  const pw = W - M.left - M.right, ph = H - M.top - M.bottom;
  const x = (v) => +(M.left + (x1 > x0 ? (v - x0) / (x1 - x0) : 0.5) * pw).toFixed(1);
  const y = (v) => +(M.top + ph - ((Math.min(Math.max(v, yMin), y1) - yMin) / (y1 - yMin)) * ph).toFixed(1);
  let body = '';
  series.forEach((s, i) => {
    const color = s.color ?? PALETTE[i % PALETTE.length];
    s.color = color;
    const pts = [...s.points].sort((a, b) => a.x - b.x);
    if (pts.some((p) => p.sd)) {
      const upper = pts.map((p) => `${x(p.x)},${y(p.y + (p.sd ?? 0))}`);
      const lower = pts.map((p) => `${x(p.x)},${y(p.y - (p.sd ?? 0))}`).reverse();
      body += `<polygon points="${[...upper, ...lower].join(' ')}" fill="${color}" fill-opacity="0.15" stroke="none"/>`;
    }
    body += `<polyline points="${pts.map((p) => `${x(p.x)},${y(p.y)}`).join(' ')}" fill="none" stroke="${color}" stroke-width="2"${s.dash ? ` stroke-dasharray="${s.dash}"` : ''}/>`;
    if (pts.length <= 30) body += pts.map((p) => `<circle cx="${x(p.x)}" cy="${y(p.y)}" r="2.5" fill="${color}"/>`).join('');
  });
  if (hline) {
    body += `<line x1="${M.left}" x2="${M.left + pw}" y1="${y(hline.y)}" y2="${y(hline.y)}" stroke="#000" stroke-dasharray="6 4"/>` +
      `<text x="${M.left + pw - 4}" y="${y(hline.y) - 5}" text-anchor="end">${esc(hline.label)}</text>`;
  }
  const xTicks = ticks(x0, x1, 8).filter((v) => v >= x0 && v <= x1).map((v) => ({ v, label: num(v) }));
  return frame(text, x, y, xTicks, yTicks, body, series.map((s) => ({ name: s.name, color: s.color, dash: s.dash })));
}

/**
 * Grouped bar chart. groups: ['1 thread', '2 threads']; bars: [{ name, color?, values: [..] }]
 * (one value per group; null = not measured). Values are written on the bars.
 */
export function barChart({ groups, bars, hline, ...text }) {
  const max = Math.max(1e-9, ...bars.flatMap((b) => b.values.filter((v) => v !== null)), hline ? hline.y : 0);
  const yTicks = ticks(0, max * 1.1);
  const y1 = yTicks[yTicks.length - 1];
  const pw = W - M.left - M.right, ph = H - M.top - M.bottom;
  const y = (v) => +(M.top + ph - (v / y1) * ph).toFixed(1);
  const gw = pw / groups.length, bw = (gw * 0.8) / bars.length;
  let body = '';
  bars.forEach((b, j) => {
    b.color = b.color ?? PALETTE[j % PALETTE.length];
    b.values.forEach((v, g) => {
      if (v === null || v === undefined) return;
      const bx = M.left + g * gw + gw * 0.1 + j * bw;
      body += `<rect x="${bx.toFixed(1)}" y="${y(v)}" width="${(bw - 2).toFixed(1)}" height="${(M.top + ph - y(v)).toFixed(1)}" fill="${b.color}"/>` +
        `<text x="${(bx + bw / 2).toFixed(1)}" y="${y(v) - 3}" text-anchor="middle" font-size="10">${num(v)}</text>`;
    });
  });
  if (hline) {
    body += `<line x1="${M.left}" x2="${M.left + pw}" y1="${y(hline.y)}" y2="${y(hline.y)}" stroke="#000" stroke-dasharray="6 4"/>` +
      `<text x="${M.left + pw - 4}" y="${y(hline.y) - 5}" text-anchor="end">${esc(hline.label)}</text>`;
  }
  const x = (v) => v;
  const xTicks = groups.map((label, g) => ({ v: M.left + g * gw + gw / 2, label }));
  return frame(text, x, y, xTicks, yTicks, body, bars.map((b) => ({ name: b.name, color: b.color, bar: true })));
}
