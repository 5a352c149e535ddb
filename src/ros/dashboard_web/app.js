// rocking_monitor live dashboard: vanilla JS, no framework, no network beyond this node.
// Data: GET /api/snapshot once (and again when the server says so), then Server-Sent Events from
// /api/events: "states" (items whose state changed, <= 10 Hz), "alarm" (at once), "health" (1 Hz).
'use strict';

const COLOURS = { REST: '#2e9d4a', ROCKING: '#e8c31c', BEYOND_TIPPING: '#f08a1c', COMMITTED: '#d62828',
                  OVERTURNED: '#7b2cbf', UNKNOWN: '#bbbbbb' };
const SEVERITY = { REST: 0, ROCKING: 1, BEYOND_TIPPING: 2, COMMITTED: 3, OVERTURNED: 4, UNKNOWN: -1 };
const LABELS = { REST: 'rest', ROCKING: 'rocking', BEYOND_TIPPING: 'beyond tipping', COMMITTED: 'committed',
                 OVERTURNED: 'overturned', UNKNOWN: 'no state yet' };
const HISTORY_S = 60;  // chart window, s

const view = {
  items: [], byId: new Map(), alarms: [], alarmKeys: new Set(), health: [],
  selected: null, history: new Map(), latestStamp: 0, rows: new Map(), dirty: true,
  plan: null,  // world -> canvas transform of the floor plan
  input: [], inputTopic: '',  // [t, ax, ay, az] of the last 60 s (50 ms bins), m/s^2
  colourBy: 'mode',  // 'p': items with uncertain parameters coloured by P(overturned)
};

const $ = (id) => document.getElementById(id);
const modeOf = (it) => (it.state ? it.state.mode : 'UNKNOWN');
const pOf = (it) => (it.state && typeof it.state.p_overturned === 'number' ? it.state.p_overturned : null);
// P(overturned) 0 -> green, 0.5 -> red, 1 -> purple (the mode colours of rest, committed, overturned).
function pColour(p) {
  const stops = [[0, [46, 157, 74]], [0.25, [232, 195, 28]], [0.5, [214, 40, 40]], [1, [123, 44, 191]]];
  let k = 1;
  while (k < stops.length - 1 && p > stops[k][0]) ++k;
  const [p0, c0] = stops[k - 1], [p1, c1] = stops[k], f = Math.max(0, Math.min(1, (p - p0) / (p1 - p0)));
  return 'rgb(' + c0.map((v, i) => Math.round(v + f * (c1[i] - v))).join(',') + ')';
}
function colourOf(it) {
  const p = pOf(it);
  return view.colourBy === 'p' && p !== null ? pColour(p) : COLOURS[modeOf(it)];
}
const fmt = (v, d = 3) => (typeof v === 'number' && isFinite(v) ? v.toFixed(d) : '–');
const signedRatio = (s) => (s.theta < 0 ? -1 : 1) * s.rotation_ratio;

function utc(seconds) {
  if (!(seconds > 0)) return '–';
  return new Date(seconds * 1000).toISOString().replace('T', ' ').replace('Z', ' UTC');
}

// ------------------------------------------------------------------ data
function loadSnapshot() {
  return fetch('/api/snapshot', { cache: 'no-store' })
    .then((r) => r.json())
    .then(applySnapshot)
    .catch((e) => setConn('conn-bad', 'snapshot failed: ' + e));
}

function applySnapshot(s) {
  const t0 = performance.now();
  $('monitor').textContent = 'monitor ' + s.monitor;
  view.items = s.items;
  view.byId = new Map(s.items.map((it) => [it.id, it]));
  for (const it of s.items) if (it.state) addHistory(it.id, it.state);
  view.alarms = [];
  view.alarmKeys = new Set();
  for (const a of s.alarms.slice().reverse()) addAlarm(a, false);
  renderAlarms();
  view.health = s.health;
  renderHealth();
  if (s.stamp > 0) view.latestStamp = Math.max(view.latestStamp, s.stamp);
  if (view.selected && !view.byId.has(view.selected)) view.selected = null;
  layoutPlan();
  buildItemTable();
  loadInput();
  updateBanner();
  renderDetail();
  requestDraw();
  document.body.dataset.snapshotMs = (performance.now() - t0).toFixed(1);  // for load measurements
}

function addHistory(id, st) {
  let h = view.history.get(id);
  if (!h) { h = []; view.history.set(id, h); }
  // A restarted monitor or a replayed bag starts its clock again: start the chart again too.
  if (h.length && st.stamp < h[h.length - 1].t - 1.0) h.length = 0;
  h.push({ t: st.stamp, r: signedRatio(st), e: st.energy_margin });
  const cut = st.stamp - HISTORY_S;
  let drop = 0;
  while (drop < h.length - 1 && h[drop + 1].t < cut) ++drop;
  if (drop) h.splice(0, drop);
  if (st.stamp > view.latestStamp) view.latestStamp = st.stamp;
}

