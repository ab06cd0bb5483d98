#!/usr/bin/env node
// Drives headless Chromium (the system one, through puppeteer-core) over the HTML pages that
// `shadow-oracle compare` and `shadow-oracle index` write, and checks what a reader does with them:
//
//   node report_test.mjs --screenshots DIR [--index INDEX.html] [--browser PATH] REPORT.html...
//
// Every page: no console error, no page error, no request outside file:, data: and blob: (those are
// aborted and count as failures), no broken <img> (lazy ones are loaded); a full-page PNG goes to DIR.
// Every report page, per light (<section class="light">):
//   table.summary: a click on a th[data-col] whose column holds numbers sorts the rows ascending by
//     the cells' data-v, empty data-v last; a second click sorts descending, empty still last;
//   .chart-box: another option of select.error-select changes the circle.pt of svg.chart (their cy
//     values or their count); with data-exact, penumbra_mae against frame_ms draws path.oracle-exact
//     (the oracle's exact penumbra pass) with its title;
// and once per page: a click on the first visible img.zoomable opens #zoom (class "open", visible)
// with a drawn #zoom-canvas; #zoom-flip changes the canvas pixels (read with toDataURL, or as an
// element screenshot where file: images taint the canvas); where the first image's flip changes
// nothing (the oracle's own, which flips to itself) the next images are tried, up to 8; Escape
// closes #zoom, #zoom-close too. Screenshots of the zoom view go to DIR as well.
// The index page: at least one table.matrix; every relative a[href] names an existing file; every
// report given on the command line is linked.
// One line per check (PASS/FAIL/NOTE); exit 1 on any failure, 2 on bad arguments, 0 otherwise.
import fs from 'node:fs';
import path from 'node:path';
import {fileURLToPath, pathToFileURL} from 'node:url';

import puppeteer from 'puppeteer-core';

const USAGE = 'usage: node report_test.mjs --screenshots DIR [--index INDEX.html] [--browser PATH] REPORT.html...';
const WAIT_MS = 5000;  // the longest any single UI reaction may take

function parseArgs(argv) {
  const a = {screenshots: null, index: null, browser: null, reports: []};
  for (let i = 0; i < argv.length; i++) {
    const k = argv[i];
    const value = () => {
      if (i + 1 >= argv.length) usageError(`${k} needs a value`);
      return argv[++i];
    };
    if (k === '--screenshots') a.screenshots = value();
    else if (k === '--index') a.index = value();
    else if (k === '--browser') a.browser = value();
    else if (k === '-h' || k === '--help') { console.log(USAGE); process.exit(0); }
    else if (k.startsWith('--')) usageError(`unknown option ${k}`);
    else a.reports.push(k);
  }
  if (!a.screenshots) usageError('--screenshots DIR is required');
  if (a.reports.length === 0 && !a.index) usageError('no page to check');
  for (const f of [...a.reports, ...(a.index ? [a.index] : [])])
    if (!fs.existsSync(f)) usageError(`no such file: ${f}`);
  return a;
}

function usageError(msg) {
  console.error(`report_test: ${msg}\n${USAGE}`);
  process.exit(2);
}

function findBrowser(given) {
  const candidates = [given, process.env.CHROMIUM, '/usr/bin/chromium', '/usr/bin/chromium-browser',
                      '/usr/bin/google-chrome'].filter(Boolean);
  return candidates.find(p => fs.existsSync(p)) ?? null;
}

// --- results -------------------------------------------------------------------------------------

let checks = 0, failures = 0;
function check(ok, where, what) {
  checks++;
  if (!ok) failures++;
  console.log(`${ok ? 'PASS' : 'FAIL'} ${where}: ${what}`);
  return ok;
}
const note = (where, what) => console.log(`NOTE ${where}: ${what}`);

