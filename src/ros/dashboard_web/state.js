// The dashboard's shared module: the one state object the panels read and write (`view`), the mode
// colours and labels, the formatting helpers, and the drawing request (one frame for every panel).
// Modules are strict mode and have their own scope: nothing here is a global.

export const COLOURS = { REST: '#2e9d4a', ROCKING: '#e8c31c', BEYOND_TIPPING: '#f08a1c', COMMITTED: '#d62828',
                         OVERTURNED: '#7b2cbf', UNKNOWN: '#bbbbbb' };
export const SEVERITY = { REST: 0, ROCKING: 1, BEYOND_TIPPING: 2, COMMITTED: 3, OVERTURNED: 4, UNKNOWN: -1 };
export const LABELS = { REST: 'rest', ROCKING: 'rocking', BEYOND_TIPPING: 'beyond tipping', COMMITTED: 'committed',
                        OVERTURNED: 'overturned', UNKNOWN: 'no state yet' };
export const HISTORY_S = 60;  // chart window, s

export const view = {
  items: [], byId: new Map(), alarms: [], alarmKeys: new Set(), health: [],
  selected: null, history: new Map(), latestStamp: 0, rows: new Map(), dirty: true,
  plan: null,  // world -> canvas transform of the floor plan
  input: [], inputTopic: '',  // [t, ax, ay, az] of the last 60 s (50 ms bins), m/s^2
  colourBy: 'mode',  // 'p': items with uncertain parameters coloured by P(overturned)
  bounds: null,  // the floor plan's extent in metres (plan.js, layoutPlan)
};

export const $ = (id) => document.getElementById(id);
export const modeOf = (it) => (it.state ? it.state.mode : 'UNKNOWN');
export const pOf = (it) => (it.state && typeof it.state.p_overturned === 'number' ? it.state.p_overturned : null);
// P(overturned) 0 -> green, 0.5 -> red, 1 -> purple (the mode colours of rest, committed, overturned).
export function pColour(p) {
  const stops = [[0, [46, 157, 74]], [0.25, [232, 195, 28]], [0.5, [214, 40, 40]], [1, [123, 44, 191]]];
  let k = 1;
  while (k < stops.length - 1 && p > stops[k][0]) ++k;
  const [p0, c0] = stops[k - 1], [p1, c1] = stops[k], f = Math.max(0, Math.min(1, (p - p0) / (p1 - p0)));
  return 'rgb(' + c0.map((v, i) => Math.round(v + f * (c1[i] - v))).join(',') + ')';
}
export function colourOf(it) {
  const p = pOf(it);
  return view.colourBy === 'p' && p !== null ? pColour(p) : COLOURS[modeOf(it)];
}
export const fmt = (v, d = 3) => (typeof v === 'number' && isFinite(v) ? v.toFixed(d) : '–');
export const signedRatio = (s) => (s.theta < 0 ? -1 : 1) * s.rotation_ratio;

export function utc(seconds) {
  if (!(seconds > 0)) return '–';
  return new Date(seconds * 1000).toISOString().replace('T', ' ').replace('Z', ' UTC');
}

export function esc(s) {
  return String(s).replace(/[&<>"]/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;' }[c]));
}

// Any panel may ask for a redraw; every panel is drawn in the next animation frame, once, by the
// drawing the entry module registers (app.js: drawFrame), so that no panel imports the entry.
let drawQueued = false;
let drawing = () => {};
export function onFrame(draw) { drawing = draw; }
export function requestDraw() {
  if (drawQueued) return;
  drawQueued = true;
  requestAnimationFrame(() => {
    drawQueued = false;
    drawing();
  });
}
