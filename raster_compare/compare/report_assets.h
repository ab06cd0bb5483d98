// The report's style sheet and script (docs/report.md), inlined into every page: no external file,
// font or network. The script reads the page's data (a JSON block, id "so-data") to draw each
// light's chart for the error and cost its selectors name, sorts the tables, and opens the zoom
// view. The DOM it relies on is what tests/browser/report_test.mjs drives.
#pragma once

namespace so::report_assets {

inline constexpr const char* kStyle = R"css(
body{font-family:system-ui,sans-serif;margin:20px 24px;background:#f6f6f4;color:#222;font-size:14px}
h1{font-size:21px;margin:0 0 6px}h2{font-size:18px;margin:28px 0 8px}h3{font-size:15px;margin:18px 0 6px}
a{color:#0062a0}.muted{color:#666;font-size:12px}sup.fidelity{color:#9a4d00;font-size:11px;cursor:help}nav a{margin-right:12px}
.top{display:flex;flex-wrap:wrap;gap:18px;align-items:flex-start}
table{border-collapse:collapse;background:#fff;font-size:13px}th,td{padding:3px 7px;border-bottom:1px solid #ddd;text-align:right;white-space:nowrap}
th{background:#eee;position:sticky;top:0;z-index:1}th[data-col]{cursor:pointer}th[data-col]::after{content:" \2195";color:#aaa}
th.asc::after{content:" \25B2";color:#333}th.desc::after{content:" \25BC";color:#333}
td.text,th.text{text-align:left}td.best{font-weight:700;background:#e3f1e3}td.best::after{content:" \2605";color:#2a7a2a;font-size:10px}
.chart-box{background:#fff;border-radius:6px;padding:8px;box-shadow:0 1px 3px #0002}.chart-box select{margin:0 10px 4px 4px}
.chart .axis{stroke:#444}.chart .grid{stroke:#eee}.chart text{font-size:11px;fill:#444}.chart .label{fill:#222}
.chart .pt{fill:#888;cursor:pointer}.chart .pt.front{fill:#d55e00}.chart .curve{fill:none;stroke:#999;stroke-width:1.2}
.chart .oracle{fill:none;stroke:#0072b2;stroke-width:1.6}.chart .oracle-exact{fill:#0072b2;stroke:#fff;stroke-width:1}.chart .pareto{fill:none;stroke:#d55e00;stroke-width:1.5;stroke-dasharray:5 3}
.caption{font-size:12px;color:#444;max-width:640px;margin:4px 0}
table.images td,table.images th{vertical-align:top;text-align:left;white-space:normal}table.images th{max-width:250px}.summary-col{flex:1 1 100%;min-width:0}.summary-wrap{max-width:100%;overflow-x:auto}table.images img{display:block;width:240px;image-rendering:pixelated;cursor:zoom-in}
table.images img.crop{width:128px;display:inline-block;margin-right:4px}table.images tr:target{outline:3px solid #d55e00}
.sequence-box{background:#fff;border-radius:6px;padding:8px;box-shadow:0 1px 3px #0002;display:inline-block}.chart .series{fill:none;stroke-width:1.6}
.flicker-strip{display:flex;flex-wrap:wrap;gap:8px}.flicker-strip figure{margin:0}.flicker-strip img{display:block;width:240px;image-rendering:pixelated}
.legend span{display:inline-block;margin:2px 10px 2px 0;font-size:12px}.legend i{display:inline-block;width:11px;height:11px;margin-right:4px;vertical-align:-1px;box-shadow:0 0 0 1px #0006}
.note{background:#fff;border-left:4px solid #0072b2;padding:6px 10px;max-width:900px;font-size:13px}
#zoom{display:none;position:fixed;inset:0;background:#161616;z-index:10;color:#fff}#zoom.open{display:flex;flex-direction:column}
#zoom .bar{padding:8px 12px;display:flex;gap:12px;align-items:center}#zoom .view{overflow:auto;flex:1;padding:0 12px 12px}
#zoom canvas{image-rendering:pixelated;display:block}#zoom button,#zoom select{font-size:14px}
footer{margin-top:28px}
)css";

inline constexpr const char* kScript = R"js(
(() => {
const data = JSON.parse(document.getElementById('so-data').textContent);
const NS = 'http://www.w3.org/2000/svg';
const el = (tag, attrs, text) => {
  const e = document.createElementNS(NS, tag);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (text !== undefined) e.textContent = text;
  return e;
};
const fmt = v => v === 0 ? '0' : (Math.abs(v) >= 1e4 || Math.abs(v) < 1e-3) ? v.toExponential(0) : String(+v.toPrecision(3));
// Round log-scale ticks: 1, 2, 5 per decade, or decades only when that is too many.
const ticks = (lo, hi) => {
  const out = [];
  for (let d = Math.floor(Math.log10(lo)); d <= Math.ceil(Math.log10(hi)); ++d)
    for (const m of [1, 2, 5]) { const v = m * Math.pow(10, d); if (v >= lo * 0.999 && v <= hi * 1.001) out.push(v); }
  return out.length > 8 ? out.filter(v => Math.abs(Math.log10(v) - Math.round(Math.log10(v))) < 1e-9) : out;
};
const W = 640, H = 360, ML = 64, MR = 16, MT = 14, MB = 42;
function drawChart(box, L) {
  const svg = box.querySelector('svg.chart');
  const ek = box.querySelector('.error-select').value, ck = box.querySelector('.cost-select').value;
  const pts = L.points.filter(p => p.e[ek] != null && p.c[ck] != null).map(p => ({p, x: p.c[ck], y: p.e[ek]}));
  const oracle = ek === L.oracle_error && ck === 'frame_ms' ? L.oracle : [];
  // The exact pass's V has no sampling error: its point sits on the axis's bottom (0).
  const exact = ek === L.oracle_error && ck === 'frame_ms' ? L.oracle_exact : null;
  const xs = pts.map(q => q.x).concat(oracle.map(o => o[0]), exact ? [exact.ms] : []).filter(v => v > 0);
  const ys = pts.map(q => q.y).concat(oracle.map(o => o[1])).filter(v => v > 0);
  const x0 = xs.length ? Math.min(...xs) / 1.4 : 1e-3, x1 = xs.length ? Math.max(...xs) * 1.4 : 1;
  const y0 = ys.length ? Math.min(...ys) / 2 : 1e-4, y1 = ys.length ? Math.max(...ys) * 1.6 : 1;
  const X = v => ML + (W - ML - MR) * Math.log(Math.max(v, x0) / x0) / Math.log(x1 / x0);
  const Y = v => H - MB - (H - MB - MT) * Math.log(Math.max(v, y0) / y0) / Math.log(y1 / y0);
  svg.replaceChildren();
  for (const t of ticks(x0, x1)) {
    svg.append(el('line', {x1: X(t), x2: X(t), y1: MT, y2: H - MB, class: 'grid'}));
    svg.append(el('text', {x: X(t), y: H - MB + 15, 'text-anchor': 'middle'}, fmt(t)));
  }
  for (const t of ticks(y0, y1)) {
    svg.append(el('line', {x1: ML, x2: W - MR, y1: Y(t), y2: Y(t), class: 'grid'}));
    svg.append(el('text', {x: ML - 5, y: Y(t) + 4, 'text-anchor': 'end'}, fmt(t)));
  }
  svg.append(el('line', {x1: ML, x2: W - MR, y1: H - MB, y2: H - MB, class: 'axis'}));
  svg.append(el('line', {x1: ML, x2: ML, y1: MT, y2: H - MB, class: 'axis'}));
  const name = (list, k) => (list.find(o => o[0] === k) || [k, k])[1];
  svg.append(el('text', {x: (ML + W - MR) / 2, y: H - 6, 'text-anchor': 'middle'}, name(L.costs, ck) + ', log scale'));
  svg.append(el('text', {x: 12, y: (MT + H - MB) / 2, transform: `rotate(-90 12 ${(MT + H - MB) / 2})`, 'text-anchor': 'middle'},
                name(L.errors, ek) + ', log scale (0 at the bottom)'));
  if (oracle.length) {
    svg.append(el('polyline', {class: 'oracle', points: oracle.map(o => X(o[0]) + ',' + Y(o[1])).join(' ')}));
  }
  // The Pareto front: by cost, each point more accurate than every cheaper one.
  const sorted = [...pts].sort((a, b) => a.x - b.x || a.y - b.y), front = [];
  for (const q of sorted) if (!front.length || q.y < front[front.length - 1].y) front.push(q);
  if (front.length) svg.append(el('polyline', {class: 'pareto', points: front.map(q => X(q.x) + ',' + Y(q.y)).join(' ')}));
  const curves = new Map();
  for (const q of pts) if (q.p.quality != null) { if (!curves.has(q.p.curve)) curves.set(q.p.curve, []); curves.get(q.p.curve).push(q); }
  const placed = [];
  const fits = b => b.x >= ML && b.x + b.w <= W - MR && b.y >= MT && b.y + b.h <= H - MB &&
    !placed.some(o => b.x < o.x + o.w && o.x < b.x + b.w && b.y < o.y + o.h && o.y < b.y + b.h);
  const label = (x, y, text, cls) => {
    const w = 6.2 * text.length + 4, h = 12;
    for (const [dx, dy, anchor] of [[7, -5, 'start'], [-7, -5, 'end'], [7, 13, 'start'], [-7, 13, 'end']]) {
      const b = {x: anchor === 'start' ? x + dx : x + dx - w, y: y + dy - 10, w, h};
      if (!fits(b)) continue;
      placed.push(b);
      svg.append(el('text', {x: x + dx, y: y + dy, 'text-anchor': anchor, class: cls || 'label'}, text));
      return;
    }
  };
  for (const q of pts) placed.push({x: X(q.x) - 5, y: Y(q.y) - 5, w: 10, h: 10});
  for (const [key, list] of curves) {
    if (list.length < 2) { curves.delete(key); continue; }
    list.sort((a, b) => a.p.quality - b.p.quality);
    svg.append(el('polyline', {class: 'curve', points: list.map(q => X(q.x) + ',' + Y(q.y)).join(' ')}));
  }
  const onCurve = new Set([...curves.values()].flat());
  for (const q of pts) {
    const c = el('circle', {cx: X(q.x), cy: Y(q.y), r: 5, class: 'pt' + (front.includes(q) ? ' front' : ''), 'data-label': q.p.label});
    c.append(el('title', {}, `${q.p.label}: ${fmt(q.y)} at ${fmt(q.x)}`));
    c.addEventListener('click', () => { location.hash = '#' + q.p.row; });
    svg.append(c);
  }
  if (oracle.length) { const o = oracle[oracle.length - 1]; label(X(o[0]), Y(o[1]), 'oracle (its 95% half-width)'); }
  if (exact) {
    const x = X(exact.ms), y = H - MB, d = el('path', {class: 'oracle-exact', d: `M${x},${y - 7}L${x + 6},${y}L${x},${y + 7}L${x - 6},${y}Z`});
    d.append(el('title', {}, `oracle, exact pass: ${exact.pixels} pixels without sampling error in ${fmt(exact.ms)} ms`));
    svg.append(d);
    placed.push({x: x - 6, y: y - 7, w: 12, h: 14});
    label(x, y - 4, 'oracle, exact');
  }
  for (const q of [...front, ...pts.filter(q => !front.includes(q))]) {
    if (onCurve.has(q)) label(X(q.x), Y(q.y), q.p.curve.split(' ')[0] + ' ' + String(q.p.quality), 'label');
    else label(X(q.x), Y(q.y), q.p.label);
  }
  // The budget table of the cost selected (report.cpp writes one per cost).
  box.querySelectorAll('.budget-box').forEach(b => { b.hidden = b.dataset.cost !== ck; });
  box.querySelector('.caption').textContent = pts.length
    ? `${pts.length} settings. Orange dashed: the Pareto front (${front.map(q => q.p.label).join(', ')}): no other setting is both cheaper and more accurate. Grey lines join the settings of one technique that differ only in its quality parameter.` +
      (oracle.length ? ' Blue: the oracle, its penumbra\'s mean stated 95% half-width against its own time.' : '') +
      (exact ? ` Blue diamond on the axis: the oracle's exact pass (${exact.pixels} pixels, no sampling error), with the sampled pass that found them.` : '')
    : 'No setting has both values for this light.';
}
document.querySelectorAll('.chart-box').forEach(box => {
  const L = data.lights[+box.dataset.light];
  box.querySelectorAll('select').forEach(s => s.addEventListener('change', () => drawChart(box, L)));
  drawChart(box, L);
});
// Tables: numbers by data-v (empty cells last either way), text otherwise.
document.querySelectorAll('table.sortable th[data-col]').forEach(th => th.addEventListener('click', () => {
  const table = th.closest('table'), body = table.tBodies[0], col = [...th.parentNode.children].indexOf(th);
  const dir = th.classList.contains('asc') ? 'desc' : 'asc';
  table.querySelectorAll('th').forEach(h => h.classList.remove('asc', 'desc'));
  th.classList.add(dir);
  const key = r => { const c = r.cells[col]; return c.dataset.v === undefined ? c.textContent : c.dataset.v === '' ? null : parseFloat(c.dataset.v); };
  const rows = [...body.rows].sort((a, b) => {
    const x = key(a), y = key(b);
    if (x === null || y === null) return (x === null) - (y === null);
    const s = x < y ? -1 : x > y ? 1 : 0;
    return dir === 'asc' ? s : -s;
  });
  rows.forEach(r => body.appendChild(r));
}));
// The zoom view: one image at 1x, 2x or 4x, flipped with the oracle's at the same crop.
const zoom = document.getElementById('zoom'), canvas = document.getElementById('zoom-canvas');
const title = document.getElementById('zoom-title'), scaleSel = document.getElementById('zoom-scale');
let current = null, flipped = false;
const drawZoom = () => {
  const img = flipped ? document.getElementById(current.dataset.oracle) : current;
  const s = +scaleSel.value;
  canvas.width = img.naturalWidth * s; canvas.height = img.naturalHeight * s;
  const ctx = canvas.getContext('2d');
  ctx.imageSmoothingEnabled = false;
  ctx.drawImage(img, 0, 0, canvas.width, canvas.height);
  title.textContent = (flipped ? 'oracle' : current.alt) + ` (${s}x; F flips, Esc closes)`;
};
document.querySelectorAll('img.zoomable').forEach(img => img.addEventListener('click', () => {
  current = img; flipped = false; zoom.classList.add('open'); drawZoom();
}));
const close = () => zoom.classList.remove('open');
document.getElementById('zoom-flip').addEventListener('click', () => { flipped = !flipped; drawZoom(); });
document.getElementById('zoom-close').addEventListener('click', close);
scaleSel.addEventListener('change', drawZoom);
document.addEventListener('keydown', e => {
  if (!zoom.classList.contains('open')) return;
  if (e.key === 'Escape') close();
  if (e.key === 'f' || e.key === 'F') { flipped = !flipped; drawZoom(); }
});
})();
)js";

}  // namespace so::report_assets