// Polls fn() (async) until pred(value) holds or WAIT_MS passes; returns the last value and whether
// pred held. The UI may react in a later task or animation frame, so nothing is read just once.
async function poll(fn, pred, ms = WAIT_MS) {
  const end = Date.now() + ms;
  for (;;) {
    const v = await fn();
    if (pred(v)) return {ok: true, value: v};
    if (Date.now() > end) return {ok: false, value: v};
    await new Promise(r => setTimeout(r, 50));
  }
}

// --- pages ---------------------------------------------------------------------------------------

const ALLOWED_SCHEMES = new Set(['file:', 'data:', 'blob:']);

async function openPage(browser, file) {
  const page = await browser.newPage();
  page.setDefaultTimeout(20000);
  await page.setViewport({width: 1280, height: 900});
  const problems = {console: [], page: [], blocked: [], failed: []};
  page.on('console', m => { if (m.type() === 'error') problems.console.push(m.text()); });
  page.on('pageerror', e => problems.page.push(String(e?.message ?? e)));
  await page.setRequestInterception(true);
  page.on('request', req => {
    if (req.isInterceptResolutionHandled()) return;
    let scheme = '';
    try { scheme = new URL(req.url()).protocol; } catch { /* not a URL: block it */ }
    if (ALLOWED_SCHEMES.has(scheme)) return req.continue();
    problems.blocked.push(req.url().slice(0, 120));
    return req.abort('blockedbyclient');
  });
  page.on('requestfailed', req => {
    const url = req.url();
    if (!problems.blocked.includes(url.slice(0, 120)))
      problems.failed.push(`${url.slice(0, 120)} (${req.failure()?.errorText})`);
  });
  const url = pathToFileURL(path.resolve(file)).href;
  const response = await page.goto(url, {waitUntil: 'load', timeout: 60000});
  return {page, problems, url, status: response?.status()};
}

// Waits for every <img> (lazy ones are made eager: a screenshot is no scroll) and lists the broken.
async function checkImages(page, where) {
  const r = await page.evaluate(async ms => {
    const imgs = [...document.images];
    for (const i of imgs) if (i.loading === 'lazy') i.loading = 'eager';
    await Promise.all(imgs.map(i => i.complete ? null : new Promise(res => {
      i.addEventListener('load', res, {once: true});
      i.addEventListener('error', res, {once: true});
      setTimeout(res, ms);
    })));
    const broken = imgs.filter(i => !i.complete || i.naturalWidth === 0)
        .map(i => `${i.alt || '(no alt)'} <${(i.getAttribute('src') ?? '').slice(0, 60)}>`);
    return {count: imgs.length, broken};
  }, 3 * WAIT_MS);
  check(r.broken.length === 0, where,
        r.broken.length === 0 ? `${r.count} <img> all decoded` : `${r.broken.length} of ${r.count} <img> broken: ${r.broken.slice(0, 5).join('; ')}`);
}

function checkProblems(problems, where) {
  const list = (xs) => xs.slice(0, 5).map(x => `\n      ${x}`).join('') + (xs.length > 5 ? `\n      ... ${xs.length - 5} more` : '');
  check(problems.blocked.length === 0, where,
        problems.blocked.length === 0 ? 'no request outside file:/data:/blob:' : `${problems.blocked.length} request(s) outside file:/data:/blob: blocked:${list(problems.blocked)}`);
  check(problems.failed.length === 0, where,
        problems.failed.length === 0 ? 'no failed request' : `${problems.failed.length} failed request(s):${list(problems.failed)}`);
  check(problems.page.length === 0, where,
        problems.page.length === 0 ? 'no page error' : `${problems.page.length} page error(s):${list(problems.page)}`);
  check(problems.console.length === 0, where,
        problems.console.length === 0 ? 'no console error' : `${problems.console.length} console error(s):${list(problems.console)}`);
}

async function screenshot(page, file, fullPage) {
  await page.screenshot({path: file, fullPage, captureBeyondViewport: fullPage});
  return file;
}

// --- report: the summary table -------------------------------------------------------------------