// A delta is compact (10,000 items must fit): one array per changed item, fields named in msg.fields,
// the governing plane's values only. The selected item's full state (both planes) comes from /api/item.
// Load measurement (scripts/measure_dashboard_load.sh): handler and drawing times, real milliseconds,
// kept in the DOM (body data-*) and, with ?measure=1, in the page title, which a headless browser's
// DevTools endpoint (/json/list) shows while the page stays live.
const timing = { delta: [], draw: [], deltaItems: 0, measure: new URLSearchParams(location.search).has('measure') };
function record(kind, ms) {
  const a = timing[kind];
  a.push(ms);
  const mean = a.reduce((s, v) => s + v, 0) / a.length;
  const sorted = a.slice().sort((x, y) => x - y);
  const d = document.body.dataset;
  d[kind + 'Count'] = a.length;
  d[kind + 'MeanMs'] = mean.toFixed(2);
  d[kind + 'P95Ms'] = sorted[Math.min(a.length - 1, Math.floor(0.95 * a.length))].toFixed(2);
  d[kind + 'MaxMs'] = sorted[a.length - 1].toFixed(2);
  if (timing.measure) document.title = 'measure ' + JSON.stringify(Object.assign({}, d));
}

function onStates(msg) {
  const tStart = performance.now();
  let unknown = false, selectedChanged = false;
  const f = msg.fields;
  for (const row of msg.items) {
    const d = {};
    f.forEach((name, k) => { d[name] = row[k]; });
    const it = view.byId.get(d.id);
    if (!it) { unknown = true; continue; }
    it.state = Object.assign({}, it.state || {}, {
      mode: d.mode, plane: d.plane, theta: d.theta, rotation_ratio: d.rotation_ratio,
      energy_margin: d.energy_margin, impacts: d.impacts, stamp: d.stamp });
    it.criteria = d.criteria || undefined;
    if (typeof d.p_overturned === 'number') it.state.p_overturned = d.p_overturned;
    addHistory(d.id, it.state);
    updateRow(it);
    if (d.id === view.selected) selectedChanged = true;
  }
  if (msg.stamp > view.latestStamp) view.latestStamp = msg.stamp;
  if (unknown) loadSnapshot();  // the monitor restarted with other items
  updateBanner();
  if (selectedChanged) { renderDetail(); loadItem(view.selected); }
  requestDraw();
  timing.deltaItems = Math.max(timing.deltaItems, msg.items.length);
  document.body.dataset.deltaItemsMax = timing.deltaItems;
  record('delta', performance.now() - tStart);
}

let itemPending = false;
function loadItem(id) {
  if (itemPending) return;  // at most one request in flight: never more than the delta rate
  itemPending = true;
  fetch('/api/item?id=' + encodeURIComponent(id), { cache: 'no-store' })
    .then((r) => (r.ok ? r.json() : null))
    .then((j) => {
      const it = j && view.byId.get(j.id);
      // Only if not older than what the deltas already brought.
      if (it && j.state && (!it.state || !(it.state.stamp > j.state.stamp))) { it.state = j.state; it.criteria = j.criteria; }
      renderDetail();
      requestDraw();
    })
    .catch(() => {})
    .finally(() => { itemPending = false; });
}

function addAlarm(a, render = true) {
  // A redundant pair's better copy of an alarm shown (docs/journal.md): it takes the other's place.
  if (a.replaces !== undefined) {
    const old = a.item + '/' + a.level + '/' + a.replaces;
    const i = view.alarms.findIndex((b) => b.item + '/' + b.level + '/' + b.stamp === old);
    if (i >= 0) view.alarms.splice(i, 1);
    view.alarmKeys.delete(old);
  }
  const key = a.item + '/' + a.level + '/' + a.stamp;
  if (view.alarmKeys.has(key)) return;
  view.alarmKeys.add(key);
  view.alarms.unshift(a);  // newest first
  if (render) renderAlarms();
}

function setConn(cls, text) {
  const c = $('conn');
  c.className = cls;
  c.textContent = text;
}

function connect() {
  const es = new EventSource('/api/events');
  es.addEventListener('hello', () => { setConn('conn-ok', 'live'); loadSnapshot(); });
  es.addEventListener('states', (e) => onStates(JSON.parse(e.data)));
  es.addEventListener('alarm', (e) => { addAlarm(JSON.parse(e.data)); });
  es.addEventListener('health', (e) => { view.health = JSON.parse(e.data); renderHealth(); });
  es.addEventListener('catalogue', () => loadSnapshot());
  es.addEventListener('input', (e) => addInput(JSON.parse(e.data).points));
  es.onerror = () => setConn('conn-bad', 'disconnected, retrying');  // EventSource reconnects itself
}

// ------------------------------------------------------------------ tables and banner
function buildItemTable() {
  const body = $('items').tBodies[0];
  const frag = document.createDocumentFragment();
  view.rows = new Map();
  for (const it of view.items) {
    const tr = document.createElement('tr');
    tr.dataset.item = it.id;
    for (let i = 0; i < 8; ++i) tr.appendChild(document.createElement('td'));
    tr.cells[0].textContent = it.id;
    tr.title = it.description || '';
    tr.addEventListener('click', () => select(it.id));
    view.rows.set(it.id, tr);
    fillRow(tr, it);
    frag.appendChild(tr);
  }
  body.replaceChildren(frag);
  $('item-count').textContent = '(' + view.items.length + ')';
}

function fillRow(tr, it) {
  const m = modeOf(it);
  tr.dataset.mode = m;
  tr.classList.toggle('selected', it.id === view.selected);
  const s = it.state;
  tr.cells[1].innerHTML = '<span class="mode m-' + esc(m) + '">' + esc(LABELS[m]) + '</span>';
  tr.cells[2].textContent = s ? s.plane : '';
  tr.cells[3].textContent = s ? fmt(s.rotation_ratio) : '';
  tr.cells[4].textContent = s ? fmt(s.energy_margin) : '';
  tr.cells[5].textContent = s ? s.impacts : '';
  tr.cells[6].textContent = (it.criteria || []).join(', ');
  const p = pOf(it);
  if (p !== null) tr.dataset.pOverturned = p;
  tr.cells[7].textContent = p !== null ? fmt(p, 2) : '';
  if (p !== null) tr.cells[7].style.background = pColour(p) + '40';
}

