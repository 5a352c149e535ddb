// rocking_monitor live dashboard: vanilla JS (ES modules), no framework, no network beyond this node.
// Data: GET /api/snapshot once (and again when the server says so), then Server-Sent Events from
// /api/events: "states" (items whose state changed, <= 10 Hz), "alarm" (at once), "health" (1 Hz).
// The entry module (index.html loads it as a module, which loads the others): the data, the live
// stream, the drawing of every panel in one frame, and the page's start. The panels: plan.js (floor
// plan), item_view.js (item table, selected item), alarms.js (alarm log, banner), health.js (sensor
// health, input acceleration); state.js holds what they share.
import { $, COLOURS, LABELS, onFrame, pColour, requestDraw, utc, view } from './state.js';
import { drawPlan, layoutPlan, pickAt } from './plan.js';
import { addHistory, buildItemTable, drawChart, drawSide, loadHistory, loadItem, renderDetail, select,
         updateRow } from './item_view.js';
import { addAlarm, markAlarmLayout, renderAlarms, updateBanner } from './alarms.js';
import { addInput, drawInput, loadInput, renderHealth } from './health.js';

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

// ------------------------------------------------------------------ drawing (state.js requestDraw)
function drawFrame() {
  const t0 = performance.now();
  drawPlan();
  drawSide();
  drawChart();
  drawInput();
  document.body.dataset.drawMs = (performance.now() - t0).toFixed(1);  // for load measurements
  record('draw', performance.now() - t0);
  $('clock').textContent = view.latestStamp > 0 ? utc(view.latestStamp) : 'no data yet';
}

function init() {
  window.addEventListener('resize', markAlarmLayout);  // the alarm log's layout, for the browser test
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

onFrame(drawFrame);
init();