// Body rows: every row of the table's bodies that holds no sortable header.
async function columnValues(table, index) {
  return table.evaluate((t, i) => [...t.tBodies].flatMap(b => [...b.rows])
      .filter(r => !r.querySelector('th[data-col]'))
      .map(r => r.cells[i] ? r.cells[i].getAttribute('data-v') : null), index);
}

function ordered(values, dir) {
  let seenEmpty = false, prev = null;
  for (const v of values) {
    if (v === '' || v === null) { seenEmpty = true; continue; }
    if (seenEmpty) return false;  // a number after an empty cell
    const x = parseFloat(v);
    if (prev !== null && (dir === 'asc' ? x < prev : x > prev)) return false;
    prev = x;
  }
  return true;
}

const sameMultiset = (a, b) => a.length === b.length && [...a].sort().join('\u0001') === [...b].sort().join('\u0001');

async function checkSort(page, section, where) {
  const table = await section.$('table.summary');
  if (!table) {
    // A class attribute written twice keeps only the first: list what the section's tables have.
    const classes = await section.$$eval('table', ts => ts.map(t => `table.${[...t.classList].join('.')}`));
    check(false, where, `no table.summary (the section's tables: ${classes.join(', ') || 'none'})`);
    return;
  }
  check(true, where, 'has table.summary');
  // The header to click: a th[data-col] whose body cells all carry data-v, numbers or empty, with at
  // least two distinct numbers; one with empty cells as well is preferred.
  const columns = await table.evaluate(t => {
    const rows = [...t.tBodies].flatMap(b => [...b.rows]).filter(r => !r.querySelector('th[data-col]'));
    return [...t.querySelectorAll('th[data-col]')].map((th, k) => ({
      k, key: th.dataset.col, index: th.cellIndex,
      values: rows.map(r => r.cells[th.cellIndex] ? r.cells[th.cellIndex].getAttribute('data-v') : null)}));
  });
  if (!check(columns.length > 0, where, `table.summary has ${columns.length} th[data-col]`)) return;
  const numeric = columns.filter(c => c.values.every(v => v === '' || (v !== null && Number.isFinite(parseFloat(v))))
                                      && new Set(c.values.filter(v => v !== '').map(parseFloat)).size >= 2);
  const col = numeric.find(c => c.values.includes('')) ?? numeric[0];
  if (!check(!!col, where, col ? `sortable numeric column "${col.key}" (${col.values.length} rows, ${col.values.filter(v => v === '').length} empty)`
                               : `no th[data-col] column with data-v numbers in every body cell: ${columns.map(c => c.key).join(', ')}`)) return;
  const before = col.values;
  const headers = await table.$$('th[data-col]');
  for (const dir of ['asc', 'desc']) {
    await headers[col.k].click();
    const r = await poll(() => columnValues(table, col.index), v => sameMultiset(v, before) && ordered(v, dir), 2000);
    check(r.ok, where, `click ${dir === 'asc' ? '1' : '2'} on th[data-col=${col.key}] sorts ${dir === 'asc' ? 'ascending' : 'descending'}, empty last` +
          (r.ok ? '' : `: data-v order is [${r.value.map(v => v === '' ? '∅' : v).join(', ')}]` +
                       (sameMultiset(r.value, before) ? '' : ' (not the same cells as before)')));
  }
}

// --- report: the chart ---------------------------------------------------------------------------

async function pointSignature(box) {
  return box.evaluate(b => {
    const cy = [...b.querySelectorAll('svg.chart circle.pt')].map(c => c.getAttribute('cy'));
    return {count: cy.length, bad: cy.filter(v => !Number.isFinite(parseFloat(v))).length,
            key: cy.map(v => parseFloat(v)).sort((x, y) => x - y).join(',')};
  });
}