function updateRow(it) {
  const tr = view.rows.get(it.id);
  if (tr) fillRow(tr, it);
}

function updateBanner() {
  const bad = view.items.filter((it) => SEVERITY[modeOf(it)] >= SEVERITY.COMMITTED);
  const b = $('banner');
  if (!bad.length) { b.hidden = true; return; }
  bad.sort((a, c) => SEVERITY[modeOf(c)] - SEVERITY[modeOf(a)]);
  const names = bad.slice(0, 8).map((it) => it.id + ' ' + LABELS[modeOf(it)].toUpperCase());
  b.textContent = '\u26a0 ' + bad.length + (bad.length === 1 ? ' item' : ' items') + ' committed or overturned: ' +
                  names.join(', ') + (bad.length > 8 ? ', \u2026' : '');
  b.hidden = false;
}

// An OVERTURNED alarm's cause (OverturnAlarm.cause): "fell_off_support" when the item slid off its
// plinth, shelf or pedestal (docs/dashboard.md); rocking, the usual way, adds nothing.
const CAUSES = { fell_off_support: 'fell off its support' };

function renderAlarms() {
  const rows = view.alarms.slice(0, 500).map((a) =>
    '<tr data-item="' + esc(a.item) + '" data-level="' + a.level + '"><td>' + utc(a.event_time) + '</td><td>' +
    fmt(a.t, 3) + '</td><td title="' + esc(a.description) + '">' + esc(a.item) + '</td><td data-cause="' +
    esc(a.cause || 'rocking') + '"><span class="mode m-' +
    a.level + '">' + LABELS[a.level] + '</span>' + (CAUSES[a.cause] ? '<br>' + CAUSES[a.cause] : '') + '</td><td>' +
    esc(a.plane) + '</td><td>' + fmt(a.rotation_ratio, 2) +
    '</td><td>' + esc((a.predicted_by || []).join(', ') || 'none') + '</td></tr>');
  $('alarms').tBodies[0].innerHTML = rows.join('') ||
    '<tr><td colspan="7" class="hint">no alarms</td></tr>';
  markAlarmLayout();
}

// Where the alarm log's last column ("predicted by") lies and what of it shows without scrolling, as
// data attributes on the table: the headless browser test (test/ros/dashboard_browser.py) cannot
// measure layout itself, and checks from these that the column is not cut at a 1280-pixel window.
function markAlarmLayout() {
  const table = $('alarms');
  const col = table.tHead.rows[0].lastElementChild.getBoundingClientRect();
  const scroller = table.parentElement;  // the .scroll box
  const left = scroller.getBoundingClientRect().left + scroller.clientLeft;
  const viewport = document.documentElement.clientWidth;
  table.dataset.viewport = viewport;
  table.dataset.lastColumn = Math.round(col.left) + ',' + Math.round(col.right);
  table.dataset.visible = Math.round(left) + ',' + Math.round(Math.min(left + scroller.clientWidth, viewport));
}
window.addEventListener('resize', markAlarmLayout);

function esc(s) {
  return String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));
}

function renderHealth() {
  // The monitor reports each sensor twice: "sensor NAME input TOPIC" (rate) and "sensor NAME samples".
  const sensors = new Map();
  let catalogue = null;
  for (const st of view.health) {
    const m = /^sensor (\S+) (input|samples)/.exec(st.name);
    if (!m) { if (st.name === 'catalogue') catalogue = st; continue; }
    const s = sensors.get(m[1]) || { name: m[1], level: 0, messages: [], values: {} };
    s.level = Math.max(s.level, st.level);
    if (st.message && st.message !== 'ok' && st.message !== 'OK') s.messages.push(st.message);
    Object.assign(s.values, st.values);
    sensors.set(m[1], s);
  }
  const num = (v) => (v === undefined ? NaN : parseFloat(v));
  const rows = [];
  for (const s of sensors.values()) {
    const v = s.values;
    const dropped = num(v['dropped duplicate stamp']) + num(v['dropped out-of-order stamp']) + num(v['dropped zero stamp']);
    const rejected = num(v['rejected non-finite']) + num(v['rejected beyond max_abs_acceleration']);
    const proc = num(v['processing per sample, mean (s)']), period = num(v['mean sample period (s)']);
    const share = period > 0 ? ' (' + (100 * proc / period).toFixed(2) + ' %)' : '';
    rows.push('<tr><td>' + esc(s.name) + '</td><td class="lvl-' + s.level + '">' +
      esc(['OK', 'WARN', 'ERROR', 'STALE'][s.level] || s.level) + (s.messages.length ? ': ' + esc(s.messages.join('; ')) : '') +
      '</td><td>' + fmt(num(v['Actual frequency (Hz)']), 1) + '</td><td>' + esc(v['received'] || '–') + '</td><td>' +
      [dropped, rejected, num(v['data gaps (not bridged)'])].map((x) => (isFinite(x) ? x : '–')).join(' / ') + '</td><td>' +
      fmt(proc * 1e3, 3) + ' ms of ' + fmt(period * 1e3, 2) + ' ms' + share + '</td></tr>');
  }
  $('health').tBodies[0].innerHTML = rows.join('') || '<tr><td colspan="6" class="hint">no diagnostics yet</td></tr>';
  $('catalogue-status').textContent = catalogue ? 'catalogue: ' + catalogue.message : '';
}

