// The sensor health panel: each sensor's rate, counts and processing time from /diagnostics, the
// catalogue's status, and the chart of the input acceleration of the last 60 s.
import { $, HISTORY_S, esc, fmt, requestDraw, view } from './state.js';

export function renderHealth() {
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

// ------------------------------------------------------------------ input acceleration
export function loadInput() {
  fetch('/api/input', { cache: 'no-store' }).then((r) => r.json()).then((j) => {
    view.inputTopic = j.topic;
    view.input = j.points;
    requestDraw();
  }).catch(() => {});
}

export function addInput(points) {
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

export function drawInput() {
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
