// The item view: the item table (one row per item; a click selects), and the selected item's detail,
// side view (planar, or seen along the 3-D model's axis) and 60 s chart of theta/alpha and the energy margin.
import { $, COLOURS, HISTORY_S, LABELS, esc, fmt, modeOf, pColour, pOf, requestDraw, signedRatio, view } from './state.js';
import { footprint } from './plan.js';

// ------------------------------------------------------------------ item table
export function buildItemTable() {
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

export function updateRow(it) {
  const tr = view.rows.get(it.id);
  if (tr) fillRow(tr, it);
}

// ------------------------------------------------------------------ selected item
export function addHistory(id, st) {
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

let itemPending = false;
export function loadItem(id) {
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

// The server keeps each item's last 60 s (what it sent): a page opened after the alarm still has the chart.
export function loadHistory(id) {
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

export function select(id) {
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

export function renderDetail() {
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

export function drawSide() {
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
    else if (/support/.test(st.contact)) axisLabel = 'about ' + st.contact;  // its plinth's edge (issue 51)
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

export function drawChart() {
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