// A chart-box with data-exact (the oracle's exact penumbra pass applied to its light) draws the
// pass's point (path.oracle-exact) on the bottom axis when penumbra_mae is plotted against frame ms.
async function checkExactPoint(box, sel, where) {
  if (!(await box.evaluate(b => b.dataset.exact === '1'))) return;
  const cost = await box.$('select.cost-select');
  if (cost) await cost.select('frame_ms');
  await sel.select('penumbra_mae');
  const r = await poll(() => box.evaluate(b => {
    const p = b.querySelector('svg.chart path.oracle-exact');
    return p ? {d: p.getAttribute('d'), title: (p.querySelector('title') || {}).textContent || ''} : null;
  }), v => v !== null, 1500);
  check(r.ok && /^M[\d.]+,[\d.]+L/.test(r.value.d) && /pixels without sampling error/.test(r.value.title), where,
        'data-exact: the chart draws the exact pass\'s point (path.oracle-exact)' + (r.ok ? `: "${r.value.title}"` : ': none drawn'));
}

async function checkChart(page, section, where) {
  const box = await section.$('.chart-box');
  if (!check(!!box, where, 'has .chart-box')) return;
  const sel = await box.$('select.error-select');
  const svg = await box.$('svg.chart');
  if (!check(!!sel && !!svg, where, '.chart-box has select.error-select and svg.chart')) return;
  const {options, current} = await sel.evaluate(s => ({options: [...s.options].map(o => o.value), current: s.value}));
  const before = await pointSignature(box);
  if (!check(before.count > 0 && before.bad === 0, where,
             `chart draws ${before.count} circle.pt for "${current}"` + (before.bad ? `, ${before.bad} with a cy that is not a number` : ''))) return;
  await checkExactPoint(box, sel, where);
  await sel.select(current);
  await poll(() => pointSignature(box), s => s.count === before.count && s.key === before.key, 1500);
  const others = options.filter(o => o !== current);
  if (!check(others.length > 0, where, `select.error-select offers ${options.length} option(s): ${options.join(', ')}`)) return;
  const tried = [];
  for (const o of others) {
    await sel.select(o);
    const r = await poll(() => pointSignature(box), s => s.count !== before.count || s.key !== before.key, 1500);
    tried.push(`${o}: ${r.value.count} pts`);
    if (r.ok) {
      check(r.value.bad === 0, where,
            `error-select "${current}" -> "${o}" redraws the points (${before.count} -> ${r.value.count} circle.pt, cy changed)` +
            (r.value.bad ? `, but ${r.value.bad} have a cy that is not a number` : ''));
      return;
    }
  }
  check(false, where, `no other option of select.error-select changes the circle.pt cy values or count (from "${current}": ${tried.join('; ')})`);
}

// A work axis (docs/metrics.md, Work): select.cost-select offers work.* costs; choosing one redraws
// the points at new x positions, keeps the Pareto front (where the chart draws one) and shows that
// cost's budget table (.budget-box[data-cost]) alone. A screenshot of the box is kept.
async function chartXs(box) {
  return box.evaluate(b => [...b.querySelectorAll('svg.chart circle.pt')].map(c => c.getAttribute('cx')));
}

async function checkWorkAxis(box, where, shotFile) {
  const cost = await box.$('select.cost-select');
  if (!check(!!cost, where, '.chart-box has select.cost-select')) return;
  const {options, current} = await cost.evaluate(s => ({options: [...s.options].map(o => o.value), current: s.value}));
  const work = options.filter(o => o.startsWith('work.'));
  if (!check(work.length > 0, where, `select.cost-select offers work axes (${work.join(', ') || 'none of: ' + options.join(', ')})`)) return;
  const axis = work.includes('work.bytes_moved') ? 'work.bytes_moved' : work[0];
  const before = await chartXs(box);
  const hadFront = await box.evaluate(b => !!b.querySelector('svg.chart polyline.pareto'));
  await cost.select(axis);
  const r = await poll(() => chartXs(box), xs => xs.length > 0 && xs.join() !== before.join(), 1500);
  check(r.ok && r.value.every(x => Number.isFinite(parseFloat(x))), where,
        `cost-select "${current}" -> "${axis}" redraws ${r.value.length} circle.pt at new x positions`);
  if (hadFront)
    check(await box.evaluate(b => !!b.querySelector('svg.chart polyline.pareto')), where, `the Pareto front is drawn against "${axis}"`);
  const budgets = await box.evaluate(b => [...b.querySelectorAll('.budget-box')].map(d => ({cost: d.dataset.cost, hidden: d.hidden})));
  if (budgets.length > 0) {
    const shown = budgets.filter(b => !b.hidden).map(b => b.cost);
    check(shown.length === 1 && shown[0] === axis, where,
          `the budget table shown is "${axis}"'s alone (shown: ${shown.join(', ') || 'none'} of ${budgets.length})`);
  }
  note(where, `screenshot ${shotFile}`);
  await box.screenshot({path: shotFile});
  await cost.select(current);
}