// ------------------------------------------------------------------ floor plan
function footprint(it) {
  const w = it.width > 0 ? it.width : 0.3;
  const d = it.depth > 0 ? it.depth : w;  // an x-plane-only item: drawn square
  const nu = it.eccentricity > 0 ? it.eccentricity : 0.5, nuy = it.eccentricity_y > 0 ? it.eccentricity_y : 0.5;
  return { w, d, nu, nuy };
}

function layoutPlan() {
  // Items without a pose in the catalogue go on a row below the others (their place is unknown).
  let minx = Infinity, maxx = -Infinity, miny = Infinity, maxy = -Infinity;
  const posed = view.items.filter((it) => it.pose);
  for (const it of posed) {
    const f = footprint(it), r = Math.hypot(f.w, f.d);
    minx = Math.min(minx, it.pose.x - r); maxx = Math.max(maxx, it.pose.x + r);
    miny = Math.min(miny, it.pose.y - r); maxy = Math.max(maxy, it.pose.y + r);
  }
  if (!posed.length) { minx = 0; maxx = 4; miny = 0; maxy = 3; }
  const loose = view.items.filter((it) => !it.pose);
  const perRow = Math.max(1, Math.ceil(Math.sqrt(loose.length * 4)));
  loose.forEach((it, k) => {
    it.auto = { x: minx + 0.5 + 1.0 * (k % perRow), y: miny - 1.0 - 1.0 * Math.floor(k / perRow), yaw: 0 };
  });
  if (loose.length) miny -= 1.5 + Math.ceil(loose.length / perRow);
  view.bounds = { minx, maxx, miny, maxy };
}

function placeOf(it) { return it.pose || it.auto || { x: 0, y: 0, yaw: 0 }; }

function fitCanvas(c) {
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(50, Math.round(c.clientWidth * dpr)), h = Math.max(50, Math.round(c.clientHeight * dpr));
  if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
  return dpr;
}

function drawPlan() {
  const c = $('plan'), ctx = c.getContext('2d');
  const dpr = fitCanvas(c);
  const W = c.width, H = c.height, pad = 28 * dpr;
  ctx.clearRect(0, 0, W, H);
  if (!view.bounds) return;
  const b = view.bounds;
  const s = Math.min((W - 2 * pad) / (b.maxx - b.minx), (H - 2 * pad) / (b.maxy - b.miny));
  const ox = pad + ((W - 2 * pad) - s * (b.maxx - b.minx)) / 2 - s * b.minx;
  const oy = H - pad - ((H - 2 * pad) - s * (b.maxy - b.miny)) / 2 + s * b.miny;
  view.plan = { s, ox, oy, dpr };  // canvas = (ox + s x, oy - s y): x right, y up (REP 103)

  // 1 m grid (coarser when the site is large), so distances read off the plan.
  let step = 1;
  while (s * step < 25 * dpr) step *= 5;
  ctx.strokeStyle = '#e6eaee';
  ctx.lineWidth = 1;
  ctx.beginPath();
  for (let x = Math.ceil(b.minx / step) * step; x <= b.maxx; x += step) { ctx.moveTo(ox + s * x, 0); ctx.lineTo(ox + s * x, H); }
  for (let y = Math.ceil(b.miny / step) * step; y <= b.maxy; y += step) { ctx.moveTo(0, oy - s * y); ctx.lineTo(W, oy - s * y); }
  ctx.stroke();
  // scale bar
  ctx.fillStyle = '#444';
  ctx.fillRect(pad, H - 12 * dpr, s * step, 3 * dpr);
  ctx.font = 11 * dpr + 'px system-ui, sans-serif';
  ctx.fillText(step + ' m', pad + s * step + 6 * dpr, H - 8 * dpr);
  ctx.fillText('x \u2192   y \u2191', W - 80 * dpr, H - 8 * dpr);

  const labels = view.items.length <= 300;
  for (const it of view.items) {
    const p = placeOf(it), f = footprint(it), m = modeOf(it);
    ctx.save();
    ctx.translate(ox + s * p.x, oy - s * p.y);
    ctx.rotate(-p.yaw);  // canvas y points down: a counter-clockwise yaw turns the other way here
    // The item frame's origin is under the centre of mass: the base spans -nu B .. (1 - nu) B.
    const x0 = -f.nu * f.w * s, y0 = -(1 - f.nuy) * f.d * s;
    ctx.fillStyle = colourOf(it);
    ctx.globalAlpha = it.pose ? 1 : 0.6;
    ctx.fillRect(x0, y0, f.w * s, f.d * s);
    ctx.globalAlpha = 1;
    ctx.lineWidth = (it.id === view.selected ? 3 : 1) * dpr;
    ctx.strokeStyle = it.id === view.selected ? '#0b3d91' : '#0006';
    ctx.strokeRect(x0, y0, f.w * s, f.d * s);
    if (m === 'OVERTURNED') {  // a cross as well as the colour: readable in grey print too
      ctx.beginPath();
      ctx.moveTo(x0, y0); ctx.lineTo(x0 + f.w * s, y0 + f.d * s);
      ctx.moveTo(x0 + f.w * s, y0); ctx.lineTo(x0, y0 + f.d * s);
      ctx.strokeStyle = '#fff';
      ctx.lineWidth = 2 * dpr;
      ctx.stroke();
    }
    ctx.restore();
    if (labels) {
      ctx.fillStyle = '#222';
      ctx.font = (it.id === view.selected ? 'bold ' : '') + 12 * dpr + 'px system-ui, sans-serif';
      const r = Math.hypot(f.w, f.d) * s / 2, tw = ctx.measureText(it.id).width;
      let lx = ox + s * p.x + r + 4 * dpr;
      if (lx + tw > W - 4 * dpr) lx = ox + s * p.x - r - 4 * dpr - tw;  // near the right edge: on the left
      ctx.fillText(it.id, lx, oy - s * p.y - r);
    }
  }
}