// --- report: the zoom view -----------------------------------------------------------------------

const zoomState = page => page.evaluate(() => {
  const z = document.getElementById('zoom');
  if (!z) return {exists: false};
  const s = getComputedStyle(z), r = z.getBoundingClientRect();
  const visible = s.display !== 'none' && s.visibility !== 'hidden' && parseFloat(s.opacity) > 0 && r.width > 0 && r.height > 0;
  return {exists: true, open: z.classList.contains('open'), visible};
});

// The canvas's pixels as a string (`pixels`), and whether it holds anything (a blank canvas of the
// same size reads back differently). Its data URL where it can be read back; where it cannot (drawn
// from images in files: a file: page's images taint the canvas), a PNG screenshot of the element
// (a tainted canvas has had an image drawn on it, so it counts as drawn).
async function canvasState(page) {
  const s = await page.evaluate(() => {
    const c = document.getElementById('zoom-canvas');
    if (!c) return {exists: false};
    if (!(c instanceof HTMLCanvasElement)) return {exists: true, error: `#zoom-canvas is a <${c.localName}>`};
    const r = {exists: true, width: c.width, height: c.height};
    if (c.width === 0 || c.height === 0) return {...r, pixels: '', drawn: false};
    try {
      const blank = document.createElement('canvas');
      blank.width = c.width; blank.height = c.height;
      const pixels = c.toDataURL();
      return {...r, pixels, drawn: pixels !== blank.toDataURL(), how: 'toDataURL'};
    } catch (e) {
      if (e.name === 'SecurityError') return {...r, tainted: true, drawn: true};
      return {...r, error: `toDataURL: ${e.name}: ${e.message}`};
    }
  });
  if (s.tainted) {
    const h = await page.$('#zoom-canvas');
    s.pixels = Buffer.from(await h.screenshot({type: 'png'})).toString('base64');
    s.how = 'an element screenshot (the canvas is tainted by file: images)';
  }
  return s;
}

// Waits until the canvas is drawn and unchanged over two reads (the image may decode late).
async function stableCanvas(page) {
  let last = null;
  return poll(() => canvasState(page), s => {
    const stable = s.drawn && last !== null && s.pixels === last;
    last = s.pixels ?? null;
    return stable || !!s.error;
  });
}

async function closeZoom(page, how) {
  if (how === 'Escape') await page.keyboard.press('Escape');
  else await page.click('#zoom-close');
  return poll(() => zoomState(page), s => !s.open && !s.visible);
}

async function openZoom(page, img) {
  await img.click();
  return poll(() => zoomState(page), s => s.open && s.visible);
}

async function checkZoom(page, where, shotBase) {
  const all = await page.$$('img.zoomable');
  const imgs = [];
  for (const h of all) { const b = await h.boundingBox(); if (b && b.width > 0 && b.height > 0) imgs.push(h); }
  if (!check(imgs.length > 0, where, `${all.length} img.zoomable, ${imgs.length} visible`)) return;
  const alt = h => h.evaluate(i => i.alt || i.getAttribute('src').slice(0, 40));

  const opened = await openZoom(page, imgs[0]);
  if (!check(opened.ok, where, `click on the first img.zoomable ("${await alt(imgs[0])}") opens #zoom` +
             (opened.ok ? '' : `: ${JSON.stringify(opened.value)}`))) return;
  const first = await stableCanvas(page);
  if (!check(first.ok && !first.value.error && first.value.width > 0, where,
             first.value.exists ? (first.value.error ?? `#zoom-canvas ${first.value.width}x${first.value.height}${first.value.drawn ? `, drawn (pixels read by ${first.value.how})` : ', blank'}`)
                                : 'no #zoom-canvas')) return;
  note(where, `screenshot ${await screenshot(page, `${shotBase}-zoom.png`, false)}`);

  // The flip: the first image's, else (e.g. it is the oracle itself, whose flip shows the same) the
  // next zoomable images', up to 8 in all.
  let flipped = false;
  for (let i = 0; i < Math.min(imgs.length, 8) && !flipped; i++) {
    if (i > 0) {
      if (!(await openZoom(page, imgs[i])).ok) { check(false, where, `img.zoomable #${i + 1} does not open #zoom`); return; }
    }
    const before = i === 0 ? first : await stableCanvas(page);
    if (!before.ok || before.value.error) { check(false, where, `img.zoomable #${i + 1}: #zoom-canvas not drawn: ${before.value.error ?? 'blank'}`); return; }
    if (!(await page.$('#zoom-flip'))) { check(false, where, 'no #zoom-flip'); return; }
    await page.click('#zoom-flip');
    const after = await poll(() => canvasState(page), s => s.drawn && s.pixels !== before.value.pixels, 3000);
    if (after.ok) {
      flipped = true;
      check(true, where, `#zoom-flip changes the canvas pixels (img.zoomable #${i + 1}, "${await alt(imgs[i])}")`);
      note(where, `screenshot ${await screenshot(page, `${shotBase}-zoom-flipped.png`, false)}`);
    } else {
      note(where, `#zoom-flip on img.zoomable #${i + 1} ("${await alt(imgs[i])}") leaves the canvas unchanged`);
    }
    const closed = await closeZoom(page, 'Escape');
    if (i === 0 || flipped)
      check(closed.ok, where, 'Escape closes #zoom' + (closed.ok ? '' : `: ${JSON.stringify(closed.value)}`));
    if (!closed.ok) return;
  }
  if (!flipped) check(false, where, `#zoom-flip changed the canvas of none of the first ${Math.min(imgs.length, 8)} img.zoomable`);

  // #zoom-close, the other way out.
  if (!(await openZoom(page, imgs[0])).ok) { check(false, where, 'the first img.zoomable does not open #zoom again'); return; }
  if (!check(!!(await page.$('#zoom-close')), where, 'has #zoom-close')) return;
  const closed = await closeZoom(page, 'button');
  check(closed.ok, where, '#zoom-close closes #zoom' + (closed.ok ? '' : `: ${JSON.stringify(closed.value)}`));
}

// --- pages ---------------------------------------------------------------------------------------

async function checkReport(browser, file, shotBase) {
  const where = displayName(file);
  const {page, problems} = await openPage(browser, file);
  try {
    await checkImages(page, where);
    const sections = await page.$$('section.light');
    const ids = await Promise.all(sections.map(s => s.evaluate(e => e.id)));
    check(sections.length > 0, where, `${sections.length} section.light (${ids.join(', ')})`);
    if (sections.length > 0)
      check(ids.every(id => id.startsWith('light-')), where, 'every section.light has an id "light-NAME"');
    note(where, `screenshot ${await screenshot(page, `${shotBase}.png`, true)}`);
    for (let i = 0; i < sections.length; i++) {
      const w = `${where}#${ids[i] || `section-${i + 1}`}`;
      await checkSort(page, sections[i], w);
      await checkChart(page, sections[i], w);
      const box = await sections[i].$('.chart-box');
      if (box) await checkWorkAxis(box, w, `${shotBase}-work-axis-${i + 1}.png`);
    }
    await checkZoom(page, where, shotBase);
  } catch (e) {
    check(false, where, `harness error: ${e.stack ?? e}`);
  }
  checkProblems(problems, where);
  await page.close();
}