function pickAt(px, py) {
  const P = view.plan;
  if (!P) return null;
  const wx = (px * P.dpr - P.ox) / P.s, wy = (P.oy - py * P.dpr) / P.s;
  const tol = 4 * P.dpr / P.s;  // a few pixels around small items
  let best = null, bestArea = Infinity;
  for (const it of view.items) {
    const p = placeOf(it), f = footprint(it);
    const dx = wx - p.x, dy = wy - p.y, c = Math.cos(p.yaw), sn = Math.sin(p.yaw);
    const lx = c * dx + sn * dy, ly = -sn * dx + c * dy;  // into the item's frame
    if (lx >= -f.nu * f.w - tol && lx <= (1 - f.nu) * f.w + tol && ly >= -f.nuy * f.d - tol && ly <= (1 - f.nuy) * f.d + tol) {
      const area = f.w * f.d;
      if (area < bestArea) { best = it; bestArea = area; }  // the smaller one when they overlap
    }
  }
  return best;
}

// ------------------------------------------------------------------ selected item
// The server keeps each item's last 60 s (what it sent): a page opened after the alarm still has the chart.
function loadHistory(id) {
  fetch('/api/history?id=' + encodeURIComponent(id), { cache: 'no-store' })
    .then((r) => (r.ok ? r.json() : null))
    .then((j) => {
      if (!j || !j.points.length) return;
      const local = view.history.get(id) || [];
      const lastServer = j.points[j.points.length - 1][0];
      const merged = j.points.map(([t, r, e]) => ({ t, r, e })).concat(local.filter((p) => p.t > lastServer));
      view.history.set(id, merged);
      requestDraw();
    })
    .catch(() => {});
}

function select(id) {
  const old = view.rows.get(view.selected);
  if (id !== view.selected) loadHistory(id);
  view.selected = id;
  loadItem(id);
  if (old) old.classList.remove('selected');
  const tr = view.rows.get(id);
  if (tr) { tr.classList.add('selected'); tr.scrollIntoView({ block: 'nearest' }); }
  renderDetail();
  requestDraw();
}

function renderDetail() {
  const it = view.selected && view.byId.get(view.selected);
  if (!it) return;
  const s = it.state, m = modeOf(it);
  $('sel-title').innerHTML = esc(it.id) + ' <span class="mode m-' + esc(m) + '">' + esc(LABELS[m]) + '</span>';
  $('sel-desc').textContent = it.description || '';
  const rows = [];
  const row = (k, v) => rows.push('<tr><td>' + k + '</td><td>' + v + '</td></tr>');
  row('base B \u00d7 D, h', fmt(it.width, 2) + ' \u00d7 ' + (it.depth ? fmt(it.depth, 2) : '\u2013') + ' m, ' + fmt(it.cg_height, 2) + ' m');
  if (s) {
    row('governing plane', esc(s.plane) + (s.plane_count > 1 ? ' (of 2)' : s.plane_count === 1 ? ' (x only)' : ''));
    row('\u03b8, \u03b8/\u03b1', fmt(s.theta, 4) + ' rad, ' + fmt(s.rotation_ratio, 3));
    row('energy margin', fmt(s.energy_margin, 3));
    if (s.x) row('impacts x / y', s.x.impacts + (s.y ? ' / ' + s.y.impacts : ''));
    if (s.model) row('model', esc(s.model) + (s.model_valid ? '' : ' (pure rocking not valid)'));
    if (s.model === 'rocking_3d') {
      row('tilt, contact', fmt(s.tilt, 4) + ' rad, ' +
          esc(s.contact || (s.mode === 'OVERTURNED' ? 'on its side' : 'flat on its base')));
      // on a plinth, shelf or pedestal: the live margin to its edge, like the energy margin to tipping
      if (s.support_margin !== undefined) row('support margin', fmt(s.support_margin, 3) + ' m to the edge');
    }
  }
  row('criteria exceeded', esc((it.criteria || []).join(', ') || 'none'));
  $('sel-details').tBodies[0].innerHTML = rows.join('');
}