async function checkIndex(browser, file, reports, shotBase) {
  const where = displayName(file);
  const {page, problems, url} = await openPage(browser, file);
  try {
    await checkImages(page, where);
    const matrices = await page.$$eval('table.matrix', ts => ts.map(t => t.dataset.metric ?? ''));
    check(matrices.length > 0, where, `${matrices.length} table.matrix (data-metric: ${matrices.join(', ')})`);
    note(where, `screenshot ${await screenshot(page, `${shotBase}.png`, true)}`);
    const hrefs = await page.$$eval('a[href]', as => as.map(a => a.getAttribute('href')));
    const relative = hrefs.filter(h => h !== '' && !/^[a-zA-Z][a-zA-Z0-9+.-]*:/.test(h) && !h.startsWith('//') && !h.startsWith('#'));
    const missing = [], targets = new Set();
    for (const h of relative) {
      const u = new URL(h, url);
      u.hash = ''; u.search = '';
      const p = fileURLToPath(u);
      targets.add(path.resolve(p));
      let ok = false;
      try { ok = fs.statSync(p).isFile(); } catch { /* missing */ }
      if (!ok) missing.push(h);
    }
    check(relative.length > 0 && missing.length === 0, where,
          relative.length === 0 ? `no relative a[href] (of ${hrefs.length} links)`
          : missing.length === 0 ? `${relative.length} relative a[href] all name existing files`
          : `${missing.length} of ${relative.length} relative a[href] name no file: ${missing.slice(0, 5).join(', ')}`);
    const unlinked = reports.filter(r => !targets.has(path.resolve(r)));
    if (reports.length > 0)
      check(unlinked.length === 0, where, unlinked.length === 0 ? `links all ${reports.length} report(s) given`
                                                                : `links none of: ${unlinked.join(', ')}`);
  } catch (e) {
    check(false, where, `harness error: ${e.stack ?? e}`);
  }
  checkProblems(problems, where);
  await page.close();
}

function displayName(file) {
  const rel = path.relative(process.cwd(), file);
  return rel === '' || rel.startsWith('..') ? path.resolve(file) : rel;
}

function shotName(dir, n, file) {
  const abs = path.resolve(file);
  const base = path.basename(abs, '.html');
  const parent = path.basename(path.dirname(abs));
  const label = (base === 'report' ? `${parent}-${base}` : base).replace(/[^A-Za-z0-9._-]+/g, '_');
  return path.join(dir, `${String(n).padStart(2, '0')}-${label}`);
}

async function main() {
  const args = parseArgs(process.argv.slice(2));
  const executablePath = findBrowser(args.browser);
  if (!executablePath) { console.error('report_test: no chromium found (give --browser PATH or set CHROMIUM)'); process.exit(2); }
  fs.mkdirSync(args.screenshots, {recursive: true});
  const browser = await puppeteer.launch({
    executablePath,
    headless: true,
    // Root in a container: no sandbox; a small /dev/shm must not crash the renderer.
    args: ['--no-sandbox', '--disable-dev-shm-usage', '--no-first-run', '--no-default-browser-check',
           '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  console.log(`report_test: ${await browser.version()} (${executablePath}), screenshots in ${args.screenshots}`);
  try {
    let n = 0;
    for (const r of args.reports) await checkReport(browser, r, shotName(args.screenshots, ++n, r));
    if (args.index) await checkIndex(browser, args.index, args.reports, shotName(args.screenshots, ++n, args.index));
  } finally {
    await browser.close();
  }
  console.log(`report_test: ${checks} checks, ${failures} failed`);
  process.exit(failures === 0 ? 0 : 1);
}

main().catch(e => {
  console.log(`FAIL report_test: ${e.stack ?? e}`);
  process.exit(1);
});