function drawSide() {
  const c = $('side'), ctx = c.getContext('2d');
  const W = c.width, H = c.height;
  ctx.clearRect(0, 0, W, H);
  const it = view.selected && view.byId.get(view.selected);
  ctx.font = '12px system-ui, sans-serif';
  if (!it) { ctx.fillStyle = '#888'; ctx.fillText('side view of the selected item', 10, 20); return; }
  const st = it.state, plane = st ? st.plane : 'x';
  if (it.base_polygon && st && st.model === 'rocking_3d') { drawSide3d(ctx, W, H, it, st); return; }
  const ps = { theta: st ? st.theta : 0 };  // item level = the governing plane's
  const f = footprint(it);
  const B = plane === 'y' ? f.d : f.w, nu = plane === 'y' ? f.nuy : f.nu;
  const h2 = 2 * (it.cg_height > 0 ? it.cg_height : 0.5);  // drawn as a homogeneous B x 2h block
  const reach = Math.max(B + h2, h2 * 1.1);
  const s = Math.min((W - 40) / (2 * reach), (H - 50) / reach);
  const gx = W / 2, gy = H - 28;  // ground point under the centre of mass
  ctx.strokeStyle = '#555'; ctx.lineWidth = 2;
  ctx.beginPath(); ctx.moveTo(10, gy); ctx.lineTo(W - 10, gy); ctx.stroke();
  // theta > 0: about corner 1 (-B nu), tipping towards -x (left); theta < 0: about corner 2, right.
  const th = Math.max(-Math.PI / 2, Math.min(Math.PI / 2, ps.theta || 0));
  const px = th >= 0 ? -nu * B : (1 - nu) * B;
  const corners = [[-nu * B, 0], [(1 - nu) * B, 0], [(1 - nu) * B, h2], [-nu * B, h2]];
  const rot = ([u, z]) => {
    const du = u - px, c1 = Math.cos(th), s1 = Math.sin(th);
    return [px + du * c1 - z * s1, du * s1 + z * c1];
  };
  const toC = ([u, z]) => [gx + s * u, gy - s * z];
  ctx.beginPath();
  corners.map(rot).map(toC).forEach(([x, y], k) => (k ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
  ctx.closePath();
  ctx.fillStyle = COLOURS[modeOf(it)];
  ctx.globalAlpha = 0.85; ctx.fill(); ctx.globalAlpha = 1;
  ctx.strokeStyle = '#222'; ctx.lineWidth = 1.5; ctx.stroke();
  const [cx, cy] = toC(rot([0, h2 / 2]));  // centre of mass
  ctx.fillStyle = '#000'; ctx.beginPath(); ctx.arc(cx, cy, 3, 0, 2 * Math.PI); ctx.fill();
  const [qx, qy] = toC([px, 0]);  // pivot
  ctx.strokeStyle = '#000'; ctx.beginPath(); ctx.arc(qx, qy, 4, 0, 2 * Math.PI); ctx.stroke();
  ctx.fillStyle = '#222';
  ctx.fillText('side view, plane ' + plane + (plane === 'y' ? ' (across the depth)' : ' (across the width)'), 10, 16);
  ctx.fillText('\u03b8 = ' + fmt(ps.theta, 3) + ' rad (' + fmt((ps.theta || 0) * 180 / Math.PI, 1) + '\u00b0)', 10, 32);
}

// The 3-D model's item (docs/rocking_3d.md): seen along the axis it turns about (the contact edge, or
// for a corner the line through it across the direction to the base's centre), tilted by the state's
// tilt; an inset plan of the base polygon marks the contact and the centre of mass.
function drawSide3d(ctx, W, H, it, st) {
  const base = it.base_polygon, n = base.length, com = it.centre_of_mass;
  const m = /^(edge|vertex) (\d+)$/.exec(st.contact || '');
  const k = m ? (parseInt(m[2], 10) - 1) % n : -1;
  const cx = base.reduce((a, v) => a + v[0], 0) / n, cy = base.reduce((a, v) => a + v[1], 0) / n;
  // pivot point p and inward unit direction u (from the axis towards the base)
  let p = [cx, cy], u = [1, 0], axisLabel = 'at rest';
  if (m && m[1] === 'edge') {
    const a = base[k], b = base[(k + 1) % n], ex = b[0] - a[0], ey = b[1] - a[1], L = Math.hypot(ex, ey) || 1;
    u = [-ey / L, ex / L];  // counter-clockwise polygon: the inward normal is on the left
    p = a;
    axisLabel = 'about edge ' + (k + 1);
  } else if (m) {
    p = base[k];
    const dx = cx - p[0], dy = cy - p[1], L = Math.hypot(dx, dy) || 1;
    u = [dx / L, dy / L];
    axisLabel = 'on corner ' + (k + 1) + ' (corner wobble)';
  } else {
    if (st.mode === 'OVERTURNED') axisLabel = 'overturned, on its side';
    else if (st.contact) axisLabel = 'on its hull: ' + st.contact;  // off its base (docs/rocking_3d.md)
    let lo = Infinity;  // at rest: seen along y, the pivot at the base's -x extreme
    for (const v of base) if (v[0] < lo) { lo = v[0]; p = v; }
  }
  const along = (v) => (v[0] - p[0]) * u[0] + (v[1] - p[1]) * u[1];
  let depth = 0;
  for (const v of base) depth = Math.max(depth, along(v));
  const h = com[2] > 0 ? com[2] : 0.5, h2 = 2 * h, cu = along(com);
  const reach = Math.max(depth + h2, h2 * 1.1);
  const s = Math.min((W - 40) / (2 * reach), (H - 50) / reach);
  const gx = W / 2, gy = H - 28;
  ctx.strokeStyle = '#555'; ctx.lineWidth = 2;
  ctx.beginPath(); ctx.moveTo(10, gy); ctx.lineTo(W - 10, gy); ctx.stroke();
  // the profile: from the pivot (u = 0) to the far side of the base (u = depth), 2h high; tilt lifts
  // the far side (towards -u, drawn leftwards as the planar view's theta > 0)
  const th = Math.max(0, Math.min(Math.PI / 2, st.tilt || 0));
  const rot = ([uu, z]) => [-(uu * Math.cos(th) - z * Math.sin(th)), uu * Math.sin(th) + z * Math.cos(th)];
  const toC = ([x, z]) => [gx + s * (x + depth / 2), gy - s * z];
  ctx.beginPath();
  [[0, 0], [depth, 0], [depth, h2], [0, h2]].map(rot).map(toC).forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
  ctx.closePath();
  ctx.fillStyle = COLOURS[modeOf(it)];
  ctx.globalAlpha = 0.85; ctx.fill(); ctx.globalAlpha = 1;
  ctx.strokeStyle = '#222'; ctx.lineWidth = 1.5; ctx.stroke();
  const [mx, my] = toC(rot([cu, h]));
  ctx.fillStyle = '#000'; ctx.beginPath(); ctx.arc(mx, my, 3, 0, 2 * Math.PI); ctx.fill();
  const [qx, qy] = toC([0, 0]);
  ctx.strokeStyle = '#000'; ctx.beginPath(); ctx.arc(qx, qy, 4, 0, 2 * Math.PI); ctx.stroke();
  // inset plan (top right): the base polygon, the contact in red, the centre of mass
  let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
  for (const v of base.concat([[com[0], com[1]]])) {
    x0 = Math.min(x0, v[0]); x1 = Math.max(x1, v[0]); y0 = Math.min(y0, v[1]); y1 = Math.max(y1, v[1]);
  }
  const box = 70, sc = box / Math.max(x1 - x0, y1 - y0, 1e-6), ox = W - box - 12, oy = 10;
  const P = (v) => [ox + sc * (v[0] - x0), oy + box - sc * (v[1] - y0)];  // +y up, as seen from above
  ctx.strokeStyle = '#444'; ctx.lineWidth = 1; ctx.beginPath();
  base.map(P).forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
  ctx.closePath(); ctx.stroke();
  ctx.strokeStyle = '#c00'; ctx.fillStyle = '#c00'; ctx.lineWidth = 3;
  if (m && m[1] === 'edge') {
    const [ax, ay] = P(base[k]), [bx, by] = P(base[(k + 1) % n]);
    ctx.beginPath(); ctx.moveTo(ax, ay); ctx.lineTo(bx, by); ctx.stroke();
  } else if (m) {
    const [ax, ay] = P(base[k]);
    ctx.beginPath(); ctx.arc(ax, ay, 4, 0, 2 * Math.PI); ctx.fill();
  }
  const [pcx, pcy] = P([com[0], com[1]]);
  ctx.fillStyle = '#000'; ctx.beginPath(); ctx.arc(pcx, pcy, 2.5, 0, 2 * Math.PI); ctx.fill();
  ctx.fillStyle = '#222';
  ctx.fillText('3-D model, ' + axisLabel, 10, 16);
  ctx.fillText('tilt = ' + fmt(st.tilt, 3) + ' rad (' + fmt((st.tilt || 0) * 180 / Math.PI, 1) + '\u00b0), ' +
               '\u03b8/\u03b1 ' + fmt(st.rotation_ratio, 3), 10, 32);
}

function drawChart() {
  const c = $('chart'), ctx = c.getContext('2d');
  const W = c.width, H = c.height, l = 34, r = 8, t = 18, b = 20;
  ctx.clearRect(0, 0, W, H);
  ctx.font = '11px system-ui, sans-serif';
  const h = view.selected ? view.history.get(view.selected) || [] : [];
  const t1 = view.latestStamp, t0 = t1 - HISTORY_S;
  let lo = -1.2, hi = 1.2;
  for (const p of h) { lo = Math.min(lo, p.r, p.e); hi = Math.max(hi, p.r, p.e); }
  lo = Math.max(lo, -2.5); hi = Math.min(hi, 2.5);  // an overturned item's ratio (up to ~10) would flatten the rest
  const X = (tt) => l + (W - l - r) * (tt - t0) / HISTORY_S, Y = (v) => t + (H - t - b) * (hi - v) / (hi - lo);
  ctx.strokeStyle = '#ccc'; ctx.lineWidth = 1;
  ctx.strokeRect(l, t, W - l - r, H - t - b);
  ctx.fillStyle = '#666';
  for (const v of [-1, 0, 1]) {
    ctx.setLineDash(v ? [4, 3] : []);
    ctx.beginPath(); ctx.moveTo(l, Y(v)); ctx.lineTo(W - r, Y(v)); ctx.stroke();
    ctx.fillText(String(v), 8, Y(v) + 4);
  }
  ctx.setLineDash([]);
  for (let k = 0; k <= 6; ++k) ctx.fillText(k < 6 ? '-' + (60 - 10 * k) + ' s' : 'now', X(t0 + 10 * k) - 12, H - 5);
  const line = (key, colour) => {
    if (!h.length) return;
    ctx.strokeStyle = colour; ctx.lineWidth = 1.6; ctx.beginPath();
    h.forEach((p, k) => {
      const x = X(Math.max(p.t, t0)), y = Y(Math.max(lo, Math.min(hi, p[key])));
      k ? ctx.lineTo(x, y) : ctx.moveTo(x, y);
    });
    const last = h[h.length - 1];
    ctx.lineTo(X(t1), Y(Math.max(lo, Math.min(hi, last[key]))));  // unchanged since: flat
    ctx.stroke();
  };
  line('e', '#2a9d8f');
  line('r', '#1d4ed8');
  ctx.fillStyle = '#1d4ed8'; ctx.fillText('\u00b1\u03b8/\u03b1', l + 4, 12);
  ctx.fillStyle = '#2a9d8f'; ctx.fillText('energy margin', l + 50, 12);
  ctx.fillStyle = '#666'; ctx.fillText('last 60 s', W - 60, 12);
}

// ------------------------------------------------------------------ drawing loop
let drawQueued = false;
function requestDraw() {
  if (drawQueued) return;
  drawQueued = true;
  requestAnimationFrame(() => {
    drawQueued = false;
    const t0 = performance.now();
    drawPlan();
    drawSide();
    drawChart();
    drawInput();
    document.body.dataset.drawMs = (performance.now() - t0).toFixed(1);  // for load measurements
    record('draw', performance.now() - t0);
    $('clock').textContent = view.latestStamp > 0 ? utc(view.latestStamp) : 'no data yet';
  });
}

// ------------------------------------------------------------------ input acceleration (health panel)
function loadInput() {
  fetch('/api/input', { cache: 'no-store' }).then((r) => r.json()).then((j) => {
    view.inputTopic = j.topic;
    view.input = j.points;
    requestDraw();
  }).catch(() => {});
}

function addInput(points) {
  if (!points.length) return;
  const last = view.input.length ? view.input[view.input.length - 1][0] : -Infinity;
  if (points[0][0] < last - 1.0) view.input = [];  // a new run: the clock went back
  for (const p of points) if (!view.input.length || p[0] > view.input[view.input.length - 1][0]) view.input.push(p);
  const cut = points[points.length - 1][0] - HISTORY_S;
  let drop = 0;
  while (drop < view.input.length && view.input[drop][0] < cut) ++drop;
  if (drop) view.input.splice(0, drop);
  requestDraw();
}

function drawInput() {
  const c = $('input-chart'), ctx = c.getContext('2d');
  const W = c.width, H = c.height, l = 34, r = 8, t = 16, b = 18;
  ctx.clearRect(0, 0, W, H);
  ctx.font = '11px system-ui, sans-serif';
  const pts = view.input;
  const t1 = pts.length ? Math.max(pts[pts.length - 1][0], view.latestStamp) : view.latestStamp, t0 = t1 - HISTORY_S;
  let peak = 0;
  for (const p of pts) peak = Math.max(peak, Math.abs(p[1]), Math.abs(p[2]), Math.abs(p[3]));
  c.dataset.points = pts.length;  // for tests: what the chart holds
  c.dataset.peak = peak;
  const lim = Math.max(0.1, peak * 1.1);
  const X = (tt) => l + (W - l - r) * (tt - t0) / HISTORY_S, Y = (v) => t + (H - t - b) * (lim - v) / (2 * lim);
  ctx.strokeStyle = '#ccc'; ctx.lineWidth = 1;
  ctx.strokeRect(l, t, W - l - r, H - t - b);
  ctx.beginPath(); ctx.moveTo(l, Y(0)); ctx.lineTo(W - r, Y(0)); ctx.stroke();
  ctx.fillStyle = '#666';
  ctx.fillText(lim.toPrecision(2), 2, Y(lim) + 8);
  ctx.fillText('-' + lim.toPrecision(2), 2, Y(-lim));
  for (let k = 0; k <= 6; ++k) ctx.fillText(k < 6 ? '-' + (60 - 10 * k) + ' s' : 'now', X(t0 + 10 * k) - 12, H - 4);
  const colours = ['#1d4ed8', '#f08a1c', '#2a9d8f'];
  for (let k = 1; k <= 3; ++k) {
    ctx.strokeStyle = colours[k - 1]; ctx.lineWidth = 1.2; ctx.beginPath();
    let first = true;
    for (const p of pts) {
      if (p[0] < t0) continue;
      first ? ctx.moveTo(X(p[0]), Y(p[k])) : ctx.lineTo(X(p[0]), Y(p[k]));
      first = false;
    }
    ctx.stroke();
  }
  ctx.fillStyle = '#222';
  ctx.fillText('input acceleration, m/s\u00b2 ' + (view.inputTopic ? '(' + view.inputTopic + ')' : '(no sensor topic)'), l, 11);
  ['x', 'y', 'z'].forEach((n, k) => { ctx.fillStyle = colours[k]; ctx.fillText(n, W - 40 + 12 * k, 11); });
}

function init() {
  const colourBy = new URLSearchParams(location.search).get('colour');
  if (colourBy === 'p') { view.colourBy = 'p'; $('colour-by').value = 'p'; }
  const showP = () => { $('p-legend').hidden = view.colourBy !== 'p'; };
  $('colour-by').addEventListener('change', (e) => { view.colourBy = e.target.value; showP(); requestDraw(); });
  $('p-legend').style.setProperty('--g', [0, 0.25, 0.5, 1].map(pColour).join(','));
  showP();
  const legend = $('legend');
  for (const m of ['REST', 'ROCKING', 'BEYOND_TIPPING', 'COMMITTED', 'OVERTURNED']) {
    const sp = document.createElement('span');
    sp.style.setProperty('--c', COLOURS[m]);
    sp.textContent = LABELS[m];
    legend.appendChild(sp);
  }
  $('plan').addEventListener('click', (e) => {
    const rect = e.target.getBoundingClientRect();
    const it = pickAt(e.clientX - rect.left, e.clientY - rect.top);
    if (it) select(it.id);
  });
  window.addEventListener('resize', requestDraw);
  renderAlarms();
  renderHealth();
  // ?poll=SECONDS: no live stream, the snapshot every SECONDS instead (headless browsers, whose
  // virtual time never runs out while a stream is open; proxies that buffer event streams).
  const poll = parseFloat(new URLSearchParams(location.search).get('poll'));
  if (poll > 0) {
    setConn('conn-wait', 'polling every ' + poll + ' s');
    loadSnapshot();
    setInterval(loadSnapshot, poll * 1000);
  } else {
    connect();
  }
  const sel = new URLSearchParams(location.search).get('select');
  if (sel) { view.selected = sel; loadHistory(sel); }  // ?select=ID: open with it selected (screenshots, links)
}

init();
